//! glam's associated functions (`Type::f(..)`, no receiver): the vector
//! and mask constructors and the matrices' `from_*`, written out after
//! glam's formulas (glam 0.34, scalar paths) so the backends differ only by
//! WGSL's rounding. `tests/tests/glam_coverage.rs` checks each row's
//! signature against glam's source and lists the ones left out, with why.

use super::MethodSig;
use crate::types::{F32, Scalar, Ty};

fn sig(params: Vec<Ty>, ret: Ty, lower: impl Fn(&[String]) -> String + 'static) -> Option<MethodSig> {
    Some(MethodSig { params, ret, lower: Box::new(lower), support: Vec::new() })
}

fn with(m: Option<MethodSig>, support: &'static str) -> Option<MethodSig> {
    let name = support.split_once('(').map(|(head, _)| head.trim_start_matches("fn ")).unwrap_or_default();
    m.map(|mut m| {
        m.support.push((name, support));
        m
    })
}

/// glam's `Mat3::from_axis_angle` (`Mat4`'s is the same, extended).
const MAT3_AXIS_ANGLE: &str = "\
fn rt_mat3_from_axis_angle(axis: vec3<f32>, angle: f32) -> mat3x3<f32> {
    let s = sin(angle);
    let c = cos(angle);
    let xyzsin = axis * s;
    let a2 = axis * axis;
    let omc = 1.0f - c;
    let xyomc = axis.x * axis.y * omc;
    let xzomc = axis.x * axis.z * omc;
    let yzomc = axis.y * axis.z * omc;
    return mat3x3<f32>(
        vec3<f32>(a2.x * omc + c, xyomc + xyzsin.z, xzomc - xyzsin.y),
        vec3<f32>(xyomc - xyzsin.z, a2.y * omc + c, yzomc + xyzsin.x),
        vec3<f32>(xzomc + xyzsin.y, yzomc - xyzsin.x, a2.z * omc + c));
}
";

/// glam's rotations about an axis: `axis` 0, 1, 2 for x, y, z.
const MAT3_ROTATION: &str = "\
fn rt_mat3_from_rotation(axis: u32, angle: f32) -> mat3x3<f32> {
    let s = sin(angle);
    let c = cos(angle);
    switch axis {
        case 0u: { return mat3x3<f32>(vec3<f32>(1.0f, 0.0f, 0.0f), vec3<f32>(0.0f, c, s), vec3<f32>(0.0f, -s, c)); }
        case 1u: { return mat3x3<f32>(vec3<f32>(c, 0.0f, -s), vec3<f32>(0.0f, 1.0f, 0.0f), vec3<f32>(s, 0.0f, c)); }
        default: { return mat3x3<f32>(vec3<f32>(c, s, 0.0f), vec3<f32>(-s, c, 0.0f), vec3<f32>(0.0f, 0.0f, 1.0f)); }
    }
}
";

/// glam's `Mat2::from_scale_angle` (`from_angle` with a unit scale).
const MAT2_SCALE_ANGLE: &str = "\
fn rt_mat2_from_scale_angle(scale: vec2<f32>, angle: f32) -> mat2x2<f32> {
    let s = sin(angle);
    let c = cos(angle);
    return mat2x2<f32>(vec2<f32>(c * scale.x, s * scale.x), vec2<f32>(-s * scale.y, c * scale.y));
}
";

/// glam's `Mat3::from_scale_angle_translation`.
const MAT3_SCALE_ANGLE_TRANSLATION: &str = "\
fn rt_mat3_from_scale_angle_translation(scale: vec2<f32>, angle: f32, t: vec2<f32>) -> mat3x3<f32> {
    let s = sin(angle);
    let c = cos(angle);
    return mat3x3<f32>(vec3<f32>(c * scale.x, s * scale.x, 0.0f), vec3<f32>(-s * scale.y, c * scale.y, 0.0f), vec3<f32>(t, 1.0f));
}
";

/// glam's `Mat2::from_mat3_minor` and `Mat3::from_mat4_minor`: column `i`
/// and row `j` left out, each clamped to the last (glam panics past it; the
/// CPU copy clamps through `rt_std::arith::Gpu`).
const MINOR: &str = "\
fn rt_minor3(m: mat3x3<f32>, i0: u32, j0: u32) -> mat2x2<f32> {
    let i = min(i0, 2u);
    let j = min(j0, 2u);
    var mm = m;
    var out: mat2x2<f32>;
    for (var k = 0u; k < 2u; k = k + 1u) {
        for (var l = 0u; l < 2u; l = l + 1u) {
            out[k][l] = mm[k + select(0u, 1u, k >= i)][l + select(0u, 1u, l >= j)];
        }
    }
    return out;
}
fn rt_minor4(m: mat4x4<f32>, i0: u32, j0: u32) -> mat3x3<f32> {
    let i = min(i0, 3u);
    let j = min(j0, 3u);
    var mm = m;
    var out: mat3x3<f32>;
    for (var k = 0u; k < 3u; k = k + 1u) {
        for (var l = 0u; l < 3u; l = l + 1u) {
            out[k][l] = mm[k + select(0u, 1u, k >= i)][l + select(0u, 1u, l >= j)];
        }
    }
    return out;
}
";

/// `m[i]` for `i` in `0..n` of an array or matrix operand.
fn parts(a: &str, n: usize) -> Vec<String> {
    (0..n).map(|i| format!("{a}[{i}]")).collect()
}

/// The associated function `ty::name`, if programs may call it.
pub fn assoc_fn(ty: &Ty, name: &str) -> Option<MethodSig> {
    let t = ty.clone();
    let w = ty.wgsl();
    match ty {
        Ty::Vec(n, s) => vector(*n, *s, t, w, name),
        Ty::Mat(n) => matrix(*n, t, w, name),
        Ty::Scalar(s) => scalar(*s, t, name),
        _ => None,
    }
}

/// std's associated functions of the scalars: `f32::from_bits`, the
/// integers' `from_be`/`from_le` (little-endian targets).
fn scalar(s: Scalar, t: Ty, name: &str) -> Option<MethodSig> {
    match (s, name) {
        (Scalar::F32, "from_bits") => sig(vec![crate::types::U32], t, |a| format!("bitcast<f32>({})", a[0])),
        (Scalar::I32 | Scalar::U32, "from_be") => {
            sig(vec![t.clone()], t, move |a| super::std_scalars::byte_swap(s, &a[0]))
        }
        (Scalar::I32 | Scalar::U32, "from_le") => sig(vec![t.clone()], t, |a| a[0].clone()),
        _ => None,
    }
}

fn vector(n: u8, s: Scalar, t: Ty, w: String, name: &str) -> Option<MethodSig> {
    let nu = n as usize;
    match name {
        "new" => sig(vec![Ty::Scalar(s); nu], t, move |a| format!("{w}({})", a.join(", "))),
        "splat" => sig(vec![Ty::Scalar(s)], t, move |a| format!("{w}({})", a[0])),
        "from_array" => sig(vec![Ty::Array(Box::new(Ty::Scalar(s)), n as u32)], t, move |a| {
            format!("{w}({})", parts(&a[0], nu).join(", "))
        }),
        // glam's `select(mask, if_true, if_false)` is WGSL's
        // `select(if_false, if_true, mask)`.
        "select" if s != Scalar::Bool => sig(vec![Ty::Vec(n, Scalar::Bool), t.clone(), t.clone()], t, |a| {
            format!("select({}, {}, {})", a[2], a[1], a[0])
        }),
        "from_angle" if n == 2 && s == Scalar::F32 => {
            sig(vec![F32], t, |a| format!("vec2<f32>(cos({0}), sin({0}))", a[0]))
        }
        "from_homogeneous" if n == 3 && s == Scalar::F32 => {
            sig(vec![Ty::vec(4)], t, |a| format!("({0}.xyz / {0}.w)", a[0]))
        }
        _ => None,
    }
}

fn matrix(n: u8, t: Ty, w: String, name: &str) -> Option<MethodSig> {
    let nu = n as usize;
    let v = Ty::vec(n);
    let flat = Ty::Array(Box::new(F32), (nu * nu) as u32);
    let nested = Ty::Array(Box::new(Ty::Array(Box::new(F32), n as u32)), n as u32);
    let cols_of_flat = move |a: &str| -> Vec<String> {
        (0..nu)
            .map(|c| {
                format!(
                    "vec{n}<f32>({})",
                    (0..nu).map(|r| format!("{a}[{}]", c * nu + r)).collect::<Vec<_>>().join(", ")
                )
            })
            .collect()
    };
    let rotation = move |axis: u32| {
        let m = with(
            sig(vec![F32], Ty::Mat(3), move |a| format!("rt_mat3_from_rotation({axis}u, {})", a[0])),
            MAT3_ROTATION,
        );
        if n == 4 { m.map(extend_to_mat4) } else { m }
    };
    match name {
        "from_cols" => sig(vec![v; nu], t, move |a| format!("{w}({})", a.join(", "))),
        "from_rows" => sig(vec![v; nu], t, move |a| format!("transpose({w}({}))", a.join(", "))),
        "from_diagonal" => sig(vec![v], t, move |a| {
            let cols: Vec<String> = (0..nu)
                .map(|c| {
                    let comps: Vec<String> =
                        (0..nu).map(|r| if r == c { format!("{}[{c}]", a[0]) } else { "0.0".into() }).collect();
                    format!("vec{n}<f32>({})", comps.join(", "))
                })
                .collect();
            format!("{w}({})", cols.join(", "))
        }),
        "from_cols_array" => sig(vec![flat], t, move |a| format!("{w}({})", cols_of_flat(&a[0]).join(", "))),
        "from_rows_array" => sig(vec![flat], t, move |a| format!("transpose({w}({}))", cols_of_flat(&a[0]).join(", "))),
        "from_cols_array_2d" => sig(vec![nested], t, move |a| {
            let cols: Vec<String> =
                (0..nu).map(|c| format!("vec{n}<f32>({})", parts(&format!("{}[{c}]", a[0]), nu).join(", "))).collect();
            format!("{w}({})", cols.join(", "))
        }),
        "from_angle" if n == 2 => with(
            sig(vec![F32], t, |a| format!("rt_mat2_from_scale_angle(vec2<f32>(1.0f), {})", a[0])),
            MAT2_SCALE_ANGLE,
        ),
        "from_scale_angle" if n == 2 => with(
            sig(vec![Ty::vec(2), F32], t, |a| format!("rt_mat2_from_scale_angle({}, {})", a[0], a[1])),
            MAT2_SCALE_ANGLE,
        ),
        "from_mat3_minor" if n == 2 => with(
            sig(vec![Ty::Mat(3), Ty::Scalar(Scalar::Usize), Ty::Scalar(Scalar::Usize)], t, |a| {
                format!("rt_minor3({}, u32({}), u32({}))", a[0], a[1], a[2])
            }),
            MINOR,
        ),
        "from_mat4_minor" if n == 3 => with(
            sig(vec![Ty::Mat(4), Ty::Scalar(Scalar::Usize), Ty::Scalar(Scalar::Usize)], t, |a| {
                format!("rt_minor4({}, u32({}), u32({}))", a[0], a[1], a[2])
            }),
            MINOR,
        ),
        "from_mat3" if n == 2 => sig(vec![Ty::Mat(3)], t, |a| format!("mat2x2<f32>({0}[0].xy, {0}[1].xy)", a[0])),
        "from_mat4" if n == 3 => {
            sig(vec![Ty::Mat(4)], t, |a| format!("mat3x3<f32>({0}[0].xyz, {0}[1].xyz, {0}[2].xyz)", a[0]))
        }
        "from_mat2" if n == 3 => sig(vec![Ty::Mat(2)], t, |a| {
            format!("mat3x3<f32>(vec3<f32>({0}[0], 0.0f), vec3<f32>({0}[1], 0.0f), vec3<f32>(0.0f, 0.0f, 1.0f))", a[0])
        }),
        "from_mat3" if n == 4 => sig(vec![Ty::Mat(3)], Ty::Mat(3), |a| a[0].clone()).map(extend_to_mat4),
        "from_mat3_translation" if n == 4 => {
            sig(vec![Ty::Mat(3), Ty::vec(3)], t, |a| mat4_of_mat3(&a[0], &format!("vec4<f32>({}, 1.0f)", a[1])))
        }
        "from_axis_angle" if n == 3 => with(
            sig(vec![Ty::vec(3), F32], t, |a| format!("rt_mat3_from_axis_angle({}, {})", a[0], a[1])),
            MAT3_AXIS_ANGLE,
        ),
        "from_axis_angle" if n == 4 => with(
            sig(vec![Ty::vec(3), F32], Ty::Mat(3), |a| format!("rt_mat3_from_axis_angle({}, {})", a[0], a[1])),
            MAT3_AXIS_ANGLE,
        )
        .map(extend_to_mat4),
        "from_rotation_x" if n >= 3 => rotation(0),
        "from_rotation_y" if n >= 3 => rotation(1),
        "from_rotation_z" if n >= 3 => rotation(2),
        "from_angle" if n == 3 => {
            with(sig(vec![F32], t, |a| format!("rt_mat3_from_rotation(2u, {})", a[0])), MAT3_ROTATION)
        }
        "from_translation" if n == 3 => sig(vec![Ty::vec(2)], t, |a| {
            format!("mat3x3<f32>(vec3<f32>(1.0f, 0.0f, 0.0f), vec3<f32>(0.0f, 1.0f, 0.0f), vec3<f32>({}, 1.0f))", a[0])
        }),
        "from_translation" if n == 4 => sig(vec![Ty::vec(3)], t, |a| {
            format!(
                "mat4x4<f32>(vec4<f32>(1.0f, 0.0f, 0.0f, 0.0f), vec4<f32>(0.0f, 1.0f, 0.0f, 0.0f), \
                 vec4<f32>(0.0f, 0.0f, 1.0f, 0.0f), vec4<f32>({}, 1.0f))",
                a[0]
            )
        }),
        "from_scale" if n == 3 => sig(vec![Ty::vec(2)], t, |a| {
            format!(
                "mat3x3<f32>(vec3<f32>({0}.x, 0.0f, 0.0f), vec3<f32>(0.0f, {0}.y, 0.0f), vec3<f32>(0.0f, 0.0f, 1.0f))",
                a[0]
            )
        }),
        "from_scale" if n == 4 => sig(vec![Ty::vec(3)], t, |a| {
            format!(
                "mat4x4<f32>(vec4<f32>({0}.x, 0.0f, 0.0f, 0.0f), vec4<f32>(0.0f, {0}.y, 0.0f, 0.0f), \
                 vec4<f32>(0.0f, 0.0f, {0}.z, 0.0f), vec4<f32>(0.0f, 0.0f, 0.0f, 1.0f))",
                a[0]
            )
        }),
        "from_scale_angle_translation" if n == 3 => with(
            sig(vec![Ty::vec(2), F32, Ty::vec(2)], t, |a| {
                format!("rt_mat3_from_scale_angle_translation({}, {}, {})", a[0], a[1], a[2])
            }),
            MAT3_SCALE_ANGLE_TRANSLATION,
        ),
        _ => None,
    }
}

/// A `Mat4` whose upper 3x3 is `m` and whose last column is `w`.
fn mat4_of_mat3(m: &str, w: &str) -> String {
    format!("mat4x4<f32>(vec4<f32>({m}[0], 0.0f), vec4<f32>({m}[1], 0.0f), vec4<f32>({m}[2], 0.0f), {w})")
}

/// `m` in the upper left of a `Mat4` whose `w_axis` is the unit `W`.
const MAT4_OF_MAT3: &str = "\
fn rt_mat4_of_mat3(m: mat3x3<f32>) -> mat4x4<f32> {
    return mat4x4<f32>(vec4<f32>(m[0], 0.0f), vec4<f32>(m[1], 0.0f), vec4<f32>(m[2], 0.0f), vec4<f32>(0.0f, 0.0f, 0.0f, 1.0f));
}
";

/// A row giving a `Mat3` made into the `Mat4` glam gives for the same
/// function (the 3x3 in the upper left, `w_axis` the unit `W`).
fn extend_to_mat4(m: MethodSig) -> MethodSig {
    let inner = m.lower;
    let mut support = m.support;
    support.push(("rt_mat4_of_mat3", MAT4_OF_MAT3));
    MethodSig {
        params: m.params,
        ret: Ty::Mat(4),
        lower: Box::new(move |a| format!("rt_mat4_of_mat3({})", inner(a))),
        support,
    }
}
