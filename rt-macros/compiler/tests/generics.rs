//! Generic helpers through the compiler alone: which instances a unit
//! gets and how they are named, how the arguments are inferred, and the
//! errors that stay.

mod common;
use common::lower;

const HELPERS: &str = "
    #[rt_function] pub fn pick<T>(first: bool, a: T, b: T) -> T { if first { a } else { b } }
    #[rt_function] pub fn larger<T: Copy + PartialOrd>(a: T, b: T) -> T { if a > b { a } else { b } }
    #[rt_function] pub fn total<const N: usize>(a: [f32; N]) -> f32 { let mut s = 0.0; for i in 0..N { s += a[i]; } s }
    #[rt_function] pub fn zero<T: Default>() -> T { T::default() }
    #[rt_function] pub fn both<T: Copy>(a: T) -> T { pick(true, a, a) }
    #[rt_struct] pub struct Span2 { pub lo: f32, pub hi: f32 }";

/// The WGSL functions the module defines, by name.
fn functions(l: &rt_compiler::Lowered) -> Vec<String> {
    l.wgsl
        .lines()
        .filter_map(|line| line.strip_prefix("fn rtf_"))
        .map(|rest| format!("rtf_{}", rest.split('(').next().unwrap()))
        .collect()
}

#[test]
fn each_instance_is_one_function_named_after_its_arguments() {
    let l = lower(
        HELPERS,
        "let s = pick(i > 0, Span2 { lo: 0.0, hi: 1.0 }, Span2 { lo: -1.0, hi: 2.0 });
         let a = pick(true, x, 2.0) + pick::<f32>(false, 1.0, x) + both(x);
         let v = both(Vec3::splat(x));
         out[i] = s.hi + a + v.y + total([x, 1.0, 2.0]) + total::<2>([x, x]);",
    )
    .unwrap();
    let mut fns = functions(&l);
    fns.sort();
    assert_eq!(
        fns,
        [
            "rtf_both__Vec3",
            "rtf_both__f32",
            "rtf_pick__Span2",
            "rtf_pick__Vec3",
            "rtf_pick__f32",
            "rtf_total__2",
            "rtf_total__3"
        ]
    );
    // Each instance has its typed form, as every helper does.
    let mut typed: Vec<&str> = l.typed_helpers.iter().map(|(n, _)| n.as_str()).collect();
    typed.sort();
    assert_eq!(typed, ["both<Vec3>", "both<f32>", "pick<Span2>", "pick<Vec3>", "pick<f32>", "total<2>", "total<3>"]);
}

#[test]
fn an_integer_literal_takes_the_other_arguments_type() {
    let l = lower(HELPERS, "out[i] = (larger(3, y) + larger(y, 4)) as f32 + larger(2, -1) as f32;").unwrap();
    let mut fns = functions(&l);
    fns.sort();
    assert_eq!(fns, ["rtf_larger__i32", "rtf_larger__u32"]);
}

#[test]
fn the_wanted_type_gives_what_the_arguments_do_not() {
    let l = lower(HELPERS, "let z: f32 = zero(); out[i] = z;").unwrap();
    assert_eq!(functions(&l), ["rtf_zero__f32"]);
}

#[test]
fn a_parameter_nothing_gives_is_an_error_naming_it() {
    let e = lower(HELPERS, "let mut z = zero(); z = z + x; out[i] = z;").unwrap_err();
    assert_eq!(e, "cannot infer the type parameter `T` of `zero` from the arguments: give it, as in `zero::<..>(..)`");
}

#[test]
fn recursion_is_refused_at_every_type() {
    let e = lower(
        "#[rt_function] pub fn halve<T: Copy + core::ops::Mul<f32, Output = T>>(x: T, n: u32) -> T {
             if n == 0 { x } else { halve(x * 0.5, n - 1) }
         }",
        "out[i] = halve(x, 3);",
    )
    .unwrap_err();
    assert_eq!(
        e,
        "recursion (`halve<f32>` calls itself) is not supported in ray programs: WGSL has no recursion; \
         rewrite it as a loop (in `halve` with T = f32)"
    );
}

#[test]
fn instances_without_end_are_refused() {
    // Directly: at the call.
    let e = lower(
        "#[rt_function] pub fn nest<T: Copy>(x: T, n: u32) -> f32 {
             if n == 0 { 0.0 } else { nest((x, x), n - 1) }
         }",
        "out[i] = nest(x, 3);",
    )
    .unwrap_err();
    assert_eq!(
        e,
        "recursion (`nest<f32>` calls `nest<(f32, f32)>`) is not supported in ray programs: WGSL has no \
         recursion; rewrite it as a loop (in `nest` with T = f32)"
    );
    // Through another generic: when the instances grow past the bound.
    let e = lower(
        "#[rt_function] pub fn ping<T: Copy>(x: T, n: u32) -> f32 { if n == 0 { 0.0 } else { pong((x, x), n - 1) } }
         #[rt_function] pub fn pong<T: Copy>(x: T, n: u32) -> f32 { if n == 0 { 0.0 } else { ping(x, n - 1) } }",
        "out[i] = ping(x, 3);",
    )
    .unwrap_err();
    assert!(e.starts_with("`gen` calls generic helpers at ever new types (`p"), "{e}");
}

#[test]
fn an_error_in_an_instance_names_the_instance() {
    let e =
        lower("#[rt_function] pub fn norm<T: Copy>(v: T) -> f32 { v.length() }", "out[i] = norm(Vec3::ONE) + norm(x);")
            .unwrap_err();
    assert!(e.contains("no method `length` on `f32`"), "{e}");
    assert!(e.ends_with("(in `norm` with T = f32)"), "{e}");
}
