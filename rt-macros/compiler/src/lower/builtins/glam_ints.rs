//! glam's methods of integer vectors that WGSL has no builtin for, and
//! std's saturating arithmetic of `i32`/`u32` (per component on vectors):
//! squared lengths and distances, `cross` (WGSL's is for floats only),
//! Manhattan and Chebyshev distances (on `abs_diff`, in `u32`), the 2D
//! `perp`/`perp_dot`/`rotate`, `min_position`/`max_position`,
//! `is_negative_bitmask`. Products and sums wrap, as every integer
//! operator of the subset does on the GPU; glam's (Rust's) panic on
//! overflow in a debug build where the CPU runs glam itself, as for `dot`.
//! Nothing here divides, so nothing can differ at a zero divisor.

use super::MethodSig;
use crate::types::{Scalar, Ty, U32};

fn sig(params: Vec<Ty>, ret: Ty, lower: impl Fn(&[String]) -> String + 'static) -> Option<MethodSig> {
    Some(MethodSig { params, ret, lower: Box::new(lower), support: Vec::new() })
}

const XYZW: [&str; 4] = ["x", "y", "z", "w"];

/// `a.abs_diff(b)` of one `i32` or `u32` component, as a `u32`.
fn abs_diff(s: Scalar, a: &str, b: &str) -> String {
    match s {
        Scalar::I32 => {
            format!("select(bitcast<u32>({a}) - bitcast<u32>({b}), bitcast<u32>({b}) - bitcast<u32>({a}), {a} < {b})")
        }
        _ => format!("select({a} - {b}, {b} - {a}, {a} < {b})"),
    }
}

/// The index of the first least (`less`) or greatest component, glam's
/// `min_position`/`max_position`: each later component replaces the one
/// kept so far only where strictly smaller (larger).
pub fn position(n: u8, v: &str, less: bool) -> String {
    let (cmp, keep) = if less { ("<", "min") } else { (">", "max") };
    let mut best = format!("{v}.x");
    let mut index = "0u".to_string();
    for (k, c) in XYZW.iter().enumerate().take(n as usize).skip(1) {
        index = format!("select({index}, {k}u, {v}.{c} {cmp} {best})");
        best = format!("{keep}({best}, {v}.{c})");
    }
    index
}

/// glam's `is_negative_bitmask`: the sign bits (of `i32`s or `f32`s), `x`
/// lowest.
pub fn negative_bitmask(n: u8, v: &str) -> String {
    let bits: Vec<String> = XYZW
        .iter()
        .take(n as usize)
        .enumerate()
        .map(|(k, c)| format!("((bitcast<u32>({v}.{c}) >> 31u) << {k}u)"))
        .collect();
    format!("({})", bits.join(" | "))
}

/// Saturating `+`, `-`, `*` of `i32` or `u32` values (scalars, or vectors
/// per component: WGSL's `select` takes a vector of conditions alike, and
/// `&`/`|` are the logical operators of both). Overflow is read off the wrapped result: for `+` and
/// `-` from the signs, for `*` by dividing back (with the one product,
/// `-1 * i32::MIN`, that division cannot see).
fn saturating(op: &str, s: Scalar, t: &Ty, a: &str, b: &str) -> String {
    let w = t.wgsl();
    let splat = |x: &str| if matches!(t, Ty::Vec(..)) { format!("{w}({x})") } else { x.to_string() };
    let zero = splat(if s == Scalar::I32 { "0i" } else { "0u" });
    match (op, s) {
        ("add", Scalar::U32) => format!("select({a} + {b}, {}, {a} + {b} < {a})", splat("4294967295u")),
        ("sub", Scalar::U32) => format!("select({a} - {b}, {zero}, {b} > {a})"),
        ("mul", Scalar::U32) => {
            format!("select({a} * {b}, {}, ({a} != {zero}) & (({a} * {b}) / {a} != {b}))", splat("4294967295u"))
        }
        (_, _) => {
            let r = match op {
                "add" => format!("({a} + {b})"),
                "sub" => format!("({a} - {b})"),
                _ => format!("({a} * {b})"),
            };
            let max = splat("2147483647i");
            let min = splat("i32(-2147483648)");
            let overflow = match op {
                "add" => format!("((({a} ^ {r}) & ({b} ^ {r})) < {zero})"),
                "sub" => format!("((({a} ^ {b}) & ({a} ^ {r})) < {zero})"),
                _ => format!("((({a} != {zero}) & ({r} / {a} != {b})) | (({a} == {}) & ({b} == {min})))", splat("-1i")),
            };
            // The saturated end: `+`/`-` toward the left operand's sign
            // (for `-`, away from the right's), `*` by the signs' product.
            let toward_max = match op {
                "add" => format!("{a} >= {zero}"),
                "sub" => format!("{a} >= {zero}"),
                _ => format!("({a} < {zero}) == ({b} < {zero})"),
            };
            format!("select({r}, select({min}, {max}, {toward_max}), {overflow})")
        }
    }
}

/// The saturating methods of integer scalars and vectors.
pub fn saturating_method(recv: &Ty, name: &str) -> Option<MethodSig> {
    let s = recv.scalar().filter(|s| s.is_int() && *s != Scalar::Usize)?;
    let op = name.strip_prefix("saturating_").filter(|o| matches!(*o, "add" | "sub" | "mul"))?.to_string();
    let t = recv.clone();
    let ty = t.clone();
    sig(vec![t.clone()], t, move |a| saturating(&op, s, &ty, &a[0], &a[1]))
}

/// The mixed-sign methods of `i32`/`u32` and their vectors:
/// `wrapping_add_unsigned`/`wrapping_sub_unsigned`,
/// `saturating_add_unsigned`/`saturating_sub_unsigned` (signed receiver),
/// `wrapping_add_signed`/`saturating_add_signed` (unsigned receiver), on
/// the bits.
pub fn mixed_sign_method(recv: &Ty, name: &str) -> Option<MethodSig> {
    let s = recv.scalar().filter(|s| s.is_int() && *s != Scalar::Usize)?;
    let other_s = if s == Scalar::I32 { Scalar::U32 } else { Scalar::I32 };
    let other = match recv {
        Ty::Vec(n, _) => Ty::Vec(*n, other_s),
        _ => Ty::Scalar(other_s),
    };
    let t = recv.clone();
    let w = t.wgsl();
    let is_vec = matches!(recv, Ty::Vec(..));
    let splat = move |x: &str| if is_vec { format!("{w}({x})") } else { x.to_string() };
    let n = match recv {
        Ty::Vec(n, _) => *n,
        _ => 1,
    };
    let as_other = move |x: &str, to: &str| {
        let target = if is_vec { format!("vec{n}<{to}>") } else { to.to_string() };
        format!("bitcast<{target}>({x})")
    };
    let lower: super::LowerFn = match (s, name) {
        (Scalar::I32, "wrapping_add_unsigned") => {
            Box::new(move |a: &[String]| format!("({} + {})", a[0], as_other(&a[1], "i32")))
        }
        (Scalar::I32, "wrapping_sub_unsigned") => {
            Box::new(move |a: &[String]| format!("({} - {})", a[0], as_other(&a[1], "i32")))
        }
        // Overflow iff `b > i32::MAX - a` (as `u32`s): then `i32::MAX`.
        (Scalar::I32, "saturating_add_unsigned") => Box::new(move |a: &[String]| {
            let room = as_other(&format!("({} - {})", splat("2147483647i"), a[0]), "u32");
            format!("select({} + {}, {}, {} > {room})", a[0], as_other(&a[1], "i32"), splat("2147483647i"), a[1])
        }),
        // Underflow iff `b > a - i32::MIN` (as `u32`s, `a`'s bits with the
        // sign flipped): then `i32::MIN`.
        (Scalar::I32, "saturating_sub_unsigned") => Box::new(move |a: &[String]| {
            let room = format!("({} ^ {})", as_other(&a[0], "u32"), splat("0x80000000u"));
            format!("select({} - {}, {}, {} > {room})", a[0], as_other(&a[1], "i32"), splat("i32(-2147483648)"), a[1])
        }),
        (Scalar::U32, "wrapping_add_signed") => {
            Box::new(move |a: &[String]| format!("({} + {})", a[0], as_other(&a[1], "u32")))
        }
        // The wrapped sum, or `u32::MAX` past it upward (`b >= 0` and the
        // sum below `a`), or 0 past it downward.
        (Scalar::U32, "saturating_add_signed") => Box::new(move |a: &[String]| {
            let r = format!("({} + {})", a[0], as_other(&a[1], "u32"));
            let zero_i = if is_vec { format!("vec{n}<i32>(0i)") } else { "0i".to_string() };
            format!(
                "select(select({r}, {}, {r} > {a0}), select({r}, {}, {r} < {a0}), {b} >= {zero_i})",
                splat("0u"),
                splat("4294967295u"),
                a0 = a[0],
                b = a[1]
            )
        }),
        _ => return None,
    };
    Some(MethodSig { params: vec![other], ret: t, lower, support: Vec::new() })
}

/// The methods of this file for an integer vector of `n` components.
pub fn method(n: u8, s: Scalar, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    let st = Ty::Scalar(s);
    match name {
        "length_squared" => sig(vec![], st, |a| format!("dot({0}, {0})", a[0])),
        "distance_squared" => sig(vec![t], st, |a| format!("dot({0} - {1}, {0} - {1})", a[0], a[1])),
        "cross" if n == 3 => sig(vec![t.clone()], t.clone(), move |a| {
            let (x, y) = (&a[0], &a[1]);
            format!(
                "{}({x}.y * {y}.z - {y}.y * {x}.z, {x}.z * {y}.x - {y}.z * {x}.x, {x}.x * {y}.y - {y}.x * {x}.y)",
                t.wgsl()
            )
        }),
        "manhattan_distance" => sig(vec![t], U32, move |a| {
            let parts: Vec<String> = XYZW
                .iter()
                .take(n as usize)
                .map(|c| abs_diff(s, &format!("{}.{c}", a[0]), &format!("{}.{c}", a[1])))
                .collect();
            format!("({})", parts.join(" + "))
        }),
        "chebyshev_distance" => sig(vec![t], U32, move |a| {
            XYZW.iter()
                .take(n as usize)
                .map(|c| abs_diff(s, &format!("{}.{c}", a[0]), &format!("{}.{c}", a[1])))
                .reduce(|m, d| format!("max({m}, {d})"))
                .unwrap_or_default()
        }),
        "perp" if n == 2 && s == Scalar::I32 => sig(vec![], t, |a| format!("vec2<i32>(-{0}.y, {0}.x)", a[0])),
        "perp_dot" if n == 2 && s == Scalar::I32 => {
            sig(vec![t], st, |a| format!("(({0}.x * {1}.y) - ({0}.y * {1}.x))", a[0], a[1]))
        }
        "rotate" if n == 2 && s == Scalar::I32 => sig(vec![t.clone()], t, |a| {
            format!("vec2<i32>({0}.x * {1}.x - {0}.y * {1}.y, {0}.y * {1}.x + {0}.x * {1}.y)", a[0], a[1])
        }),
        "min_position" => sig(vec![], Ty::Scalar(Scalar::Usize), move |a| position(n, &a[0], true)),
        "max_position" => sig(vec![], Ty::Scalar(Scalar::Usize), move |a| position(n, &a[0], false)),
        "is_negative_bitmask" if s == Scalar::I32 => sig(vec![], U32, move |a| negative_bitmask(n, &a[0])),
        _ => saturating_method(recv, name).or_else(|| mixed_sign_method(recv, name)),
    }
}
