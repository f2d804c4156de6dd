//! A study's plot: the histogram of one output over the samples, or the scatter of an output
//! against a parameter (each sample one point). Samples whose values are not numbers are left
//! out, and counted in the caption.

use serde_json::Value;

use super::axis::{Axis, extent};
use super::svg::{Anchor, Svg, text_width};
use super::{COLOURS, Err, range};
use crate::model::api::StudyResult;

const W: u32 = 760;
const H: u32 = 500;
const AREA: [f64; 4] = [90.0, 60.0, 730.0, 430.0];

fn number(v: Option<&Value>) -> Option<f64> {
    v.and_then(Value::as_f64).filter(|x| x.is_finite())
}

/// Histogram of output `k`, or its scatter against parameter `against`.
pub fn study(r: &StudyResult, k: usize, against: Option<usize>) -> Result<String, Err> {
    let output = r.outputs.get(k).ok_or("no such output")?;
    let mut svg = Svg::new(W, H);
    let ys: Vec<Option<f64>> = r.samples.iter().map(|s| number(s.outputs.get(k))).collect();
    match against {
        None => histogram(&mut svg, output, &ys),
        Some(j) => {
            let param = r.parameters.get(j).ok_or("no such parameter")?;
            let pts: Vec<(f64, f64)> = r
                .samples
                .iter()
                .zip(&ys)
                .filter_map(|(s, y)| Some((number(s.parameters.get(j))?, (*y)?)))
                .collect();
            let (xl, xh) = range(pts.iter().map(|p| p.0), 0.05);
            let (yl, yh) = range(pts.iter().map(|p| p.1), 0.05);
            let p = svg.panel(AREA, Axis::lin(xl, xh), Axis::lin(yl, yh));
            svg.axes(&p, param, output);
            for &pt in &pts {
                svg.circle_px(p.px(pt), 3.0, COLOURS[0], "none");
            }
            let left = r.samples.len() - pts.len();
            svg.caption(
                (f64::from(W) / 2.0, 30.0),
                &format!(
                    "{output} against {param}: {} samples ({left} not numbers)",
                    pts.len()
                ),
            );
        }
    }
    Ok(svg.finish())
}

/// The caption `full` if it fits the width, else `short` (the axes name the pointers).
fn caption(svg: &mut Svg, full: &str, short: &str) {
    // Bold: about a tenth wider than the estimate.
    let fits = 1.1 * text_width(full, 18.0) < f64::from(W) - 40.0;
    svg.caption((f64::from(W) / 2.0, 30.0), if fits { full } else { short });
}

fn histogram(svg: &mut Svg, output: &str, ys: &[Option<f64>]) {
    let x: Vec<f64> = ys.iter().flatten().copied().collect();
    let bins = ((x.len() as f64).sqrt().ceil() as usize).clamp(5, 40);
    let (lo, hi) = extent(x.iter().copied()).unwrap_or((0.0, 1.0));
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        (lo - 0.5, lo + 0.5)
    };
    let width = (hi - lo) / bins as f64;
    let mut counts = vec![0usize; bins];
    for v in &x {
        counts[(((v - lo) / width) as usize).min(bins - 1)] += 1;
    }
    let top = counts.iter().copied().max().unwrap_or(0).max(1) as f64;
    let p = svg.panel(AREA, Axis::lin(lo, hi), Axis::lin(0.0, top * 1.1));
    svg.axes(&p, output, "samples");
    for (i, &c) in counts.iter().enumerate() {
        let a = lo + i as f64 * width;
        let (x0, y0) = p.px((a, c as f64));
        let (x1, y1) = p.px((a + width, 0.0));
        svg.rect_px([x0, y0, x1, y1], COLOURS[0], 0.7, Some("#FFFFFF"));
    }
    let counts = format!("{} samples, {} not numbers", x.len(), ys.len() - x.len());
    caption(svg, &format!("{output}: {counts}"), &counts);
    if x.is_empty() {
        svg.text(
            ((AREA[0] + AREA[2]) / 2.0, (AREA[1] + AREA[3]) / 2.0),
            "no sample has a number here",
            14.0,
            Anchor::Middle,
            "#444444",
        );
    }
}
