//! JSON pointers (RFC 6901): checked strictly (serde_json's own lookup accepts some malformed
//! escapes), then resolved with serde_json.

use serde_json::Value;

/// Checks the syntax of `p`: empty (the whole document) or `/`-separated tokens in which `~`
/// is only `~0` or `~1`.
pub fn check(p: &str) -> Result<(), String> {
    if p.is_empty() {
        return Ok(());
    }
    if !p.starts_with('/') {
        return Err(format!(
            "{p:?} is not a JSON pointer (RFC 6901): it starts with `/`, e.g. \"/rotor/mass\""
        ));
    }
    let bytes = p.as_bytes();
    for (i, b) in bytes.iter().enumerate() {
        if *b == b'~' && !matches!(bytes.get(i + 1), Some(b'0' | b'1')) {
            return Err(format!(
                "{p:?}: `~` must be followed by 0 (for `~`) or 1 (for `/`) in a JSON pointer"
            ));
        }
    }
    Ok(())
}

/// The value `p` (checked) names in `doc`.
pub fn get<'a>(doc: &'a Value, p: &str) -> Option<&'a Value> {
    doc.pointer(p)
}

/// Replaces the value `p` names in `doc`; `false` if there is none.
pub fn set(doc: &mut Value, p: &str, v: Value) -> bool {
    match doc.pointer_mut(p) {
        Some(slot) => {
            *slot = v;
            true
        }
        None => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn pointers_resolve_and_reject_bad_escapes() {
        let mut doc = json!({"rotor": {"a/b": 1, "m~n": 2, "list": [10, 20]}});
        for p in ["", "/rotor", "/rotor/a~1b", "/rotor/m~0n", "/rotor/list/1"] {
            assert!(check(p).is_ok(), "{p}");
        }
        assert_eq!(get(&doc, "/rotor/a~1b"), Some(&json!(1)));
        assert_eq!(get(&doc, "/rotor/m~0n"), Some(&json!(2)));
        assert_eq!(get(&doc, "/rotor/list/1"), Some(&json!(20)));
        assert_eq!(get(&doc, "/rotor/missing"), None);
        assert!(check("rotor/mass").is_err());
        assert!(check("/rotor/~2").is_err());
        assert!(check("/rotor/~").is_err());
        assert!(set(&mut doc, "/rotor/list/0", json!(5)));
        assert_eq!(doc["rotor"]["list"][0], 5);
        assert!(!set(&mut doc, "/rotor/nothing/here", json!(5)));
    }
}
