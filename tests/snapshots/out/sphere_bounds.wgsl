// bounding_box program `sphere_bounds`

fn rt_bufload_vec4f(b: RtBuffer, i: u32) -> vec4<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec4f(b.offset + i * 4u);
    }
    return vec4<f32>();
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rtp_sphere_bounds(prim: u32, spheres: RtBuffer) -> RtAabb {
    let s: vec4<f32> = rt_bufload_vec4f(spheres, prim);
    let r: vec3<f32> = vec3<f32>(abs(s.w));
    if (s.w <= 0.0f) {
        return RtAabb(vec3<f32>(rt_f32_from_bits(0x7f800000u)), vec3<f32>(rt_f32_from_bits(0xff800000u)));
    }
    return RtAabb((s.xyz - r), (s.xyz + r));
}
