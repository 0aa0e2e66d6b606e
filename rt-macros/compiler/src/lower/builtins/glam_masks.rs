//! Bool vectors (`BVec2/3/4`, and `BVec4A`, what `Vec4`'s comparisons
//! return where glam's `Vec4` is SIMD): WGSL's `vecN<bool>`. The numeric
//! vectors' comparisons and masks (`cmpeq` .. `cmplt`, `is_negative_mask`,
//! `is_finite_mask`, `is_nan_mask`) make them; their own methods
//! (`any`, `all`, `bitmask`) read them, and `VecN::select` (in
//! `func/calls.rs`) chooses by them. WGSL's bools are not host-shareable:
//! a bool vector is never stored (`Ty::is_plain_data`), `bitmask()` is
//! what a buffer holds.

use super::MethodSig;
use crate::types::{Scalar, Ty, U32};

fn sig(params: Vec<Ty>, ret: Ty, lower: impl Fn(&[String]) -> String + 'static) -> Option<MethodSig> {
    Some(MethodSig { params, ret, lower: Box::new(lower), support: Vec::new() })
}

/// A comparison or mask of a numeric vector of `n` components of `s`.
pub fn numeric_method(n: u8, s: Scalar, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    let mask = Ty::Vec(n, Scalar::Bool);
    let cmp = |op: &'static str| sig(vec![t.clone()], mask.clone(), move |a| format!("({} {op} {})", a[0], a[1]));
    match name {
        "cmpeq" => cmp("=="),
        // Rust's `!=` is true where either side is NaN; naga's `!=` of
        // floats is the ordered comparison (false there). The negated
        // equality is Rust's.
        "cmpne" if s == Scalar::F32 => sig(vec![t.clone()], mask, |a| format!("!({} == {})", a[0], a[1])),
        "cmpne" => cmp("!="),
        "cmpge" => cmp(">="),
        "cmpgt" => cmp(">"),
        "cmple" => cmp("<="),
        "cmplt" => cmp("<"),
        // The sign bit, as glam's `is_sign_negative` per component: -0.0
        // and NaNs with the bit set count.
        "is_negative_mask" if s == Scalar::F32 => sig(vec![], mask, move |a| {
            format!("((bitcast<vec{n}<u32>>({}) & vec{n}<u32>(0x80000000u)) != vec{n}<u32>(0u))", a[0])
        }),
        "is_negative_mask" if s == Scalar::I32 => sig(vec![], mask, move |a| format!("({} < vec{n}<i32>(0i))", a[0])),
        // As `is_finite`/`is_nan` of the whole vector, per component.
        "is_finite_mask" if s == Scalar::F32 => {
            sig(vec![], mask, move |a| format!("(abs({}) <= vec{n}<f32>({}))", a[0], super::f32_literal(f32::MAX)))
        }
        // By the bits (an exponent of ones and a mantissa not zero): WGSL
        // lets a compiler assume no NaN, so `x != x` may fold to false.
        "is_nan_mask" if s == Scalar::F32 => sig(vec![], mask, move |a| {
            format!("((bitcast<vec{n}<u32>>({}) & vec{n}<u32>(0x7fffffffu)) > vec{n}<u32>(0x7f800000u))", a[0])
        }),
        _ => None,
    }
}

/// The methods of a bool vector of `n` components.
pub fn bool_method(n: u8, name: &str) -> Option<MethodSig> {
    match name {
        "any" => sig(vec![], Ty::Scalar(Scalar::Bool), |a| format!("any({})", a[0])),
        "all" => sig(vec![], Ty::Scalar(Scalar::Bool), |a| format!("all({})", a[0])),
        // `x` in bit 0, `y` in bit 1, ...
        "bitmask" => sig(vec![], U32, move |a| {
            let bits = ["1u", "2u", "4u", "8u"][..n as usize].join(", ");
            format!("dot(select(vec{n}<u32>(0u), vec{n}<u32>({bits}), {}), vec{n}<u32>(1u))", a[0])
        }),
        // The index clamped to the last component, as indexing is (glam
        // panics past it; the CPU copy clamps through `rt_std::arith::Gpu`).
        "test" => sig(vec![Ty::Scalar(Scalar::Usize)], Ty::Scalar(Scalar::Bool), move |a| {
            format!("{}[min(u32({}), {}u)]", a[0], a[1], n - 1)
        }),
        _ => None,
    }
}
