// any_hit program `lattice_any_hit`

struct Shadow {
    attenuation: vec3<f32>,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_lattice_any_hit(prd: ptr<function, Shadow>, transmission: vec3<f32>) {
    if ((rt_primitive_index() % 2u) == 1u) {
        rt_ignore_intersection();
        return;
    }
    (*prd).attenuation *= transmission;
    let tmp = (*prd).attenuation;
    if (max(max(tmp.x, tmp.y), tmp.z) < 0.01f) {
        rt_terminate_ray();
    }
}
