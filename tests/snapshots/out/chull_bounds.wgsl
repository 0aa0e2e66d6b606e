// bounding_box program `chull_bounds`

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_chull_bounds(prim: u32, chull_bbmin: vec3<f32>, chull_bbmax: vec3<f32>) -> RtAabb {
    _ = prim;
    return RtAabb(chull_bbmin, chull_bbmax);
}
