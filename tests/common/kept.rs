//! Answers that take minutes to compute (dense references on rotors of a thousand coordinates)
//! computed once and kept as data in `tests/data/kept/`, with the request they answer.
//!
//! A test asks for `kept(group, uri, body, keep)`: the part `keep` selects of the in-process
//! service's answer to `body`, read from `tests/data/kept/GROUP/SHA.json`, SHA the first 16
//! hex digits of the SHA-256 of the request (uri and compact JSON), so that a file answers
//! that very request; a missing file fails, saying how to write it.
//! `WHIRL_KEEP=1 cargo test --release --test it -- GROUP` recomputes and writes the files of
//! the tests that filter selects (the script that makes them).

use sha2::{Digest, Sha256};

fn digest(uri: &str, body: &serde_json::Value) -> String {
    let mut h = Sha256::new();
    h.update(uri.as_bytes());
    h.update(b"\n");
    h.update(body.to_string().as_bytes());
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// The part `keep` selects of the 200 answer to `POST uri body`, as kept (module docs).
pub async fn kept(
    group: &str,
    uri: &str,
    body: &serde_json::Value,
    keep: impl Fn(&serde_json::Value) -> serde_json::Value,
) -> serde_json::Value {
    let sha = digest(uri, body);
    let path = format!(
        "{}/tests/data/kept/{group}/{}.json",
        env!("CARGO_MANIFEST_DIR"),
        &sha[..16]
    );
    if std::env::var_os("WHIRL_KEEP").is_some() {
        // A reference may take longer than a synchronous request may (60 s).
        let config = whirl::service::Config {
            request_time_limit: std::time::Duration::from_secs(3600),
            ..whirl::service::Config::default()
        };
        let (status, _, bytes) = super::post_to(config, uri, body, "application/json").await;
        let answer: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
        assert_eq!(status, 200, "{group}: {answer}");
        let part = keep(&answer);
        let file = serde_json::json!({"uri": uri, "request_sha256": sha, "answer": part});
        std::fs::create_dir_all(std::path::Path::new(&path).parent().unwrap()).unwrap();
        std::fs::write(&path, serde_json::to_string(&file).unwrap()).unwrap();
        return part;
    }
    let again = format!("write it: WHIRL_KEEP=1 cargo test --release --test it -- {group}");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}; {again}"));
    let file: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(
        file["uri"] == uri && file["request_sha256"] == sha.as_str(),
        "{path} answers another request; {again}"
    );
    file["answer"].clone()
}

/// The poles of a `/v1/modal` answer, without their shapes.
pub fn poles(answer: &serde_json::Value) -> serde_json::Value {
    let poles: Vec<serde_json::Value> = answer["poles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let mut q = p.clone();
            if let Some(o) = q.as_object_mut() {
                o.remove("shape");
            }
            q
        })
        .collect();
    serde_json::json!({"poles": poles, "natural_frequencies": answer["natural_frequencies"]})
}
