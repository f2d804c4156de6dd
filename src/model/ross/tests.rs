use super::*;

#[test]
fn positions_count_lines_and_characters() {
    let text = "a = 1\nbé = [1,\n 2]\n";
    assert_eq!(position(text, 0), (1, 1));
    assert_eq!(position(text, 6), (2, 1));
    // After "bé = " (é is 2 bytes): the 6th character.
    assert_eq!(position(text, 12), (2, 6));
}

#[test]
fn numbers_take_integers_floats_and_refuse_the_rest() {
    let t =
        DeTable::parse("a = 3\nb = 1e-05\nc = 0x10\nd = \"x\"\ne = inf\nf = 1_000.5\n").unwrap();
    let t = t.get_ref();
    let get = |k: &str| number(t.get(k).unwrap().get_ref());
    assert_eq!(get("a"), Ok(3.0));
    assert_eq!(get("b"), Ok(1e-5));
    assert_eq!(get("c"), Ok(16.0));
    assert_eq!(get("f"), Ok(1000.5));
    assert!(get("d").unwrap_err().contains("string"));
    assert!(get("e").unwrap_err().contains("finite"));
}
