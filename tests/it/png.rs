//! Every plot as PNG (`Accept: image/png`): rasterised from the plot's own SVG by resvg with the
//! font compiled into the binary, twice the SVG's size, its text drawn (the same picture
//! without its `<text>` elements differs where the text is), and every SVG with a `<title>`.
//! `dump_png` (ignored) writes them to /tmp/plots/: `cargo test --release --test png --
//! --ignored dump_png`.

use crate::common;

use resvg::tiny_skia::Pixmap;

fn example(name: &str) -> serde_json::Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// One example of each plotted analysis, and the three rotors the plots are checked on.
const PLOTS: [(&str, &str); 13] = [
    ("/v1/campbell", "compressor-nvd.campbell.json"),
    ("/v1/campbell", "example1-nvd.campbell.json"),
    ("/v1/campbell", "anisotropic.campbell.json"),
    ("/v1/stability", "compressor-equivalent.stability.json"),
    ("/v1/modal", "compressor-nvd.modal.json"),
    ("/v1/modal", "example1-nvd.modal.json"),
    (
        "/v1/unbalance-response",
        "example1-nvd.unbalance-response.json",
    ),
    ("/v1/time-response", "example1-shock-nvd.time-response.json"),
    (
        "/v1/frequency-response",
        "example1-hysteretic.frequency-response.json",
    ),
    ("/v1/level1", "example1-hysteretic.level1.json"),
    ("/v1/critical-speed-map", "rotor-a.critical-speed-map.json"),
    ("/v1/static", "ross-rotor-example.static.json"),
    ("/v1/stability", "jeffcott-equivalent.stability.json"),
];

/// `width="W" height="H"` of the root element.
fn svg_size(svg: &str) -> (u32, u32) {
    let attr = |k: &str| -> u32 {
        let at = svg.find(&format!(" {k}=\"")).unwrap() + k.len() + 3;
        let end = at + svg[at..].find('"').unwrap();
        svg[at..end].parse::<f64>().unwrap().round() as u32
    };
    (attr("width"), attr("height"))
}

/// `svg` without its `<text>` elements.
fn textless(svg: &str) -> String {
    let mut out = String::new();
    let mut rest = svg;
    while let Some(a) = rest.find("<text") {
        out.push_str(&rest[..a]);
        let b = a + rest[a..].find("</text>").unwrap() + "</text>".len();
        rest = &rest[b..];
    }
    out.push_str(rest);
    out
}

/// Pixels whose colours differ by more than a shade.
fn differing(a: &Pixmap, b: &Pixmap) -> usize {
    a.pixels()
        .iter()
        .zip(b.pixels())
        .filter(|(p, q)| {
            let d = |x: u8, y: u8| (x as i32 - y as i32).abs();
            d(p.red(), q.red()) + d(p.green(), q.green()) + d(p.blue(), q.blue()) > 24
        })
        .count()
}

#[tokio::test]
async fn every_plot_is_a_png_with_its_text() {
    for (uri, file) in PLOTS {
        let body = example(file);
        let (status, ctype, svg) = common::post_as(uri, &body, "image/svg+xml").await;
        assert_eq!((status, ctype.as_str()), (200, "image/svg+xml"), "{file}");
        let svg = String::from_utf8(svg).unwrap();
        let title = svg
            .split_once("<title>")
            .and_then(|(_, t)| t.split_once("</title>"))
            .map(|(t, _)| t.to_string())
            .unwrap_or_default();
        assert!(title.len() > 10, "{file}: no <title>");
        let (status, ctype, png) = common::post_as(uri, &body, "image/png").await;
        assert_eq!((status, ctype.as_str()), (200, "image/png"), "{file}");
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{file}");
        let pixmap = Pixmap::decode_png(&png).unwrap();
        let (w, h) = svg_size(&svg);
        assert_eq!((pixmap.width(), pixmap.height()), (2 * w, 2 * h), "{file}");
        // The same picture without its text: the text covers thousands of pixels (a 12 px
        // digit alone covers ~40 at this scale), drawn with the embedded font.
        let bare = Pixmap::decode_png(&whirl::render::png::png(&textless(&svg)).unwrap()).unwrap();
        let text_px = differing(&pixmap, &bare);
        let texts = svg.matches("<text").count();
        assert!(texts >= 8, "{file}: {texts} texts");
        assert!(
            text_px >= 40 * texts,
            "{file}: the text covers {text_px} pixels for {texts} texts"
        );
        eprintln!("{file}: {w}x{h}, {texts} texts over {text_px} pixels, \"{title}\"");
    }
}

/// The fonts are the embedded ones, whatever the host has: regular and bold DejaVu Sans.
#[test]
fn fonts_are_embedded_only() {
    let db = whirl::render::png::fonts();
    let faces: Vec<_> = db.faces().collect();
    assert_eq!(faces.len(), 2);
    assert!(faces.iter().all(|f| f.families[0].0 == "DejaVu Sans"));
    assert!(
        faces
            .iter()
            .all(|f| matches!(f.source, resvg::usvg::fontdb::Source::Binary(_)))
    );
}

/// Asking for a picture of a result that has none: 406 naming PNG among none.
#[tokio::test]
async fn png_negotiation() {
    let (status, ctype, _) = common::post_as(
        "/v1/campbell",
        &example("jeffcott-nvd.campbell.json"),
        "image/*",
    )
    .await;
    assert_eq!((status, ctype.as_str()), (200, "image/svg+xml"));
    let (status, ctype, _) = common::post_as(
        "/v1/campbell",
        &example("jeffcott-nvd.campbell.json"),
        "image/png, image/svg+xml;q=0.5",
    )
    .await;
    assert_eq!((status, ctype.as_str()), (200, "image/png"));
    let (status, _, body) = common::post_as(
        "/v1/damping",
        &example("example1-nvd-fit.damping.json"),
        "image/png",
    )
    .await;
    assert_eq!(status, 406, "{}", String::from_utf8_lossy(&body));
}

/// Writes every plot above as PNG to /tmp/plots/ (`-- --ignored dump_png`).
#[tokio::test]
#[ignore]
async fn dump_png() {
    let dir = std::path::Path::new("/tmp/plots");
    std::fs::create_dir_all(dir).unwrap();
    for (uri, file) in PLOTS {
        let (status, _, body) = common::post_as(uri, &example(file), "image/png").await;
        assert_eq!(status, 200, "{file}: {}", String::from_utf8_lossy(&body));
        std::fs::write(
            dir.join(file.trim_end_matches(".json").to_string() + ".png"),
            body,
        )
        .unwrap();
    }
    eprintln!("wrote {}", dir.display());
}
