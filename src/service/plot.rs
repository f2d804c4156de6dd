//! SVG plots of analysis results (plotters' SVG backend: no fonts needed on the server, the
//! viewer renders the text).

use plotters::prelude::*;

use crate::model::api::{
    CampbellResponse, StabilityResponse, TimeResponseResponse, UnbalanceResponseResponse, Whirl,
};

pub(crate) const RPM: f64 = 60.0 / (2.0 * std::f64::consts::PI);
const FORWARD: RGBColor = RGBColor(31, 119, 180);
const BACKWARD: RGBColor = RGBColor(214, 39, 40);
pub(crate) const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

/// Fill of a shaded operating range.
pub(crate) const SHADE: RGBAColor = RGBAColor(255, 170, 40, 0.22);

type Err = Box<dyn std::error::Error>;

/// `[lo, hi]` of finite values, padded; a flat or empty set gets a unit range.
pub(crate) fn range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
    (lo - pad * span, hi + pad * span)
}

/// Runs of consecutive defined points (a `null` breaks the line).
pub(crate) fn runs(xs: &[f64], ys: &[Option<f64>]) -> Vec<Vec<(f64, f64)>> {
    let mut out = vec![vec![]];
    for (x, y) in xs.iter().zip(ys) {
        match y {
            Some(y) if y.is_finite() => out.last_mut().expect("non-empty").push((*x, *y)),
            _ => {
                if !out.last().expect("non-empty").is_empty() {
                    out.push(vec![]);
                }
            }
        }
    }
    out.retain(|r| !r.is_empty());
    out
}

/// The series legend, boxed, at `pos`.
pub(crate) fn legend<'a, DB: DrawingBackend + 'a, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    pos: SeriesLabelPosition,
) -> Result<(), Err>
where
    CT: plotters::coord::CoordTranslate,
    DB::ErrorType: 'static,
{
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE.mix(0.85))
        .position(pos)
        .draw()?;
    Ok(())
}

/// One labelled line per node, in the palette's colours.
fn node_lines<'a, DB: DrawingBackend + 'a, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    xs: &[f64],
    nodes: &[(usize, Vec<f64>)],
) -> Result<(), Err>
where
    CT: plotters::coord::CoordTranslate<From = (f64, f64)>,
    DB::ErrorType: 'static,
{
    for (k, (node, ys)) in nodes.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        chart
            .draw_series(LineSeries::new(
                xs.iter().cloned().zip(ys.iter().cloned()),
                color.stroke_width(1),
            ))?
            .label(format!("node {node}"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    legend(chart, SeriesLabelPosition::UpperRight)
}

/// Campbell diagram (|frequency| against speed) over the decay-rate plot.
pub fn campbell(c: &CampbellResponse) -> Result<String, Err> {
    campbell_with(c, None)
}

/// `[lo, hi]` clipped to `[x0, x1]`, if they overlap.
fn clip(shade: Option<[f64; 2]>, x0: f64, x1: f64) -> Option<(f64, f64)> {
    let [lo, hi] = shade?;
    let (lo, hi) = (lo.min(hi).max(x0), hi.max(lo).min(x1));
    (lo.is_finite() && hi.is_finite() && hi > lo).then_some((lo, hi))
}

/// A vertical band `[lo, hi]` of x over `[y0, y1]`, labelled for the legend when `label`.
fn band<DB: DrawingBackend, CT>(
    chart: &mut ChartContext<'_, DB, CT>,
    (lo, hi): (f64, f64),
    (y0, y1): (f64, f64),
    label: bool,
) -> Result<(), Err>
where
    CT: plotters::coord::CoordTranslate<From = (f64, f64)>,
    DB::ErrorType: 'static,
{
    let series = chart.draw_series(std::iter::once(Rectangle::new(
        [(lo, y0), (hi, y1)],
        SHADE.filled(),
    )))?;
    if label {
        series
            .label("operating range")
            .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], SHADE.filled()));
    }
    Ok(())
}

/// [`campbell`] with the operating speeds `shade = [min, max]` (rad/s) shaded.
pub fn campbell_with(c: &CampbellResponse, shade: Option<[f64; 2]>) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 900)).into_drawing_area();
        root.fill(&WHITE)?;
        let (top, bottom) = root.split_vertically(470);
        let (x0, x1) = range(c.speeds.iter().cloned(), 0.0);
        let freqs = c
            .branches
            .iter()
            .flat_map(|b| b.frequency.iter().flatten().map(|f| f.abs()));
        let (_, f_hi) = range(freqs.chain(std::iter::once(0.0)), 0.05);
        let rates = c
            .branches
            .iter()
            .flat_map(|b| b.decay_rate.iter().flatten().cloned());
        let (d_lo, d_hi) = range(rates.chain(std::iter::once(0.0)), 0.08);

        let mut chart = ChartBuilder::on(&top)
            .caption("Campbell diagram", ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(70)
            .top_x_label_area_size(36)
            .build_cartesian_2d(x0..x1, 0.0..f_hi)?
            .set_secondary_coord(x0 * RPM..x1 * RPM, 0.0..f_hi);
        chart
            .configure_mesh()
            .x_desc("spin speed [rad/s]")
            .y_desc("whirl frequency |ω| [rad/s]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("spin speed [rpm]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_labels(0)
            .draw()?;
        let shade = clip(shade, x0, x1);
        if let Some(s) = shade {
            band(&mut chart, s, (0.0, f_hi), true)?;
        }
        // The 1x line: synchronous excitation.
        chart
            .draw_series(LineSeries::new(
                vec![(x0, x0), (x1, x1)],
                BLACK.mix(0.4).stroke_width(1),
            ))?
            .label("1x")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.4)));
        draw_branches(&mut chart, c, |b| &b.frequency, true)?;
        for &w in &c.critical_speeds {
            chart.draw_series(std::iter::once(Circle::new((w, w), 5, BLACK.filled())))?;
        }
        if let Some(t) = c.threshold {
            chart.draw_series(LineSeries::new(
                vec![(t, 0.0), (t, f_hi)],
                RED.stroke_width(2),
            ))?;
        }
        legend(&mut chart, SeriesLabelPosition::UpperLeft)?;

        let mut chart = ChartBuilder::on(&bottom)
            .caption("Decay-rate plot", ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, d_lo..d_hi)?;
        chart
            .configure_mesh()
            .x_desc("spin speed [rad/s]")
            .y_desc("decay rate σ [1/s]  (> 0 unstable)")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        if let Some(s) = shade {
            band(&mut chart, s, (d_lo, d_hi), false)?;
        }
        chart.draw_series(LineSeries::new(
            vec![(x0, 0.0), (x1, 0.0)],
            BLACK.stroke_width(1),
        ))?;
        draw_branches(&mut chart, c, |b| &b.decay_rate, false)?;
        for &w in &c.critical_speeds {
            chart.draw_series(DashedLineSeries::new(
                vec![(w, d_lo), (w, d_hi)],
                4,
                4,
                BLACK.mix(0.5).stroke_width(1),
            ))?;
        }
        if let Some(t) = c.threshold {
            chart
                .draw_series(LineSeries::new(
                    vec![(t, d_lo), (t, d_hi)],
                    RED.stroke_width(2),
                ))?
                .label(format!("threshold {t:.1} rad/s ({:.0} rpm)", t * RPM))
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
            legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
        }
        root.present()?;
    }
    Ok(svg)
}

fn draw_branches<DB: DrawingBackend, CT>(
    chart: &mut ChartContext<'_, DB, CT>,
    c: &CampbellResponse,
    values: impl Fn(&crate::model::api::Branch) -> &Vec<Option<f64>>,
    absolute: bool,
) -> Result<(), Err>
where
    CT: plotters::coord::CoordTranslate<From = (f64, f64)>,
    DB::ErrorType: 'static,
{
    let mut labelled = (false, false);
    for b in &c.branches {
        let ys: Vec<Option<f64>> = values(b)
            .iter()
            .map(|v| v.map(|x| if absolute { x.abs() } else { x }))
            .collect();
        for run in runs(&c.speeds, &ys) {
            let forward = b.whirl == Whirl::Forward;
            let style = if forward {
                FORWARD.stroke_width(2)
            } else {
                BACKWARD.stroke_width(2)
            };
            let series = if forward {
                chart.draw_series(LineSeries::new(run, style))?
            } else {
                chart.draw_series(DashedLineSeries::new(run, 8, 5, style))?
            };
            if absolute && forward && !labelled.0 {
                labelled.0 = true;
                series.label("forward").legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], FORWARD.stroke_width(2))
                });
            } else if absolute && !forward && !labelled.1 {
                labelled.1 = true;
                series.label("backward (dashed)").legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], BACKWARD.stroke_width(2))
                });
            }
        }
    }
    Ok(())
}

/// Largest decay rate against speed, the threshold marked.
pub fn stability(s: &StabilityResponse) -> Result<String, Err> {
    stability_with(s, None)
}

/// [`stability`] with the operating speeds `shade = [min, max]` (rad/s) shaded.
pub fn stability_with(s: &StabilityResponse, shade: Option<[f64; 2]>) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 520)).into_drawing_area();
        root.fill(&WHITE)?;
        let (x0, x1) = range(s.speeds.iter().cloned(), 0.0);
        let (y0, y1) = range(
            s.max_decay_rate.iter().cloned().chain(std::iter::once(0.0)),
            0.08,
        );
        let mut chart = ChartBuilder::on(&root)
            .caption("Stability: largest decay rate", ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .top_x_label_area_size(36)
            .build_cartesian_2d(x0..x1, y0..y1)?
            .set_secondary_coord(x0 * RPM..x1 * RPM, y0..y1);
        chart
            .configure_mesh()
            .x_desc("spin speed [rad/s]")
            .y_desc("largest decay rate σ [1/s]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("spin speed [rpm]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_labels(0)
            .draw()?;
        let shade = clip(shade, x0, x1);
        if let Some(b) = shade {
            band(&mut chart, b, (y0, y1), true)?;
        }
        chart.draw_series(LineSeries::new(
            vec![(x0, 0.0), (x1, 0.0)],
            BLACK.stroke_width(1),
        ))?;
        chart.draw_series(LineSeries::new(
            s.speeds
                .iter()
                .cloned()
                .zip(s.max_decay_rate.iter().cloned()),
            FORWARD.stroke_width(2),
        ))?;
        if let Some(t) = s.threshold {
            chart
                .draw_series(LineSeries::new(vec![(t, y0), (t, y1)], RED.stroke_width(2)))?
                .label(format!("threshold {t:.2} rad/s ({:.0} rpm)", t * RPM))
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
        }
        if s.threshold.is_some() || shade.is_some() {
            legend(&mut chart, SeriesLabelPosition::UpperRight)?;
        }
        root.present()?;
    }
    Ok(svg)
}

/// Whirl amplitude `|x + i y|` of each node against time.
pub fn time(r: &TimeResponseResponse) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 520)).into_drawing_area();
        root.fill(&WHITE)?;
        let (t0, t1) = range(r.time.iter().cloned(), 0.0);
        let amps: Vec<Vec<f64>> = r
            .nodes
            .iter()
            .map(|n| n.x.iter().zip(&n.y).map(|(x, y)| x.hypot(*y)).collect())
            .collect();
        let (_, a1) = range(
            amps.iter().flatten().cloned().chain(std::iter::once(0.0)),
            0.05,
        );
        let mut chart = ChartBuilder::on(&root)
            .caption("Time response: whirl amplitude", ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(t0..t1, 0.0..a1)?;
        chart
            .configure_mesh()
            .x_desc("time [s]")
            .y_desc("amplitude |x + i y| [m]")
            .y_label_formatter(&|v| format!("{v:.2e}"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        let lines: Vec<(usize, Vec<f64>)> =
            r.nodes.iter().zip(amps).map(|(n, a)| (n.node, a)).collect();
        node_lines(&mut chart, &r.time, &lines)?;
        root.present()?;
    }
    Ok(svg)
}

/// Orbit radius of each node against speed.
pub fn unbalance(r: &UnbalanceResponseResponse) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 520)).into_drawing_area();
        root.fill(&WHITE)?;
        let (x0, x1) = range(r.speeds.iter().cloned(), 0.0);
        let (_, a1) = range(
            r.nodes
                .iter()
                .flat_map(|n| n.amplitude.iter().cloned())
                .chain(std::iter::once(0.0)),
            0.05,
        );
        let mut chart = ChartBuilder::on(&root)
            .caption("Unbalance response", ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .top_x_label_area_size(36)
            .build_cartesian_2d(x0..x1, 0.0..a1)?
            .set_secondary_coord(x0 * RPM..x1 * RPM, 0.0..a1);
        chart
            .configure_mesh()
            .x_desc("spin speed [rad/s]")
            .y_desc("orbit radius [m]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.2e}"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("spin speed [rpm]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_labels(0)
            .draw()?;
        let lines: Vec<(usize, Vec<f64>)> = r
            .nodes
            .iter()
            .map(|n| (n.node, n.amplitude.clone()))
            .collect();
        node_lines(&mut chart, &r.speeds, &lines)?;
        root.present()?;
    }
    Ok(svg)
}
