//! glam methods that WGSL has no builtin for, written out: matrix
//! inverses (glam's own cofactor formulas), vector projections and
//! rejections, `any_orthonormal_vector`, Euclidean division and remainder of
//! floats, `log10`, `copysign`, integer rotations. Each follows glam's (or
//! std's) definition operation for operation, so the two backends differ
//! only by WGSL's rounding; [`super::method_sig`] asks here first.

use super::MethodSig;
use crate::types::{F32, Scalar, Ty};

fn sig(params: Vec<Ty>, ret: Ty, lower: impl Fn(&[String]) -> String + 'static) -> Option<MethodSig> {
    Some(MethodSig { params, ret, lower: Box::new(lower), support: Vec::new() })
}

fn with_support(m: Option<MethodSig>, name: &'static str, text: &'static str) -> Option<MethodSig> {
    m.map(|mut m| {
        m.support.push((name, text));
        m
    })
}

/// glam's `Mat2::inverse`: the adjugate over the determinant.
const INVERSE2: &str = "\
fn rt_inverse2(m: mat2x2<f32>) -> mat2x2<f32> {
    let inv_det = 1.0f / (m[0].x * m[1].y - m[1].x * m[0].y);
    return mat2x2<f32>(vec2<f32>(m[1].y, m[0].y * -1.0f) * inv_det, vec2<f32>(m[1].x * -1.0f, m[0].x) * inv_det);
}
";

/// glam's `Mat3::inverse`: the cross products of the columns over the
/// determinant, transposed.
const INVERSE3: &str = "\
fn rt_inverse3(m: mat3x3<f32>) -> mat3x3<f32> {
    let tmp0 = cross(m[1], m[2]);
    let tmp1 = cross(m[2], m[0]);
    let tmp2 = cross(m[0], m[1]);
    let inv_det = vec3<f32>(1.0f / dot(m[0], tmp0));
    return transpose(mat3x3<f32>(tmp0 * inv_det, tmp1 * inv_det, tmp2 * inv_det));
}
";

/// glam's `Mat4::inverse` (its scalar path): 2x2 cofactors, the adjugate's
/// columns with alternating signs, over the determinant.
const INVERSE4: &str = "\
fn rt_inverse4(m: mat4x4<f32>) -> mat4x4<f32> {
    let m00 = m[0].x; let m01 = m[0].y; let m02 = m[0].z; let m03 = m[0].w;
    let m10 = m[1].x; let m11 = m[1].y; let m12 = m[1].z; let m13 = m[1].w;
    let m20 = m[2].x; let m21 = m[2].y; let m22 = m[2].z; let m23 = m[2].w;
    let m30 = m[3].x; let m31 = m[3].y; let m32 = m[3].z; let m33 = m[3].w;
    let coef00 = m22 * m33 - m32 * m23;
    let coef02 = m12 * m33 - m32 * m13;
    let coef03 = m12 * m23 - m22 * m13;
    let coef04 = m21 * m33 - m31 * m23;
    let coef06 = m11 * m33 - m31 * m13;
    let coef07 = m11 * m23 - m21 * m13;
    let coef08 = m21 * m32 - m31 * m22;
    let coef10 = m11 * m32 - m31 * m12;
    let coef11 = m11 * m22 - m21 * m12;
    let coef12 = m20 * m33 - m30 * m23;
    let coef14 = m10 * m33 - m30 * m13;
    let coef15 = m10 * m23 - m20 * m13;
    let coef16 = m20 * m32 - m30 * m22;
    let coef18 = m10 * m32 - m30 * m12;
    let coef19 = m10 * m22 - m20 * m12;
    let coef20 = m20 * m31 - m30 * m21;
    let coef22 = m10 * m31 - m30 * m11;
    let coef23 = m10 * m21 - m20 * m11;
    let fac0 = vec4<f32>(coef00, coef00, coef02, coef03);
    let fac1 = vec4<f32>(coef04, coef04, coef06, coef07);
    let fac2 = vec4<f32>(coef08, coef08, coef10, coef11);
    let fac3 = vec4<f32>(coef12, coef12, coef14, coef15);
    let fac4 = vec4<f32>(coef16, coef16, coef18, coef19);
    let fac5 = vec4<f32>(coef20, coef20, coef22, coef23);
    let vec0 = vec4<f32>(m10, m00, m00, m00);
    let vec1 = vec4<f32>(m11, m01, m01, m01);
    let vec2_ = vec4<f32>(m12, m02, m02, m02);
    let vec3_ = vec4<f32>(m13, m03, m03, m03);
    let inv0 = vec1 * fac0 - vec2_ * fac1 + vec3_ * fac2;
    let inv1 = vec0 * fac0 - vec2_ * fac3 + vec3_ * fac4;
    let inv2 = vec0 * fac1 - vec1 * fac3 + vec3_ * fac5;
    let inv3 = vec0 * fac2 - vec1 * fac4 + vec2_ * fac5;
    let sign_a = vec4<f32>(1.0f, -1.0f, 1.0f, -1.0f);
    let sign_b = vec4<f32>(-1.0f, 1.0f, -1.0f, 1.0f);
    let inverse = mat4x4<f32>(inv0 * sign_a, inv1 * sign_b, inv2 * sign_a, inv3 * sign_b);
    let col0 = vec4<f32>(inverse[0].x, inverse[1].x, inverse[2].x, inverse[3].x);
    let dot0 = m[0] * col0;
    let dot1 = dot0.x + dot0.y + dot0.z + dot0.w;
    return inverse * (1.0f / dot1);
}
";

/// `f32::rem_euclid`: `r = a % b` (Rust's `fmod`, `rt_fmod`), plus `|b|`
/// when negative.
const REM_EUCLID: &str = "\
fn rt_rem_euclid(a: f32, b: f32) -> f32 {
    let r = rt_fmod(a, b);
    return select(r, r + abs(b), r < 0.0f);
}
";

/// `f32::div_euclid`: the truncated quotient, one step further from zero
/// where the remainder is negative.
const DIV_EUCLID: &str = "\
fn rt_div_euclid(a: f32, b: f32) -> f32 {
    let q = trunc(a / b);
    if rt_fmod(a, b) < 0.0f {
        return select(q + 1.0f, q - 1.0f, b > 0.0f);
    }
    return q;
}
";

/// glam's `normalize_or`: `self * (1 / length)` where that factor is
/// finite and positive, else the fallback; a function, so that a constant
/// zero vector's infinite factor is never a constant expression.
const NORMALIZE_OR: [&str; 3] = [
    "\
fn rt_normalize_or2(v: vec2<f32>, fallback: vec2<f32>) -> vec2<f32> {
    let rcp = 1.0f / length(v);
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        return v * rcp;
    }
    return fallback;
}
",
    "\
fn rt_normalize_or3(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let rcp = 1.0f / length(v);
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        return v * rcp;
    }
    return fallback;
}
",
    "\
fn rt_normalize_or4(v: vec4<f32>, fallback: vec4<f32>) -> vec4<f32> {
    let rcp = 1.0f / length(v);
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        return v * rcp;
    }
    return fallback;
}
",
];

/// glam's `normalize_and_length`: as `normalize_or`, with the length (or
/// `(X, 0.0)`).
const NORMALIZE_AND_LENGTH: [&str; 3] = [
    "\
fn rt_normalize_and_length2(v: vec2<f32>) -> rt_tuple_vec2f_f32_ {
    let length = length(v);
    let rcp = 1.0f / length;
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        return rt_tuple_vec2f_f32_(v * rcp, length);
    }
    return rt_tuple_vec2f_f32_(vec2<f32>(1.0f, 0.0f), 0.0f);
}
",
    "\
fn rt_normalize_and_length3(v: vec3<f32>) -> rt_tuple_vec3f_f32_ {
    let length = length(v);
    let rcp = 1.0f / length;
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        return rt_tuple_vec3f_f32_(v * rcp, length);
    }
    return rt_tuple_vec3f_f32_(vec3<f32>(1.0f, 0.0f, 0.0f), 0.0f);
}
",
    "\
fn rt_normalize_and_length4(v: vec4<f32>) -> rt_tuple_vec4f_f32_ {
    let length = length(v);
    let rcp = 1.0f / length;
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        return rt_tuple_vec4f_f32_(v * rcp, length);
    }
    return rt_tuple_vec4f_f32_(vec4<f32>(1.0f, 0.0f, 0.0f, 0.0f), 0.0f);
}
",
];

/// glam's `inverse_or_zero`: the inverse, or zero where it is not finite
/// (read from the bits, which no implementation may assume away, after a
/// zero determinant, where the division itself is not defined on every GPU).
const INVERSE_OR_ZERO: [&str; 3] = [
    "\
fn rt_inverse_or_zero2(m: mat2x2<f32>) -> mat2x2<f32> {
    if determinant(m) == 0.0f {
        return mat2x2<f32>();
    }
    let r = rt_inverse2(m);
    if any((bitcast<vec2<u32>>(r[0]) & vec2<u32>(0x7f800000u)) == vec2<u32>(0x7f800000u)) {
        return mat2x2<f32>();
    }
    if any((bitcast<vec2<u32>>(r[1]) & vec2<u32>(0x7f800000u)) == vec2<u32>(0x7f800000u)) {
        return mat2x2<f32>();
    }
    return r;
}
",
    "\
fn rt_inverse_or_zero3(m: mat3x3<f32>) -> mat3x3<f32> {
    if determinant(m) == 0.0f {
        return mat3x3<f32>();
    }
    let r = rt_inverse3(m);
    if any((bitcast<vec3<u32>>(r[0]) & vec3<u32>(0x7f800000u)) == vec3<u32>(0x7f800000u)) {
        return mat3x3<f32>();
    }
    if any((bitcast<vec3<u32>>(r[1]) & vec3<u32>(0x7f800000u)) == vec3<u32>(0x7f800000u)) {
        return mat3x3<f32>();
    }
    if any((bitcast<vec3<u32>>(r[2]) & vec3<u32>(0x7f800000u)) == vec3<u32>(0x7f800000u)) {
        return mat3x3<f32>();
    }
    return r;
}
",
    "\
fn rt_inverse_or_zero4(m: mat4x4<f32>) -> mat4x4<f32> {
    if determinant(m) == 0.0f {
        return mat4x4<f32>();
    }
    let r = rt_inverse4(m);
    if any((bitcast<vec4<u32>>(r[0]) & vec4<u32>(0x7f800000u)) == vec4<u32>(0x7f800000u)) {
        return mat4x4<f32>();
    }
    if any((bitcast<vec4<u32>>(r[1]) & vec4<u32>(0x7f800000u)) == vec4<u32>(0x7f800000u)) {
        return mat4x4<f32>();
    }
    if any((bitcast<vec4<u32>>(r[2]) & vec4<u32>(0x7f800000u)) == vec4<u32>(0x7f800000u)) {
        return mat4x4<f32>();
    }
    if any((bitcast<vec4<u32>>(r[3]) & vec4<u32>(0x7f800000u)) == vec4<u32>(0x7f800000u)) {
        return mat4x4<f32>();
    }
    return r;
}
",
];

/// The glam methods of this file for `recv.name(...)`, if it is one.
pub fn method(recv: &Ty, name: &str) -> Option<MethodSig> {
    match recv {
        Ty::Mat(n) if name == "inverse" => {
            let (f, text) = match n {
                2 => ("rt_inverse2", INVERSE2),
                3 => ("rt_inverse3", INVERSE3),
                _ => ("rt_inverse4", INVERSE4),
            };
            with_support(sig(vec![], recv.clone(), move |a| format!("{f}({})", a[0])), f, text)
        }
        Ty::Mat(n) if name == "inverse_or_zero" => {
            let i = *n as usize - 2;
            let (f, text) = [("rt_inverse2", INVERSE2), ("rt_inverse3", INVERSE3), ("rt_inverse4", INVERSE4)][i];
            let g: &'static str = ["rt_inverse_or_zero2", "rt_inverse_or_zero3", "rt_inverse_or_zero4"][i];
            let m = with_support(sig(vec![], recv.clone(), move |a| format!("{g}({})", a[0])), f, text);
            with_support(m, g, INVERSE_OR_ZERO[i])
        }
        Ty::Mat(n) => mat(*n, name),
        Ty::Scalar(Scalar::F32) => float(name),
        Ty::Vec(n, Scalar::F32) => float_vec(*n, recv, name).or_else(|| any_vec(*n, recv, name)),
        Ty::Vec(n, _) => any_vec(*n, recv, name),
        Ty::Scalar(s @ (Scalar::U32 | Scalar::I32)) => int(*s, name),
        _ => None,
    }
}

/// Methods of every glam vector: component replacement, `dot_into_vec`.
fn any_vec(n: u8, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    let w = t.wgsl();
    let s = Ty::Scalar(recv.scalar()?);
    let axis = ["with_x", "with_y", "with_z", "with_w"].iter().position(|a| *a == name).filter(|i| *i < n as usize);
    if let Some(i) = axis {
        return sig(vec![s], t, move |a| {
            let parts: Vec<String> = (0..n as usize)
                .map(|k| if k == i { a[1].clone() } else { format!("{}.{}", a[0], &"xyzw"[k..k + 1]) })
                .collect();
            format!("{w}({})", parts.join(", "))
        });
    }
    match name {
        "dot_into_vec" => sig(vec![t.clone()], t, move |a| format!("{w}(dot({}, {}))", a[0], a[1])),
        _ => None,
    }
}

/// Matrix methods glam has beyond the products: rows, the diagonal, sums
/// and scalings, `abs`, transposed products, 2D and projective transforms.
fn mat(n: u8, name: &str) -> Option<MethodSig> {
    let t = Ty::Mat(n);
    let v = Ty::vec(n);
    let cols = move |f: &dyn Fn(String) -> String, m: &str| {
        let parts: Vec<String> = (0..n).map(|i| f(format!("{m}[{i}]"))).collect();
        format!("mat{n}x{n}<f32>({})", parts.join(", "))
    };
    match name {
        "row" => sig(vec![Ty::Scalar(Scalar::Usize)], v, move |a| {
            let parts: Vec<String> = (0..n).map(|i| format!("{}[{i}][{}]", a[0], a[1])).collect();
            format!("vec{n}<f32>({})", parts.join(", "))
        }),
        "diagonal" => sig(vec![], v, move |a| {
            let parts: Vec<String> = (0..n).map(|i| format!("{}[{i}][{i}]", a[0])).collect();
            format!("vec{n}<f32>({})", parts.join(", "))
        }),
        "add_mat2" | "add_mat3" | "add_mat4" if name.ends_with(&n.to_string()) => {
            sig(vec![t.clone()], t, |a| format!("({} + {})", a[0], a[1]))
        }
        "sub_mat2" | "sub_mat3" | "sub_mat4" if name.ends_with(&n.to_string()) => {
            sig(vec![t.clone()], t, |a| format!("({} - {})", a[0], a[1]))
        }
        "mul_scalar" => sig(vec![F32], t, |a| format!("({} * {})", a[0], a[1])),
        "div_scalar" => sig(vec![F32], t, move |a| cols(&|c| format!("({c} / vec{n}<f32>({}))", a[1]), &a[0])),
        "abs" => sig(vec![], t, move |a| cols(&|c| format!("abs({c})"), &a[0])),
        "transpose_mul_vec2" | "transpose_mul_vec3" | "transpose_mul_vec4" if name.ends_with(&n.to_string()) => {
            // `v * m` in WGSL: the dot of each column with `v`.
            sig(vec![v.clone()], v, |a| format!("({} * {})", a[1], a[0]))
        }
        "mul_transpose_vec2" | "mul_transpose_vec3" | "mul_transpose_vec4" if name.ends_with(&n.to_string()) => {
            sig(vec![v.clone()], v, |a| format!("({} * {})", a[1], a[0]))
        }
        "mul_diagonal_scale" => sig(vec![v.clone()], t, move |a| {
            let parts: Vec<String> = (0..n).map(|i| format!("({}[{i}] * {}[{i}])", a[0], a[1])).collect();
            format!("mat{n}x{n}<f32>({})", parts.join(", "))
        }),
        "recip" => sig(vec![], t, move |a| cols(&|c| format!("(vec{n}<f32>(1.0) / {c})"), &a[0])),
        "abs_diff_eq" => sig(vec![t.clone(), F32], Ty::Scalar(Scalar::Bool), move |a| {
            let parts: Vec<String> = (0..n)
                .map(|i| format!("all(abs({0}[{i}] - {1}[{i}]) <= vec{n}<f32>({2}))", a[0], a[1], a[2]))
                .collect();
            format!("({})", parts.join(" && "))
        }),
        "is_finite" => sig(vec![], Ty::Scalar(Scalar::Bool), move |a| {
            let parts: Vec<String> = (0..n)
                .map(|i| format!("all(abs({}[{i}]) <= vec{n}<f32>({}))", a[0], super::f32_literal(f32::MAX)))
                .collect();
            format!("({})", parts.join(" && "))
        }),
        "is_nan" => sig(vec![], Ty::Scalar(Scalar::Bool), move |a| {
            let parts: Vec<String> = (0..n).map(|i| format!("any({0}[{i}] != {0}[{i}])", a[0])).collect();
            format!("({})", parts.join(" || "))
        }),
        "mul_vec2" if n == 2 => sig(vec![v.clone()], v, |a| format!("({} * {})", a[0], a[1])),
        "mul_mat2" if n == 2 => sig(vec![t.clone()], t, |a| format!("({} * {})", a[0], a[1])),
        "transform_point2" if n == 3 => {
            sig(vec![Ty::vec(2)], Ty::vec(2), |a| format!("({} * vec3<f32>({}, 1.0f)).xy", a[0], a[1]))
        }
        "transform_vector2" if n == 3 => {
            sig(vec![Ty::vec(2)], Ty::vec(2), |a| format!("({} * vec3<f32>({}, 0.0f)).xy", a[0], a[1]))
        }
        "project_point3" if n == 4 => {
            let f = "rt_project_point3";
            let text = "\
fn rt_project_point3(m: mat4x4<f32>, p: vec3<f32>) -> vec3<f32> {
    let r = m * vec4<f32>(p, 1.0f);
    return (r / r.w).xyz;
}
";
            with_support(sig(vec![Ty::vec(3)], Ty::vec(3), move |a| format!("{f}({}, {})", a[0], a[1])), f, text)
        }
        _ => None,
    }
}

fn float(name: &str) -> Option<MethodSig> {
    match name {
        // WGSL has `log2` only: log10(x) = log2(x) * log10(2).
        "log10" => sig(vec![], F32, |a| format!("(log2({}) * 0.30102999566f)", a[0])),
        "log" => sig(vec![F32], F32, |a| format!("(log({}) / log({}))", a[0], a[1])),
        "copysign" => sig(vec![F32], F32, |a| {
            format!("bitcast<f32>((bitcast<u32>({}) & 0x7fffffffu) | (bitcast<u32>({}) & 0x80000000u))", a[0], a[1])
        }),
        "rem_euclid" => with_fmod(with_support(
            sig(vec![F32], F32, |a| format!("rt_rem_euclid({}, {})", a[0], a[1])),
            "rt_rem_euclid",
            REM_EUCLID,
        )),
        "div_euclid" => with_fmod(with_support(
            sig(vec![F32], F32, |a| format!("rt_div_euclid({}, {})", a[0], a[1])),
            "rt_div_euclid",
            DIV_EUCLID,
        )),
        _ => None,
    }
}

/// A method whose support function calls `rt_fmod`: the lowering adds
/// `rt_fmod` too (see `calls.rs`, which adds a method's support).
fn with_fmod(m: Option<MethodSig>) -> Option<MethodSig> {
    m.map(|mut m| {
        m.support.push(("rt_fmod", super::FMOD));
        m
    })
}

/// Methods of the float vectors, one group of methods after another.
fn float_vec(n: u8, recv: &Ty, name: &str) -> Option<MethodSig> {
    geometry(n, recv, name)
        .or_else(|| blend(n, recv, name))
        .or_else(|| lengths(n, recv, name))
        .or_else(|| vec2_method(n, recv, name))
        .or_else(|| per_component(n, recv, name))
}

/// Projections and rejections, reflection and refraction, homogeneous
/// coordinates, `any_orthonormal_vector`.
fn geometry(n: u8, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    match name {
        "project_onto" => sig(vec![t.clone()], t, |a| format!("({1} * (dot({0}, {1}) / dot({1}, {1})))", a[0], a[1])),
        "reject_from" => {
            sig(vec![t.clone()], t, |a| format!("({0} - {1} * (dot({0}, {1}) / dot({1}, {1})))", a[0], a[1]))
        }
        "project_onto_normalized" => sig(vec![t.clone()], t, |a| format!("({1} * dot({0}, {1}))", a[0], a[1])),
        "reject_from_normalized" => sig(vec![t.clone()], t, |a| format!("({0} - {1} * dot({0}, {1}))", a[0], a[1])),
        "reflect" if n != 3 => sig(vec![t.clone()], t, |a| format!("reflect({}, {})", a[0], a[1])),
        "refract" if n != 3 => sig(vec![t.clone(), F32], t, |a| format!("refract({}, {}, {})", a[0], a[1], a[2])),
        "to_homogeneous" if n == 3 => sig(vec![], Ty::vec(4), |a| format!("vec4<f32>({}, 1.0f)", a[0])),
        "project" if n == 4 => sig(vec![], Ty::vec(3), |a| format!("({0}.xyz / {0}.w)", a[0])),
        "any_orthonormal_vector" if n == 3 => {
            let f = "rt_any_orthonormal_vector";
            let text = "\
fn rt_any_orthonormal_vector(v: vec3<f32>) -> vec3<f32> {
    let sign = select(1.0f, -1.0f, (bitcast<u32>(v.z) & 0x80000000u) != 0u);
    let a = -1.0f / (sign + v.z);
    let b = v.x * v.y * a;
    return vec3<f32>(b, sign + v.y * v.y * a, -v.y);
}
";
            with_support(sig(vec![], t, move |a| format!("{f}({})", a[0])), f, text)
        }
        _ => None,
    }
}

/// Interpolation and clamping to `[0, 1]`: `midpoint`, `lerp_monotonic`,
/// `saturate`, `step`, `smoothstep`.
fn blend(n: u8, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    match name {
        "midpoint" => sig(vec![t.clone()], t, |a| format!("(({} + {}) * 0.5f)", a[0], a[1])),
        "saturate" => sig(vec![], t, |a| format!("saturate({})", a[0])),
        // glam: 0 where `rhs < self`, else 1; WGSL's `step(edge, x)`.
        "step" => sig(vec![t.clone()], t, |a| format!("step({}, {})", a[0], a[1])),
        "smoothstep" => sig(vec![t.clone(), t.clone()], t, move |a| {
            let tt = format!("saturate((({} - {1}) / ({2} - {1})))", a[0], a[1], a[2]);
            format!("({tt} * {tt} * ({w3}(3.0f) - {w3}(2.0f) * {tt}))", w3 = recv_w(n))
        }),
        "lerp_monotonic" => sig(vec![t.clone(), F32], t, |a| format!("({0} + ({1} - {0}) * {2})", a[0], a[1], a[2])),
        _ => None,
    }
}

/// Lengths: `is_normalized`, the `clamp_length` family, `normalize_or`,
/// `normalize_and_length`.
fn lengths(n: u8, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    match name {
        "is_normalized" => {
            sig(vec![], Ty::Scalar(Scalar::Bool), |a| format!("(abs(dot({0}, {0}) - 1.0f) <= 2e-4f)", a[0]))
        }
        "clamp_length" | "clamp_length_max" | "clamp_length_min" => {
            let params = if name == "clamp_length" { vec![F32, F32] } else { vec![F32] };
            let which = name.to_string();
            sig(params, t, move |a| {
                let (v, ls) = (&a[0], format!("dot({0}, {0})", a[0]));
                let scaled = |l: &str| format!("({l} * ({v} / sqrt({ls})))");
                match which.as_str() {
                    "clamp_length" => {
                        let (lo, hi) = (&a[1], &a[2]);
                        let (slo, shi) = (scaled(lo), scaled(hi));
                        format!("select(select({v}, {shi}, {ls} > {hi} * {hi}), {slo}, {ls} < {lo} * {lo})")
                    }
                    "clamp_length_max" => {
                        let (hi, shi) = (&a[1], scaled(&a[1]));
                        format!("select({v}, {shi}, {ls} > {hi} * {hi})")
                    }
                    _ => {
                        let (lo, slo) = (&a[1], scaled(&a[1]));
                        format!("select({v}, {slo}, {ls} < {lo} * {lo})")
                    }
                }
            })
        }
        "normalize_or" => {
            let i = n as usize - 2;
            let f: &'static str = ["rt_normalize_or2", "rt_normalize_or3", "rt_normalize_or4"][i];
            with_support(sig(vec![t.clone()], t, move |a| format!("{f}({}, {})", a[0], a[1])), f, NORMALIZE_OR[i])
        }
        "normalize_and_length" => {
            let i = n as usize - 2;
            let f: &'static str =
                ["rt_normalize_and_length2", "rt_normalize_and_length3", "rt_normalize_and_length4"][i];
            let ret = Ty::Tuple(vec![t.clone(), F32]);
            with_support(sig(vec![], ret, move |a| format!("{f}({})", a[0])), f, NORMALIZE_AND_LENGTH[i])
        }
        _ => None,
    }
}

/// `Vec2`'s own: `perp`, `perp_dot`, `rotate`, `to_angle`.
fn vec2_method(n: u8, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    match name {
        "perp" if n == 2 => sig(vec![], t, |a| format!("vec2<f32>(-{0}.y, {0}.x)", a[0])),
        "perp_dot" if n == 2 => {
            sig(vec![t.clone()], F32, |a| format!("(({0}.x * {1}.y) - ({0}.y * {1}.x))", a[0], a[1]))
        }
        "rotate" if n == 2 => sig(vec![t.clone()], t, |a| {
            format!("vec2<f32>({0}.x * {1}.x - {0}.y * {1}.y, {0}.y * {1}.x + {0}.x * {1}.y)", a[0], a[1])
        }),
        "to_angle" if n == 2 => sig(vec![], F32, |a| format!("atan2({0}.y, {0}.x)", a[0])),
        _ => None,
    }
}

/// Per component: `copysign`, `sin_cos`, the Euclidean `rem_euclid` and
/// `div_euclid`, the tests (`abs_diff_eq`, `is_finite`, `is_nan`,
/// `is_negative_bitmask`) and `min_position`/`max_position`.
fn per_component(n: u8, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    match name {
        "copysign" => sig(vec![t.clone()], t, move |a| {
            let u = format!("vec{n}<u32>");
            format!(
                "bitcast<vec{n}<f32>>((bitcast<{u}>({}) & {u}(0x7fffffffu)) | (bitcast<{u}>({}) & {u}(0x80000000u)))",
                a[0], a[1]
            )
        }),
        "abs_diff_eq" => sig(vec![t.clone(), F32], Ty::Scalar(Scalar::Bool), move |a| {
            format!("all(abs({} - {}) <= vec{n}<f32>({}))", a[0], a[1], a[2])
        }),
        "sin_cos" => {
            let pair = Ty::Tuple(vec![t.clone(), t]);
            let name = pair.wgsl();
            sig(vec![], pair, move |a| format!("{name}(sin({0}), cos({0}))", a[0]))
        }
        "rem_euclid" | "div_euclid" => {
            let f = if name == "rem_euclid" { "rt_rem_euclid" } else { "rt_div_euclid" };
            let text = if name == "rem_euclid" { REM_EUCLID } else { DIV_EUCLID };
            let w = t.wgsl();
            with_fmod(with_support(
                sig(vec![t.clone()], t, move |a| {
                    let parts: Vec<String> = (0..n as usize)
                        .map(|k| format!("{f}({}.{c}, {}.{c})", a[0], a[1], c = &"xyzw"[k..k + 1]))
                        .collect();
                    format!("{w}({})", parts.join(", "))
                }),
                f,
                text,
            ))
        }
        "min_position" => sig(vec![], Ty::Scalar(Scalar::Usize), move |a| super::glam_ints::position(n, &a[0], true)),
        "max_position" => sig(vec![], Ty::Scalar(Scalar::Usize), move |a| super::glam_ints::position(n, &a[0], false)),
        "is_negative_bitmask" => {
            sig(vec![], Ty::Scalar(Scalar::U32), move |a| super::glam_ints::negative_bitmask(n, &a[0]))
        }
        // As the scalar `is_finite`/`is_nan`, per component.
        "is_finite" => sig(vec![], Ty::Scalar(Scalar::Bool), move |a| {
            format!("all(abs({}) <= vec{n}<f32>({}))", a[0], super::f32_literal(f32::MAX))
        }),
        "is_nan" => sig(vec![], Ty::Scalar(Scalar::Bool), |a| format!("any({0} != {0})", a[0])),
        _ => None,
    }
}

fn recv_w(n: u8) -> String {
    format!("vec{n}<f32>")
}

fn int(s: Scalar, name: &str) -> Option<MethodSig> {
    let t = Ty::Scalar(s);
    let rotate = move |left: bool| {
        move |a: &[String]| {
            // On the bits as u32; amounts modulo 32, as Rust's.
            let x = if s == Scalar::I32 { format!("bitcast<u32>({})", a[0]) } else { a[0].clone() };
            let k = format!("({} & 31u)", a[1]);
            let (l, r) = if left { ("<<", ">>") } else { (">>", "<<") };
            let bits = format!("(({x} {l} {k}) | ({x} {r} ((32u - {k}) & 31u)))");
            if s == Scalar::I32 { format!("bitcast<i32>({bits})") } else { bits }
        }
    };
    match name {
        "rotate_left" => sig(vec![Ty::Scalar(Scalar::U32)], t, rotate(true)),
        "rotate_right" => sig(vec![Ty::Scalar(Scalar::U32)], t, rotate(false)),
        "swap_bytes" => sig(vec![], t, move |a| {
            let x = if s == Scalar::I32 { format!("bitcast<u32>({})", a[0]) } else { a[0].clone() };
            let bits =
                format!("((({x} & 0xffu) << 24u) | (({x} & 0xff00u) << 8u) | (({x} >> 8u) & 0xff00u) | ({x} >> 24u))");
            if s == Scalar::I32 { format!("bitcast<i32>({bits})") } else { bits }
        }),
        "is_power_of_two" if s == Scalar::U32 => {
            sig(vec![], Ty::Scalar(Scalar::Bool), |a| format!("(countOneBits({}) == 1u)", a[0]))
        }
        _ => None,
    }
}
