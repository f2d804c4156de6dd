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

/// POSTs `body` to the in-process app (no socket) and returns the status and the JSON answer.
pub async fn post_json(uri: &str, body: &serde_json::Value) -> (u16, serde_json::Value) {
    let (status, _, bytes) = post_as(uri, body, "application/json").await;
    (
        status,
        serde_json::from_slice(&bytes).expect("a JSON answer"),
    )
}

/// POSTs `body` asking for `accept`: status, content type and body.
pub async fn post_as(uri: &str, body: &serde_json::Value, accept: &str) -> (u16, String, Vec<u8>) {
    use http_body_util::BodyExt;
    use tower::ServiceExt;
    let req = axum::http::Request::builder()
        .method("POST")
        .uri(uri)
        .header("content-type", "application/json")
        .header("accept", accept)
        .body(axum::body::Body::from(body.to_string()))
        .unwrap();
    let resp = whirl::service::app(whirl::service::Config::default())
        .oneshot(req)
        .await
        .unwrap();
    let status = resp.status().as_u16();
    let ctype = resp
        .headers()
        .get("content-type")
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let bytes = resp
        .into_body()
        .collect()
        .await
        .unwrap()
        .to_bytes()
        .to_vec();
    (status, ctype, bytes)
}
