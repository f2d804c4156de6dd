//! Schematic of a beam rotor: shaft segments to scale in length (diameters exaggerated), node
//! numbers, disks as taller blocks, supports as springs on triangles under their nodes.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::{Area, Err, FRAME, INK, Labels, NOTE, PALETTE, text, text_box};
use crate::model::api::{BeamInput, Coefficient, RotorInput, SupportInput};

const W: i32 = 960;
const H: i32 = 350;
const LEFT: i32 = 60;
const RIGHT: i32 = 60;
/// Centre line, node-number row, scale bar.
const AXIS: i32 = 165;
const NODES_Y: i32 = 48;
const SCALE_Y: i32 = 312;
/// Tallest shaft and tallest disk, px.
const SHAFT_PX: f64 = 56.0;
const DISK_PX: f64 = 150.0;
const GREY: RGBColor = RGBColor(110, 110, 110);
const STEEL: RGBColor = RGBColor(178, 190, 204);
const STEEL_EDGE: RGBColor = RGBColor(90, 100, 115);
/// Couplings, apart from the shafts they join.
const COUPLING: RGBColor = RGBColor(226, 168, 92);
const COUPLING_EDGE: RGBColor = RGBColor(150, 95, 30);

/// Axial positions of the nodes, m (each segment split into its equal elements).
pub(crate) fn node_positions(b: &BeamInput) -> Vec<f64> {
    let mut at = vec![0.0];
    let mut x = 0.0;
    for s in &b.shaft {
        let n = s.elements.unwrap_or(1).max(1);
        for k in 1..=n {
            at.push(x + s.length * k as f64 / n as f64);
        }
        x += s.length;
    }
    at
}

/// A coefficient's value or range; a list is over the speeds `Ω` or, for a table over whirl
/// frequency alone (`over_frequency`), over the frequencies `ω`.
fn coefficient(c: &Option<Coefficient>, over_frequency: bool) -> Option<String> {
    match c.as_ref()? {
        Coefficient::Number(v) if v.is_finite() => Some(format!("{v:.3e}")),
        Coefficient::Number(_) => None,
        Coefficient::Table(t) => {
            let (lo, hi) = super::range(t.iter().copied(), 0.0);
            let axis = if over_frequency { "ω" } else { "Ω" };
            Some(format!("{lo:.2e}..{hi:.2e} ({axis})"))
        }
        Coefficient::Grid(g) => {
            let (lo, hi) = super::range(g.iter().flatten().copied(), 0.0);
            Some(format!("{lo:.2e}..{hi:.2e} (Ω, ω)"))
        }
    }
}

/// `k = ... N/m` of a support (its `kxx`/`kyy` when general).
pub(crate) fn support_stiffness(s: &SupportInput) -> String {
    if let Some(k) = s.stiffness.filter(|k| k.is_finite()) {
        return format!("k {k:.3e} N/m");
    }
    let over_frequency = s.frequencies.is_some() && s.speeds.is_none();
    let kxx = coefficient(&s.kxx, over_frequency);
    let kyy = coefficient(&s.kyy, over_frequency);
    match (kxx, kyy) {
        (Some(a), Some(b)) if a != b => format!("kxx {a}, kyy {b} N/m"),
        (Some(a), _) => format!("k {a} N/m"),
        (None, Some(b)) => format!("kyy {b} N/m"),
        (None, None) => "k 0".into(),
    }
}

/// Diameter and thickness of a solid disk of mass `m` with these inertias, m (none unknown).
fn disk_size(m: f64, ip: f64, id: f64) -> (Option<f64>, Option<f64>) {
    if !(m > 0.0 && ip > 0.0 && ip.is_finite()) {
        return (None, None);
    }
    let r2 = 2.0 * ip / m;
    let h2 = 12.0 * id / m - 3.0 * r2;
    (
        Some(2.0 * r2.sqrt()),
        (h2 > 0.0 && h2.is_finite()).then(|| h2.sqrt()),
    )
}

/// A coupling drawn from `a` to `e` px, `h` px high: two flanges and a spring between them.
fn coupling(root: &Area, a: i32, e: i32, h: i32) -> Result<(), Err> {
    let flange = ((e - a) / 4).clamp(2, 10);
    for (l, r) in [(a, a + flange), (e - flange, e)] {
        root.draw(&Rectangle::new(
            [(l, AXIS - h), (r, AXIS + h)],
            COUPLING.filled(),
        ))?;
        root.draw(&Rectangle::new([(l, AXIS - h), (r, AXIS + h)], STEEL_EDGE))?;
    }
    let (l, r) = (a + flange, e - flange);
    let turns = 4;
    let mut zigzag = vec![(l, AXIS)];
    for k in 0..2 * turns {
        let xk = l + (r - l) * (2 * k + 1) / (4 * turns);
        let up = if k % 2 == 0 { -h / 2 } else { h / 2 };
        zigzag.push((xk, AXIS + up));
    }
    zigzag.push((r, AXIS));
    root.draw(&PathElement::new(zigzag, COUPLING_EDGE.stroke_width(2)))?;
    Ok(())
}

/// A sketch of the rotor; non-beam rotors get a short note instead.
pub fn rotor_sketch(rotor: &RotorInput) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (W as u32, H as u32)).into_drawing_area();
        root.fill(&WHITE)?;
        match rotor {
            RotorInput::Beam(b) if !b.shaft.is_empty() => beam(&root, b)?,
            _ => {
                let s = "Rotor sketch: drawn for beam rotors only";
                text(
                    &root,
                    s,
                    (W / 2, H / 2),
                    20,
                    INK,
                    (HPos::Center, VPos::Center),
                )?;
            }
        }
        root.present()?;
    }
    Ok(svg)
}

fn beam(root: &Area<'_>, b: &BeamInput) -> Result<(), Err> {
    let nodes = node_positions(b);
    let length: f64 = b.shaft.iter().map(|s| s.length).sum();
    let length = if length.is_finite() && length > 0.0 {
        length
    } else {
        1.0
    };
    let px_m = f64::from(W - LEFT - RIGHT) / length;
    let px = |x: f64| LEFT + (x * px_m).round() as i32;
    let d_max = b
        .shaft
        .iter()
        .flat_map(|s| [Some(s.outer_diameter), s.outer_diameter_right])
        .chain(
            b.sleeves
                .iter()
                .flat_map(|s| [Some(s.outer_diameter), s.outer_diameter_right]),
        )
        .flatten()
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max);
    let d_px = if d_max > 0.0 {
        (SHAFT_PX / d_max).min(px_m * 6.0)
    } else {
        1.0
    };
    let exaggeration = d_px / px_m;
    let title = format!("Rotor model: {length:.3} m long, diameters drawn ×{exaggeration:.1}");
    text(
        root,
        &title,
        (W / 2, 14),
        22,
        INK,
        (HPos::Center, VPos::Top),
    )?;
    let mut labels = Labels::new([0, 30, W, H]);

    let half = |d: f64, min: i32| ((d * d_px / 2.0).round() as i32).max(min);
    // A section from a to e, its half heights at both ends (a cone is a trapezium).
    let section = |a: i32, e: i32, hl: i32, hr: i32| {
        vec![
            (a, AXIS - hl),
            (e, AXIS - hr),
            (e, AXIS + hr),
            (a, AXIS + hl),
        ]
    };
    // Sleeves first, lighter, under the shaft they sit on.
    for s in &b.sleeves {
        let first = s.node.max(0) as usize;
        let last = first + s.elements.unwrap_or(1).max(1) as usize;
        let (Some(&x0), Some(&x1)) = (nodes.get(first), nodes.get(last)) else {
            continue;
        };
        let (hl, hr) = (
            half(s.outer_diameter, 2),
            half(s.outer_diameter_right.unwrap_or(s.outer_diameter), 2),
        );
        let outline = section(px(x0), px(x1), hl, hr);
        root.draw(&Polygon::new(outline.clone(), STEEL.mix(0.45).filled()))?;
        let mut closed = outline;
        closed.push(closed[0]);
        root.draw(&PathElement::new(closed, STEEL_EDGE.mix(0.6)))?;
    }
    // Shaft segments, bores lighter.
    let mut x = 0.0;
    let mut half_at = vec![0; nodes.len()];
    let mut node = 0;
    for s in &b.shaft {
        let (hl, hr) = (
            half(s.outer_diameter, 2),
            half(s.outer_diameter_right.unwrap_or(s.outer_diameter), 2),
        );
        let h = hl.max(hr);
        let (a, e) = (px(x), px(x + s.length));
        if s.coupling.is_some() {
            // A coupling between two shafts: a flange at each end, a spring between them.
            coupling(root, a, e, h)?;
            labels.block([a, AXIS - h, e, AXIS + h]);
            let end = (node + 1).min(nodes.len() - 1);
            for half in &mut half_at[node.min(end)..=end] {
                *half = (*half).max(h);
            }
            node += 1;
            x += s.length;
            continue;
        }
        let outline = section(a, e, hl, hr);
        root.draw(&Polygon::new(outline.clone(), STEEL.filled()))?;
        let mut closed = outline;
        closed.push(closed[0]);
        root.draw(&PathElement::new(closed, STEEL_EDGE.stroke_width(1)))?;
        labels.block([a, AXIS - h, e, AXIS + h]);
        let inner_r = s.inner_diameter_right.unwrap_or(s.inner_diameter);
        if s.inner_diameter.max(inner_r) > 0.0 {
            let (il, ir) = (half(s.inner_diameter, 0), half(inner_r, 0));
            root.draw(&Polygon::new(
                section(a + 1, e - 1, il, ir),
                WHITE.mix(0.7).filled(),
            ))?;
        }
        let n = s.elements.unwrap_or(1).max(1) as usize;
        let end = (node + n).min(nodes.len() - 1);
        for half in &mut half_at[node.min(end)..=end] {
            *half = (*half).max(h);
        }
        node += n;
        x += s.length;
    }
    let centre = vec![(px(0.0) - 14, AXIS), (px(length) + 14, AXIS)];
    root.draw(&PathElement::new(
        centre,
        STEEL_EDGE.mix(0.6).stroke_width(1),
    ))?;
    // Element boundaries and node numbers (thinned when crowded; disk and support nodes kept).
    let special = |n: usize| {
        b.disks.iter().any(|d| d.node as usize == n)
            || b.supports.iter().any(|s| s.node as usize == n)
    };
    let step = {
        let gap = f64::from(W - LEFT - RIGHT) / nodes.len().max(1) as f64;
        (22.0 / gap).ceil().max(1.0) as usize
    };
    let mut last = i32::MIN / 2;
    for (n, &xn) in nodes.iter().enumerate() {
        let p = px(xn);
        if nodes.len() <= 400 {
            let h = half_at[n];
            root.draw(&PathElement::new(
                vec![(p, AXIS - h), (p, AXIS + h)],
                STEEL_EDGE.mix(0.5),
            ))?;
        }
        let end = n + 1 == nodes.len();
        if (n % step == 0 || special(n) || end) && p - last >= 18 {
            text(
                root,
                &n.to_string(),
                (p, NODES_Y),
                NOTE,
                INK,
                (HPos::Center, VPos::Top),
            )?;
            root.draw(&PathElement::new(
                vec![(p, NODES_Y + 18), (p, NODES_Y + 26)],
                INK.mix(0.5),
            ))?;
            last = p;
        }
    }
    let (nw, nh) = text_box("node", NOTE);
    text(
        root,
        "node",
        (LEFT - 8 - nw, NODES_Y),
        NOTE,
        GREY,
        (HPos::Left, VPos::Top),
    )?;
    labels.block([0, NODES_Y, W, NODES_Y + nh + 10]);

    // Disks: diameter from the polar inertia (solid disk), joint scale, taller than the shaft.
    let sizes: Vec<_> = b
        .disks
        .iter()
        .map(|d| disk_size(d.mass, d.polar_inertia, d.transverse_inertia))
        .collect();
    let dd_max = sizes.iter().filter_map(|s| s.0).fold(0.0, f64::max);
    let dd_px = if dd_max > 0.0 {
        d_px.min(DISK_PX / dd_max)
    } else {
        d_px
    };
    for (d, (dia, thick)) in b.disks.iter().zip(&sizes) {
        let Some(&xn) = nodes.get(d.node.max(0) as usize) else {
            continue;
        };
        let shaft = half_at[d.node as usize];
        let h = dia
            .map_or(shaft * 3, |v| (v * dd_px / 2.0).round() as i32)
            .max(shaft * 3 / 2 + 4);
        let w = thick.map_or(14, |t| (t * px_m).round() as i32).clamp(8, 40);
        let p = px(xn);
        let r = [(p - w / 2, AXIS - h), (p + w / 2, AXIS + h)];
        root.draw(&Rectangle::new(r, PALETTE[0].mix(0.75).filled()))?;
        root.draw(&Rectangle::new(r, PALETTE[0].stroke_width(1)))?;
        labels.block([p - w / 2, AXIS - h, p + w / 2, AXIS + h]);
        let s = format!("{:.1} kg", d.mass);
        let (tw, th) = text_box(&s, NOTE);
        let spot = (p - tw / 2, AXIS + h + 4);
        labels.block([spot.0, spot.1, spot.0 + tw, spot.1 + th]);
        text(root, &s, spot, NOTE, PALETTE[0], (HPos::Left, VPos::Top))?;
    }

    // Supports: a triangle under the shaft, a spring, the ground.
    let mut stacked = vec![0; nodes.len()];
    for s in &b.supports {
        let Some(&xn) = nodes.get(s.node.max(0) as usize) else {
            continue;
        };
        let n = s.node as usize;
        // Several supports at one node stand side by side, centred on it.
        let here = b.supports.iter().filter(|o| o.node == s.node).count() as i32;
        let p = px(xn) + 26 * stacked[n] - 13 * (here - 1);
        stacked[n] += 1;
        let top = AXIS + half_at[n];
        let c = PALETTE[1];
        root.draw(&Polygon::new(
            vec![(p, top), (p - 9, top + 14), (p + 9, top + 14)],
            c.filled(),
        ))?;
        let mut zig = vec![(p, top + 14), (p, top + 18)];
        for k in 0..6 {
            zig.push((p + if k % 2 == 0 { 7 } else { -7 }, top + 21 + 4 * k));
        }
        zig.extend([(p, top + 42), (p, top + 46)]);
        root.draw(&PathElement::new(zig, c.stroke_width(2)))?;
        root.draw(&PathElement::new(
            vec![(p - 14, top + 46), (p + 14, top + 46)],
            INK.stroke_width(2),
        ))?;
        for k in 0..4 {
            let gx = p - 12 + 8 * k;
            root.draw(&PathElement::new(
                vec![(gx, top + 46), (gx - 5, top + 52)],
                INK.mix(0.6),
            ))?;
        }
        labels.block([p - 14, top, p + 14, top + 52]);
    }
    // Their stiffness under them, one line per support, centred when there is room.
    let mut below = vec![0; nodes.len()];
    for s in &b.supports {
        let Some(&xn) = nodes.get(s.node.max(0) as usize) else {
            continue;
        };
        let n = s.node as usize;
        let (p, top) = (px(xn), AXIS + half_at[n] + 54);
        let line = support_stiffness(s);
        let (w, h) = text_box(&line, NOTE);
        let y = top + h * below[n];
        below[n] += 1;
        let cx = (p - w / 2).clamp(2, W - 2 - w);
        let (x, y) = if labels.take([cx, y, cx + w, y + h]) {
            (cx, y)
        } else {
            labels.place((p, y), &line, NOTE, p > W / 2)
        };
        text(
            root,
            &line,
            (x, y),
            NOTE,
            PALETTE[1],
            (HPos::Left, VPos::Top),
        )?;
    }

    // Scale bar along the axis.
    root.draw(&PathElement::new(
        vec![(px(0.0), SCALE_Y), (px(length), SCALE_Y)],
        FRAME.stroke_width(1),
    ))?;
    let tick = nice_step(length / 6.0);
    let mut t = 0.0;
    while t <= length * (1.0 + 1e-9) {
        let p = px(t);
        root.draw(&PathElement::new(
            vec![(p, SCALE_Y - 4), (p, SCALE_Y + 4)],
            FRAME.stroke_width(1),
        ))?;
        text(
            root,
            &format!("{t:.2}"),
            (p, SCALE_Y + 7),
            NOTE,
            INK,
            (HPos::Center, VPos::Top),
        )?;
        t += tick;
    }
    text(
        root,
        "m",
        (px(length) + 10, SCALE_Y),
        NOTE,
        INK,
        (HPos::Left, VPos::Center),
    )?;
    Ok(())
}

/// 1, 2 or 5 times a power of ten, at least `x`.
fn nice_step(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|s| *s >= x)
        .unwrap_or(10.0 * p)
}
