//! PNG of a plot: its SVG rasterised by resvg with the font compiled into the binary (DejaVu
//! Sans, regular and bold, from Debian's `fonts-dejavu-core`; licence in
//! `assets/fonts/LICENSE`). No system font is looked up, so a container without fonts draws
//! the same text as a desktop.

use std::sync::{Arc, OnceLock};

use resvg::{tiny_skia, usvg};

static REGULAR: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
static BOLD: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans-Bold.ttf");

/// The family every plot's text is drawn in, whatever family the SVG names.
pub const FAMILY: &str = "DejaVu Sans";

/// Pixels per SVG unit: twice the SVG's size, sharp when pasted into a printed report.
pub const SCALE: f32 = 2.0;

/// The embedded fonts only.
pub fn fonts() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_source(usvg::fontdb::Source::Binary(Arc::new(REGULAR)));
        db.load_font_source(usvg::fontdb::Source::Binary(Arc::new(BOLD)));
        db.set_sans_serif_family(FAMILY);
        db.set_serif_family(FAMILY);
        db.set_monospace_family(FAMILY);
        Arc::new(db)
    })
    .clone()
}

/// `svg` as a PNG, [`SCALE`] pixels per unit.
pub fn png(svg: &str) -> Result<Vec<u8>, String> {
    let opt = usvg::Options {
        font_family: FAMILY.into(),
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &opt).map_err(|e| format!("SVG: {e}"))?;
    let size = tree
        .size()
        .to_int_size()
        .scale_by(SCALE)
        .ok_or("empty plot")?;
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| format!("no {}x{} pixmap", size.width(), size.height()))?;
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(SCALE, SCALE),
        &mut pixmap.as_mut(),
    );
    pixmap.encode_png().map_err(|e| format!("PNG: {e}"))
}
