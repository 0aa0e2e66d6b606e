//! glam's angles and rotations of float vectors, written out after its
//! formulas (glam 0.34, scalar paths): `angle_to`, `angle_between` (through
//! glam's `acos_approx`, not WGSL's `acos`), the axis rotations,
//! `rotate_axis`, `rotate_towards` and `slerp` (glam's quaternion product,
//! expanded),
//! `move_towards`, `any_orthogonal_vector` and `any_orthonormal_pair`. As in
//! the rest of [`super::glam_formulas`], operation for operation, so the
//! backends differ only by WGSL's rounding.

use super::MethodSig;
use crate::types::{F32, Ty};

fn sig(params: Vec<Ty>, ret: Ty, lower: impl Fn(&[String]) -> String + 'static) -> Option<MethodSig> {
    Some(MethodSig { params, ret, lower: Box::new(lower), support: Vec::new() })
}

fn with(m: Option<MethodSig>, support: &[(&'static str, &'static str)]) -> Option<MethodSig> {
    m.map(|mut m| {
        m.support.extend_from_slice(support);
        m
    })
}

/// glam's `acos_approx`: DirectXMath's 7-degree minimax polynomial, with
/// the input clamped to `[-1, 1]`.
const ACOS_APPROX: &str = "\
fn rt_acos_approx(v: f32) -> f32 {
    let x = abs(v);
    let root = sqrt(max(1.0f - x, 0.0f));
    let p = ((((((-0.0012624911f * x + 0.00667009f) * x - 0.017088126f) * x + 0.03089188f) * x - 0.050174303f) * x + 0.08897899f) * x - 0.2145988f) * x + 1.5707963f;
    let r = p * root;
    return select(3.1415927f - r, r, v >= 0.0f);
}
";

/// glam's `Vec2::angle_to`.
const ANGLE_TO2: &str = "\
fn rt_angle_to2(a: vec2<f32>, b: vec2<f32>) -> f32 {
    let angle = rt_acos_approx(dot(a, b) / sqrt(dot(a, a) * dot(b, b)));
    let perp_dot = a.x * b.y - a.y * b.x;
    return angle * select(1.0f, -1.0f, (bitcast<u32>(perp_dot) & 0x80000000u) != 0u);
}
";

/// glam's `Vec2::rotate_towards`: no further than `max_angle` (and than
/// `rhs`), `Vec2::from_angle(angle).rotate(self)`.
const ROTATE_TOWARDS2: &str = "\
fn rt_rotate_towards2(v: vec2<f32>, rhs: vec2<f32>, max_angle: f32) -> vec2<f32> {
    let a = rt_angle_to2(v, rhs);
    let abs_a = abs(a);
    let angle = clamp(max_angle, abs_a - 3.1415927f, abs_a) * select(1.0f, -1.0f, (bitcast<u32>(a) & 0x80000000u) != 0u);
    let c = cos(angle);
    let s = sin(angle);
    return vec2<f32>(c * v.x - s * v.y, s * v.x + c * v.y);
}
";

/// `Quat::from_axis_angle(axis, angle) * v`: glam's `mul_vec3`.
const ROTATE_AXIS: &str = "\
fn rt_rotate_axis(v: vec3<f32>, axis: vec3<f32>, angle: f32) -> vec3<f32> {
    let s = sin(angle * 0.5f);
    let w = cos(angle * 0.5f);
    let b = axis * s;
    let b2 = dot(b, b);
    return v * (w * w - b2) + b * (dot(v, b) * 2.0f) + cross(b, v) * (w * 2.0f);
}
";

/// glam's `Vec3::any_orthogonal_vector`.
fn any_orthogonal(v: &str) -> String {
    format!("select(vec3<f32>(0.0f, {v}.z, -{v}.y), vec3<f32>(-{v}.z, 0.0f, {v}.x), abs({v}.x) > abs({v}.y))")
}

/// glam's `Vec3::rotate_towards`: the angle clamped as in 2D, about the
/// normalized cross product (or, for parallel vectors, any orthogonal
/// axis).
const ROTATE_TOWARDS3: &str = "\
fn rt_rotate_towards3(v: vec3<f32>, rhs: vec3<f32>, max_angle: f32) -> vec3<f32> {
    let between = rt_acos_approx(dot(v, rhs) / sqrt(dot(v, v) * dot(rhs, rhs)));
    let angle = clamp(max_angle, between - 3.1415927f, between);
    let c = cross(v, rhs);
    let rcp = 1.0f / length(c);
    var axis = normalize(select(vec3<f32>(0.0f, v.z, -v.y), vec3<f32>(-v.z, 0.0f, v.x), abs(v.x) > abs(v.y)));
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        axis = c * rcp;
    }
    return rt_rotate_axis(v, axis, angle);
}
";

/// glam's `Vec3::any_orthonormal_pair` (Pixar's branchless basis).
const ORTHONORMAL_PAIR: &str = "\
fn rt_any_orthonormal_pair(v: vec3<f32>) -> rt_tuple_vec3f_vec3f_ {
    let sign = select(1.0f, -1.0f, (bitcast<u32>(v.z) & 0x80000000u) != 0u);
    let a = -1.0f / (sign + v.z);
    let b = v.x * v.y * a;
    return rt_tuple_vec3f_vec3f_(vec3<f32>(1.0f + sign * v.x * v.x * a, sign * b, -sign * v.x), vec3<f32>(b, sign + v.y * v.y * a, -v.y));
}
";

/// glam's `Vec3::slerp`: along the great arc, lengths interpolated
/// monotonically; about any orthogonal axis for nearly opposite vectors;
/// a plain `lerp` for nearly equal ones.
const SLERP: &str = "\
fn rt_slerp3(v: vec3<f32>, rhs: vec3<f32>, s: f32) -> vec3<f32> {
    let self_length = length(v);
    let rhs_length = length(rhs);
    let d = dot(v, rhs) / (self_length * rhs_length);
    let result_length = self_length + (rhs_length - self_length) * s;
    if abs(d) < 1.0f - 3e-7f {
        let theta = rt_acos_approx(d);
        let sin_theta = sin(theta);
        let t1 = sin(theta * (1.0f - s));
        let t2 = sin(theta * s);
        return (v * (result_length / self_length) * t1 + rhs * (result_length / rhs_length) * t2) * (1.0f / sin_theta);
    }
    if d < 0.0f {
        let axis = normalize(select(vec3<f32>(0.0f, v.z, -v.y), vec3<f32>(-v.z, 0.0f, v.x), abs(v.x) > abs(v.y)));
        return rt_rotate_axis(v, axis, 3.1415927f * s) * (result_length / self_length);
    }
    return v * (1.0f - s) + rhs * s;
}
";

/// glam's `move_towards`, per size.
const MOVE_TOWARDS: [&str; 3] = [
    "\
fn rt_move_towards2(v: vec2<f32>, rhs: vec2<f32>, d: f32) -> vec2<f32> {
    let a = rhs - v;
    let len = length(a);
    if len <= d || len <= 1e-4f {
        return rhs;
    }
    return v + a / len * d;
}
",
    "\
fn rt_move_towards3(v: vec3<f32>, rhs: vec3<f32>, d: f32) -> vec3<f32> {
    let a = rhs - v;
    let len = length(a);
    if len <= d || len <= 1e-4f {
        return rhs;
    }
    return v + a / len * d;
}
",
    "\
fn rt_move_towards4(v: vec4<f32>, rhs: vec4<f32>, d: f32) -> vec4<f32> {
    let a = rhs - v;
    let len = length(a);
    if len <= d || len <= 1e-4f {
        return rhs;
    }
    return v + a / len * d;
}
",
];

/// The methods of this file for a float vector of `n` components.
pub fn method(n: u8, recv: &Ty, name: &str) -> Option<MethodSig> {
    let t = recv.clone();
    let v3 = Ty::vec(3);
    let acos = ("rt_acos_approx", ACOS_APPROX);
    match (n, name) {
        (_, "move_towards") => {
            let f: &'static str = ["rt_move_towards2", "rt_move_towards3", "rt_move_towards4"][n as usize - 2];
            let text = MOVE_TOWARDS[n as usize - 2];
            with(sig(vec![t.clone(), F32], t, move |a| format!("{f}({}, {}, {})", a[0], a[1], a[2])), &[(f, text)])
        }
        (2, "angle_to") => with(
            sig(vec![t.clone()], F32, |a| format!("rt_angle_to2({}, {})", a[0], a[1])),
            &[acos, ("rt_angle_to2", ANGLE_TO2)],
        ),
        (2, "rotate_angle") => sig(vec![F32], t, |a| {
            format!("vec2<f32>({0}.x * cos({1}) - {0}.y * sin({1}), {0}.y * cos({1}) + {0}.x * sin({1}))", a[0], a[1])
        }),
        (2, "rotate_towards") => with(
            sig(vec![t.clone(), F32], t, |a| format!("rt_rotate_towards2({}, {}, {})", a[0], a[1], a[2])),
            &[acos, ("rt_angle_to2", ANGLE_TO2), ("rt_rotate_towards2", ROTATE_TOWARDS2)],
        ),
        (3, "angle_between") => with(
            sig(vec![t.clone()], F32, |a| {
                format!("rt_acos_approx(dot({0}, {1}) / sqrt(dot({0}, {0}) * dot({1}, {1})))", a[0], a[1])
            }),
            &[acos],
        ),
        (3, "angle_to") => sig(vec![t.clone(), t], F32, |a| {
            format!("atan2(dot(cross({0}, {1}), {2}), dot({0}, {1}))", a[0], a[1], a[2])
        }),
        (3, "rotate_x") => sig(vec![F32], t, |a| {
            format!(
                "vec3<f32>({0}.x, {0}.y * cos({1}) - {0}.z * sin({1}), {0}.y * sin({1}) + {0}.z * cos({1}))",
                a[0], a[1]
            )
        }),
        (3, "rotate_y") => sig(vec![F32], t, |a| {
            format!(
                "vec3<f32>({0}.x * cos({1}) + {0}.z * sin({1}), {0}.y, {0}.x * -sin({1}) + {0}.z * cos({1}))",
                a[0], a[1]
            )
        }),
        (3, "rotate_z") => sig(vec![F32], t, |a| {
            format!(
                "vec3<f32>({0}.x * cos({1}) - {0}.y * sin({1}), {0}.x * sin({1}) + {0}.y * cos({1}), {0}.z)",
                a[0], a[1]
            )
        }),
        (3, "rotate_axis") => with(
            sig(vec![t.clone(), F32], t, |a| format!("rt_rotate_axis({}, {}, {})", a[0], a[1], a[2])),
            &[("rt_rotate_axis", ROTATE_AXIS)],
        ),
        (3, "rotate_towards") => with(
            sig(vec![t.clone(), F32], t, |a| format!("rt_rotate_towards3({}, {}, {})", a[0], a[1], a[2])),
            &[acos, ("rt_rotate_axis", ROTATE_AXIS), ("rt_rotate_towards3", ROTATE_TOWARDS3)],
        ),
        (3, "slerp") => with(
            sig(vec![t.clone(), F32], t, |a| format!("rt_slerp3({}, {}, {})", a[0], a[1], a[2])),
            &[acos, ("rt_rotate_axis", ROTATE_AXIS), ("rt_slerp3", SLERP)],
        ),
        (3, "any_orthogonal_vector") => sig(vec![], t, |a| any_orthogonal(&a[0])),
        (3, "any_orthonormal_pair") => with(
            sig(vec![], Ty::Tuple(vec![v3.clone(), v3]), |a| format!("rt_any_orthonormal_pair({})", a[0])),
            &[("rt_any_orthonormal_pair", ORTHONORMAL_PAIR)],
        ),
        _ => None,
    }
}
