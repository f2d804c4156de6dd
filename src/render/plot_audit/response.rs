//! The Level I screen, the frequency response (Bode) and the unbalance response with its peaks.

use super::*;

/// API 617 Level I screen: log decrement of the first forward mode against cross-coupling.
pub fn level1(l: &Level1Response) -> Result<String, Err> {
    let fin = |v: &Option<f64>| v.filter(|x| x.is_finite());
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        let qmax = l
            .cross_coupling
            .iter()
            .copied()
            .filter(|q| q.is_finite())
            .fold(0.0, f64::max);
        // q0 and q_A widen the axis unless far beyond the curve (then they are only named).
        let near = |q: Option<f64>| fin(&q).filter(|q| *q <= 2.0 * qmax.max(f64::MIN_POSITIVE));
        let extra = [near(l.q0), near(l.qa)].into_iter().flatten();
        let (q_lo, q_hi) = range(l.cross_coupling.iter().copied().chain(extra), 0.0);
        let (div, unit) = stiffness_unit(q_hi.abs().max(q_lo.abs()));
        let (x0, x1) = (q_lo / div, q_hi / div);
        let ds = l
            .log_decrement
            .iter()
            .chain([&l.log_decrement_0, &l.log_decrement_at_qa]);
        let (y0, y1) = range(ds.filter_map(fin).chain([0.0, 0.1]), 0.1);
        let caption = format!(
            "API 617 Level I screen at {:.0} rpm ({})",
            l.speed * RPM,
            l.model
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, (FONT, 22))
            .margin(14)
            .margin_right(30)
            .x_label_area_size(52)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let unit_name = if unit == "MN/m" { "MN/m = kN/mm" } else { unit };
        chart
            .configure_mesh()
            .x_desc(format!("cross-coupled stiffness q [{unit_name}]"))
            .y_desc("log decrement δ, first forward mode")
            .x_label_formatter(&lin_tick(x1 - x0))
            .y_label_formatter(&lin_tick(y1 - y0))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        let area = frame(&root, &chart)?;
        let mut labels = Labels::new(area);
        let qs: Vec<f64> = l.cross_coupling.iter().map(|q| q / div).collect();
        chart.draw_series(LineSeries::new([(x0, 0.0), (x1, 0.0)], INK.stroke_width(1)))?;
        chart.draw_series(DashedLineSeries::new(
            [(x0, 0.1), (x1, 0.1)],
            8,
            6,
            FAIL.stroke_width(2),
        ))?;
        let curves = runs(&qs, &l.log_decrement);
        for run in &curves {
            chart.draw_series(LineSeries::new(
                run.iter().copied(),
                PALETTE[0].stroke_width(2),
            ))?;
            chart.draw_series(run.iter().map(|p| Circle::new(*p, 3, PALETTE[0].filled())))?;
            labels.block_path(&pixels(&chart, run));
        }
        let at = chart.backend_coord(&(x1, 0.1));
        let s = "API 617 minimum δ = 0.1";
        let (w, h) = text_box(s, NOTE);
        let spot = (at.0 - w - 6, at.1 - h - 2);
        labels.block([spot.0, spot.1, spot.0 + w, spot.1 + h]);
        text(&root, s, spot, NOTE, FAIL, (HPos::Left, VPos::Top))?;
        let mut notes = vec![];
        if let Some(qa) = fin(&l.qa) {
            let x = qa / div;
            let name = format!("q_A = {:.3} {unit}", x);
            if (x0..=x1).contains(&x) {
                let c = PALETTE[4];
                chart.draw_series(LineSeries::new([(x, y0), (x, y1)], c.stroke_width(2)))?;
                labels.block_path(&pixels(&chart, &[(x, y0), (x, y1)]));
                let at = chart.backend_coord(&(x, y1));
                let (w, h) = text_box(&name, NOTE);
                let (px, py) = if at.0 + 6 + w < area[2] {
                    (at.0 + 6, at.1 + 4)
                } else {
                    (at.0 - 6 - w, at.1 + 4)
                };
                labels.block([px, py, px + w, py + h]);
                text(&root, &name, (px, py), NOTE, c, (HPos::Left, VPos::Top))?;
                if let Some(d) = fin(&l.log_decrement_at_qa) {
                    chart.draw_series([Circle::new((x, d), 5, c.filled())])?;
                    let at = chart.backend_coord(&(x, d));
                    label(
                        &root,
                        &mut labels,
                        &format!("δ(q_A) = {d:.3}"),
                        at,
                        c,
                        false,
                    )?;
                }
            } else {
                notes.push(name);
            }
        }
        if let Some(q0) = fin(&l.q0) {
            let x = q0 / div;
            let name = format!("q0 = {:.3} {unit}", x);
            if (x0..=x1).contains(&x) {
                chart.draw_series([Circle::new((x, 0.0), 6, FAIL.filled())])?;
                let at = chart.backend_coord(&(x, 0.0));
                label(&root, &mut labels, &name, at, FAIL, false)?;
            } else {
                notes.push(format!("{name} (beyond the plot)"));
            }
        } else {
            notes.push("q0: stable over the range searched".into());
        }
        if let Some(r) = fin(&l.ratio) {
            notes.push(format!("q0 / q_A = {r:.2}"));
        }
        if let Some(p) = l.passes {
            notes.push(if p {
                "Level I: passes".into()
            } else {
                "Level I: Level II required".into()
            });
        }
        note_box(&root, &mut labels, &notes)?;
        root.present()?;
    }
    Ok(svg)
}

/// Bode plot of the frequency response: amplitude (m/N, log) over phase (degrees).
pub fn frequency_response(r: &FrequencyResponseResponse) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 820)).into_drawing_area();
        root.fill(&WHITE)?;
        let (top, bottom) = root.split_vertically(470);
        let (x0, x1) = range(r.frequencies.iter().copied(), 0.0);
        let (a0, a1) = log_range(r.amplitude.iter().copied(), 0.05);
        let caption = format!(
            "Frequency response: node {} → node {} at {:.0} rpm ({})",
            r.input_node,
            r.output_node,
            r.speed * RPM,
            r.model
        );
        let mut chart = ChartBuilder::on(&top)
            .caption(caption, (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .top_x_label_area_size(44)
            .build_cartesian_2d(x0..x1, (a0..a1).log_scale())?
            .set_secondary_coord(x0 * RPM..x1 * RPM, 0.0..1.0);
        chart
            .configure_mesh()
            .x_desc("excitation frequency ω [rad/s]")
            .y_desc("amplitude [m/N]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_labels(log_labels(a0, a1))
            .y_label_formatter(&|v| log_tick(*v))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("excitation frequency [cpm]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .y_labels(0)
            .draw()?;
        let area = frame(&root, &chart)?;
        log_minor_labels(&root, area, (a0, a1), false)?;
        let ok = |(f, a): &(f64, f64)| f.is_finite() && a.is_finite() && *a > 0.0;
        let pts = r
            .frequencies
            .iter()
            .copied()
            .zip(r.amplitude.iter().copied());
        chart.draw_series(LineSeries::new(pts.filter(ok), PALETTE[0].stroke_width(2)))?;

        let mut chart = ChartBuilder::on(&bottom)
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .build_cartesian_2d(x0..x1, -180.0..180.0)?;
        chart
            .configure_mesh()
            .x_desc("excitation frequency ω [rad/s]")
            .y_desc("phase [deg]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_labels(0)
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        // Grid every 45 degrees, labelled every 90.
        for k in -4..=4 {
            let d = f64::from(k) * 45.0;
            let c = if k % 2 == 0 {
                RGBColor(200, 200, 200)
            } else {
                GRID
            };
            chart.draw_series(LineSeries::new([(x0, d), (x1, d)], c.stroke_width(1)))?;
            if k % 2 == 0 {
                let at = chart.backend_coord(&(x0, d));
                root.draw(&PathElement::new(
                    vec![(at.0 - 5, at.1), at],
                    BLACK.stroke_width(1),
                ))?;
                text(
                    &root,
                    &format!("{d:.0}"),
                    (at.0 - 10, at.1),
                    TICK,
                    BLACK,
                    (HPos::Right, VPos::Center),
                )?;
            }
        }
        frame(&root, &chart)?;
        // Wrapped to (-180, 180]; a wrap breaks the line.
        let mut run: Vec<(f64, f64)> = vec![];
        for (f, p) in r.frequencies.iter().zip(&r.phase) {
            if !(f.is_finite() && p.is_finite()) {
                chart.draw_series(LineSeries::new(
                    std::mem::take(&mut run),
                    PALETTE[1].stroke_width(2),
                ))?;
                continue;
            }
            let d = -((-p.to_degrees() + 180.0).rem_euclid(360.0) - 180.0);
            if run.last().is_some_and(|l| (l.1 - d).abs() > 180.0) {
                chart.draw_series(LineSeries::new(
                    std::mem::take(&mut run),
                    PALETTE[1].stroke_width(2),
                ))?;
            }
            run.push((*f, d));
        }
        chart.draw_series(LineSeries::new(run, PALETTE[1].stroke_width(2)))?;
        root.present()?;
    }
    Ok(svg)
}

/// `N_c = ... rpm, AF = ..., SM = ...% (req ...%)` of a peak.
fn peak_label(p: &crate::model::api::ResponsePeak) -> String {
    let fin = |v: Option<f64>| v.filter(|x| x.is_finite());
    let mut s = format!("N_c = {:.0} rpm", p.speed * RPM);
    match fin(p.amplification_factor) {
        Some(af) => s += &format!(", AF = {af:.1}"),
        None => s += ", AF = n/a",
    }
    if let Some(sm) = fin(p.separation_margin) {
        s += &format!(", SM = {sm:.1}%");
        match fin(p.required_margin) {
            Some(req) => s += &format!(" (req {req:.1}%)"),
            None => s += " (none req)",
        }
    }
    s
}

/// Semi-major axis of each node's orbit (zero to peak) against speed, each peak marked with its critical speed,
/// amplification factor and separation margin; the operating speeds `shade` shaded.
pub fn unbalance_with(
    r: &UnbalanceResponseResponse,
    shade: Option<[f64; 2]>,
) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        amplitude(&root, r, shade)?;
        root.present()?;
    }
    Ok(svg)
}

/// The unbalance response as a Bode plot: [`unbalance_with`]'s amplitudes over the phase of
/// each node's forward circular part (degrees, relative to the unbalance at phase 0).
pub fn unbalance_bode(
    r: &UnbalanceResponseResponse,
    shade: Option<[f64; 2]>,
) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 900)).into_drawing_area();
        root.fill(&WHITE)?;
        let (top, bottom) = root.split_vertically(600);
        amplitude(&top, r, shade)?;
        let (x0, x1) = range(r.speeds.iter().copied(), 0.0);
        // Unwrapped along speed (a lag passing 180 degrees goes on, as on a Bode plot).
        let phases: Vec<Vec<(f64, f64)>> = r
            .nodes
            .iter()
            .map(|n| {
                let mut last: Option<f64> = None;
                r.speeds
                    .iter()
                    .zip(&n.phase)
                    .filter(|(s, p)| s.is_finite() && p.is_finite())
                    .map(|(s, p)| {
                        let mut d = p.to_degrees();
                        if let Some(l) = last {
                            d -= 360.0 * ((d - l) / 360.0).round();
                        }
                        last = Some(d);
                        (*s, d)
                    })
                    .collect()
            })
            .collect();
        let lo = phases.iter().flatten().map(|p| p.1).fold(0.0, f64::min);
        let hi = phases.iter().flatten().map(|p| p.1).fold(0.0, f64::max);
        let (lo, hi) = ((lo / 90.0).floor() * 90.0, (hi / 90.0).ceil() * 90.0);
        let (lo, hi) = if hi - lo < 90.0 {
            (lo - 90.0, hi)
        } else {
            (lo, hi)
        };
        let mut chart = ChartBuilder::on(&bottom)
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .build_cartesian_2d(x0..x1, lo..hi)?;
        chart
            .configure_mesh()
            .x_desc("spin speed [rad/s]")
            .y_desc("phase [deg]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_labels(((hi - lo) / 45.0) as usize + 1)
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        frame(&root, &chart)?;
        if let Some((a, b)) = clip(shade, x0, x1) {
            chart.draw_series([Rectangle::new([(a, lo), (b, hi)], SHADE.filled())])?;
        }
        for (k, pts) in phases.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            chart.draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))?;
        }
        root.present()?;
    }
    Ok(svg)
}

/// The amplitude panel of the unbalance response on `root`.
fn amplitude(
    root: &Area<'_>,
    r: &UnbalanceResponseResponse,
    shade: Option<[f64; 2]>,
) -> Result<(), Err> {
    {
        let (x0, x1) = range(r.speeds.iter().copied(), 0.0);
        let max = r
            .nodes
            .iter()
            .flat_map(|n| &n.amplitude)
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let (scale, unit) = length_unit(max);
        let (_, a1) = range([0.0, max * scale].into_iter(), 0.0);
        let a1 = a1 * 1.3;
        let mut chart = ChartBuilder::on(root)
            .caption("Unbalance response", (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .top_x_label_area_size(44)
            .build_cartesian_2d(x0..x1, 0.0..a1)?
            .set_secondary_coord(x0 * RPM..x1 * RPM, 0.0..a1);
        chart
            .configure_mesh()
            .x_desc("spin speed [rad/s]")
            .y_desc(format!("semi-major axis of the orbit, 0-pk [{unit}]"))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&lin_tick(a1))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("spin speed [rpm]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .y_labels(0)
            .draw()?;
        let area = frame(root, &chart)?;
        let mut labels = Labels::new(area);
        let mut entries = vec![];
        if let Some((lo, hi)) = clip(shade, x0, x1) {
            operating_range(root, &mut chart, &mut labels, (lo, 0.0), (hi, a1))?;
        }
        for (k, n) in r.nodes.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let pts = r
                .speeds
                .iter()
                .zip(&n.amplitude)
                .filter(|(s, a)| s.is_finite() && a.is_finite());
            let pts: Vec<(f64, f64)> = pts.map(|(s, a)| (*s, a * scale)).collect();
            labels.block_path(&pixels(&chart, &pts));
            chart.draw_series(LineSeries::new(pts, color.stroke_width(2)))?;
            entries.push((format!("node {}", n.node), color, false));
        }
        let key_box = key(root, (area[2] - 8, area[1] + 8), &entries)?;
        labels.block(key_box);
        let many = r.nodes.iter().filter(|n| !n.peaks.is_empty()).count() > 1;
        let mut marks = vec![];
        for (k, n) in r.nodes.iter().enumerate() {
            for p in &n.peaks {
                let pt = (p.speed, p.amplitude * scale);
                if !(pt.0.is_finite() && pt.1.is_finite() && (x0..=x1).contains(&pt.0)) {
                    continue;
                }
                let color = PALETTE[k % PALETTE.len()];
                chart.draw_series([
                    Circle::new(pt, 5, color.filled()),
                    Circle::new(pt, 5, INK.stroke_width(1)),
                ])?;
                let at = chart.backend_coord(&pt);
                labels.block([at.0 - 5, at.1 - 5, at.0 + 5, at.1 + 5]);
                let s = peak_label(p);
                let ink = if p.passes == Some(false) { FAIL } else { INK };
                // Peaks drawn on one another (symmetric nodes) share a label.
                let same = |m: &&mut ((i32, i32), Vec<usize>, String, RGBColor)| {
                    (m.0.0 - at.0).abs() <= 2 && (m.0.1 - at.1).abs() <= 2 && m.2 == s
                };
                match marks.iter_mut().find(same) {
                    Some(m) => m.1.push(n.node),
                    None => marks.push((at, vec![n.node], s, ink)),
                }
            }
        }
        marks.sort_by_key(|m| m.0.1);
        for (at, nodes, s, ink) in marks {
            let names: Vec<String> = nodes.iter().map(usize::to_string).collect();
            let s = match (many, nodes.len()) {
                (false, _) => s,
                (true, 1) => format!("node {}: {s}", names[0]),
                (true, _) => format!("nodes {}: {s}", names.join(", ")),
            };
            let left = at.0 > (area[0] + area[2]) / 2;
            label(root, &mut labels, &s, at, ink, left)?;
        }
    }
    Ok(())
}
