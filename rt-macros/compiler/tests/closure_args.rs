//! Closures given to generic helpers: the call inlined where it is
//! written, so no helper function is emitted for it; what an inlined body
//! cannot do is an error naming the helper.

mod common;

const APPLY: &str = "#[rt_function] pub fn apply<F: Fn(f32) -> f32>(f: F, x: f32) -> f32 { let y = f(x); y + f(1.0) }";

#[test]
fn a_call_given_a_closure_is_inlined() {
    let l = common::lower(APPLY, "let k = x * 2.0; out[i] = apply(|a: f32| a * k, x);").unwrap();
    assert!(!l.wgsl.contains("fn rtf_apply"), "{}", l.wgsl);
    // The helper's local, renamed apart from the caller's names.
    assert!(l.wgsl.contains("y_rt_inl1"), "{}", l.wgsl);
}

#[test]
fn an_impl_fn_parameter_and_a_helper_declared_in_the_body_are_inlined_too() {
    let l = common::lower(
        "",
        "fn twice(f: impl Fn(u32) -> u32, v: u32) -> u32 { f(f(v)) }
         out[i] = twice(|a| a + y, i) as f32;",
    )
    .unwrap();
    assert!(!l.wgsl.contains("twice"), "{}", l.wgsl);
}

#[test]
fn what_an_inlined_body_cannot_do_is_an_error_naming_the_helper() {
    let early = "#[rt_function] pub fn early<F: Fn(f32) -> f32>(f: F, x: f32) -> f32 { if x > 0.0 { return f(x); } x }";
    assert_eq!(
        common::lower(early, "out[i] = early(|a: f32| a, x);").unwrap_err(),
        "`early` is given a closure, so it is inlined where it is called, and its body returns early: give it one \
         value at its end"
    );
    let by_ref = "#[rt_function] pub fn add_to<F: Fn() -> f32>(f: F, acc: &mut f32) { *acc += f(); }";
    assert_eq!(
        common::lower(by_ref, "let mut s = 0.0; add_to(|| x, &mut s); out[i] = s;").unwrap_err(),
        "`add_to` is given a closure, so it is inlined where it is called, and it takes a reference: pass the value \
         and return the result"
    );
    assert_eq!(
        common::lower(APPLY, "let g = |a: f32| a * 2.0; out[i] = apply(g, x);").unwrap_err(),
        "a closure given to `apply` is inlined where it is written: pass the closure itself here (`apply(|..| .., \
         ..)`), not a name bound to one"
    );
    let typed = "#[rt_function] pub fn zero<T: Default, F: Fn(T) -> f32>(f: F) -> f32 { f(T::default()) }";
    assert_eq!(
        common::lower(typed, "out[i] = zero::<f32, _>(|a: f32| a);").unwrap_err(),
        "`zero` is given a closure, so it is inlined where it is called, and its body names its type parameter `T`: \
         name the type"
    );
}

#[test]
fn an_inlined_closure_body_that_starts_with_a_block_keeps_its_operator() {
    // `{ a } * 2.0` spliced as statements would read as a block, then `*2.0`.
    let l = common::lower("", "let f = |a: f32| { a } * 2.0; out[i] = f(x);").unwrap();
    assert!(l.wgsl.contains("* 2.0f"), "{}", l.wgsl);
}
