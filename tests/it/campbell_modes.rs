//! `modes: N` on a Campbell sweep: the N branches of lowest |frequency| at the first speed,
//! as ROSS's `run_campbell(frequencies=N)` returns them, equal to those branches of the
//! unbounded sweep of the full model.

use serde_json::{Value, json};

use crate::common;

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn branch<'a>(c: &'a Value, mode: &Value, whirl: &Value) -> &'a Value {
    c["branches"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| &b["mode"] == mode && &b["whirl"] == whirl)
        .unwrap_or_else(|| panic!("no branch {mode} {whirl}"))
}

/// Largest |s - s_full| / |s_full| over the kept branches and speeds.
fn worst(bounded: &Value, full: &Value) -> f64 {
    let mut worst: f64 = 0.0;
    for b in bounded["branches"].as_array().unwrap() {
        let f = branch(full, &b["mode"], &b["whirl"]);
        for k in 0..b["frequency"].as_array().unwrap().len() {
            let (w, d) = (b["frequency"][k].as_f64(), b["decay_rate"][k].as_f64());
            let (wf, df) = (f["frequency"][k].as_f64(), f["decay_rate"][k].as_f64());
            let (Some(w), Some(d), Some(wf), Some(df)) = (w, d, wf, df) else {
                assert_eq!(w.is_some(), wf.is_some(), "defined alike");
                continue;
            };
            let e = ((w - wf).powi(2) + (d - df).powi(2)).sqrt() / wf.hypot(df);
            worst = worst.max(e);
        }
    }
    worst
}

/// |frequency| of every branch of `c` at the first speed, ascending.
fn first_frequencies(c: &Value) -> Vec<f64> {
    let mut f: Vec<f64> = c["branches"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|b| b["frequency"][0].as_f64().map(f64::abs))
        .collect();
    f.sort_by(f64::total_cmp);
    f
}

async fn check(name: &str, speeds: Value, n: usize) -> Value {
    let mut body = example(name);
    body["speeds"] = speeds;
    body.as_object_mut().unwrap().remove("max_frequency");
    body["modal_reduction"] = json!(false);
    let (status, full) = common::post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{full}");
    body["modal_reduction"] = json!(true);
    body["modes"] = json!(n);
    let (status, bounded) = common::post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{bounded}");

    assert_eq!(bounded["branches"].as_array().unwrap().len(), n, "{name}");
    // The lowest n of the full sweep at the first speed, and the same branches throughout.
    let lowest = first_frequencies(&full);
    let kept = first_frequencies(&bounded);
    for (a, b) in kept.iter().zip(&lowest[..n]) {
        assert!((a - b).abs() <= 1e-6 * b, "{name}: {a} vs {b}");
    }
    let e = worst(&bounded, &full);
    assert!(e <= 1e-6, "{name}: {e:e}");
    println!(
        "{name}: {n} branches, reduction {}, worst {e:.1e}",
        bounded["reduction"]
    );
    bounded
}

#[tokio::test]
async fn the_lowest_branches_of_example1_equal_the_full_sweep() {
    let speeds = json!({"start": 0, "stop": 3000, "count": 31});
    for n in [1, 2, 3, 5] {
        check("example1-nvd.campbell.json", speeds.clone(), n).await;
        check("example1-equivalent.campbell.json", speeds.clone(), n).await;
    }
}

#[tokio::test]
async fn the_six_lowest_branches_of_the_compressor_run_on_a_checked_reduction() {
    let speeds = json!({"start": 0, "stop": 2000, "count": 21});
    let r = check("compressor-nvd.campbell.json", speeds, 6).await;
    let red = &r["reduction"];
    assert!(red.is_object(), "the bound engages the reduction: {red}");
    assert!(red["max_relative_error"].as_f64().unwrap() <= 1e-6);
}

#[tokio::test]
async fn modes_out_of_range_are_422_naming_the_field() {
    let mut body = example("example1-nvd.campbell.json");
    for bad in [json!(0), json!(-3), json!(1000)] {
        body["modes"] = bad.clone();
        let (status, p) = common::post_json("/v1/campbell", &body).await;
        assert_eq!(status, 422, "{bad}: {p}");
        assert_eq!(p["errors"][0]["path"], "modes", "{p}");
    }
}
