// ray_generation program `glam_in_place`

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

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rtf_put_row(m: ptr<function, mat3x3<f32>>, i: u32, v: vec3<f32>) {
    let row = min(u32(i), 2u);
    let value = v;
    (*m)[0][row] = value.x;
    (*m)[1][row] = value.y;
    (*m)[2][row] = value.z;
}

fn rtp_glam_in_place(v: vec4<f32>, k: u32, out: RtBuffer) {
    var out_1 = out;
    var m: mat4x4<f32> = mat4x4<f32>(vec4<f32>(1.0, 0.0, 0.0, 0.0), vec4<f32>(0.0, 1.0, 0.0, 0.0), vec4<f32>(0.0, 0.0, 1.0, 0.0), vec4<f32>(0.0, 0.0, 0.0, 1.0));
    let row = min(u32(k), 3u);
    let value = v;
    m[0][row] = value.x;
    m[1][row] = value.y;
    m[2][row] = value.z;
    m[3][row] = value.w;
    var n: mat3x3<f32> = mat3x3<f32>();
    rtf_put_row(&n, (k + 1u), v.xyz);
    m[min(u32(k), 3u)] += v;
    n[min(u32(2u), 2u)].y = v.x;
    var mask: vec4<bool> = (v > vec4<f32>(0.0));
    let row_1 = min(u32(k), 3u);
    let value_1 = false;
    mask[row_1] = value_1;
    let tmp = 0u;
    rt_bufstore_f32(out_1, tmp, (((m[3].y + n[2].x) + f32(dot(select(vec4<u32>(0u), vec4<u32>(1u, 2u, 4u, 8u), mask), vec4<u32>(1u)))) + f32(u32(mask[min(u32(3u), 3u)]))));
}
