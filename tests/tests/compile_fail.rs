//! Compile-fail tests: each file in `compile_fail/` is a small program with
//! one mistake, and its `.stderr` is what the user sees. Every error must
//! point at the offending token and say what to write instead. Regenerate
//! with `TRYBUILD=overwrite cargo test -p rt-tests --test compile_fail`, then
//! read every changed `.stderr`.

#[test]
fn compile_fail() {
    let t = trybuild::TestCases::new();
    t.compile_fail("compile_fail/*.rs");
}
