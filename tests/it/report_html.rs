//! The audit page on the sample answers of `report_sample.rs`: its plots, verdict and
//! escaping; and `dump` (ignored), which writes every plot and the page to /tmp/whirl_report/:
//! `cargo test --release --test report_html -- --ignored dump`.

use crate::common;
use crate::report_sample as sample;

use sample::*;
use whirl::render::plot::campbell_with;
use whirl::render::plot_audit::*;
use whirl::render::report::{escape, html};

#[test]
fn report_page_holds_every_plot_and_check() {
    let r = report();
    let page = html(&r, &rotor()).unwrap();
    assert!(page.starts_with("<!DOCTYPE html>"));
    assert_eq!(
        page.matches("<svg ").count(),
        6,
        "sketch, map, static, Campbell, unbalance, Level I"
    );
    assert_eq!(page.matches("<tr class=\"check ").count(), r.checks.len());
    assert_eq!(page.matches("<tr class=\"check fail\">").count(), 1);
    assert!(page.contains("1 of 5 checks fail."));
    for external in ["<script", "<link", "src=", "href=", "url(", "@import"] {
        assert!(!page.contains(external), "{external}");
    }
    // The models side by side: one column each.
    let models = &page[page.find("id=\"models\"").unwrap()..];
    let head = &models[models.find("<thead>").unwrap()..models.find("</thead>").unwrap()];
    assert_eq!(head.matches("<th>").count(), 1 + r.models.len());
    assert!(
        page.contains("534.") && page.contains("54.5"),
        "total weight, N and kg"
    );
    assert!(page.contains("elements / nodes</th><td>10 / 11"));
    finite_text(&page);
}

#[test]
fn report_page_escapes_text() {
    let mut r = report();
    r.models[0].model = "<script>alert('x')</script> & co".into();
    r.checks[0].value = "<b>31%</b>".into();
    r.warnings
        .push("support \"A\" <held> at its table's end".into());
    let page = html(&r, &rotor()).unwrap();
    assert!(!page.contains("<script>") && !page.contains("<b>31%"));
    assert!(page.contains("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; co"));
    assert!(page.contains("support &quot;A&quot; &lt;held&gt; at its table&#39;s end"));
    assert_eq!(escape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&#39;");
}

/// Writes every plot and the page to /tmp/whirl_report/ (`-- --ignored dump`).
#[test]
#[ignore]
fn dump() {
    let dir = std::path::Path::new("/tmp/whirl_report");
    std::fs::create_dir_all(dir).unwrap();
    let r = report();
    let range = Some([180.0, 300.0]);
    let files = [
        (
            "map.svg",
            critical_speed_map_with(&r.critical_speed_map, range).unwrap(),
        ),
        (
            "static.svg",
            static_deflection(&r.static_deflection).unwrap(),
        ),
        ("level1.svg", level1(&r.level1).unwrap()),
        (
            "frequency.svg",
            frequency_response(&frequency_data()).unwrap(),
        ),
        ("sketch.svg", rotor_sketch(&rotor()).unwrap()),
        ("sketch_dense.svg", rotor_sketch(&dense_rotor()).unwrap()),
        (
            "unbalance.svg",
            unbalance_with(&r.unbalance, range).unwrap(),
        ),
        ("campbell.svg", campbell_with(&r.campbell, range).unwrap()),
        ("report.html", html(&r, &rotor()).unwrap()),
    ];
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    eprintln!("wrote {}", dir.display());
}

/// The examples' answers from the in-process service, rendered to /tmp/whirl_report/real_*
/// (`-- --ignored dump_examples`): the plots on computed data, the page as the service serves it.
#[tokio::test]
#[ignore]
async fn dump_examples() {
    use whirl::model::api::*;
    let dir = std::path::Path::new("/tmp/whirl_report");
    std::fs::create_dir_all(dir).unwrap();
    let example = |name: &str| -> serde_json::Value {
        let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    };
    async fn answer<T: serde::de::DeserializeOwned>(uri: &str, body: &serde_json::Value) -> T {
        let (status, v) = common::post_json(uri, body).await;
        assert_eq!(status, 200, "{uri}: {v}");
        serde_json::from_value(v).unwrap()
    }
    let report = example("rotor-a-nvd.report.json");
    let r: ReportResponse = answer("/v1/report", &report).await;
    let range = Some([r.operating_range.min, r.operating_range.max]);
    let map: CriticalSpeedMapResponse = answer(
        "/v1/critical-speed-map",
        &example("rotor-a.critical-speed-map.json"),
    )
    .await;
    let statics: StaticResponse =
        answer("/v1/static", &example("ross-rotor-example.static.json")).await;
    let level: Level1Response =
        answer("/v1/level1", &example("example1-hysteretic.level1.json")).await;
    let frf: FrequencyResponseResponse = answer(
        "/v1/frequency-response",
        &example("example1-hysteretic.frequency-response.json"),
    )
    .await;
    let (status, _, page) = common::post_as("/v1/report", &report, "text/html").await;
    assert_eq!(status, 200);
    let files = [
        (
            "real_report_map.svg",
            critical_speed_map_with(&r.critical_speed_map, range).unwrap(),
        ),
        (
            "real_report_static.svg",
            static_deflection(&r.static_deflection).unwrap(),
        ),
        ("real_report_level1.svg", level1(&r.level1).unwrap()),
        (
            "real_report_unbalance.svg",
            unbalance_with(&r.unbalance, range).unwrap(),
        ),
        (
            "real_report_campbell.svg",
            campbell_with(&r.campbell, range).unwrap(),
        ),
        ("real_report_sketch.svg", rotor_sketch(&r.rotor).unwrap()),
        ("real_map.svg", critical_speed_map(&map).unwrap()),
        ("real_static.svg", static_deflection(&statics).unwrap()),
        ("real_level1.svg", level1(&level).unwrap()),
        ("real_frequency.svg", frequency_response(&frf).unwrap()),
        ("real_report.html", String::from_utf8(page).unwrap()),
    ];
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
}
