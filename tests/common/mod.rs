//! Helpers shared by the integration tests.
#![allow(dead_code)]

/// Asserts that `value` rounds to `printed` at the printed number of decimals, i.e. agrees to
/// every printed digit: `|value - printed| <= 0.5 ulp(printed)` (plus round-off).
pub fn assert_printed(value: f64, printed: &str, what: &str) {
    let p: f64 = printed.parse().unwrap();
    let decimals = printed.split('.').nth(1).map_or(0, |d| d.len());
    let half = 0.5 * 10f64.powi(-(decimals as i32));
    assert!(
        (value - p).abs() <= half * (1.0 + 1e-9),
        "{what}: computed {value}, printed {printed}"
    );
}
