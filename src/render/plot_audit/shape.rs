//! The mode shapes of the report's unbalance cases: each mode's signed major semi-axis along
//! the shaft, the bearings and the unbalances marked.

use super::*;
use crate::model::api::UnbalanceCase;

/// One line per case (its shape scaled to 1 where it moves most) against axial position;
/// bearings as triangles on the axis, unbalances as filled dots on their mode.
pub fn mode_shapes(cases: &[UnbalanceCase], bearings: &[f64]) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 420)).into_drawing_area();
        root.fill(&WHITE)?;
        let xs = cases
            .iter()
            .flat_map(|c| c.shape.iter().map(|p| p.position))
            .chain(bearings.iter().copied());
        let (x0, x1) = range(xs, 0.02);
        // Room above the shapes (scaled to 1) for the key, one line per case.
        let top = 1.3 + 0.22 * cases.len() as f64;
        let mut chart = ChartBuilder::on(&root)
            .caption("Mode shapes at the critical speeds", (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, -1.25..top)?;
        chart
            .configure_mesh()
            .x_desc("axial position [m]")
            .y_desc("major semi-axis (scaled)")
            .x_label_formatter(&lin_tick(x1 - x0))
            .y_label_formatter(&lin_tick(top + 1.25))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        frame(&root, &chart)?;
        chart.draw_series(LineSeries::new(
            [(x0, 0.0), (x1, 0.0)],
            INK.mix(0.6).stroke_width(1),
        ))?;
        for (k, c) in cases.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            // The interpolated shape where there is one, else the nodes joined straight.
            let pts: Vec<(f64, f64)> = if c.shape_curve.is_empty() {
                c.shape.iter().map(|p| (p.position, p.value)).collect()
            } else {
                c.shape_curve.iter().map(|p| (p[0], p[1])).collect()
            };
            let pts: Vec<(f64, f64)> = pts
                .into_iter()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), colour.stroke_width(2)))?
                .label(format!(
                    "mode {} at {:.0} rpm",
                    c.mode,
                    c.critical_speed * RPM
                ))
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            let loaded = c.unbalances.iter().filter_map(|u| {
                c.shape
                    .iter()
                    .find(|p| p.node == u.node)
                    .map(|p| Circle::new((p.position, p.value), 6, colour.filled()))
            });
            chart.draw_series(loaded)?;
        }
        let tri = bearings.iter().map(|&x| {
            let at = chart.backend_coord(&(x, 0.0));
            Polygon::new(
                vec![(at.0, at.1), (at.0 - 8, at.1 + 12), (at.0 + 8, at.1 + 12)],
                PALETTE[1].filled(),
            )
        });
        for t in tri {
            root.draw(&t)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(INK.mix(0.4))
            .label_font((FONT, NOTE))
            .draw()?;
        root.present()?;
    }
    Ok(svg)
}
