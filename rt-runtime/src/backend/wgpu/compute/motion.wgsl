
// ---- motion transforms (linked with the graph walk) ----
// rt-runtime's MotionTransform::matrix_at (motion.rs) step by step on the
// words MotionTransform::encode wrote at scene word m + 1: [key kind (0
// matrices, 1 scale-rotate-translate), key count, t0, t1, keys...], a
// matrix key 16 words (column by column), an SRT key 12 (scale, 0,
// rotation xyzw, translation, 0).

// The motion transform's object-to-world matrix at the current ray's time:
// the time clamped to [t0, t1], the keys spread evenly over it.
fn rt_motion_matrix(m: u32) -> mat4x4<f32> {
    let kind = rt_scene[m + 1u];
    let n = rt_scene[m + 2u];
    let t0 = rt_f(m + 3u);
    let t1 = rt_f(m + 4u);
    let s = rt_motion_segment(n, t0, t1);
    let i = u32(s.x);
    let f = s.y;
    let keys = m + 5u;
    if kind == 0u {
        return rt_m4(keys + i * 16u) * (1.0 - f) + rt_m4(keys + (i + 1u) * 16u) * f;
    }
    let a = keys + i * 12u;
    let b = a + 12u;
    let scale = rt_v3(a) * (1.0 - f) + rt_v3(b) * f;
    let translation = rt_v3(a + 8u) * (1.0 - f) + rt_v3(b + 8u) * f;
    let ra = vec4<f32>(rt_v3(a + 4u), rt_f(a + 7u));
    let rb = vec4<f32>(rt_v3(b + 4u), rt_f(b + 7u));
    return rt_srt_matrix(scale, rt_slerp(ra, rb, f), translation);
}

// motion.rs's slerp: the shorter arc, nearly equal rotations lerped.
fn rt_slerp(a: vec4<f32>, b_in: vec4<f32>, f: f32) -> vec4<f32> {
    var b = b_in;
    var d = dot(a, b);
    if d < 0.0 {
        b = -b;
        d = -d;
    }
    var q = a + (b - a) * f;
    if d <= 0.9995 {
        let theta = acos(min(d, 1.0));
        q = (a * sin((1.0 - f) * theta) + b * sin(f * theta)) / sin(theta);
    }
    return normalize(q);
}

// T * R * S for unit quaternion q (xyzw), as glam's
// Mat4::from_scale_rotation_translation.
fn rt_srt_matrix(s: vec3<f32>, q: vec4<f32>, t: vec3<f32>) -> mat4x4<f32> {
    let x2 = q.x + q.x;
    let y2 = q.y + q.y;
    let z2 = q.z + q.z;
    let xx = q.x * x2;
    let xy = q.x * y2;
    let xz = q.x * z2;
    let yy = q.y * y2;
    let yz = q.y * z2;
    let zz = q.z * z2;
    let wx = q.w * x2;
    let wy = q.w * y2;
    let wz = q.w * z2;
    return mat4x4<f32>(
        vec4<f32>(1.0 - (yy + zz), xy + wz, xz - wy, 0.0) * s.x,
        vec4<f32>(xy - wz, 1.0 - (xx + zz), yz + wx, 0.0) * s.y,
        vec4<f32>(xz + wy, yz - wx, 1.0 - (xx + yy), 0.0) * s.z,
        vec4<f32>(t, 1.0),
    );
}

// The inverse of affine matrix m (last row 0 0 0 1), or the zero matrix
// where it has none (a singular instant hides the transform's child).
fn rt_affine_inverse(m: mat4x4<f32>) -> mat4x4<f32> {
    let a = m[0].xyz;
    let b = m[1].xyz;
    let c = m[2].xyz;
    let r0 = cross(b, c);
    let r1 = cross(c, a);
    let r2 = cross(a, b);
    let det = dot(a, r0);
    if det == 0.0 || !(abs(det) <= RT_F32_MAX) {
        return mat4x4<f32>();
    }
    // The inverse's rows are r0, r1 and r2 over the determinant.
    let i = transpose(mat3x3<f32>(r0, r1, r2)) * (1.0 / det);
    return mat4x4<f32>(vec4<f32>(i[0], 0.0), vec4<f32>(i[1], 0.0), vec4<f32>(i[2], 0.0), vec4<f32>(-(i * m[3].xyz), 1.0));
}
