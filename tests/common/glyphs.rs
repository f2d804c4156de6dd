//! The boxes of a plot's texts as resvg lays out their glyphs (what its PNG shows), for the
//! tests that keep labels apart.

/// Every `<text>` of `svg` with the box of its glyphs as resvg lays them out in the embedded
/// DejaVu Sans (what the PNG shows), `[x0, y0, x1, y1]` in SVG pixels.
pub fn glyph_boxes(svg: &str) -> Vec<(String, [f64; 4])> {
    use resvg::usvg;
    fn walk(g: &usvg::Group, out: &mut Vec<(String, [f64; 4])>) {
        for n in g.children() {
            match n {
                usvg::Node::Group(g) => walk(g, out),
                usvg::Node::Text(t) => {
                    let s: String = t.chunks().iter().map(|c| c.text()).collect();
                    let b = t.abs_bounding_box();
                    let r = [b.left(), b.top(), b.right(), b.bottom()].map(f64::from);
                    out.push((s, r));
                }
                _ => {}
            }
        }
    }
    let opt = usvg::Options {
        font_family: whirl::render::png::FAMILY.into(),
        fontdb: whirl::render::png::fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &opt).unwrap();
    let mut out = vec![];
    walk(tree.root(), &mut out);
    out
}
