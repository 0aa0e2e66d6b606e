// ray_generation program `glam_assoc`

fn rt_bufload_f32(b: RtBuffer, i: u32) -> f32 {
    if rt_buf_check(b, i) {
        return rt_load_f32(b.offset + i * 1u);
    }
    return f32();
}

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_mat2_from_scale_angle(scale: vec2<f32>, angle: f32) -> mat2x2<f32> {
    let s = sin(angle);
    let c = cos(angle);
    return mat2x2<f32>(vec2<f32>(c * scale.x, s * scale.x), vec2<f32>(-s * scale.y, c * scale.y));
}

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

fn rt_mat3_from_rotation(axis: u32, angle: f32) -> mat3x3<f32> {
    let s = sin(angle);
    let c = cos(angle);
    switch axis {
        case 0u: { return mat3x3<f32>(vec3<f32>(1.0f, 0.0f, 0.0f), vec3<f32>(0.0f, c, s), vec3<f32>(0.0f, -s, c)); }
        case 1u: { return mat3x3<f32>(vec3<f32>(c, 0.0f, -s), vec3<f32>(0.0f, 1.0f, 0.0f), vec3<f32>(s, 0.0f, c)); }
        default: { return mat3x3<f32>(vec3<f32>(c, s, 0.0f), vec3<f32>(-s, c, 0.0f), vec3<f32>(0.0f, 0.0f, 1.0f)); }
    }
}

fn rt_mat3_from_scale_angle_translation(scale: vec2<f32>, angle: f32, t: vec2<f32>) -> mat3x3<f32> {
    let s = sin(angle);
    let c = cos(angle);
    return mat3x3<f32>(vec3<f32>(c * scale.x, s * scale.x, 0.0f), vec3<f32>(-s * scale.y, c * scale.y, 0.0f), vec3<f32>(t, 1.0f));
}

fn rt_mat4_of_mat3(m: mat3x3<f32>) -> mat4x4<f32> {
    return mat4x4<f32>(vec4<f32>(m[0], 0.0f), vec4<f32>(m[1], 0.0f), vec4<f32>(m[2], 0.0f), vec4<f32>(0.0f, 0.0f, 0.0f, 1.0f));
}

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

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rtp_glam_assoc(a: vec4<f32>, t: f32, out: RtBuffer) {
    var out_1 = out;
    var m3: mat3x3<f32> = ((rt_mat3_from_axis_angle(a.xyz, t) * rt_mat3_from_rotation(1u, t)) * transpose(mat3x3<f32>(a.xyz, a.yzw, a.zwx)));
    var m4: mat4x4<f32> = ((rt_mat4_of_mat3(rt_mat3_from_rotation(0u, t)) * mat4x4<f32>(vec4<f32>(1.0f, 0.0f, 0.0f, 0.0f), vec4<f32>(0.0f, 1.0f, 0.0f, 0.0f), vec4<f32>(0.0f, 0.0f, 1.0f, 0.0f), vec4<f32>(a.xyz, 1.0f))) * rt_mat4_of_mat3(m3));
    let tmp = array<f32, 4>(a.x, a.y, a.z, a.w);
    var m2: mat2x2<f32> = (rt_mat2_from_scale_angle(a.xy, t) + mat2x2<f32>(vec2<f32>(tmp[0], tmp[1]), vec2<f32>(tmp[2], tmp[3])));
    var s: mat3x3<f32> = rt_mat3_from_scale_angle_translation(a.zw, t, a.xy);
    let tmp_1 = array<f32, 3>(t, t, 1.0f);
    let v: vec3<f32> = ((a.xyz / a.w) + vec3<f32>(tmp_1[0], tmp_1[1], tmp_1[2]));
    let tmp_2 = array<bool, 2>((t > 0.0f), (a.x > 0.0f));
    let m: vec2<bool> = vec2<bool>(tmp_2[0], tmp_2[1]);
    var minor: mat2x2<f32> = rt_minor3(rt_minor4(m4, u32(1u), u32(2u)), u32(0u), u32(1u));
    let tmp_3 = 0u;
    rt_bufstore_f32(out_1, tmp_3, ((((((m4[3].x + m2[1].y) + s[2].x) + v.y) + f32(dot(select(vec2<u32>(0u), vec2<u32>(1u, 2u), m), vec2<u32>(1u)))) + vec2<f32>(cos(t), sin(t)).x) + minor[1].x));
}
