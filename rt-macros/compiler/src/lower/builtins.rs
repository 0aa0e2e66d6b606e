//! Methods and associated constants of the builtin types (scalars, glam
//! vectors and matrices) that have WGSL equivalents, with their lowering.
//! Semantics follow Rust/glam; where WGSL differs (Rust's `round` rounds
//! half away from zero, `fract` is `x - trunc(x)`, `signum(0.0)` is 1) the
//! lowering spells Rust's definition out.

mod glam_angles;
mod glam_assoc;
mod glam_formulas;
mod glam_ints;
mod glam_masks;
mod int_division;
mod std_scalars;

pub use glam_assoc::assoc_fn;

use super::value::{Val, f32_literal};
use crate::types::{F32, Scalar, Ty, U32};

/// Builds a method call's WGSL from the lowered receiver and arguments.
pub type LowerFn = Box<dyn Fn(&[String]) -> String>;

/// A method's parameter types, result type and lowering (`args[0]` is the
/// receiver).
pub struct MethodSig {
    pub params: Vec<Ty>,
    pub ret: Ty,
    pub lower: LowerFn,
    /// WGSL functions the lowering calls, `(name, text)`, for the module's
    /// function section.
    pub support: Vec<(&'static str, &'static str)>,
}

fn sig(params: Vec<Ty>, ret: Ty, lower: impl Fn(&[String]) -> String + 'static) -> Option<MethodSig> {
    Some(MethodSig { params, ret, lower: Box::new(lower), support: Vec::new() })
}

/// `f32::powi` as Rust computes it (LLVM's `powi`, compiler-rt's
/// `__powisf2`): repeated squaring. WGSL's `pow` is undefined for negative
/// bases, which `powi` must handle (`(-0.5f32).powi(2)` is 0.25).
const POWI: &str = "\
fn rt_powi(x: f32, n: i32) -> f32 {
    var base = x;
    var e = n;
    var r = 1.0f;
    loop {
        if (e & 1i) != 0i {
            r *= base;
        }
        e /= 2i;
        if e == 0i {
            break;
        }
        base *= base;
    }
    return select(r, 1.0f / r, n < 0i);
}
";

/// Rust's float `%` (`fmod`: the exact remainder, with the dividend's
/// sign). WGSL's `%` is `x - y * trunc(x / y)`, which is off by a whole `y`
/// where `x / y` rounds up to an integer (`1.0 % 0.1` is 0.1 in Rust and 0
/// that way). This is musl's `fmodf`, on the bits: exact, no float
/// arithmetic to reassociate. (NaN and infinite operands, which WGSL may
/// assume away, fall back to WGSL's `%`.)
pub const FMOD: &str = "\
fn rt_fmod(x: f32, y: f32) -> f32 {
    let ux = bitcast<u32>(x);
    let uy = bitcast<u32>(y);
    var ex = i32((ux >> 23u) & 0xffu);
    var ey = i32((uy >> 23u) & 0xffu);
    let sx = ux & 0x80000000u;
    if (uy << 1u) == 0u || ex == 0xff || (uy & 0x7fffffffu) > 0x7f800000u {
        return x % y;
    }
    if (ux << 1u) <= (uy << 1u) {
        if (ux << 1u) == (uy << 1u) {
            return bitcast<f32>(sx);
        }
        return x;
    }
    var mx = (ux & 0x007fffffu) | 0x00800000u;
    if ex == 0 {
        var i = ux << 9u;
        while (i >> 31u) == 0u {
            ex -= 1;
            i <<= 1u;
        }
        mx = ux << u32(1 - ex);
    }
    var my = (uy & 0x007fffffu) | 0x00800000u;
    if ey == 0 {
        var i = uy << 9u;
        while (i >> 31u) == 0u {
            ey -= 1;
            i <<= 1u;
        }
        my = uy << u32(1 - ey);
    }
    loop {
        let i = mx - my;
        if (i >> 31u) == 0u {
            if i == 0u {
                return bitcast<f32>(sx);
            }
            mx = i;
        }
        if ex <= ey {
            break;
        }
        mx <<= 1u;
        ex -= 1;
    }
    while (mx >> 23u) == 0u {
        mx <<= 1u;
        ex -= 1;
    }
    if ex > 0 {
        mx = (mx - 0x00800000u) | (u32(ex) << 23u);
    } else {
        mx >>= u32(1 - ex);
    }
    return bitcast<f32>(mx | sx);
}
";

/// [`FMOD`] per component, for `VecN % VecN` (glam's `%` is `f32`'s per
/// component): `(name, text)`.
pub fn fmod_vec(n: u8) -> (&'static str, &'static str) {
    match n {
        2 => (
            "rt_fmod2",
            "fn rt_fmod2(x: vec2<f32>, y: vec2<f32>) -> vec2<f32> {\n    return vec2<f32>(rt_fmod(x.x, y.x), rt_fmod(x.y, y.y));\n}\n",
        ),
        3 => (
            "rt_fmod3",
            "fn rt_fmod3(x: vec3<f32>, y: vec3<f32>) -> vec3<f32> {\n    return vec3<f32>(rt_fmod(x.x, y.x), rt_fmod(x.y, y.y), rt_fmod(x.z, y.z));\n}\n",
        ),
        _ => (
            "rt_fmod4",
            "fn rt_fmod4(x: vec4<f32>, y: vec4<f32>) -> vec4<f32> {\n    return vec4<f32>(rt_fmod(x.x, y.x), rt_fmod(x.y, y.y), rt_fmod(x.z, y.z), rt_fmod(x.w, y.w));\n}\n",
        ),
    }
}

/// glam's `Vec4 % Vec4` (and `% f32`) on targets where `Vec4` is SIMD
/// (SSE2, NEON, wasm32: `x - floor(x / y) * y`, a floored remainder), as
/// opposed to `Vec2` and `Vec3` (`f32`'s `%`, [`fmod_vec`]): `(name, text)`.
pub const VEC4_REM: (&str, &str) =
    ("rt_rem_vec4", "fn rt_rem_vec4(x: vec4<f32>, y: vec4<f32>) -> vec4<f32> {\n    return x - floor(x / y) * y;\n}\n");

/// Float to integer conversion as Rust's `as` (and glam's `as_ivecN`,
/// `as_uvecN`): truncate, saturate at the type's limits. WGSL clamps to the
/// largest *float* below the limit first (`i32(1e20)` is 2147483520,
/// `u32(1e20)` 4294967040, where Rust gives `i32::MAX` and `u32::MAX`), so
/// values from 2^31 (2^32) up select the maximum. NaN converts to 0, as in
/// Rust (WGSL leaves it to the driver: lavapipe gives `i32::MIN`), found by
/// its bits: WGSL lets a compiler assume no NaN, so `x != x` may fold away. `(name, text)` for an
/// `n`-vector (`n == 1`: scalar) to `i32` (`signed`) or `u32`.
pub fn float_to_int(n: u8, signed: bool) -> (&'static str, &'static str) {
    macro_rules! f2i {
        ($name:literal, $from:literal, $to:literal, $bits:literal, $max:literal, $limit:literal) => {
            (
                $name,
                concat!(
                    "fn ",
                    $name,
                    "(x: ",
                    $from,
                    ") -> ",
                    $to,
                    " {\n    return select(select(",
                    $to,
                    "(x), ",
                    $to,
                    "(",
                    $max,
                    "), x >= ",
                    $from,
                    "(",
                    $limit,
                    ")), ",
                    $to,
                    "(0), (bitcast<",
                    $bits,
                    ">(x) & ",
                    $bits,
                    "(0x7fffffffu)) > ",
                    $bits,
                    "(0x7f800000u));\n}\n"
                ),
            )
        };
    }
    match (n, signed) {
        (1, true) => f2i!("rt_f2i", "f32", "i32", "u32", "2147483647i", "2147483648.0"),
        (2, true) => f2i!("rt_f2i2", "vec2<f32>", "vec2<i32>", "vec2<u32>", "2147483647i", "2147483648.0"),
        (3, true) => f2i!("rt_f2i3", "vec3<f32>", "vec3<i32>", "vec3<u32>", "2147483647i", "2147483648.0"),
        (_, true) => f2i!("rt_f2i4", "vec4<f32>", "vec4<i32>", "vec4<u32>", "2147483647i", "2147483648.0"),
        (1, false) => f2i!("rt_f2u", "f32", "u32", "u32", "4294967295u", "4294967296.0"),
        (2, false) => f2i!("rt_f2u2", "vec2<f32>", "vec2<u32>", "vec2<u32>", "4294967295u", "4294967296.0"),
        (3, false) => f2i!("rt_f2u3", "vec3<f32>", "vec3<u32>", "vec3<u32>", "4294967295u", "4294967296.0"),
        (_, false) => f2i!("rt_f2u4", "vec4<f32>", "vec4<u32>", "vec4<u32>", "4294967295u", "4294967296.0"),
    }
}

/// `a * (1 - t) + b * t` (glam's `lerp`, rt-std's `mix`), exact at both
/// ends. (Callers evaluate an operand with effects once: `t` appears twice.)
pub fn lerp_formula(a: &str, b: &str, t: &str) -> String {
    format!("({a} * (1.0 - {t}) + {b} * {t})")
}

/// The zero value of a builtin type. A vector's zeros are spelled out:
/// naga turns `vec3(vec2<T>(), x)` into SPIR-V that lavapipe's compiler
/// rejects (it loses the device), `vec3(vec2<T>(0), x)` is fine.
pub fn zero_value(ty: &Ty) -> String {
    match ty {
        Ty::Vec(n, s) => {
            let zero = match s {
                Scalar::F32 => "0.0",
                Scalar::I32 => "0i",
                Scalar::Bool => "false",
                _ => "0u",
            };
            format!("vec{n}<{}>({zero})", s.wgsl())
        }
        _ => format!("{}()", ty.wgsl()),
    }
}

/// `f(recv, args...)`.
fn wgsl_fn(name: &'static str) -> impl Fn(&[String]) -> String {
    move |a| format!("{name}({})", a.join(", "))
}

pub fn method_sig(recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    let is_float = recv.scalar() == Some(Scalar::F32) && !matches!(recv, Ty::Mat(_));
    let is_int = matches!(recv, Ty::Scalar(s) | Ty::Vec(_, s) if s.is_int());
    // Methods shared by every copyable value.
    if name == "clone" && recv.is_value() {
        return sig(vec![], t, |a| a[0].clone());
    }
    if let Some(m) = glam_formulas::method(recv, name) {
        return Some(m);
    }
    if let Some(m) = std_scalars::method(recv, name) {
        return Some(m);
    }
    if is_int && let Some(m) = int_division::method(recv, name) {
        return Some(m);
    }
    match recv {
        Ty::Vec(n, Scalar::Bool) => return glam_masks::bool_method(*n, name),
        Ty::Vec(n, s) if let Some(m) = glam_masks::numeric_method(*n, *s, recv, name) => return Some(m),
        _ => {}
    }
    match recv {
        Ty::Vec(n, Scalar::F32) => {
            if let Some(m) = glam_angles::method(*n, recv, name) {
                return Some(m);
            }
        }
        Ty::Vec(n, s) if s.is_int() => {
            if let Some(m) = glam_ints::method(*n, *s, recv, name) {
                return Some(m);
            }
        }
        Ty::Scalar(s) if s.is_int() => {
            if let Some(m) =
                glam_ints::saturating_method(recv, name).or_else(|| glam_ints::mixed_sign_method(recv, name))
            {
                return Some(m);
            }
        }
        _ => {}
    }
    if let Ty::Mat(m) = recv {
        return mat_method(*m, name);
    }
    if is_float && let Some(m) = float_method(recv, name) {
        return Some(m);
    }
    if is_int && let Some(m) = int_method(recv, name) {
        return Some(m);
    }
    if is_float || is_int {
        match name {
            "min" => return sig(vec![t.clone()], t, wgsl_fn("min")),
            "max" => return sig(vec![t.clone()], t, wgsl_fn("max")),
            "clamp" => return sig(vec![t.clone(), t.clone()], t, wgsl_fn("clamp")),
            _ => {}
        }
    }
    if matches!(recv, Ty::Vec(..)) && recv.scalar() != Some(Scalar::Bool) {
        return vec_method(recv, name);
    }
    None
}

/// Methods of `f32` and float vectors (glam's).
fn float_method(recv: &Ty, name: &str) -> Option<MethodSig> {
    if let Some(f) = float_wgsl_builtin(name) {
        return sig(vec![], recv.clone(), wgsl_fn(f));
    }
    float_formula(recv, name).or_else(|| float_vec_method(recv, name))
}

/// The WGSL builtin that is the float method `name` of no arguments.
fn float_wgsl_builtin(name: &str) -> Option<&'static str> {
    match name {
        "abs" => Some("abs"),
        "sqrt" => Some("sqrt"),
        "exp" => Some("exp"),
        "exp2" => Some("exp2"),
        "ln" => Some("log"),
        "log2" => Some("log2"),
        "sin" => Some("sin"),
        "cos" => Some("cos"),
        "tan" => Some("tan"),
        "asin" => Some("asin"),
        "acos" => Some("acos"),
        "atan" => Some("atan"),
        "sinh" => Some("sinh"),
        "cosh" => Some("cosh"),
        "tanh" => Some("tanh"),
        "asinh" => Some("asinh"),
        "acosh" => Some("acosh"),
        "atanh" => Some("atanh"),
        "floor" => Some("floor"),
        "ceil" => Some("ceil"),
        "trunc" => Some("trunc"),
        "fract_gl" => Some("fract"),
        "to_radians" => Some("radians"),
        "to_degrees" => Some("degrees"),
        "round_ties_even" => Some("round"),
        _ => None,
    }
}

/// The float methods of `f32` and float vectors alike that WGSL spells
/// otherwise (a formula, or a builtin of other arguments), and `f32`'s own.
fn float_formula(recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    let is_vec = matches!(recv, Ty::Vec(..));
    let is_scalar = matches!(recv, Ty::Scalar(_));
    let n = match recv {
        Ty::Vec(n, _) => *n,
        _ => 1,
    };
    let w = t.wgsl();
    let one = if is_vec { format!("{w}(1.0)") } else { "1.0f".to_string() };
    match name {
        "recip" => sig(vec![], t, move |a| format!("({one} / {})", a[0])),
        "fract" => sig(vec![], t, |a| format!("({0} - trunc({0}))", a[0])),
        // Half away from zero. (`floor(abs(x) + 0.5)` is wrong where the
        // addition rounds: 0.49999997, and odd values from 2^23 on.)
        "round" => {
            let half = if is_vec { format!("{w}(0.5)") } else { "0.5f".to_string() };
            sig(vec![], t, move |a| format!("(trunc({0}) + sign({0}) * step({half}, abs({0} - trunc({0}))))", a[0]))
        }
        "signum" => {
            let (pos, neg) =
                if is_vec { (format!("{w}(1.0)"), format!("{w}(-1.0)")) } else { ("1.0f".into(), "-1.0f".into()) };
            let sign_bit = if is_vec {
                format!("(bitcast<vec{n}<u32>>({{}}) & vec{n}<u32>(0x80000000u)) != vec{n}<u32>(0u)")
            } else {
                "(bitcast<u32>({}) & 0x80000000u) != 0u".to_string()
            };
            sig(vec![], t, move |a| format!("select({pos}, {neg}, {})", sign_bit.replace("{}", &a[0])))
        }
        "powf" => sig(vec![F32], t, move |a| {
            if is_vec { format!("pow({}, {w}({}))", a[0], a[1]) } else { format!("pow({}, {})", a[0], a[1]) }
        }),
        "powi" if is_scalar => {
            let mut s = sig(vec![Ty::Scalar(Scalar::I32)], t, |a| format!("rt_powi({}, {})", a[0], a[1]))?;
            s.support = vec![("rt_powi", POWI)];
            Some(s)
        }
        "atan2" if is_scalar => sig(vec![F32], t, |a| format!("atan2({}, {})", a[0], a[1])),
        "mul_add" => sig(vec![t.clone(), t.clone()], t, wgsl_fn("fma")),
        "is_nan" if is_scalar => sig(vec![], Ty::Scalar(Scalar::Bool), |a| format!("({0} != {0})", a[0])),
        "is_finite" if is_scalar => {
            sig(vec![], Ty::Scalar(Scalar::Bool), |a| format!("(abs({}) <= {})", a[0], f32_literal(f32::MAX)))
        }
        "is_infinite" if is_scalar => {
            sig(vec![], Ty::Scalar(Scalar::Bool), |a| format!("(abs({}) > {})", a[0], f32_literal(f32::MAX)))
        }
        "sin_cos" if is_scalar => {
            let pair = Ty::Tuple(vec![F32, F32]);
            let name = pair.wgsl();
            sig(vec![], pair, move |a| format!("{name}(sin({0}), cos({0}))", a[0]))
        }
        "hypot" if is_scalar => sig(vec![F32], t, |a| format!("length(vec2<f32>({}, {}))", a[0], a[1])),
        _ => None,
    }
}

/// The float vectors' own: lengths, normalization, distances, `lerp`, and
/// `Vec3`'s `reflect`, `refract` and `cross`.
fn float_vec_method(recv: &Ty, name: &str) -> Option<MethodSig> {
    let Ty::Vec(n, _) = *recv else {
        return None;
    };
    let t = recv.clone();
    let w = t.wgsl();
    let v3 = Ty::vec(3);
    match name {
        "length" => sig(vec![], F32, wgsl_fn("length")),
        "length_squared" => sig(vec![], F32, |a| format!("dot({0}, {0})", a[0])),
        "length_recip" => sig(vec![], F32, |a| format!("inverseSqrt(dot({0}, {0}))", a[0])),
        "normalize" => sig(vec![], t, wgsl_fn("normalize")),
        // (`inverseSqrt` of a positive length only: WGSL rejects a
        // constant zero vector's `inverseSqrt(0.0)` even unselected.)
        "normalize_or_zero" => sig(vec![], t, move |a| {
            format!(
                "select({w}(), {0} * inverseSqrt(select(1.0, dot({0}, {0}), dot({0}, {0}) > 0.0)), dot({0}, {0}) > 0.0)",
                a[0]
            )
        }),
        "distance" => sig(vec![t.clone()], F32, wgsl_fn("distance")),
        "distance_squared" => sig(vec![t.clone()], F32, |a| format!("dot({0} - {1}, {0} - {1})", a[0], a[1])),
        // glam's formula, not WGSL's `mix`: GPUs compute that as
        // `a + t * (b - a)`, which misses `b` at `t == 1` (glam
        // promises both ends exactly).
        "lerp" => sig(vec![t.clone(), F32], t, |a| lerp_formula(&a[0], &a[1], &a[2])),
        "reflect" if n == 3 => sig(vec![v3.clone()], v3, wgsl_fn("reflect")),
        "refract" if n == 3 => sig(vec![v3.clone(), F32], v3, wgsl_fn("refract")),
        "cross" if n == 3 => sig(vec![v3.clone()], v3, wgsl_fn("cross")),
        _ => None,
    }
}

/// Methods of the integer scalars and vectors.
fn int_method(recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    let is_scalar = matches!(recv, Ty::Scalar(_));
    let u = U32;
    let cnt = |f: &'static str| {
        let scalar_is_u = recv.scalar() == Some(Scalar::U32);
        move |a: &[String]| if scalar_is_u { format!("{f}({})", a[0]) } else { format!("u32({f}({}))", a[0]) }
    };
    match name {
        "abs" if recv.scalar() == Some(Scalar::I32) => return sig(vec![], t, wgsl_fn("abs")),
        "signum" if recv.scalar() == Some(Scalar::I32) => return sig(vec![], t, wgsl_fn("sign")),
        "count_ones" if is_scalar => return sig(vec![], u, cnt("countOneBits")),
        "leading_zeros" if is_scalar => return sig(vec![], u, cnt("countLeadingZeros")),
        "trailing_zeros" if is_scalar => return sig(vec![], u, cnt("countTrailingZeros")),
        "reverse_bits" if is_scalar => return sig(vec![], t, wgsl_fn("reverseBits")),
        // `n.is_multiple_of(0)` is `n == 0`. (The divisor is never a
        // zero: WGSL rejects `n % 0u` when it can see the zero.)
        "is_multiple_of" if matches!(recv, Ty::Scalar(Scalar::U32 | Scalar::Usize)) => {
            return sig(vec![t.clone()], Ty::Scalar(Scalar::Bool), |a| {
                format!("select(({0} % select({1}, 1u, {1} == 0u)) == 0u, {0} == 0u, {1} == 0u)", a[0], a[1])
            });
        }
        "wrapping_add" => return sig(vec![t.clone()], t, |a| format!("({} + {})", a[0], a[1])),
        "wrapping_sub" => return sig(vec![t.clone()], t, |a| format!("({} - {})", a[0], a[1])),
        "wrapping_mul" => return sig(vec![t.clone()], t, |a| format!("({} * {})", a[0], a[1])),
        // `(wrapped, overflowed)`: unsigned, the result passed an operand;
        // signed, the operands' signs agreed and the result's differs.
        "overflowing_add" | "overflowing_sub" if is_scalar => {
            let pair = Ty::Tuple(vec![t.clone(), Ty::Scalar(Scalar::Bool)]);
            let name_ = pair.wgsl();
            let signed = recv.scalar() == Some(Scalar::I32);
            let add = name == "overflowing_add";
            return sig(vec![t.clone()], pair, move |a| {
                let (x, y) = (&a[0], &a[1]);
                let r = if add { format!("({x} + {y})") } else { format!("({x} - {y})") };
                let over = match (signed, add) {
                    (false, true) => format!("({r} < {x})"),
                    (false, false) => format!("({x} < {y})"),
                    (true, true) => format!("((({x} ^ {r}) & ({y} ^ {r})) < 0i)"),
                    (true, false) => format!("((({x} ^ {y}) & ({x} ^ {r})) < 0i)"),
                };
                format!("{name_}({r}, {over})")
            });
        }
        _ => {}
    }
    None
}

/// Methods of every numeric vector: reductions, `extend`/`truncate`,
/// conversions and swizzles.
fn vec_method(recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    let n = match recv {
        Ty::Vec(n, _) => *n,
        _ => 1,
    };
    let s = recv.scalar().unwrap();
    let comps = |f: &'static str| {
        move |a: &[String]| {
            let parts: Vec<String> =
                (0..n).map(|i| format!("{}.{}", a[0], &"xyzw"[i as usize..i as usize + 1])).collect();
            match f {
                "+" | "*" => format!("({})", parts.join(&format!(" {f} "))),
                _ => parts[1..].iter().fold(parts[0].clone(), |acc, p| format!("{f}({acc}, {p})")),
            }
        }
    };
    match name {
        "dot" => return sig(vec![t.clone()], Ty::Scalar(s), wgsl_fn("dot")),
        "element_sum" => return sig(vec![], Ty::Scalar(s), comps("+")),
        "element_product" => return sig(vec![], Ty::Scalar(s), comps("*")),
        "min_element" => return sig(vec![], Ty::Scalar(s), comps("min")),
        "max_element" => return sig(vec![], Ty::Scalar(s), comps("max")),
        "to_array" => {
            let parts: Vec<&'static str> = ["x", "y", "z", "w"][..n as usize].to_vec();
            let out = Ty::Array(Box::new(Ty::Scalar(s)), n as u32);
            let w = out.wgsl();
            return sig(vec![], out, move |a| {
                let comps: Vec<String> = parts.iter().map(|c| format!("{}.{c}", a[0])).collect();
                format!("{w}({})", comps.join(", "))
            });
        }
        "extend" if n < 4 => {
            let out = Ty::Vec(n + 1, s);
            let w = out.wgsl();
            return sig(vec![Ty::Scalar(s)], out, move |a| format!("{w}({}, {})", a[0], a[1]));
        }
        "truncate" if n > 2 => {
            let sw = &"xyzw"[..(n - 1) as usize];
            let sw = sw.to_string();
            return sig(vec![], Ty::Vec(n - 1, s), move |a| format!("{}.{sw}", a[0]));
        }
        _ => {}
    }
    for (prefix, target) in [("as_vec", Scalar::F32), ("as_ivec", Scalar::I32), ("as_uvec", Scalar::U32)] {
        if name == format!("{prefix}{n}") {
            let out = Ty::Vec(n, target);
            if s == Scalar::F32 && target != Scalar::F32 {
                // Saturating, as `as i32` / `as u32` per component.
                let (f, text) = float_to_int(n, target == Scalar::I32);
                let mut m = sig(vec![], out, move |a| format!("{f}({})", a[0]))?;
                m.support = vec![(f, text)];
                return Some(m);
            }
            let w = out.wgsl();
            return sig(vec![], out, move |a| format!("{w}({})", a[0]));
        }
    }
    // Swizzles: `v.xy()`, `v.zyx()`, `v.xxxx()`.
    if (2..=4).contains(&name.len()) && name.chars().all(|c| "xyzw"[..n as usize].contains(c)) {
        let sw = name.to_string();
        return sig(vec![], Ty::Vec(name.len() as u8, s), move |a| format!("{}.{sw}", a[0]));
    }
    None
}

fn mat_method(n: u8, name: &str) -> Option<MethodSig> {
    let t = Ty::Mat(n);
    let v = Ty::vec(n);
    match name {
        "transpose" => sig(vec![], t, wgsl_fn("transpose")),
        // Column-major (glam's storage order) or row-major; `_2d` is an
        // array of the columns as arrays.
        "to_cols_array" | "to_rows_array" => {
            let rows = name == "to_rows_array";
            let out = Ty::Array(Box::new(F32), (n * n) as u32);
            let w = out.wgsl();
            sig(vec![], out, move |a| {
                let comps: Vec<String> = (0..n * n)
                    .map(|k| {
                        let (outer, inner) = (k / n, k % n);
                        let (c, r) = if rows { (inner, outer) } else { (outer, inner) };
                        format!("{}[{c}][{r}]", a[0])
                    })
                    .collect();
                format!("{w}({})", comps.join(", "))
            })
        }
        "to_cols_array_2d" => {
            let col = Ty::Array(Box::new(F32), n as u32);
            let out = Ty::Array(Box::new(col.clone()), n as u32);
            let (w, cw) = (out.wgsl(), col.wgsl());
            sig(vec![], out, move |a| {
                let cols: Vec<String> = (0..n)
                    .map(|c| {
                        let comps: Vec<String> = (0..n).map(|r| format!("{}[{c}][{r}]", a[0])).collect();
                        format!("{cw}({})", comps.join(", "))
                    })
                    .collect();
                format!("{w}({})", cols.join(", "))
            })
        }
        "determinant" => sig(vec![], F32, wgsl_fn("determinant")),
        "col" => sig(vec![Ty::Scalar(Scalar::Usize)], v, |a| format!("{}[{}]", a[0], a[1])),
        "mul_vec3" if n == 3 => sig(vec![v.clone()], v, |a| format!("({} * {})", a[0], a[1])),
        "mul_vec4" if n == 4 => sig(vec![v.clone()], v, |a| format!("({} * {})", a[0], a[1])),
        "mul_mat3" if n == 3 => sig(vec![t.clone()], t, |a| format!("({} * {})", a[0], a[1])),
        "mul_mat4" if n == 4 => sig(vec![t.clone()], t, |a| format!("({} * {})", a[0], a[1])),
        "transform_point3" if n == 4 => {
            sig(vec![Ty::vec(3)], Ty::vec(3), |a| format!("({} * vec4<f32>({}, 1.0)).xyz", a[0], a[1]))
        }
        "transform_vector3" if n == 4 => {
            sig(vec![Ty::vec(3)], Ty::vec(3), |a| format!("({} * vec4<f32>({}, 0.0)).xyz", a[0], a[1]))
        }
        _ => None,
    }
}

/// glam's methods that change the receiver in place (`&mut self`): their
/// parameters and result. `set_row` and `BVecN::set` are assignments to the
/// receiver's place; `col_mut` is a place itself (`*m.col_mut(i) = v`,
/// `m.col_mut(i).x += 1.0`), its `&mut Vec` result spelled `&mut VecN`.
/// The index is clamped to the last row, column or component, as indexing
/// is (lowered in `func/places.rs`).
pub fn in_place_method(recv: &Ty, name: &str) -> Option<(Vec<Ty>, Ty)> {
    let usize_ = Ty::Scalar(Scalar::Usize);
    match (recv, name) {
        (Ty::Mat(n), "set_row") => Some((vec![usize_, Ty::vec(*n)], Ty::Unit)),
        (Ty::Mat(n), "col_mut") => Some((vec![usize_], Ty::Ref(true, Box::new(Ty::vec(*n))))),
        (Ty::Vec(_, Scalar::Bool), "set") => Some((vec![usize_, Ty::Scalar(Scalar::Bool)], Ty::Unit)),
        _ => None,
    }
}

/// Extra advice for methods users reach for that have no WGSL equivalent.
pub fn method_hint(recv: &Ty, name: &str) -> String {
    match (recv, name) {
        (Ty::Vec(..), "map") => {
            ": it takes a closure, which ray programs cannot have; write the components out (`Vec3::new(a.x.round(), ..)`) or use a method of the whole vector".into()
        }
        (_, "iter" | "into_iter" | "map" | "for_each") => {
            ": iterators are not supported; loop over an index range".into()
        }
        (_, "to_string") => ": strings are not supported".into(),
        (_, "unwrap" | "expect") => ": Option and Result are not supported".into(),
        _ => ": write it with the methods rt_std documents as supported (a #[rt_function] helper can hold it)".into(),
    }
}

/// Associated constants: `Vec3::ZERO`, `f32::MAX`, `Mat4::IDENTITY`, ...
pub fn assoc_const(owner: &str, name: &str) -> Option<Val> {
    let ty = crate::types::builtin_type(owner)?;
    let w = ty.wgsl();
    match &ty {
        Ty::Scalar(Scalar::F32) => {
            let v = match name {
                "MAX" => f32::MAX,
                "MIN" => f32::MIN,
                "MIN_POSITIVE" => f32::MIN_POSITIVE,
                "EPSILON" => f32::EPSILON,
                "INFINITY" => f32::INFINITY,
                "NEG_INFINITY" => f32::NEG_INFINITY,
                "NAN" => f32::NAN,
                _ => return None,
            };
            Some(Val::new(f32_literal(v), ty))
        }
        Ty::Scalar(Scalar::I32) => match name {
            "MAX" => Some(Val::new("2147483647i", ty)),
            "MIN" => Some(Val::new("i32(-2147483648)", ty)),
            _ => None,
        },
        Ty::Scalar(Scalar::U32) => match name {
            "MAX" => Some(Val::new("4294967295u", ty)),
            "MIN" => Some(Val::new("0u", ty)),
            _ => None,
        },
        Ty::Vec(n, s) => {
            let (one, zero, neg) = match s {
                Scalar::F32 => ("1.0", "0.0", Some("-1.0")),
                Scalar::I32 => ("1i", "0i", Some("-1i")),
                _ => ("1u", "0u", None),
            };
            let axis = |i: usize, v: &str| {
                let parts: Vec<&str> = (0..*n as usize).map(|j| if j == i { v } else { zero }).collect();
                format!("{w}({})", parts.join(", "))
            };
            let code = match name {
                "ZERO" => zero_value(&ty),
                "ONE" => format!("{w}({one})"),
                "NEG_ONE" => format!("{w}({})", neg?),
                "X" => axis(0, one),
                "Y" => axis(1, one),
                "Z" if *n >= 3 => axis(2, one),
                "W" if *n >= 4 => axis(3, one),
                "NEG_X" => axis(0, neg?),
                "NEG_Y" => axis(1, neg?),
                "NEG_Z" if *n >= 3 => axis(2, neg?),
                "NEG_W" if *n >= 4 => axis(3, neg?),
                // glam's `MIN`/`MAX`: the element type's, splatted
                // (`f32::MIN`/`MAX` are finite, spelled as hex floats).
                "MIN" | "MAX" => {
                    let v = assoc_const(s.rust(), name)?;
                    format!("{w}({})", v.code)
                }
                _ => return None,
            };
            Some(Val::new(code, ty))
        }
        Ty::Mat(n) => match name {
            "ZERO" => Some(Val::new(format!("{w}()"), ty)),
            "IDENTITY" => {
                let cols: Vec<String> = (0..*n)
                    .map(|i| {
                        let c: Vec<&str> = (0..*n).map(|j| if i == j { "1.0" } else { "0.0" }).collect();
                        format!("vec{n}<f32>({})", c.join(", "))
                    })
                    .collect();
                Some(Val::new(format!("{w}({})", cols.join(", ")), ty))
            }
            _ => None,
        },
        _ => None,
    }
}
