// ray_generation program `generic_blend`

fn rt_bufload_vec4f(b: RtBuffer, i: u32) -> vec4<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec4f(b.offset + i * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore_vec4f(b: RtBuffer, i: u32, v: vec4<f32>) {
    if rt_buf_check(b, i) {
        rt_store_vec4f(b.offset + i * 4u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_vec4f(w: u32, v: vec4<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
    rt_store_f32(w + 3u, v[3]);
}

fn rtf_average__2(xs: array<f32, 2>) -> f32 {
    var s: f32 = 0.0f;
    var i: u32 = 0u;
    while (i < 2u) {
        s += xs[i];
        i += 1u;
    }
    return (s / f32(2u));
}

fn rtf_average__3(xs: array<f32, 3>) -> f32 {
    var s: f32 = 0.0f;
    var i: u32 = 0u;
    while (i < 3u) {
        s += xs[i];
        i += 1u;
    }
    return (s / f32(3u));
}

fn rtf_blend__Vec3(a: vec3<f32>, b: vec3<f32>, t: f32) -> vec3<f32> {
    return (a + ((b - a) * t));
}

fn rtf_blend__f32(a: f32, b: f32, t: f32) -> f32 {
    return (a + ((b - a) * t));
}

fn rtf_fade(c: vec3<f32>) -> vec3<f32> {
    return rtf_blend__Vec3(c, vec3<f32>(0.0), 0.25f);
}

fn rtf_halfway__Vec3(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return rtf_blend__Vec3(a, b, 0.5f);
}

fn rtp_generic_blend(out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let x: f32 = f32(i);
    let a: f32 = rtf_blend__f32(x, 1.0f, 0.5f);
    let c: vec3<f32> = rtf_blend__Vec3(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), x);
    let d: vec3<f32> = rtf_halfway__Vec3(c, rtf_fade(c));
    let m: f32 = (rtf_average__3(array<f32, 3>(x, 2.0f, a)) + rtf_average__2(array<f32, 2>(x, x)));
    let tmp = i;
    rt_bufstore_vec4f(out_1, tmp, vec4<f32>(a, d.x, d.y, m));
}
