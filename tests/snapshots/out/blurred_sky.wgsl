// miss program `blurred_sky`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rtp_blurred_sky(prd: ptr<function, Radiance>, sky: RtSampler, fog: u32, roughness: f32) {
    let d: vec3<f32> = rt_current_ray().direction;
    let lod: f32 = (roughness * f32((max(sky.mode >> 24u, 1u) - 1u)));
    let tmp = rt_texid3(fog);
    let tmp_1 = rt_texid3(fog);
    (*prd).result = ((rt_texcube_sample_lod(sky, d, lod).xyz * rt_tex3_sample_lod(tmp, ((d * 0.5f) + 0.5f), lod).w) / f32(max(tmp_1.mode >> 24u, 1u)));
}
