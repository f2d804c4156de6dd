//! The settings table of docs/operations.md is `whirl --help`'s list of settings, row for row: a setting
//! added, renamed or reworded in `SETTINGS` fails here until the page says the same. On a
//! difference the test prints the table to paste.

use std::process::Command;

/// `(variable, default, meaning)` of every setting `whirl --help` lists.
fn help_settings() -> Vec<(String, String, String)> {
    let out = Command::new(env!("CARGO_BIN_EXE_whirl"))
        .arg("--help")
        .output()
        .expect("whirl --help runs");
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let list = text
        .split_once("settings (environment variables, default in brackets):\n")
        .expect("--help lists the settings")
        .1;
    let mut rows = vec![];
    let mut lines = list.lines();
    while let Some(line) = lines.next() {
        let head = line.trim();
        let (var, default) = head
            .split_once(" [")
            .unwrap_or_else(|| panic!("a setting line: {line:?}"));
        let default = default.strip_suffix(']').expect("default in brackets");
        let meaning = lines.next().expect("a meaning under each setting").trim();
        rows.push((var.to_string(), default.to_string(), meaning.to_string()));
    }
    rows
}

/// The table as docs/operations.md must have it.
fn table(rows: &[(String, String, String)]) -> String {
    let mut t = String::from("| variable | default | meaning |\n|---|---|---|\n");
    for (var, default, meaning) in rows {
        t.push_str(&format!("| `{var}` | {default} | {meaning} |\n"));
    }
    t
}

#[test]
fn the_readme_settings_table_is_whirl_help() {
    let rows = help_settings();
    assert!(rows.len() >= 29, "{rows:?}");
    assert!(rows.iter().any(|r| r.0 == "WHIRL_MAX_STEPS"));
    let expected = table(&rows);
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/operations.md"))
            .unwrap();
    let start = readme
        .find("| variable | default | meaning |")
        .expect("docs/operations.md has the settings table");
    let end = readme[start..]
        .find("\n\n")
        .map_or(readme.len(), |e| start + e + 1);
    let actual = &readme[start..end];
    if actual != expected {
        for (a, e) in actual.lines().zip(expected.lines()) {
            if a != e {
                eprintln!("docs:      {a}\n--help:    {e}");
            }
        }
        panic!(
            "docs/operations.md's settings table differs from `whirl --help`; replace it with:\n\n{expected}"
        );
    }
}
