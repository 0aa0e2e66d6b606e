//! std's methods of `i32`, `u32` and `f32` that WGSL has no builtin for,
//! written out after std's definitions: bit counts of ones, the wrapping,
//! saturating and overflowing forms of negation, `abs`, shifts, `pow` and
//! products, integer roots and logarithms, `div_ceil`, `next_multiple_of`,
//! `next_power_of_two`, `midpoint`, byte order, sign casts; `f32`'s bit
//! tests, `next_up`/`next_down`, `exp_m1`, `ln_1p`, `cbrt`, `midpoint`.
//!
//! Where std panics (an overflowing `pow` in a debug build, a zero divisor,
//! the logarithm or root of a number that has none), the GPU's meaning
//! holds on both backends (the CPU copy calls `rt_std::arith::Gpu`'s
//! methods): `pow` wraps, as `*` does; a zero divisor is read as one, as
//! in the dividing methods; `ilog`, `ilog2`, `ilog10` and `isqrt` give 0
//! where std has no answer (a number `<= 0`, a base below 2; what
//! `checked_ilog2(..).unwrap_or(0)` gives); `next_power_of_two` past
//! `2^31` gives 0 (std's release build).

use super::MethodSig;
use crate::types::{F32, Scalar, Ty, U32};

fn sig(params: Vec<Ty>, ret: Ty, lower: impl Fn(&[String]) -> String + 'static) -> Option<MethodSig> {
    Some(MethodSig { params, ret, lower: Box::new(lower), support: Vec::new() })
}

fn with(m: Option<MethodSig>, support: &[(&'static str, &'static str)]) -> Option<MethodSig> {
    m.map(|mut m| {
        m.support.extend_from_slice(support);
        m
    })
}

const BOOL: Ty = Ty::Scalar(Scalar::Bool);
const I32: Ty = Ty::Scalar(Scalar::I32);

/// `(a * b, overflowed)` of `u32`s and of `i32`s, as std's
/// `overflowing_mul`: the product divided back (and the one product of
/// `i32`s division cannot see, `-1 * i32::MIN`).
const MUL_OVER: &str = "\
fn rt_mul_over_u32(a: u32, b: u32) -> bool {
    return a != 0u && (a * b) / a != b;
}
fn rt_mul_over_i32(a: i32, b: i32) -> bool {
    return (a != 0i && (a * b) / a != b) || (a == -1i && b == i32(-2147483648));
}
";

/// std's `overflowing_pow` (square and multiply; overflow of any product
/// used), for `u32` and `i32`.
const POW_U32: &str = "\
fn rt_pow_u32(base0: u32, exp0: u32) -> RtPowU32 {
    if exp0 == 0u { return RtPowU32(1u, false); }
    var base = base0;
    var exp = exp0;
    var acc = 1u;
    var over = false;
    loop {
        if (exp & 1u) == 1u {
            let o = rt_mul_over_u32(acc, base);
            acc = acc * base;
            over = over || o;
            if exp == 1u { break; }
        }
        exp = exp / 2u;
        over = over || rt_mul_over_u32(base, base);
        base = base * base;
    }
    return RtPowU32(acc, over);
}
struct RtPowU32 { value: u32, over: bool }
";

const POW_I32: &str = "\
fn rt_pow_i32(base0: i32, exp0: u32) -> RtPowI32 {
    if exp0 == 0u { return RtPowI32(1i, false); }
    var base = base0;
    var exp = exp0;
    var acc = 1i;
    var over = false;
    loop {
        if (exp & 1u) == 1u {
            let o = rt_mul_over_i32(acc, base);
            acc = acc * base;
            over = over || o;
            if exp == 1u { break; }
        }
        exp = exp / 2u;
        over = over || rt_mul_over_i32(base, base);
        base = base * base;
    }
    return RtPowI32(acc, over);
}
struct RtPowI32 { value: i32, over: bool }
";

/// The integer square root of a `u32`: the float's, corrected to the
/// largest `r` with `r * r <= x` (without overflow: `r <= x / r`).
const ISQRT: &str = "\
fn rt_isqrt(x: u32) -> u32 {
    var r = min(u32(sqrt(f32(x))), 65535u);
    if r > 0u && r > x / r { r = r - 1u; }
    if r > 0u && r > x / r { r = r - 1u; }
    if r < 65535u && r + 1u <= x / (r + 1u) { r = r + 1u; }
    return r;
}
";

/// `floor(log_base(x))` of a `u32` by repeated division; 0 where std
/// panics (`x == 0`, `base < 2`).
const ILOG: &str = "\
fn rt_ilog(x0: u32, base: u32) -> u32 {
    if x0 == 0u || base < 2u { return 0u; }
    var x = x0;
    var n = 0u;
    loop {
        if x < base { break; }
        x = x / base;
        n = n + 1u;
    }
    return n;
}
";

/// The bits of an `i32` operand as `u32`.
fn bits(s: Scalar, a: &str) -> String {
    if s == Scalar::I32 { format!("bitcast<u32>({a})") } else { a.to_string() }
}

/// The methods of this file for the integer scalar `s`, one group of
/// methods after another.
fn int(s: Scalar, name: &str) -> Option<MethodSig> {
    bit_method(s, name)
        .or_else(|| shift(s, name))
        .or_else(|| wrapping(s, name))
        .or_else(|| overflowing(s, name))
        .or_else(|| power(s, name))
        .or_else(|| root_or_log(s, name))
        .or_else(|| sign_or_mean(s, name))
        .or_else(|| round_up(s, name))
}

/// `(ty, bool)`: what the `overflowing_` methods return.
fn pair(ty: Ty) -> Ty {
    Ty::Tuple(vec![ty, BOOL])
}

/// Bit counts of ones (`count_zeros`, `leading_ones`, `trailing_ones`),
/// byte order (`to_be`, `to_le`) and the sign casts.
fn bit_method(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let signed = s == Scalar::I32;
    let count = |f: &'static str| move |a: &[String]| format!("{f}(~{})", bits(s, &a[0]));
    match name {
        "count_zeros" => sig(vec![], U32, count("countOneBits")),
        "leading_ones" => sig(vec![], U32, count("countLeadingZeros")),
        "trailing_ones" => sig(vec![], U32, count("countTrailingZeros")),
        "to_be" => sig(vec![], t, move |a| byte_swap(s, &a[0])),
        // Little-endian, as every target the CPU backend builds for.
        "to_le" => sig(vec![], t, |a| a[0].clone()),
        "cast_unsigned" if signed => sig(vec![], U32, |a| format!("bitcast<u32>({})", a[0])),
        // `u32` only.
        "cast_signed" if !signed => sig(vec![], I32, |a| format!("bitcast<i32>({})", a[0])),
        _ => None,
    }
}

/// The shifts by an amount of 32 or more: `wrapping_`, `overflowing_` and
/// `unbounded_shl`/`shr`.
fn shift(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let signed = s == Scalar::I32;
    let zero = if signed { "0i" } else { "0u" };
    let pair_w = pair(t.clone()).wgsl();
    match name {
        "wrapping_shl" => sig(vec![U32], t, |a| format!("({} << ({} & 31u))", a[0], a[1])),
        "wrapping_shr" => sig(vec![U32], t, |a| format!("({} >> ({} & 31u))", a[0], a[1])),
        "overflowing_shl" => {
            sig(vec![U32], pair(t), move |a| format!("{pair_w}(({} << ({1} & 31u)), {1} >= 32u)", a[0], a[1]))
        }
        "overflowing_shr" => {
            sig(vec![U32], pair(t), move |a| format!("{pair_w}(({} >> ({1} & 31u)), {1} >= 32u)", a[0], a[1]))
        }
        "unbounded_shl" => {
            sig(vec![U32], t, move |a| format!("select({0} << ({1} & 31u), {zero}, {1} >= 32u)", a[0], a[1]))
        }
        "unbounded_shr" => sig(vec![U32], t, move |a| {
            let fill = if signed { format!("select(0i, -1i, {} < 0i)", a[0]) } else { "0u".into() };
            format!("select({0} >> ({1} & 31u), {fill}, {1} >= 32u)", a[0], a[1])
        }),
        _ => None,
    }
}

/// The `wrapping_` forms of negation, `abs`, the remainder and the
/// Euclidean division and remainder (the shifts and `pow` are [`shift`]'s
/// and [`power`]'s).
fn wrapping(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let signed = s == Scalar::I32;
    let zero = if signed { "0i" } else { "0u" };
    match name {
        "wrapping_neg" => sig(vec![], t, move |a| format!("({zero} - {})", a[0])),
        // `x % 0` is 0 and `MIN % -1` is 0 on the GPU, std's wrapping
        // values where it does not panic.
        "wrapping_rem" => sig(vec![t.clone()], t, |a| format!("({} % {})", a[0], a[1])),
        "wrapping_div_euclid" => super::int_division::method(&t, "div_euclid"),
        "wrapping_rem_euclid" => super::int_division::method(&t, "rem_euclid"),
        // `i32` only.
        "wrapping_abs" if signed => sig(vec![], t, |a| format!("abs({})", a[0])),
        _ => None,
    }
}

/// The `overflowing_` forms of division, the remainder, negation, `abs`,
/// products and mixed-sign sums (the shifts and `pow` are [`shift`]'s and
/// [`power`]'s): the value and whether it overflowed.
fn overflowing(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let signed = s == Scalar::I32;
    let zero = if signed { "0i" } else { "0u" };
    let pair_w = pair(t.clone()).wgsl();
    match name {
        // A zero divisor reads as one (std panics); `MIN / -1` and its
        // remainder overflow (the quotient wraps to `MIN`, the remainder
        // is 0).
        "overflowing_div" | "overflowing_rem" => {
            let op = if name.ends_with("div") { "/" } else { "%" };
            sig(vec![t.clone()], pair(t), move |a| {
                let d = format!("select({0}, {1}, {0} == {zero})", a[1], if signed { "1i" } else { "1u" });
                format!("{pair_w}(({} {op} {d}), {})", a[0], min_by_minus_one(signed, &a[0], &a[1]))
            })
        }
        "overflowing_div_euclid" | "overflowing_rem_euclid" => {
            let inner = super::int_division::method(&t, &name["overflowing_".len()..])?;
            let lower = inner.lower;
            Some(MethodSig {
                params: inner.params,
                ret: pair(t),
                lower: Box::new(move |a| format!("{pair_w}({}, {})", lower(a), min_by_minus_one(signed, &a[0], &a[1]))),
                support: inner.support,
            })
        }
        "overflowing_add_unsigned" | "overflowing_sub_unsigned" if signed => {
            let add = name == "overflowing_add_unsigned";
            sig(vec![U32], pair(t), move |a| {
                // std: the signed operation's overflow, flipped where the
                // operand read as `i32` is negative.
                let (x, y) = (&a[0], format!("bitcast<i32>({})", a[1]));
                let r = if add { format!("({x} + {y})") } else { format!("({x} - {y})") };
                let over = if add {
                    format!("((({x} ^ {r}) & ({y} ^ {r})) < 0i)")
                } else {
                    format!("((({x} ^ {y}) & ({x} ^ {r})) < 0i)")
                };
                format!("{pair_w}({r}, {over} != ({y} < 0i))")
            })
        }
        "overflowing_mul" => with(
            sig(vec![t.clone()], pair(t), move |a| {
                let f = if signed { "rt_mul_over_i32" } else { "rt_mul_over_u32" };
                format!("{pair_w}(({0} * {1}), {f}({0}, {1}))", a[0], a[1])
            }),
            &[("rt_mul_over_u32", MUL_OVER)],
        ),
        "overflowing_neg" if signed => {
            sig(vec![], pair(t), move |a| format!("{pair_w}(0i - {0}, {0} == i32(-2147483648))", a[0]))
        }
        "overflowing_neg" => sig(vec![], pair(t), move |a| format!("{pair_w}(0u - {0}, {0} != 0u)", a[0])),
        "overflowing_abs" if signed => {
            sig(vec![], pair(t), move |a| format!("{pair_w}(abs({0}), {0} == i32(-2147483648))", a[0]))
        }
        "overflowing_add_signed" if !signed => sig(vec![I32], pair(t), move |a| {
            let r = format!("({} + bitcast<u32>({}))", a[0], a[1]);
            format!("{pair_w}({r}, select({r} < {0}, {r} > {0}, {1} < 0i))", a[0], a[1])
        }),
        _ => None,
    }
}

/// `pow` and its `wrapping_`, `overflowing_` and `saturating_` forms.
fn power(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let signed = s == Scalar::I32;
    let pair_w = pair(t.clone()).wgsl();
    let (pow_fn, pow_text) = if signed { ("rt_pow_i32", POW_I32) } else { ("rt_pow_u32", POW_U32) };
    let pow = [(pow_fn, pow_text), ("rt_mul_over_u32", MUL_OVER)];
    match name {
        "pow" | "wrapping_pow" => with(sig(vec![U32], t, move |a| format!("{pow_fn}({}, {}).value", a[0], a[1])), &pow),
        "overflowing_pow" => with(
            sig(vec![U32], pair(t), move |a| {
                let r = format!("{pow_fn}({}, {})", a[0], a[1]);
                format!("{pair_w}({r}.value, {r}.over)")
            }),
            &pow,
        ),
        // Past the range: the end the true power lies toward (a negative
        // base to an odd power: `i32::MIN`).
        "saturating_pow" => with(
            sig(vec![U32], t, move |a| {
                let r = format!("{pow_fn}({}, {})", a[0], a[1]);
                let end = if signed {
                    format!("select(2147483647i, i32(-2147483648), {} < 0i && ({} & 1u) == 1u)", a[0], a[1])
                } else {
                    "4294967295u".into()
                };
                format!("select({r}.value, {end}, {r}.over)")
            }),
            &pow,
        ),
        _ => None,
    }
}

/// Integer roots and logarithms: `isqrt`, `ilog2`, `ilog10`, `ilog`.
fn root_or_log(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let signed = s == Scalar::I32;
    let zero = if signed { "0i" } else { "0u" };
    match name {
        "isqrt" => with(
            sig(vec![], t, move |a| {
                if signed {
                    format!("select(i32(rt_isqrt(bitcast<u32>({0}))), 0i, {0} < 0i)", a[0])
                } else {
                    format!("rt_isqrt({})", a[0])
                }
            }),
            &[("rt_isqrt", ISQRT)],
        ),
        "ilog2" => sig(vec![], U32, move |a| {
            format!("select(31u - countLeadingZeros({}), 0u, {} <= {zero})", bits(s, &a[0]), a[0])
        }),
        "ilog10" => with(
            sig(vec![], U32, move |a| format!("select(rt_ilog({}, 10u), 0u, {} <= {zero})", bits(s, &a[0]), a[0])),
            &[("rt_ilog", ILOG)],
        ),
        "ilog" => with(
            sig(vec![t.clone()], U32, move |a| {
                format!(
                    "select(rt_ilog({}, {}), 0u, {} <= {zero} || {} < {})",
                    bits(s, &a[0]),
                    bits(s, &a[1]),
                    a[0],
                    a[1],
                    if signed { "2i" } else { "2u" }
                )
            }),
            &[("rt_ilog", ILOG)],
        ),
        _ => None,
    }
}

/// Signs, distances and means: `abs_diff`, `midpoint`, and `i32`'s
/// `unsigned_abs`, `saturating_neg`, `saturating_abs`, `is_positive`,
/// `is_negative`.
fn sign_or_mean(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let signed = s == Scalar::I32;
    match name {
        "abs_diff" => sig(vec![t.clone()], U32, move |a| {
            let (x, y) = (bits(s, &a[0]), bits(s, &a[1]));
            format!("select({x} - {y}, {y} - {x}, {} < {})", a[0], a[1])
        }),
        "midpoint" if !signed => {
            sig(vec![t.clone()], t, |a| format!("(({0} & {1}) + (({0} ^ {1}) >> 1u))", a[0], a[1]))
        }
        // The floor of the mean, then toward zero (std rounds toward zero).
        "midpoint" => sig(vec![t.clone()], t, |a| {
            let floor = format!("(({0} & {1}) + (({0} ^ {1}) >> 1u))", a[0], a[1]);
            format!("({floor} + select(0i, 1i, {floor} < 0i && (({0} ^ {1}) & 1i) != 0i))", a[0], a[1])
        }),
        "unsigned_abs" if signed => {
            sig(vec![], U32, |a| format!("select(bitcast<u32>({0}), 0u - bitcast<u32>({0}), {0} < 0i)", a[0]))
        }
        "saturating_neg" if signed => {
            sig(vec![], t, |a| format!("select(0i - {0}, 2147483647i, {0} == i32(-2147483648))", a[0]))
        }
        "saturating_abs" if signed => {
            sig(vec![], t, |a| format!("select(abs({0}), 2147483647i, {0} == i32(-2147483648))", a[0]))
        }
        "is_positive" if signed => sig(vec![], BOOL, |a| format!("({} > 0i)", a[0])),
        "is_negative" if signed => sig(vec![], BOOL, |a| format!("({} < 0i)", a[0])),
        _ => None,
    }
}

/// `u32`'s rounding up: `div_ceil`, `next_multiple_of`,
/// `next_power_of_two`.
fn round_up(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let signed = s == Scalar::I32;
    match name {
        "div_ceil" if !signed => sig(vec![t.clone()], t, |a| {
            let d = format!("select({0}, 1u, {0} == 0u)", a[1]);
            format!("(({0} / {d}) + select(0u, 1u, ({0} % {d}) != 0u))", a[0])
        }),
        "next_multiple_of" if !signed => sig(vec![t.clone()], t, |a| {
            let d = format!("select({0}, 1u, {0} == 0u)", a[1]);
            format!("select({0} + ({d} - ({0} % {d})), {0}, ({0} % {d}) == 0u)", a[0])
        }),
        "next_power_of_two" if !signed => sig(vec![], t, |a| {
            format!(
                "select(select(1u << (32u - countLeadingZeros({0} - 1u)), 0u, {0} > 2147483648u), 1u, {0} <= 1u)",
                a[0]
            )
        }),
        _ => None,
    }
}

/// Whether `a / b` overflows: `i32::MIN / -1` (never for `u32`).
fn min_by_minus_one(signed: bool, a: &str, b: &str) -> String {
    if signed { format!("({a} == i32(-2147483648) && {b} == -1i)") } else { "false".into() }
}

/// The bytes of an `i32` or `u32` in the other order.
pub fn byte_swap(s: Scalar, a: &str) -> String {
    let x = bits(s, a);
    let swapped =
        format!("((({x} & 0xffu) << 24u) | (({x} & 0xff00u) << 8u) | (({x} >> 8u) & 0xff00u) | ({x} >> 24u))");
    if s == Scalar::I32 { format!("bitcast<i32>({swapped})") } else { swapped }
}

/// `f32`'s: bit tests, neighbours, and formulas WGSL has no builtin for.
fn float(name: &str) -> Option<MethodSig> {
    let b = |f: &'static str| move |a: &[String]| f.replace("{x}", &format!("bitcast<u32>({})", a[0]));
    match name {
        "to_bits" => sig(vec![], U32, |a| format!("bitcast<u32>({})", a[0])),
        "is_sign_positive" => sig(vec![], BOOL, b("(({x} >> 31u) == 0u)")),
        "is_sign_negative" => sig(vec![], BOOL, b("(({x} >> 31u) == 1u)")),
        // Exponent bits neither all 0 (zero, subnormal) nor all 1.
        "is_normal" => sig(vec![], BOOL, b("((({x} >> 23u) & 0xffu) != 0u && (({x} >> 23u) & 0xffu) != 0xffu)")),
        "is_subnormal" => sig(vec![], BOOL, b("((({x} >> 23u) & 0xffu) == 0u && ({x} & 0x7fffffu) != 0u)")),
        // std's: NaN and the infinity it moves toward stay; a zero steps
        // to the smallest subnormal of the direction; else one unit of the
        // bits toward it.
        "next_up" => sig(vec![], F32, |a| neighbour(&a[0], true)),
        "next_down" => sig(vec![], F32, |a| neighbour(&a[0], false)),
        "exp_m1" => sig(vec![], F32, |a| format!("(exp({}) - 1.0f)", a[0])),
        "ln_1p" => sig(vec![], F32, |a| format!("log(1.0f + {})", a[0])),
        "cbrt" => sig(vec![], F32, |a| format!("(sign({0}) * pow(abs({0}), 0.33333334f))", a[0])),
        // std's: the mean where halving cannot overflow or lose the last
        // bit, else halves first.
        "midpoint" => sig(vec![F32], F32, |a| {
            let (x, y) = (&a[0], &a[1]);
            format!(
                "select(select(select(({x} * 0.5f) + ({y} * 0.5f), ({x} * 0.5f) + {y}, abs({y}) < 2.3509887e-38f), \
                 {x} + ({y} * 0.5f), abs({x}) < 2.3509887e-38f), ({x} + {y}) * 0.5f, \
                 abs({x}) <= 1.7014117e38f && abs({y}) <= 1.7014117e38f)"
            )
        }),
        _ => None,
    }
}

fn neighbour(x: &str, up: bool) -> String {
    let bits = format!("bitcast<u32>({x})");
    let (toward_inf, step_pos, step_neg, zero_to) =
        if up { ("0x7f800000u", "1u", "0u - 1u", "1u") } else { ("0xff800000u", "0u - 1u", "1u", "0x80000001u") };
    format!(
        "select(select(select(bitcast<f32>({bits} + ({step_neg})), bitcast<f32>({bits} + ({step_pos})), ({bits} >> 31u) == 0u), \
         bitcast<f32>({zero_to}), ({bits} & 0x7fffffffu) == 0u), {x}, ({bits} & 0x7fffffffu) > 0x7f800000u || {bits} == {toward_inf})"
    )
}

/// std's method `name` of the scalar type `recv`, where this file has it.
pub fn method(recv: &Ty, name: &str) -> Option<MethodSig> {
    match recv {
        Ty::Scalar(s @ (Scalar::I32 | Scalar::U32)) => int(*s, name),
        Ty::Scalar(Scalar::F32) => float(name),
        _ => None,
    }
}
