//! `cargo build --release` and `cargo test --release` build every shared crate with the same
//! features, so the test build after a release build compiles only the crate and its tests
//! (and the few dev-dependencies), not again the crates whose features a dev-dependency would
//! change (tempfile once turned on bitflags' `std` and rebuilt 21 crates, about 7 minutes).

use std::collections::{BTreeMap, BTreeSet};
use std::process::Command;

/// Package -> its feature sets (one for the target, maybe another for build scripts and
/// macros), as cargo resolves them with these edges.
fn features(edges: &str) -> BTreeMap<String, BTreeSet<String>> {
    let out = Command::new(env!("CARGO"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "tree", "--locked", "--prefix", "none", "-f", "{p}|{f}", "-e", edges,
        ])
        .output()
        .expect("cargo tree runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut all: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for l in String::from_utf8(out.stdout).unwrap().lines() {
        let Some((p, f)) = l.split_once('|') else {
            continue;
        };
        // `(*)` marks a package already printed; `(proc-macro)` its kind.
        let p = p.replace(" (proc-macro)", "");
        let f = f.trim_end_matches(" (*)").trim().to_string();
        all.entry(p.trim().to_string()).or_default().insert(f);
    }
    all
}

#[test]
fn tests_build_the_shared_crates_with_the_release_build_features() {
    let build = features("normal,build");
    let test = features("normal,build,dev");
    let differ: Vec<String> = build
        .iter()
        .filter_map(|(p, f)| {
            let t = test.get(p)?;
            (t != f).then(|| format!("{p}: build {f:?}, test {t:?}"))
        })
        .collect();
    assert!(build.len() > 200, "{} packages", build.len());
    assert!(
        differ.is_empty(),
        "features differ between the build and the tests (ask for the test's features in \
         [dependencies]):\n{}",
        differ.join("\n")
    );
}
