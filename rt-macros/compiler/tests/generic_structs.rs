//! Generic structs through the compiler alone: one WGSL struct per
//! instance, named after its arguments, the methods of the generic block
//! instantiated per instance, the arguments of a literal inferred, and the
//! errors.

mod common;
use common::lower;

const PAIR: &str = "
    #[rt_struct(impl)] pub struct Pair<T> { pub a: T, pub b: T }
    #[rt_impl] impl<T: Copy + core::ops::Add<Output = T>> Pair<T> {
        pub fn new(a: T, b: T) -> Self { Pair { a, b } }
        pub fn sum(&self) -> T { self.a + self.b }
        pub fn swapped(self) -> Self { Self { a: self.b, b: self.a } }
        pub fn with<U: Copy>(&self, u: U) -> (T, U) { (self.a, u) }
    }
    #[rt_struct] pub struct Wrap<T> { pub inner: Pair<T>, pub n: u32 }";

/// The WGSL names the module declares with `prefix` (`struct `, `fn `).
fn declared(l: &rt_compiler::Lowered, prefix: &str) -> Vec<String> {
    let mut v: Vec<String> = l
        .wgsl
        .lines()
        .filter_map(|line| line.strip_prefix(prefix))
        .map(|rest| rest.split(['(', ' ', '{']).next().unwrap().to_string())
        .filter(|n| n.starts_with("rt_Pair") || n.starts_with("rt_Wrap") || n.starts_with("rtm_Pair"))
        .collect();
    v.sort();
    v
}

#[test]
fn each_instance_is_one_struct_and_its_methods_are_instantiated_with_it() {
    let l = lower(
        PAIR,
        "let p: Pair<f32> = Pair::new(x, 1.0);
         let q = Pair { a: Vec3::splat(x), b: Vec3::ONE }.swapped();
         let w = Wrap { inner: p, n: 2 };
         out[i] = p.sum() + q.sum().y + w.inner.a + p.with(y).1 as f32;",
    )
    .unwrap();
    assert_eq!(declared(&l, "struct "), ["rt_Pair__Vec3", "rt_Pair__f32", "rt_Wrap__f32"]);
    assert_eq!(
        declared(&l, "fn "),
        [
            "rtm_Pair__new__f32",
            "rtm_Pair__sum__Vec3",
            "rtm_Pair__sum__f32",
            "rtm_Pair__swapped__Vec3",
            "rtm_Pair__with__f32__u32"
        ]
    );
    // The fields are the template's, substituted.
    assert!(l.wgsl.contains("struct rt_Pair__Vec3 {\n    a: vec3<f32>,\n    b: vec3<f32>,\n}"), "{}", l.wgsl);
    assert!(l.wgsl.contains("struct rt_Wrap__f32 {\n    inner: rt_Pair__f32,\n    n: u32,\n}"), "{}", l.wgsl);
}

#[test]
fn a_literal_takes_its_arguments_from_the_turbofish_the_wanted_type_or_its_fields() {
    let l = lower(
        PAIR,
        "let a = Pair::<u32> { a: 1, b: 2 };
         let b: Pair<i32> = Pair { a: 1, b: -2 };
         let c = Pair { a: 1, b: y };
         out[i] = (a.a + c.b) as f32 + b.b as f32;",
    )
    .unwrap();
    assert_eq!(declared(&l, "struct "), ["rt_Pair__i32", "rt_Pair__u32"]);
}

#[test]
fn misuse_is_an_error_naming_the_struct() {
    assert_eq!(
        lower(PAIR, "let p: Pair<f32, f32> = Pair::new(x, x); out[i] = p.a;").unwrap_err(),
        "struct `Pair` takes 1 generic argument (`Pair<T>`), found 2"
    );
    assert_eq!(
        lower(PAIR, "let p: Pair = Pair::new(x, x); out[i] = p.a;").unwrap_err(),
        "struct `Pair` takes 1 generic argument (`Pair<T>`), found 0"
    );
    assert_eq!(
        lower(PAIR, "let p = Pair { a: x, b: x }; let z: Pair<u32> = p; out[i] = z.a as f32;").unwrap_err(),
        "mismatched types: expected `Pair<u32>`, found `Pair<f32>`"
    );
    assert_eq!(
        lower("#[rt_struct] pub struct Plain { pub v: f32 }", "let p: Plain<f32> = Plain { v: x }; out[i] = p.v;")
            .unwrap_err(),
        "`Plain` takes no generic arguments (found 1): it is not a generic struct"
    );
}

#[test]
fn an_instance_never_crosses_to_the_host() {
    let err = rt_compiler::lower_source(
        &format!(
            "use rt_std::prelude::*;
            {PAIR}
            #[rt_program(ray_generation)]
            pub fn gen(#[var] out: RwBuffer<Pair<f32>>) {{ }}"
        ),
        "gen",
    )
    .unwrap_err();
    let msgs: Vec<String> = err.0.iter().filter(|e| !e.is_silent()).map(|e| e.message.clone()).collect();
    assert_eq!(
        msgs,
        ["`Pair<f32>` (an instance of the generic struct `Pair`) as a buffer element is not supported in ray \
          programs: the host reads and writes it by a layout, and a generic struct has none: declare a struct with \
          concrete fields for it (`struct PairF32 { .. }`); a generic struct lives inside programs and helpers"]
    );
}

const WRAP: &str = "
    #[rt_struct(impl)] pub struct Two<T>(pub T, pub T);
    #[rt_impl] impl<T: Copy + core::ops::Add<Output = T>> Two<T> {
        pub fn sum(&self) -> T { self.0 + self.1 }
    }";

#[test]
fn a_generic_tuple_struct_is_built_by_call_read_by_index_and_destructured() {
    let l = lower(
        WRAP,
        "let a = Two(x, 2.0);
         let b = Two::<u32>(1, 2);
         let c: Two<i32> = Two(1, -2);
         let Two(p, q) = a;
         out[i] = a.0 + b.1 as f32 + c.sum() as f32 + p * q;",
    )
    .unwrap();
    let mut structs: Vec<&str> = l.wgsl.lines().filter(|s| s.starts_with("struct rt_Two")).collect();
    structs.sort();
    assert_eq!(structs, ["struct rt_Two__f32 {", "struct rt_Two__i32 {", "struct rt_Two__u32 {"], "{}", l.wgsl);
    assert!(l.wgsl.contains("rt_Two__u32(1u, 2u)"), "{}", l.wgsl);
    assert!(l.wgsl.contains("struct rt_Two__f32 {\n    f0: f32,\n    f1: f32,\n}"), "{}", l.wgsl);
}

#[test]
fn a_generic_tuple_struct_names_what_it_cannot_infer_or_match() {
    assert_eq!(lower(WRAP, "let a = Two(x); out[i] = a.0;").unwrap_err(), "`Two<f32>` has 2 fields, and this gives 1");
    assert_eq!(
        lower(WRAP, "let a = Two(x, 1); out[i] = a.0;").unwrap_err(),
        "mismatched types: expected `f32`, found integer (write `1.0`)"
    );
    assert_eq!(
        lower(WRAP, "let a = Two(x, x); let Two(p) = a; out[i] = p;").unwrap_err(),
        "`Two` has 2 fields, and this pattern has 1"
    );
}

#[test]
fn a_generic_structs_default_is_its_zero_value_at_the_instance_named_or_wanted() {
    let l = lower(
        PAIR,
        "let a = Pair::<u32>::default();
         let b: Pair<Vec3> = Pair::default();
         let c = Pair { a: x, ..Default::default() };
         let d: Pair<i32> = Pair { b: 3, ..Pair::default() };
         let e = Pair { a: 1u32, ..Pair::<u32>::default() };
         out[i] = (a.a + e.b) as f32 + b.b.x + c.b + d.a as f32;",
    )
    .unwrap();
    assert_eq!(declared(&l, "struct "), ["rt_Pair__Vec3", "rt_Pair__f32", "rt_Pair__i32", "rt_Pair__u32"]);
    for zero in ["rt_Pair__u32()", "rt_Pair__Vec3()", "rt_Pair__f32()", "rt_Pair__i32()"] {
        assert!(l.wgsl.contains(zero), "{zero} in {}", l.wgsl);
    }
}

#[test]
fn a_generic_structs_default_names_what_it_cannot_infer_or_zero() {
    assert_eq!(
        lower(PAIR, "let a = Pair::default(); out[i] = x;").unwrap_err(),
        "cannot infer the type parameter `T` of `Pair`: give it, as in `Pair::<..>::default()`, or the type of the \
         binding"
    );
    assert_eq!(
        lower(PAIR, "let a = Pair::<Mat3>::default(); out[i] = a.a.x_axis.x;").unwrap_err(),
        "`Pair<Mat3>::default()` is not supported in ray programs: the WGSL default of `Pair<Mat3>` is all zeros, \
         and the `Default` of one of its fields is not (an enum's first variant, a matrix's identity): build the \
         value with a literal"
    );
    assert_eq!(
        lower(PAIR, "let a: Pair<u32> = Pair::<f32>::default(); out[i] = x;").unwrap_err(),
        "mismatched types: expected `Pair<u32>`, found `Pair<f32>`"
    );
}

const OPS: &str = "
    #[rt_struct(impl, impl Add, impl Mul<f32>, impl Neg, impl Scale)] pub struct Pair<T> { pub a: T, pub b: T }
    #[rt_impl] impl<T: Copy + core::ops::Add<Output = T>> Pair<T> {
        pub fn sum(&self) -> T { self.a + self.b }
    }
    #[rt_impl] impl<T: Copy + core::ops::Add<Output = T>> core::ops::Add for Pair<T> {
        type Output = Self;
        fn add(self, o: Self) -> Self { Pair { a: self.a + o.a, b: self.b + o.b } }
    }
    #[rt_impl] impl<T: Copy + core::ops::Mul<f32, Output = T>> core::ops::Mul<f32> for Pair<T> {
        type Output = Pair<T>;
        fn mul(self, k: f32) -> Pair<T> { Pair { a: self.a * k, b: self.b * k } }
    }
    #[rt_impl] impl<T: Copy + core::ops::Neg<Output = T>> core::ops::Neg for Pair<T> {
        type Output = Self;
        fn neg(self) -> Self { Pair { a: -self.a, b: -self.b } }
    }
    #[rt_trait] pub trait Scale {
        fn scaled(&self, k: f32) -> Self;
        fn twice(&self) -> Self where Self: Sized { self.scaled(2.0) }
    }
    #[rt_impl] impl<T: Copy + core::ops::Mul<f32, Output = T>> Scale for Pair<T> {
        fn scaled(&self, k: f32) -> Self { Pair { a: self.a * k, b: self.b * k } }
    }
    #[rt_function] pub fn halve<S: Scale>(s: S) -> S { s.scaled(0.5) }";

#[test]
fn a_generic_structs_operator_and_trait_impls_are_instantiated_per_instance() {
    let l = lower(
        OPS,
        "let p = Pair { a: x, b: 1.0 };
         let v = Pair { a: Vec3::splat(x), b: Vec3::ONE };
         let q = -(p + p * 2.0);
         let w = v.add(v).twice();
         let h = halve(p).scaled(3.0);
         out[i] = q.sum() + w.sum().y + h.a + halve(v).b.z;",
    )
    .unwrap();
    let mut fns: Vec<&str> = l
        .wgsl
        .lines()
        .filter_map(|s| s.strip_prefix("fn "))
        .map(|s| s.split('(').next().unwrap())
        .filter(|n| n.starts_with("rto_") || n.starts_with("rtm_") || n.starts_with("rtf_"))
        .collect();
    fns.sort();
    assert_eq!(
        fns,
        [
            "rtf_halve__Pair_Vec3",
            "rtf_halve__Pair_f32",
            "rtm_Pair__scaled__Vec3",
            "rtm_Pair__scaled__f32",
            "rtm_Pair__sum__Vec3",
            "rtm_Pair__sum__f32",
            "rtm_Pair__twice__Vec3",
            "rto_Pair__add__Pair__Vec3",
            "rto_Pair__add__Pair__f32",
            "rto_Pair__mul__f32__f32",
            "rto_Pair__neg__f32",
        ],
        "{}",
        l.wgsl
    );
}
