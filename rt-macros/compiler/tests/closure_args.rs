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

const SPAN: &str = "#[rt_struct(impl)] pub struct Span1 { pub lo: f32, pub hi: f32 }
    #[rt_struct(impl)] pub struct Other { pub v: f32 }
    #[rt_impl] impl Span1 {
        pub fn sample<F: Fn(f32) -> f32>(&self, f: F) -> f32 { let m = self.lo; f(m) + f(self.hi) }
        pub fn push<F: Fn(f32) -> f32>(&mut self, f: F) { self.lo = f(self.lo); }
        pub fn each<F: Fn(f32) -> f32>(&self, f: F) -> f32 { f(self.lo) }
        pub fn map<F: Fn(f32) -> f32>(&self, f: F) -> f32 { f(self.hi) }
    }
    #[rt_impl] impl Other { pub fn each(&self, k: f32) -> f32 { self.v * k } }";

#[test]
fn a_method_given_a_closure_is_inlined_by_name_and_by_path() {
    let l = common::lower(
        SPAN,
        "let s = Span1 { lo: x, hi: 1.0 }; out[i] = s.sample(|a| a * x) + Span1::sample(&s, |a| a - x);",
    )
    .unwrap();
    assert!(!l.wgsl.contains("rtm_Span1__sample"), "{}", l.wgsl);
    assert!(
        l.wgsl.contains("let self_rt_inl1: Span1 = s;") && l.wgsl.contains("let self_rt_inl2: Span1 = s;"),
        "{}",
        l.wgsl
    );
}

#[test]
fn what_a_method_given_a_closure_cannot_do_is_an_error_naming_it() {
    assert_eq!(
        common::lower(SPAN, "let mut s = Span1 { lo: x, hi: 1.0 }; s.push(|a| a * 2.0); out[i] = s.lo;").unwrap_err(),
        "`push` is given a closure, so it is inlined where it is called, and it takes `&mut self`: take `self` and \
         return the new value"
    );
    // Two types have an `each`: only its path says which.
    assert_eq!(
        common::lower(SPAN, "let s = Span1 { lo: x, hi: 1.0 }; out[i] = s.each(|a| a);").unwrap_err(),
        "a method given a closure is inlined where it is called, and `each` may be more than one type's method: \
         call it by its path, `Span1::each(&value, ..)`"
    );
    assert_eq!(
        common::lower(SPAN, "let s = Span1 { lo: x, hi: 1.0 }; out[i] = s.map(|a| a);").unwrap_err(),
        "a method given a closure is inlined where it is called, and `map` may be std's method too: call it by its \
         path, `Span1::map(&value, ..)`"
    );
    // By path, both are inlined; the other type's `each` is a plain call.
    let l = common::lower(
        SPAN,
        "let s = Span1 { lo: x, hi: 1.0 }; let o = Other { v: x };
         out[i] = Span1::each(&s, |a| a) + Span1::map(&s, |a| a) + o.each(2.0);",
    )
    .unwrap();
    assert!(l.wgsl.contains("rtm_Other__each"), "{}", l.wgsl);
}
