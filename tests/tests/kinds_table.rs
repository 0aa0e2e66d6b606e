//! rt-std's docs and the compiler's table of intrinsics agree: each
//! kind-restricted intrinsic documents exactly the program kinds the
//! compiler lets call it, and carries its OptiX name as a doc alias.

use rt_compiler::kinds::INTRINSICS;

/// The doc comment and attributes directly above `pub fn name` or
/// `macro_rules! name` in rt-std's sources.
fn doc_of(name: &str) -> Option<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../rt-std/src");
    for e in std::fs::read_dir(dir).unwrap() {
        let text = std::fs::read_to_string(e.unwrap().path()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let pos = lines.iter().position(|l| {
            let l = l.trim_start();
            l.starts_with(&format!("pub fn {name}("))
                || l.starts_with(&format!("pub fn {name}<"))
                || *l == format!("macro_rules! {name} {{")
        });
        if let Some(pos) = pos {
            let mut doc = Vec::new();
            for l in lines[..pos].iter().rev() {
                let t = l.trim_start();
                if t.starts_with("///") || t.starts_with("#[") {
                    doc.push(t.to_string());
                } else {
                    break;
                }
            }
            doc.reverse();
            return Some(doc.join("\n"));
        }
    }
    None
}

#[test]
fn rt_std_docs_match_the_compiler_table() {
    for i in INTRINSICS {
        let doc = doc_of(i.name).unwrap_or_else(|| panic!("rt-std has no `{}`", i.name));
        let line = format!("/// {}", i.callers.doc_line());
        assert!(
            doc.lines().any(|l| l == line),
            "`{}` should document `{}`, its docs are:\n{doc}",
            i.name,
            i.callers.doc_line()
        );
        let alias = format!("#[doc(alias = \"{}\")]", i.optix);
        assert!(doc.contains(&alias), "`{}` should carry {alias}", i.name);
    }
}

#[test]
fn every_kind_has_a_distinct_name() {
    let names: std::collections::HashSet<&str> = rt_compiler::kinds::ALL_KINDS.iter().map(|k| k.name()).collect();
    assert_eq!(names.len(), 8);
    for k in rt_compiler::kinds::ALL_KINDS {
        assert_eq!(rt_compiler::Kind::from_name(k.name()), Some(k));
    }
}
