//! The API 684 report of a rotor held sparse: every part of it (map, statics, Campbell,
//! unbalance responses and their cases, Level I) on the sparse path, for the four models the
//! report compares by default (the equivalent and nonviscous models' dampers on the lowest
//! modes). The bundled train at 1080 elements (past WHIRL_MAX_DOFS) against the same report at
//! 180 elements (held sparse too where a part may be) and at 18 (dense).

use crate::common;

use common::post_json;
use serde_json::{Value, json};

fn train(k: usize) -> Value {
    let example: Value = serde_json::from_str(
        &std::fs::read_to_string("examples/train-hysteretic.campbell.json").unwrap(),
    )
    .unwrap();
    common::refined(&example["rotor"], k).0
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// The headline numbers of a report: the forward critical speeds of its Campbell diagram, its
/// unbalance cases' critical speeds, and each model's log decrement (Level I).
fn headline(r: &Value) -> Vec<f64> {
    let mut out: Vec<f64> = r["campbell"]["critical_speeds"]
        .as_array()
        .unwrap()
        .iter()
        .map(f)
        .collect();
    out.extend(
        r["unbalance_cases"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| f(&c["critical_speed"])),
    );
    out.extend(
        r["models"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| f(&m["log_decrement"])),
    );
    out
}

#[tokio::test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
async fn train_report_held_sparse() {
    let body = |k: usize| {
        json!({"rotor": train(k), "damping": {"model": "hysteretic"},
               "operating_range": {"min": 250, "max": 350}})
    };
    let mut heads = vec![];
    for k in [1, 10, 60] {
        let t = std::time::Instant::now();
        let (status, r) = post_json("/v1/report", &body(k)).await;
        assert_eq!(status, 200, "{r}");
        let h = headline(&r);
        eprintln!(
            "train x{k}: report in {:.1} s, {} unbalance cases, unbalance {:?}, Level I {:?}: {h:?}",
            t.elapsed().as_secs_f64(),
            r["unbalance_cases"].as_array().unwrap().len(),
            r["unbalance"]["full_model"],
            r["level1"]["reduction"]["full_model"],
        );
        assert_eq!(r["models"].as_array().unwrap().len(), 4);
        if k == 60 {
            assert_eq!(r["unbalance"]["full_model"], "sparse");
            assert_eq!(r["campbell"]["reduction"]["full_model"], "sparse");
            assert!(!r["unbalance_cases"].as_array().unwrap().is_empty());
        }
        heads.push(h);
    }
    let worst = |a: &[f64], b: &[f64]| {
        assert_eq!(a.len(), b.len(), "{a:?} {b:?}");
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs() / y.abs())
            .fold(0.0, f64::max)
    };
    let fine = worst(&heads[2], &heads[1]);
    let coarse = worst(&heads[2], &heads[0]);
    eprintln!("1080 vs 180 elements {fine:.1e}, vs 18 {coarse:.1e}");
    assert!(fine <= 1e-5, "{fine:e}");
    assert!(coarse <= 1e-3, "{coarse:e}");
}
