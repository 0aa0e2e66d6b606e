// ray_generation program `glam_arrays`

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

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
}

fn rt_load_mat3(w: u32) -> mat3x3<f32> {
    return mat3x3<f32>(rt_load_vec3f(w + 0u), rt_load_vec3f(w + 3u), rt_load_vec3f(w + 6u));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec2i(w: u32) -> vec2<i32> {
    return vec2<i32>(rt_load_i32(w + 0u), rt_load_i32(w + 1u));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rtp_glam_arrays(v: vec3<f32>, i: vec2<i32>, m: mat3x3<f32>, k: u32, out: RtBuffer) {
    var out_1 = out;
    var a: array<f32, 3> = array<f32, 3>(v.x, v.y, v.z);
    let tmp = (i * 2i);
    var b: array<i32, 2> = array<i32, 2>(tmp.x, tmp.y);
    let tmp_1 = vec4<u32>(1u, 2u, 3u, k);
    var c: array<u32, 4> = array<u32, 4>(tmp_1.x, tmp_1.y, tmp_1.z, tmp_1.w);
    var cols: array<f32, 9> = array<f32, 9>(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]);
    let tmp_2 = (m * 2.0f);
    var rows: array<f32, 9> = array<f32, 9>(tmp_2[0][0], tmp_2[1][0], tmp_2[2][0], tmp_2[0][1], tmp_2[1][1], tmp_2[2][1], tmp_2[0][2], tmp_2[1][2], tmp_2[2][2]);
    let tmp_3 = mat2x2<f32>(vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0));
    var grid: array<array<f32, 2>, 2> = array<array<f32, 2>, 2>(array<f32, 2>(tmp_3[0][0], tmp_3[0][1]), array<f32, 2>(tmp_3[1][0], tmp_3[1][1]));
    let tmp_4 = mat4x4<f32>(vec4<f32>(1.0, 0.0, 0.0, 0.0), vec4<f32>(0.0, 1.0, 0.0, 0.0), vec4<f32>(0.0, 0.0, 1.0, 0.0), vec4<f32>(v, 1.0f));
    var big: array<f32, 16> = array<f32, 16>(tmp_4[0][0], tmp_4[0][1], tmp_4[0][2], tmp_4[0][3], tmp_4[1][0], tmp_4[1][1], tmp_4[1][2], tmp_4[1][3], tmp_4[2][0], tmp_4[2][1], tmp_4[2][2], tmp_4[2][3], tmp_4[3][0], tmp_4[3][1], tmp_4[3][2], tmp_4[3][3]);
    let j: u32 = (k % 3u);
    let tmp_5 = 0u;
    rt_bufstore_f32(out_1, tmp_5, ((((((a[j] + f32(b[(j % 2u)])) + f32(c[j])) + cols[(j * 3u)]) + rows[(j + 1u)]) + grid[(j % 2u)][1u]) + big[(12u + j)]));
}
