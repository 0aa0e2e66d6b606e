//! rt-std and the contract (`rt-abi`) agree. Most of it holds by
//! construction: `#[rt_intrinsic]` writes each intrinsic function's callers
//! doc line and OptiX alias from its row and checks its signature against
//! the row at rt-std's build; this file checks what is left: that every row
//! has its item in rt-std's prelude (at compile time, below), and the one
//! intrinsic that is a `macro_rules!` (`rt_printf!`, which an attribute
//! macro cannot mark) documents its row by hand.

use rt_compiler::kinds::INTRINSICS;

/// Compiles only if rt-std's prelude exports every row's name.
macro_rules! every_row_is_in_the_prelude {
    ($($name:ident),*) => {
        #[allow(unused_imports)]
        use rt_std::prelude::{$($name),*};
        const ROWS: &[&str] = &[$(stringify!($name)),*];
    };
}
rt_macros::__rt_intrinsic_names!(every_row_is_in_the_prelude);

#[test]
fn the_prelude_check_covers_every_row() {
    assert_eq!(ROWS.len(), INTRINSICS.len());
    assert!(ROWS.iter().zip(INTRINSICS).all(|(n, i)| *n == i.name));
}

#[test]
fn rt_printf_documents_its_row() {
    let text = include_str!("../../rt-std/src/intrinsics.rs");
    let row = rt_abi::intrinsic("rt_printf").unwrap();
    let at = text.find("macro_rules! rt_printf {").expect("rt-std defines rt_printf!");
    let doc: Vec<&str> = text[..at].lines().rev().take_while(|l| l.starts_with("///") || l.starts_with("#[")).collect();
    assert!(doc.contains(&format!("/// {}", row.callers.doc_line()).as_str()), "rt_printf!'s docs: {doc:?}");
    assert!(doc.contains(&format!("#[doc(alias = \"{}\")]", row.optix).as_str()), "rt_printf!'s docs: {doc:?}");
}

#[test]
fn every_kind_has_a_distinct_name() {
    let names: std::collections::HashSet<&str> = rt_compiler::kinds::ALL_KINDS.iter().map(|k| k.name()).collect();
    assert_eq!(names.len(), rt_compiler::kinds::ALL_KINDS.len());
    for k in rt_compiler::kinds::ALL_KINDS {
        assert_eq!(rt_compiler::Kind::from_name(k.name()), Some(k));
    }
}
