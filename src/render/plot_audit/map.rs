//! The undamped critical speed map and the static deflection with its bending moment.

use super::*;

/// Undamped critical speed map: natural frequency against support stiffness, log-log.
pub fn critical_speed_map(c: &CriticalSpeedMapResponse) -> Result<String, Err> {
    critical_speed_map_with(c, None)
}

/// [`critical_speed_map`] with the operating speeds `shade = [min, max]` (rad/s) shaded.
pub fn critical_speed_map_with(
    c: &CriticalSpeedMapResponse,
    shade: Option<[f64; 2]>,
) -> Result<String, Err> {
    let ok = |v: f64| v.is_finite() && v > 0.0;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 680)).into_drawing_area();
        root.fill(&WHITE)?;
        let ks = c
            .stiffness
            .iter()
            .copied()
            .chain(c.intersections.iter().map(|i| i.stiffness));
        let (k0, k1) = log_range(ks, 0.0);
        let fs = c.frequencies.iter().flatten().copied();
        let fs = fs
            .chain(c.intersections.iter().map(|i| i.frequency))
            .chain(shade.into_iter().flatten());
        let (f0, f1) = log_range(fs, 0.06);
        let mut chart = ChartBuilder::on(&root)
            .caption("Undamped critical speed map", (FONT, 22))
            .margin(14)
            .x_label_area_size(52)
            .y_label_area_size(80)
            .right_y_label_area_size(86)
            .build_cartesian_2d((k0..k1).log_scale(), (f0..f1).log_scale())?
            .set_secondary_coord((k0..k1).log_scale(), (f0 * RPM..f1 * RPM).log_scale());
        chart
            .configure_mesh()
            .x_desc("support stiffness [N/m]")
            .y_desc("natural frequency [rad/s]")
            .x_labels(log_labels(k0, k1))
            .y_labels(log_labels(f0, f1))
            .x_label_formatter(&|v| log_tick(*v))
            .y_label_formatter(&|v| log_tick(*v))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        chart
            .configure_secondary_axes()
            .y_desc("natural frequency [rpm]")
            .y_labels(log_labels(f0 * RPM, f1 * RPM))
            .y_label_formatter(&|v| log_tick(*v))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .x_labels(0)
            .draw()?;
        let area = frame(&root, &chart)?;
        log_minor_labels(&root, area, (f0, f1), false)?;
        log_minor_labels(&root, area, (f0 * RPM, f1 * RPM), true)?;
        let mut labels = Labels::new(area);
        if let Some([lo, hi]) = shade.filter(|s| ok(s[0]) && ok(s[1]) && s[1] > s[0]) {
            let (lo, hi) = (lo.max(f0), hi.min(f1));
            operating_range(&root, &mut chart, &mut labels, (k0, lo), (k1, hi))?;
        }
        for (m, ys) in c.frequencies.iter().enumerate() {
            let color = PALETTE[m % PALETTE.len()];
            let pts: Vec<(f64, f64)> = c
                .stiffness
                .iter()
                .zip(ys)
                .filter(|(k, f)| ok(**k) && ok(**f))
                .map(|(k, f)| (*k, *f))
                .collect();
            chart.draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))?;
            labels.block_path(&pixels(&chart, &pts));
            if let Some(end) = pts.last() {
                let at = chart.backend_coord(end);
                let s = format!("mode {}", m + 1);
                let (w, h) = text_box(&s, NOTE);
                let (x, y) = (at.0 - w - 6, at.1 - h - 3);
                labels.block([x, y, x + w, y + h]);
                text(&root, &s, (x, y), NOTE, color, (HPos::Left, VPos::Top))?;
            }
        }
        // One marker per distinct point (two supports often meet a mode at the same place).
        let mut seen: Vec<(f64, f64)> = vec![];
        let mut points = vec![];
        for i in &c.intersections {
            let (k, f) = (i.stiffness, i.frequency);
            let inside = ok(k) && ok(f) && (k0..=k1).contains(&k) && (f0..=f1).contains(&f);
            if inside
                && !seen
                    .iter()
                    .any(|(a, b)| (a / k).ln().abs() < 1e-3 && (b / f).ln().abs() < 1e-3)
            {
                seen.push((k, f));
                points.push((k, f, PALETTE[(i.mode.max(1) - 1) % PALETTE.len()]));
            }
        }
        for &(k, f, color) in &points {
            let at = chart.backend_coord(&(k, f));
            labels.block([at.0 - 6, at.1 - 6, at.0 + 6, at.1 + 6]);
            chart.draw_series([
                Circle::new((k, f), 6, color.filled()),
                Circle::new((k, f), 6, INK.stroke_width(1)),
            ])?;
        }
        // The callouts in columns beside the markers (many crossings crowd them).
        let texts: Vec<String> = points
            .iter()
            .map(|(_, f, _)| format!("{f:.1} rad/s ({:.0} rpm)", f * RPM))
            .collect();
        let at: Vec<(i32, i32)> = points
            .iter()
            .map(|&(k, f, _)| chart.backend_coord(&(k, f)))
            .collect();
        let sizes: Vec<(i32, i32)> = texts.iter().map(|s| text_box(s, NOTE)).collect();
        let boxes = labels.columns(&at, &sizes);
        for (((s, &at), r), &(_, _, color)) in texts.iter().zip(&at).zip(boxes).zip(&points) {
            callout(&root, s, at, r, color)?;
        }
        root.present()?;
    }
    Ok(svg)
}

/// Static deflection (µm or mm) with the support reactions over the bending moment and the
/// shear force, along the shaft (the exact diagrams, each maximum marked).
pub fn static_deflection(s: &StaticResponse) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 1100)).into_drawing_area();
        root.fill(&WHITE)?;
        let (top, bottom) = root.split_vertically(420);
        let xs = s
            .nodes
            .iter()
            .map(|n| n.position)
            .chain(s.stations.iter().map(|t| t.position));
        let (x0, x1) = range(xs, 0.02);
        // The exact curve where the answer has it (`diagram`), else the nodes joined.
        let curve: Vec<(f64, f64)> = if s.diagram.is_empty() {
            s.nodes.iter().map(|n| (n.position, n.deflection)).collect()
        } else {
            s.diagram
                .iter()
                .map(|t| (t.position, t.deflection))
                .collect()
        };
        let max = curve
            .iter()
            .map(|p| p.1.abs())
            .chain([s.max_deflection_y.abs()])
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let (scale, unit) = length_unit(max);
        let ds = curve.iter().map(|p| p.1 * scale).chain([0.0]);
        let (y0, y1) = range(ds, 0.18);
        let caption = format!("Static deflection under gravity (weight {:.1} N)", s.weight);
        let mut chart = ChartBuilder::on(&top)
            .caption(caption, (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc("axial position [m]")
            .y_desc(format!("deflection y [{unit}]"))
            .x_label_formatter(&lin_tick(x1 - x0))
            .y_label_formatter(&lin_tick(y1 - y0))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        let area = frame(&root, &chart)?;
        chart.draw_series(LineSeries::new(
            [(x0, 0.0), (x1, 0.0)],
            INK.mix(0.6).stroke_width(1),
        ))?;
        let pts: Vec<(f64, f64)> = s
            .nodes
            .iter()
            .filter(|n| n.position.is_finite() && n.deflection.is_finite())
            .map(|n| (n.position, n.deflection * scale))
            .collect();
        let line: Vec<(f64, f64)> = curve
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|p| (p.0, p.1 * scale))
            .collect();
        chart.draw_series(LineSeries::new(
            line.iter().copied(),
            PALETTE[0].stroke_width(2),
        ))?;
        chart.draw_series(pts.iter().map(|p| Circle::new(*p, 3, PALETTE[0].filled())))?;
        let mut labels = Labels::new(area);
        labels.block_path(&pixels(&chart, &line));
        // The largest along the shaft (between nodes when it is there), else at a node.
        let largest = if s.diagram.is_empty() {
            pts.iter().copied().min_by(|a, b| a.1.total_cmp(&b.1))
        } else {
            Some((s.max_deflection_position, s.max_deflection_y * scale))
        };
        if let Some(p) = largest.filter(|p| p.0.is_finite() && p.1.is_finite()) {
            let at = chart.backend_coord(&p);
            root.draw(&Circle::new(at, 5, PALETTE[0].stroke_width(2)))?;
            let s = format!("largest {:.1} {unit} at {:.3} m", p.1.abs(), p.0);
            label(&root, &mut labels, &s, at, PALETTE[0], false)?;
        }
        for r in &s.supports {
            let Some(n) = s.nodes.iter().find(|n| n.node == r.node) else {
                continue;
            };
            if !(n.position.is_finite() && n.deflection.is_finite() && r.reaction.is_finite()) {
                continue;
            }
            let p = (n.position, n.deflection * scale);
            let at = chart.backend_coord(&p);
            let tri = vec![at, (at.0 - 8, at.1 + 15), (at.0 + 8, at.1 + 15)];
            root.draw(&Polygon::new(tri, PALETTE[1].filled()))?;
            labels.block([at.0 - 8, at.1, at.0 + 8, at.1 + 15]);
            let mut s = format!("R{} = {:.1} N (node {})", r.support, r.reaction, r.node);
            if r.reaction_x.is_finite() && r.reaction_x.abs() > 1e-6 * r.reaction.abs().max(1.0) {
                s = format!(
                    "R{} = {:.1} N, x {:.1} N (node {})",
                    r.support, r.reaction, r.reaction_x, r.node
                );
            }
            // Centred under the support when there is room.
            let (w, h) = text_box(&s, NOTE);
            let r = [at.0 - w / 2, at.1 + 19, at.0 + w / 2, at.1 + 19 + h];
            if labels.take(r) {
                text(
                    &root,
                    &s,
                    (r[0], r[1]),
                    NOTE,
                    PALETTE[1],
                    (HPos::Left, VPos::Top),
                )?;
            } else {
                let left = p.0 > (x0 + x1) / 2.0;
                label(&root, &mut labels, &s, (at.0, at.1 + 15), PALETTE[1], left)?;
            }
        }

        let along = if s.diagram.is_empty() {
            &s.stations
        } else {
            &s.diagram
        };
        let (middle, bottom) = bottom.split_vertically(340);
        let panels = [
            (
                &middle,
                "Bending moment",
                "bending moment [N m]",
                PALETTE[2],
                (s.max_moment_position, s.max_moment),
                "|M| max",
                "N m",
            ),
            (
                &bottom,
                "Shear force",
                "shear force [N]",
                PALETTE[3],
                (s.max_shear_position, s.max_shear),
                "|V| max",
                "N",
            ),
        ];
        for (k, (area_of, caption, desc, colour, max, what, unit)) in panels.into_iter().enumerate()
        {
            let value = |t: &crate::model::api::ShaftStation| {
                if k == 0 { t.bending_moment } else { t.shear }
            };
            // One line per element: the shear jumps at nodes with forces.
            let lines: Vec<Vec<(f64, f64)>> = along
                .chunk_by(|a, b| a.element == b.element)
                .map(|c| {
                    c.iter()
                        .filter(|t| t.position.is_finite() && value(t).is_finite())
                        .map(|t| (t.position, value(t)))
                        .collect()
                })
                .collect();
            let all: Vec<(f64, f64)> = lines.iter().flatten().copied().collect();
            let (m0, m1) = range(all.iter().map(|p| p.1).chain([0.0]), 0.15);
            let mut chart = ChartBuilder::on(area_of)
                .caption(caption, (FONT, 22))
                .margin(14)
                .x_label_area_size(48)
                .y_label_area_size(84)
                .build_cartesian_2d(x0..x1, m0..m1)?;
            chart
                .configure_mesh()
                .x_desc("axial position [m]")
                .y_desc(desc)
                .x_label_formatter(&lin_tick(x1 - x0))
                .y_label_formatter(&lin_tick(m1 - m0))
                .label_style((FONT, TICK))
                .axis_desc_style((FONT, DESC))
                .light_line_style(GRID)
                .draw()?;
            let area = frame(&root, &chart)?;
            chart.draw_series(LineSeries::new(
                [(x0, 0.0), (x1, 0.0)],
                INK.mix(0.6).stroke_width(1),
            ))?;
            for line in &lines {
                chart.draw_series(LineSeries::new(
                    line.iter().copied(),
                    colour.stroke_width(2),
                ))?;
            }
            if max.0.is_finite() && max.1.is_finite() {
                let at = chart.backend_coord(&max);
                let mut labels = Labels::new(area);
                labels.block_path(&pixels(&chart, &all));
                let s = format!("{what} {:.1} {unit} at {:.3} m", max.1.abs(), max.0);
                chart.draw_series([Circle::new(max, 4, colour.filled())])?;
                label(&root, &mut labels, &s, at, colour, false)?;
            }
        }
        root.present()?;
    }
    Ok(svg)
}
