//! The analysis plots (`plot.rs`, `plot/`) on the bundled examples: the 1x line along
//! ω = Ω in plot coordinates, readable ticks at every scale, a label per mode, engineering
//! units, the clipped decay-rate axis, the Bode and orbit panels, mode shapes; and `dump`
//! (ignored), which writes every plot to /tmp/plots/: `cargo test --release --test plots --
//! --ignored dump`.

use crate::common;
use crate::glyphs;
use crate::report_sample as sample;

use std::collections::BTreeMap;

use sample::elements;

use whirl::model::api::*;
use whirl::render::plot;

fn example(name: &str) -> serde_json::Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

async fn answer<T: serde::de::DeserializeOwned>(uri: &str, file: &str) -> T {
    let (status, v) = common::post_json(uri, &example(file)).await;
    assert_eq!(status, 200, "{uri}: {v}");
    serde_json::from_value(v).unwrap()
}

/// Text contents of every `<text>` element.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text ")
        .skip(1)
        .map(|p| {
            let body = &p[p.find('>').unwrap() + 1..p.find("</text>").unwrap()];
            body.replace("&amp;", "&")
                .replace("&lt;", "<")
                .replace("&gt;", ">")
        })
        .collect()
}

/// A plotting area: its pixel box and its axes, read from the frame's `data-*` attributes.
#[derive(Debug)]
struct Area {
    rect: [f64; 4],
    x: (f64, f64),
    y: (f64, f64),
    log_y: bool,
}

impl Area {
    /// The data point at a pixel.
    fn data(&self, (px, py): (f64, f64)) -> (f64, f64) {
        let [x0, y0, x1, y1] = self.rect;
        let tx = (px - x0) / (x1 - x0);
        let ty = (y1 - py) / (y1 - y0);
        let y = if self.log_y {
            (self.y.0.ln() + ty * (self.y.1.ln() - self.y.0.ln())).exp()
        } else {
            self.y.0 + ty * (self.y.1 - self.y.0)
        };
        (self.x.0 + tx * (self.x.1 - self.x.0), y)
    }
}

fn pair(s: &str) -> (f64, f64) {
    let (a, b) = s.split_once(' ').unwrap();
    (a.parse().unwrap(), b.parse().unwrap())
}

/// The plotting areas, top to bottom.
fn areas(svg: &str) -> Vec<Area> {
    let mut v: Vec<Area> = elements(svg, "rect")
        .iter()
        .filter(|a| a.contains_key("data-x"))
        .map(|a| {
            let f = |k: &str| a[k].parse::<f64>().unwrap();
            let (x, y) = (f("x"), f("y"));
            Area {
                rect: [x, y, x + f("width"), y + f("height")],
                x: pair(&a["data-x"]),
                y: pair(&a["data-y"]),
                log_y: a["data-scale"].ends_with("log"),
            }
        })
        .collect();
    v.sort_by(|a, b| a.rect[1].total_cmp(&b.rect[1]));
    v
}

/// The points of a path's `d` (M/L commands).
fn path_points(d: &str) -> Vec<(f64, f64)> {
    d.split_whitespace()
        .map(|p| {
            let (x, y) = p.trim_start_matches(['M', 'L']).split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

fn paths_of(svg: &str, class: &str) -> Vec<BTreeMap<String, String>> {
    elements(svg, "path")
        .into_iter()
        .filter(|a| {
            a.get("class")
                .is_some_and(|c| c.split(' ').any(|c| c == class))
        })
        .collect()
}

/// The 1x line of a Campbell diagram mapped back to data: every point has ω = Ω, and it
/// reaches the edge of the plotting area.
fn assert_one_x(svg: &str) {
    let top = &areas(svg)[0];
    let line = &paths_of(svg, "sync-1x")[0];
    let pts = path_points(&line["d"]);
    assert_eq!(pts.len(), 2);
    for p in &pts {
        let (x, y) = top.data(*p);
        let scale = top.x.1.max(top.y.1);
        assert!(
            (x - y).abs() < 1e-3 * scale,
            "1x point ({x}, {y}) off ω = Ω"
        );
        assert!(x >= top.x.0 - 1e-9 && x <= top.x.1 + 1e-9);
        assert!(y >= top.y.0 - 1e-9 && y <= top.y.1 + 1e-9);
    }
    let end = top.data(pts[1]);
    let at_edge =
        (end.0 - top.x.1).abs() < 1e-3 * top.x.1 || (end.1 - top.y.1).abs() < 1e-3 * top.y.1;
    assert!(at_edge, "1x stops at {end:?}, inside the area");
}

#[tokio::test]
async fn one_x_line_runs_along_omega_equals_speed() {
    // Example 1: speeds past the frequencies; the 1x meets each forward mode at its dot.
    let c: CampbellResponse = answer("/v1/campbell", "example1-nvd.campbell.json").await;
    let svg = plot::campbell(&c).unwrap();
    assert_one_x(&svg);
    let top = &areas(&svg)[0];
    for w in &c.critical_speeds {
        let dot = elements(&svg, "circle")
            .into_iter()
            .map(|a| top.data((a["cx"].parse().unwrap(), a["cy"].parse().unwrap())))
            .find(|p| (p.0 - w).abs() < 1e-4 * top.x.1)
            .unwrap_or_else(|| panic!("no dot at the critical speed {w}"));
        assert!(
            (dot.1 - w).abs() < 1e-4 * top.y.1,
            "dot at {dot:?} off the 1x line"
        );
        // Its own label, or one shared with a crossing whose mark overlaps its own.
        let label = format!("{w:.1} rad/s ({:.0} rpm)", w * plot::RPM);
        assert!(texts(&svg).iter().any(|t| t.starts_with(&label)), "{label}");
    }
    // Nondimensional Jeffcott (the paper's Fig. 1): 1x crosses ω* = 1 at Ω* = 1.
    let j: CampbellResponse = answer("/v1/campbell", "jeffcott-nvd.campbell.json").await;
    let svg = plot::campbell(&j).unwrap();
    assert_one_x(&svg);
    let top = &areas(&svg)[0];
    let pts = path_points(&paths_of(&svg, "sync-1x")[0]["d"]);
    let (a, b) = (top.data(pts[0]), top.data(pts[1]));
    let t = (1.0 - a.1) / (b.1 - a.1);
    assert!((a.0 + t * (b.0 - a.0) - 1.0).abs() < 1e-3);
}

/// The tick labels of an area: those under its bottom edge and left of its left edge.
fn tick_labels(svg: &str, area: &Area) -> (Vec<String>, Vec<String>) {
    let mut xs = vec![];
    let mut ys = vec![];
    for part in svg.split("<text ").skip(1) {
        let head = &part[..part.find('>').unwrap()];
        let body = &part[part.find('>').unwrap() + 1..part.find("</text>").unwrap()];
        let get = |k: &str| -> f64 {
            let i = head
                .find(&format!(" {k}=\""))
                .or_else(|| head.starts_with(&format!("{k}=\"")).then_some(0))
                .unwrap();
            let rest = &head[i..];
            let rest = &rest[rest.find('"').unwrap() + 1..];
            rest[..rest.find('"').unwrap()].parse().unwrap()
        };
        if head.contains("rotate") {
            continue;
        }
        let (x, y) = (get("x"), get("y"));
        let r = area.rect;
        if (y - (r[3] + 19.0)).abs() < 0.5 && x >= r[0] - 1.0 && x <= r[2] + 1.0 {
            xs.push(body.to_string());
        }
        if (x - (r[0] - 8.0)).abs() < 0.5 && y >= r[1] - 1.0 && y <= r[3] + 6.0 {
            ys.push(body.to_string());
        }
    }
    (xs, ys)
}

#[tokio::test]
async fn ticks_are_distinct_and_as_precise_as_their_steps() {
    let j: CampbellResponse = answer("/v1/campbell", "jeffcott-nvd.campbell.json").await;
    let svg = plot::campbell(&j).unwrap();
    for a in &areas(&svg) {
        let (xs, ys) = tick_labels(&svg, a);
        for labels in [&xs, &ys] {
            assert!(labels.len() >= 4, "{labels:?}");
            let mut d = labels.clone();
            d.sort();
            d.dedup();
            assert_eq!(d.len(), labels.len(), "repeated tick labels {labels:?}");
            assert!(
                labels.iter().any(|l| l.contains('.')),
                "all integers: {labels:?}"
            );
            for l in labels.iter() {
                l.parse::<f64>().unwrap_or_else(|_| panic!("tick {l}"));
            }
        }
    }
    // Dimensional: whole numbers where the steps are.
    let c: CampbellResponse = answer("/v1/campbell", "example1-nvd.campbell.json").await;
    let svg = plot::campbell(&c).unwrap();
    let (xs, _) = tick_labels(&svg, &areas(&svg)[0]);
    assert!(xs.iter().all(|l| !l.contains('.')), "{xs:?}");
}

#[tokio::test]
async fn every_mode_has_its_colour_label_and_dashes() {
    let c: CampbellResponse = answer("/v1/campbell", "example1-nvd.campbell.json").await;
    let svg = plot::campbell(&c).unwrap();
    let labels = texts(&svg);
    let top = &areas(&svg)[0];
    let mut colours = BTreeMap::new();
    for b in &c.branches {
        let w = if b.whirl == Whirl::Forward { "F" } else { "B" };
        let tag = format!("{}{w}", b.mode);
        assert!(labels.contains(&tag), "no label {tag}");
        let lines = paths_of(&svg, &format!("mode-{tag}"));
        assert!(
            !lines.is_empty() && lines.len() <= 4,
            "{tag}: {} pieces",
            lines.len()
        );
        for l in &lines {
            assert_eq!(
                l.contains_key("stroke-dasharray"),
                b.whirl == Whirl::Backward,
                "{tag}"
            );
            // Sub-pixel coordinates inside the area.
            for p in path_points(&l["d"]) {
                let (x, _) = top.data(p);
                assert!(x >= top.x.0 - 1e-6 && x <= top.x.1 + 1e-6);
            }
        }
        let colour = lines[0]["stroke"].clone();
        if let Some(other) = colours.insert(b.mode, colour.clone()) {
            assert_eq!(other, colour, "mode {} in two colours", b.mode);
        }
    }
    let distinct: std::collections::BTreeSet<_> = colours.values().collect();
    assert_eq!(distinct.len(), colours.len(), "one colour per mode");
    assert!(svg.contains("stroke-width=\"2\"") && !svg.contains("NaN"));
}

#[tokio::test]
async fn units_come_from_the_data() {
    let u: UnbalanceResponseResponse = answer(
        "/v1/unbalance-response",
        "example1-nvd.unbalance-response.json",
    )
    .await;
    let svg = plot::unbalance(&u).unwrap();
    let labels = texts(&svg);
    let max = u
        .nodes
        .iter()
        .flat_map(|n| &n.amplitude)
        .fold(0.0f64, |m, a| m.max(*a));
    let unit = if max < 1e-3 { "[µm]" } else { "[mm]" };
    assert!(
        labels
            .iter()
            .any(|l| l.starts_with("semi-major axis of the orbit, 0-pk ") && l.contains(unit)),
        "{labels:?}"
    );
    assert!(!labels.iter().any(|l| l.contains("e-")), "exponent ticks");
    assert!(!svg.contains("orbit radius"));
    // Bode: amplitude over phase, the phase in degrees; the peaks named by speed.
    let a = areas(&svg);
    assert_eq!(a.len(), 2);
    assert!(
        labels
            .iter()
            .any(|l| l.starts_with("phase") && l.contains("[°]"))
    );
    let peaks = u.nodes.iter().flat_map(|n| &n.peaks).count();
    assert!(peaks == 0 || labels.iter().any(|l| l.starts_with("peak ")));

    let t: TimeResponseResponse =
        answer("/v1/time-response", "example1-shock-nvd.time-response.json").await;
    let svg = plot::time(&t).unwrap();
    let labels = texts(&svg);
    assert!(labels.iter().any(|l| l.starts_with("whirl amplitude") && (l.contains("[µm]") || l.contains("[mm]"))));
    // The orbit panel: square, equal scales, a path per node.
    let a = areas(&svg);
    assert_eq!(a.len(), 2);
    let o = &a[1];
    assert_eq!(o.x, o.y);
    assert!(((o.rect[2] - o.rect[0]) - (o.rect[3] - o.rect[1])).abs() < 1e-6);
    assert_eq!(paths_of(&svg, "orbit").len(), t.nodes.len());
}

#[test]
fn decay_axis_clips_a_runaway_peak() {
    let (lo, hi, clipped) = plot::decay_range([-2.0, -1.0, 0.5, 400.0]);
    assert!(lo < -2.0 && hi < 4.0 && hi > 3.0, "{lo} {hi}");
    assert_eq!(clipped, Some(400.0));
    let (_, hi, clipped) = plot::decay_range([-2.0, -1.0, 0.5, 1.0]);
    assert!(hi < 1.5 && clipped.is_none());
}

#[tokio::test]
async fn modal_answers_draw_mode_shapes() {
    let m: ModalResponse = answer("/v1/modal", "example1-nvd.modal.json").await;
    let svg = plot::modal(&m).unwrap().expect("a beam rotor has shapes");
    let labels = texts(&svg);
    let shapes = paths_of(&svg, "shape");
    assert!(shapes.len() >= 2 && shapes.len() <= 6);
    assert!(
        labels
            .iter()
            .filter(|l| l.contains(" rad/s (") && (l.contains("forward") || l.contains("backward")))
            .count()
            == shapes.len()
    );
    let (status, ctype, body) = common::post_as(
        "/v1/modal",
        &example("example1-nvd.modal.json"),
        "image/svg+xml",
    )
    .await;
    assert_eq!((status, ctype.as_str()), (200, "image/svg+xml"));
    assert!(String::from_utf8(body).unwrap().starts_with("<svg"));
    // A Jeffcott rotor's single node has no shape along a shaft: no plot.
    let j: ModalResponse = answer("/v1/modal", "jeffcott-nvd.modal.json").await;
    assert!(plot::modal(&j).unwrap().is_none());
}

/// The paper's nondimensional Jeffcott rotor (mass = stiffness = 1): its answers say so, and
/// its plots give speeds, frequencies, rates and times over sqrt(k/m) with no rad/s, rpm, 1/s
/// or s (they said "1.00 rad/s (9.55 rpm)"); a 10 kg rotor on 1e6 N/m keeps its units.
#[tokio::test]
async fn nondimensional_jeffcott_plots_name_no_unit() {
    let rotor = serde_json::json!({"type": "jeffcott", "mass": 1, "stiffness": 1,
        "loss_factor_rotating": 0.01, "loss_factor_nonrotating": 0.02});
    let unbalance = serde_json::json!({"rotor": rotor, "damping": {"model": "equivalent"},
        "speeds": {"start": 0, "stop": 3, "count": 61},
        "unbalances": [{"node": 0, "amount": 0.01, "phase": 0}]});
    let time = serde_json::json!({"rotor": rotor, "damping": {"model": "equivalent"},
        "speed": 0.5, "unbalances": [{"node": 0, "amount": 0.01, "phase": 0}],
        "duration": 20, "output_interval": 0.1});
    let cases = [
        (
            "/v1/campbell",
            example("jeffcott-equivalent.campbell.json"),
            "Ω* = 1.00",
        ),
        (
            "/v1/campbell",
            example("jeffcott-hysteretic.campbell.json"),
            "Ω* = 1.00",
        ),
        (
            "/v1/stability",
            example("jeffcott-equivalent.stability.json"),
            "threshold Ω* = 3.00: mode 1F at ω* = 1.00",
        ),
        ("/v1/unbalance-response", unbalance, "peak Ω* = 1.0"),
        ("/v1/time-response", time, "time t* = t·√(k/m)"),
    ];
    for (uri, body, label) in cases {
        let (status, v) = common::post_json(uri, &body).await;
        assert_eq!(status, 200, "{uri}: {v}");
        assert_eq!(v["nondimensional"], true, "{uri}");
        let (status, _, svg) = common::post_as(uri, &body, "image/svg+xml").await;
        assert_eq!(status, 200);
        let labels = texts(&String::from_utf8(svg).unwrap());
        for l in &labels {
            assert!(
                !["rad/s", "rpm", "1/s", "[s]"].iter().any(|u| l.contains(u)),
                "{uri}: {l}"
            );
        }
        assert!(
            labels.iter().any(|l| l.starts_with(label)),
            "{uri}: {labels:?}"
        );
        if uri != "/v1/time-response" {
            assert!(
                labels.iter().any(|l| l == "spin speed Ω* = Ω/√(k/m)"),
                "{labels:?}"
            );
        }
        if uri != "/v1/unbalance-response" && uri != "/v1/time-response" {
            assert!(
                labels.iter().any(|l| l.contains("σ* = σ/√(k/m)")),
                "{labels:?}"
            );
        }
    }
    let mut physical = example("jeffcott-equivalent.campbell.json");
    physical["rotor"]["mass"] = serde_json::json!(10.0);
    physical["rotor"]["stiffness"] = serde_json::json!(1e6);
    physical["speeds"] = serde_json::json!({"start": 0, "stop": 600, "count": 61});
    let (_, v) = common::post_json("/v1/campbell", &physical).await;
    assert!(v.get("nondimensional").is_none(), "{v}");
    let (_, _, svg) = common::post_as("/v1/campbell", &physical, "image/svg+xml").await;
    let labels = texts(&String::from_utf8(svg).unwrap());
    // sqrt(1e5) = 316.23 rad/s = 3020 rpm.
    assert!(
        labels
            .iter()
            .any(|l| l.starts_with("316.2 rad/s (3020 rpm)")),
        "{labels:?}"
    );
    assert!(labels.iter().any(|l| l == "spin speed [rpm]"));
}

/// The critical speed map of ROSS's compressor (`ross-compressor.campbell.json`'s rotor, 1e6
/// to 1e10 N/m): 64 crossings of its bearings' kxx and kyy with the 4 modes, 56 distinct. Every
/// callout is inside the plotting area and its glyphs (resvg's layout, as in the PNG)
/// overlap no other text. `WHIRL_PLOT_DIR=dir` writes the PNG there.
#[tokio::test]
async fn a_map_of_64_crossings_keeps_its_callouts_apart() {
    let c = example("ross-compressor.campbell.json");
    let body = serde_json::json!({"rotor": c["rotor"],
        "stiffness": {"start": 1e6, "stop": 1e10, "count": 31}});
    let (status, v) = common::post_json("/v1/critical-speed-map", &body).await;
    assert_eq!(status, 200, "{v}");
    let n = v["intersections"].as_array().unwrap().len();
    assert!(n >= 32, "{n} crossings");
    let (status, _, svg) = common::post_as("/v1/critical-speed-map", &body, "image/svg+xml").await;
    assert_eq!(status, 200);
    let svg = String::from_utf8(svg).unwrap();
    if let Ok(dir) = std::env::var("WHIRL_PLOT_DIR") {
        let png = whirl::render::png::png(&svg).unwrap();
        std::fs::write(
            std::path::Path::new(&dir).join("ross-compressor-map.png"),
            png,
        )
        .unwrap();
    }
    let area = sample::frames(&svg)[0];
    let texts = glyphs::glyph_boxes(&svg);
    let callouts: Vec<usize> = (0..texts.len())
        .filter(|&i| texts[i].0.contains(" rad/s ("))
        .collect();
    // One callout per distinct point (two circles each: fill and ring).
    let points = sample::elements(&svg, "circle").len() / 2;
    assert!(points >= 32 && points <= n, "{points} of {n}");
    assert_eq!(callouts.len(), points);
    for &i in &callouts {
        let (s, a) = &texts[i];
        assert!(
            area[0] <= a[0] && a[2] <= area[2] && area[1] <= a[1] && a[3] <= area[3],
            "{s} {a:?} leaves the plotting area {area:?}"
        );
        for (j, (t, b)) in texts.iter().enumerate().filter(|(j, _)| *j != i) {
            let overlap = a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
            assert!(!overlap, "{s} {a:?} overlaps {t} {b:?} ({j})");
        }
    }
}

/// A threshold near the left of the sweep (275 rad/s of 3200, tabulated bearings read as ROSS
/// reads them): its label on the decay-rate plot turns to the right of the line rather than
/// run off the left edge; no text of the plot leaves the image.
#[tokio::test]
async fn a_threshold_near_the_left_edge_keeps_its_label_inside() {
    let mut r = example("fluid-film.unbalance-response.json")["rotor"].clone();
    r["materials"]["steel"]["loss_factor"] = serde_json::json!(0.002);
    r["supports"][0]["interpolation"] = serde_json::json!("ross");
    r["seals"] = serde_json::json!([{"node": 3, "speeds": [300.0, 1200.0, 2400.0],
        "kxx": [2e5, 5e5, 6e5], "kxy": [1e5, 3e5, 8e5], "kyx": [-1e5, -3e5, -8e5],
        "kyy": [2e5, 5e5, 6e5], "cxx": [300.0, 250.0, 320.0], "cyy": [300.0, 250.0, 320.0],
        "interpolation": "ross"}]);
    let body = serde_json::json!({"rotor": r, "damping": {"model": "viscous"},
        "speeds": {"start": 0, "stop": 3200, "count": 40}, "max_frequency": 1500.0});
    let (status, v) = common::post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{v}");
    let t = v["threshold"].as_f64().expect("a threshold");
    assert!(t < 0.15 * 3200.0, "{t}");
    let (status, _, svg) = common::post_as("/v1/campbell", &body, "image/svg+xml").await;
    assert_eq!(status, 200);
    let svg = String::from_utf8(svg).unwrap();
    let size = |name: &str| -> f64 {
        let at = svg.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        svg[at..at + svg[at..].find('"').unwrap()].parse().unwrap()
    };
    let (w, h) = (size("width"), size("height"));
    let texts = glyphs::glyph_boxes(&svg);
    assert!(texts.iter().any(|(s, _)| s.starts_with("threshold ")));
    for (s, b) in &texts {
        assert!(
            b[0] >= 0.0 && b[1] >= 0.0 && b[2] <= w && b[3] <= h,
            "{s} {b:?} leaves the {w} x {h} image"
        );
    }
}

/// ROSS's compressor, 24 branches: the two members of its first pair (real poles at rest, the
/// lowest |s|) whirl forward on the anisotropic bearings; the diagram tells them apart (`1Fa`,
/// `1Fb`), and no two branch ends share a label. (The real poles at rest were numbered by their
/// frequencies' round-off, which made this pair the second until requests were read correctly
/// rounded; they are numbered by |s| now.)
#[tokio::test]
async fn two_branches_of_one_mode_whirling_alike_are_told_apart() {
    let mut body = example("ross-compressor.campbell.json");
    body.as_object_mut().unwrap().remove("max_frequency");
    body["modes"] = serde_json::json!(24);
    let (status, v) = common::post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{v}");
    let c: CampbellResponse = serde_json::from_value(v).unwrap();
    let twins = c
        .branches
        .iter()
        .filter(|b| b.mode == 1 && b.whirl == Whirl::Forward)
        .count();
    assert_eq!(twins, 2, "mode 1 is no longer a forward-forward pair");
    let svg = plot::campbell(&c).unwrap();
    let labels = texts(&svg);
    assert!(labels.contains(&"1Fa".to_string()) && labels.contains(&"1Fb".to_string()));
    assert!(!labels.contains(&"1F".to_string()), "{labels:?}");
    let tags: Vec<&String> = labels
        .iter()
        .filter(|t| {
            t.len() <= 4 && t.starts_with(|c: char| c.is_ascii_digit()) && t.contains(['F', 'B'])
        })
        .collect();
    // Each panel (frequency, decay rate, log decrement) labels every branch once.
    let first = &tags[..c.branches.len()];
    let distinct: std::collections::BTreeSet<_> = first.iter().collect();
    assert_eq!(distinct.len(), first.len(), "{tags:?}");
}

/// Writes every plot of the bundled examples to /tmp/plots/ (`-- --ignored dump`).
#[tokio::test]
#[ignore]
async fn dump() {
    let dir = std::path::Path::new("/tmp/plots");
    std::fs::create_dir_all(dir).unwrap();
    for (uri, file) in [
        ("/v1/campbell", "example1-nvd.campbell.json"),
        ("/v1/campbell", "example1-hysteretic.campbell.json"),
        ("/v1/campbell", "jeffcott-nvd.campbell.json"),
        ("/v1/campbell", "jeffcott-hysteretic.campbell.json"),
        ("/v1/campbell", "compressor-nvd.campbell.json"),
        ("/v1/campbell", "ross-compressor.campbell.json"),
        ("/v1/stability", "jeffcott-equivalent.stability.json"),
        ("/v1/stability", "compressor-equivalent.stability.json"),
        ("/v1/time-response", "example1-runup-nvd.time-response.json"),
        ("/v1/time-response", "example1-shock-nvd.time-response.json"),
        (
            "/v1/unbalance-response",
            "example1-nvd.unbalance-response.json",
        ),
        (
            "/v1/unbalance-response",
            "fluid-film.unbalance-response.json",
        ),
        ("/v1/modal", "example1-nvd.modal.json"),
        ("/v1/modal", "compressor-nvd.modal.json"),
        ("/v1/modal", "ross-compressor.modal.json"),
    ] {
        let (status, _, body) = common::post_as(uri, &example(file), "image/svg+xml").await;
        assert_eq!(status, 200, "{file}: {}", String::from_utf8_lossy(&body));
        let name = file.trim_end_matches(".json").to_string() + ".svg";
        std::fs::write(dir.join(name), body).unwrap();
    }
    eprintln!("wrote {}", dir.display());
}
