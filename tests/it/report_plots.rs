//! Geometry of the audit plots (plot_audit and the shaded plot variants) on the sample
//! answers of `report_sample.rs`: one line per mode, markers inside the plotting area, labels
//! apart, the Level I zero crossing at q0, no NaN in the SVG.

use crate::glyphs;
use crate::report_sample as sample;

use sample::*;
use whirl::model::api::*;
use whirl::render::plot::{campbell, campbell_with, stability, stability_with};
use whirl::render::plot_audit::*;

const MODE_COLOURS: [&str; 4] = ["#1F77B4", "#D62728", "#2CA02C", "#9467BD"];

#[test]
fn map_draws_one_line_per_mode() {
    let svg = critical_speed_map_with(&map(), Some([180.0, 300.0])).unwrap();
    let lines = elements(&svg, "polyline");
    for (m, colour) in MODE_COLOURS.iter().enumerate() {
        let n = lines
            .iter()
            .filter(|a| a["stroke"] == *colour && a["stroke-width"] == "2")
            .count();
        assert_eq!(n, 1, "mode {} has {n} lines", m + 1);
        assert!(svg.contains(&format!("mode {}", m + 1)));
    }
    finite_text(&svg);
}

#[test]
fn map_points_lie_in_the_plotting_area() {
    let c = map();
    let svg = critical_speed_map(&c).unwrap();
    let area = frames(&svg);
    assert_eq!(area.len(), 1);
    let circles = elements(&svg, "circle");
    // Two circles (fill and ring) per distinct point: 12 intersections, all distinct.
    assert_eq!(circles.len(), 2 * c.intersections.len());
    for a in &circles {
        assert!(
            inside(&area[0], (f(a, "cx"), f(a, "cy"))),
            "{a:?} outside {:?}",
            area[0]
        );
    }
    // Every curve spans the plotting area's width, inside it.
    for a in elements(&svg, "polyline")
        .iter()
        .filter(|a| a["stroke-width"] == "2")
    {
        let p = points(a);
        assert!(p.iter().all(|q| inside(&area[0], *q)));
        assert!((p[0].0 - area[0][0]).abs() < 2.0 && (p[p.len() - 1].0 - area[0][2]).abs() < 2.0);
    }
    // A label per point, in rad/s and rpm, the first mode's at 1e6 N/m among them.
    assert_eq!(svg.matches(" rad/s (").count(), c.intersections.len());
    let f1 = c.intersections[0].frequency;
    assert!(svg.contains(&format!("{f1:.1} rad/s ({:.0} rpm)", f1 * RPM)));
}

#[test]
fn map_labels_do_not_overlap() {
    let svg = critical_speed_map_with(&map(), Some([180.0, 300.0])).unwrap();
    let boxes: Vec<[f64; 4]> = svg
        .split("<text ")
        .skip(1)
        .filter(|t| t.contains(" rad/s (") || t.contains("mode "))
        .map(|t| {
            let a = &elements(&format!("<text {t}"), "text")[0];
            let label = t[t.find('>').unwrap() + 1..t.find("</text>").unwrap()].trim();
            let size = f(a, "font-size");
            let (x, y) = (f(a, "x"), f(a, "y"));
            let w = 0.55 * size * label.chars().count() as f64;
            [x, y, x + w, y + size]
        })
        .collect();
    assert_eq!(boxes.len(), 16);
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[i + 1..] {
            let overlap = a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
            assert!(!overlap, "labels overlap: {a:?} {b:?}");
        }
    }
}

/// A map crowded with crossings: 4 modes met by two bearings whose kxx and kyy differ, 16
/// callouts within a factor 2 of stiffness. Each callout's glyphs (laid out by resvg, as in
/// the PNG) stay inside the plotting area, clear of the tick labels around it, and overlap no
/// other text: no other callout, no mode label. `WHIRL_PLOT_DIR=dir` writes the PNG there.
#[test]
fn crowded_map_callouts_do_not_overlap() {
    let mut c = map();
    c.intersections.clear();
    for (support, node, coefficient, k) in [
        (0, 1, "kxx", 8e5),
        (0, 1, "kyy", 1e6),
        (1, 9, "kxx", 1.25e6),
        (1, 9, "kyy", 1.6e6),
    ] {
        for m in 0..4 {
            c.intersections.push(MapIntersection {
                support,
                node,
                coefficient: coefficient.into(),
                mode: m + 1,
                stiffness: k,
                frequency: mode_frequency(m, k),
            });
        }
    }
    for shade in [None, Some([180.0, 300.0])] {
        let svg = critical_speed_map_with(&c, shade).unwrap();
        if let Ok(dir) = std::env::var("WHIRL_PLOT_DIR") {
            let png = whirl::render::png::png(&svg).unwrap();
            let name = format!("crowded-map-{}.png", shade.is_some());
            std::fs::write(std::path::Path::new(&dir).join(name), png).unwrap();
        }
        let area = frames(&svg)[0];
        let texts = glyphs::glyph_boxes(&svg);
        let callouts: Vec<&(String, [f64; 4])> =
            texts.iter().filter(|t| t.0.contains(" rad/s (")).collect();
        assert_eq!(callouts.len(), 16);
        let f1 = mode_frequency(0, 8e5);
        assert!(
            callouts
                .iter()
                .any(|t| t.0 == format!("{f1:.1} rad/s ({:.0} rpm)", f1 * RPM))
        );
        for (s, a) in &callouts {
            assert!(
                area[0] <= a[0] && a[2] <= area[2] && area[1] <= a[1] && a[3] <= area[3],
                "{s} {a:?} leaves the plotting area {area:?}"
            );
            for (t, b) in texts
                .iter()
                .filter(|t| !std::ptr::eq(t.0.as_str(), s.as_str()))
            {
                let overlap = a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
                assert!(!overlap, "{s} {a:?} overlaps {t} {b:?}");
            }
        }
    }
}

#[test]
fn level1_zero_crossing_is_drawn_at_q0() {
    let l = level1_data();
    let svg = level1(&l).unwrap();
    let lines = elements(&svg, "polyline");
    let curve = points(
        lines
            .iter()
            .find(|a| a["stroke"] == "#1F77B4" && a["stroke-width"] == "2")
            .unwrap(),
    );
    let zero = points(
        lines
            .iter()
            .find(|a| a["stroke"] == "#1E1E1E" && a["stroke-width"] == "1")
            .unwrap(),
    );
    assert_eq!(zero[0].1, zero[1].1, "the zero line is horizontal");
    let y0 = zero[0].1;
    let k = curve
        .windows(2)
        .position(|p| (p[0].1 - y0) * (p[1].1 - y0) <= 0.0)
        .unwrap();
    let (a, b) = (curve[k], curve[k + 1]);
    let x = a.0 + (b.0 - a.0) * (y0 - a.1) / (b.1 - a.1);
    let mark = elements(&svg, "circle")
        .into_iter()
        .find(|c| c["fill"] == "#C81414")
        .unwrap();
    assert!(
        (f(&mark, "cx") - x).abs() <= 1.5,
        "q0 marker at {} vs crossing {x}",
        f(&mark, "cx")
    );
    assert!((f(&mark, "cy") - y0).abs() <= 1.0);
    // q_A: a vertical line at q_A / q0 of the way to q0's x from q = 0.
    let qa = lines
        .iter()
        .find(|a| a["stroke"] == "#FF7F0E")
        .map(points)
        .unwrap();
    assert_eq!(qa[0].0, qa[1].0);
    let expect = curve[0].0 + (x - curve[0].0) * l.qa.unwrap() / Q0;
    assert!((qa[0].0 - expect).abs() <= 1.5);
    // The API 617 limit, dashed: many short red segments at one height.
    let dashes: Vec<_> = lines
        .iter()
        .filter(|a| a["stroke"] == "#C81414" && a["opacity"] == "1")
        .map(points)
        .collect();
    assert!(dashes.len() > 10 && dashes.iter().all(|d| d[0].1 == dashes[0][0].1));
    assert!(svg.contains("q0 = 8.600 MN/m") && svg.contains("q_A = 2.200 MN/m"));
    assert!(svg.contains("q0 / q_A = 3.91"));
    finite_text(&svg);
}

#[test]
fn static_deflection_has_three_panels_and_the_reactions() {
    let s = statics();
    assert!((s.supports[0].reaction + s.supports[1].reaction - s.weight).abs() < 1e-9);
    let svg = static_deflection(&s).unwrap();
    let area = frames(&svg);
    assert_eq!(area.len(), 3);
    assert!(area[0][3] < area[1][1], "deflection above moment");
    assert!(area[1][3] < area[2][1], "moment above shear");
    assert!(svg.contains("deflection y [µm]"));
    for r in &s.supports {
        assert!(svg.contains(&format!(
            "R{} = {:.1} N (node {})",
            r.support, r.reaction, r.node
        )));
    }
    let lines = elements(&svg, "polyline");
    let defl = points(lines.iter().find(|a| a["stroke"] == "#1F77B4").unwrap());
    // Moment and shear: one line per element (the shear jumps at a node with a force).
    let along = |colour: &str| -> Vec<(f64, f64)> {
        let lines: Vec<_> = lines.iter().filter(|a| a["stroke"] == colour).collect();
        assert_eq!(lines.len(), s.nodes.len() - 1, "{colour}");
        lines.into_iter().flat_map(points).collect()
    };
    let (moment, shear) = (along("#2CA02C"), along("#9467BD"));
    // The deflection drawn along the exact curve (the diagram's points), not node to node.
    assert_eq!(defl.len(), s.diagram.len());
    assert_eq!(moment.len(), s.diagram.len());
    assert_eq!(shear.len(), s.diagram.len());
    assert!(defl.iter().all(|p| inside(&area[0], *p)));
    assert!(moment.iter().all(|p| inside(&area[1], *p)));
    assert!(shear.iter().all(|p| inside(&area[2], *p)));
    assert!(svg.contains(&format!("|M| max {:.1} N m", s.max_moment.abs())));
    // Lowest point at the disk (node 5, mid-span): largest y in pixels.
    let low = defl
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.1.total_cmp(&b.1.1))
        .unwrap()
        .0;
    assert!((s.diagram[low].position - s.nodes[5].position).abs() < 1e-6);
    assert!(svg.contains(&format!(
        "largest {:.1} µm at {:.3} m",
        s.max_deflection * 1e6,
        s.max_deflection_position
    )));
    finite_text(&svg);
}

#[test]
fn frequency_response_is_a_bode_plot() {
    let r = frequency_data();
    let svg = frequency_response(&r).unwrap();
    let area = frames(&svg);
    assert_eq!(area.len(), 2);
    let lines = elements(&svg, "polyline");
    let amp = points(
        lines
            .iter()
            .find(|a| a["stroke"] == "#1F77B4" && a["stroke-width"] == "2")
            .unwrap(),
    );
    assert_eq!(amp.len(), r.frequencies.len());
    assert!(amp.iter().all(|p| inside(&area[0], *p)));
    let phase: Vec<_> = lines
        .iter()
        .filter(|a| a["stroke"] == "#D62728")
        .flat_map(points)
        .collect();
    assert_eq!(phase.len(), r.frequencies.len());
    assert!(phase.iter().all(|p| inside(&area[1], *p)));
    // The resonance: the amplitude's highest point (smallest y) near 123 rad/s.
    let top = amp
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.1.total_cmp(&b.1.1))
        .unwrap()
        .0;
    assert!((r.frequencies[top] - 123.0).abs() < 5.0);
    finite_text(&svg);
}

#[test]
fn rotor_sketch_draws_segments_disks_and_supports() {
    let svg = rotor_sketch(&rotor()).unwrap();
    let rects = elements(&svg, "rect");
    let disk: Vec<f64> = rects
        .iter()
        .filter(|a| a["fill"] == "#1F77B4")
        .map(|a| f(a, "height"))
        .collect();
    // Segments are polygons (a conical one a trapezium): their boxes' heights and widths.
    let polygons = elements(&svg, "polygon");
    let boxes: Vec<(f64, f64)> = polygons
        .iter()
        .filter(|a| a["fill"] == "#B2BECC")
        .map(|a| {
            let pts: Vec<(f64, f64)> = a["points"]
                .split_whitespace()
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect();
            let span = |k: fn(&(f64, f64)) -> f64| {
                let v: Vec<f64> = pts.iter().map(k).collect();
                v.iter().cloned().fold(f64::MIN, f64::max)
                    - v.iter().cloned().fold(f64::MAX, f64::min)
            };
            (span(|p| p.0), span(|p| p.1))
        })
        .collect();
    let shaft: Vec<f64> = boxes.iter().map(|b| b.1).collect();
    assert_eq!(shaft.len(), 3);
    assert_eq!(disk.len(), 1);
    assert!(shaft[1] > shaft[0] && disk[0] > 2.0 * shaft[1]);
    // Segment widths to scale: 0.1 : 1.3 : 0.1.
    let widths: Vec<f64> = boxes.iter().map(|b| b.0).collect();
    assert!((widths[1] / widths[0] - 13.0).abs() < 0.3);
    assert_eq!(
        polygons.len(),
        3 + 2,
        "the segments and a triangle per support"
    );
    for n in 0..=10 {
        assert!(
            svg.contains(&format!(">\n{n}\n</text>")),
            "node {n} numbered"
        );
    }
    assert!(svg.contains("32.6 kg") && svg.contains("kxx 1.500e6, kyy 2.000e6 N/m"));
    let jeffcott = RotorInput::Jeffcott(JeffcottInput {
        mass: 1.0,
        stiffness: 1.0,
        loss_factor_rotating: 0.0,
        loss_factor_nonrotating: 0.0,
        damping_rotating: 0.0,
        damping_nonrotating: 0.0,
    });
    let svg = rotor_sketch(&jeffcott).unwrap();
    assert!(svg.contains("beam rotors only") && svg.starts_with("<svg"));
}

#[test]
fn unbalance_peaks_are_marked_and_labelled() {
    let u = unbalance_data();
    let svg = unbalance_with(&u, Some([180.0, 300.0])).unwrap();
    let area = frames(&svg)[0];
    let marks: Vec<_> = elements(&svg, "circle")
        .into_iter()
        .filter(|c| c["fill"] != "none")
        .collect();
    assert_eq!(marks.len(), 3);
    assert!(
        marks
            .iter()
            .all(|c| inside(&area, (f(c, "cx"), f(c, "cy"))))
    );
    let p = &u.nodes[0].peaks[0];
    let s = format!(
        "node 5: N_c = {:.0} rpm, AF = {:.1}, SM = {:.1}% (req {:.1}%)",
        p.speed * RPM,
        p.amplification_factor.unwrap(),
        p.separation_margin.unwrap(),
        p.required_margin.unwrap()
    );
    assert!(svg.contains(&s), "{s}");
    let shade: Vec<_> = elements(&svg, "rect")
        .into_iter()
        .filter(|a| a["opacity"] == "0.22")
        .collect();
    assert_eq!(shade.len(), 1);
    finite_text(&svg);
}

#[test]
fn shading_keeps_the_plain_plots() {
    let c = campbell_data();
    assert_eq!(campbell(&c).unwrap(), campbell_with(&c, None).unwrap());
    let shaded = campbell_with(&c, Some([180.0, 300.0])).unwrap();
    assert_eq!(
        elements(&shaded, "rect")
            .iter()
            .filter(|a| a.get("opacity").is_some_and(|o| o == "0.22"))
            .count(),
        4,
        "three panels (frequency, decay rate, log decrement), legend"
    );
    let s = StabilityResponse {
        nondimensional: false,
        output_unit: Default::default(),
        threshold: None,
        mode: None,
        whirl: None,
        frequency: None,
        range: [0.0, 375.0],
        speeds: speeds(),
        max_decay_rate: speeds().iter().map(|w| -2.0 + 0.004 * w).collect(),
        max_frequency: None,
        reduction: None,
        threshold_closed: None,
        warnings: vec![],
    };
    assert_eq!(stability(&s).unwrap(), stability_with(&s, None).unwrap());
    assert!(
        stability_with(&s, Some([180.0, 300.0]))
            .unwrap()
            .contains("operating range")
    );
}

#[test]
fn plots_survive_missing_and_non_finite_values() {
    let mut m = map();
    m.frequencies[1][3] = f64::NAN;
    m.intersections[0].frequency = f64::INFINITY;
    finite_text(&critical_speed_map_with(&m, Some([f64::NAN, 300.0])).unwrap());
    let mut l = level1_data();
    l.log_decrement[4] = None;
    l.q0 = Some(5e9);
    l.qa = None;
    let svg = level1(&l).unwrap();
    finite_text(&svg);
    assert!(svg.contains("(beyond the plot)"));
    let mut r = frequency_data();
    r.amplitude[3] = 0.0;
    r.phase[7] = f64::NAN;
    finite_text(&frequency_response(&r).unwrap());
    let mut u = unbalance_data();
    u.nodes[0].peaks[0].amplification_factor = None;
    u.nodes[0].peaks[0].separation_margin = Some(f64::NAN);
    finite_text(&unbalance_with(&u, None).unwrap());
    let empty = CriticalSpeedMapResponse {
        output_unit: Default::default(),
        stiffness: vec![],
        frequencies: vec![],
        intersections: vec![],
        warnings: vec![],
    };
    finite_text(&critical_speed_map(&empty).unwrap());
}

#[test]
fn the_bode_plot_puts_the_phase_lag_under_the_amplitude() {
    // The sample's single mode: phase -atan2(2 zeta wn w, wn^2 - w^2), from 0 to nearly -180
    // degrees: the panel spans [-180, 0], 0 at its top.
    let u = unbalance_data();
    let svg = unbalance_bode(&u, Some([180.0, 300.0])).unwrap();
    // The plotting areas (the key has a frame too, a small one).
    let area: Vec<[f64; 4]> = frames(&svg)
        .into_iter()
        .filter(|r| r[2] - r[0] > 400.0)
        .collect();
    assert_eq!(area.len(), 2, "{area:?}");
    assert!(area[0][3] < area[1][1], "amplitude above phase");
    let lines = elements(&svg, "polyline");
    for (k, n) in u.nodes.iter().enumerate() {
        let colour = ["#1F77B4", "#D62728", "#2CA02C"][k];
        let phase: Vec<(f64, f64)> = lines
            .iter()
            .filter(|a| a["stroke"] == colour)
            .map(points)
            .find(|p| p.iter().all(|&q| inside(&area[1], q)))
            .unwrap_or_else(|| panic!("node {}: no phase line", n.node));
        assert_eq!(phase.len(), u.speeds.len());
        // A lag that only grows: y in pixels never decreases.
        assert!(phase.windows(2).all(|w| w[1].1 >= w[0].1 - 0.5));
        let (top, bottom) = (area[1][1], area[1][3]);
        assert!((phase[0].1 - top).abs() <= 1.5, "0 deg at the top");
        let last = -n.phase.last().unwrap().to_degrees() / 180.0;
        assert!((phase.last().unwrap().1 - (top + last * (bottom - top))).abs() <= 1.5);
    }
    finite_text(&svg);
}
