// miss program `sky_by_id`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rtp_sky_by_id(prd: ptr<function, Radiance>, sky: u32, fog: u32) {
    let d: vec3<f32> = rt_current_ray().direction;
    let tmp = rt_texid(sky, 3u);
    var c: vec3<f32> = rt_texcube_sample(tmp, d).xyz;
    if ((sky != 0u) && (fog != 0u)) {
        let tmp_2 = c;
        let tmp_1 = rt_texid3(fog);
        let tmp_3 = rt_texid(sky, 3u);
        c = ((tmp_2 * rt_tex3_sample(tmp_1, ((d * 0.5f) + 0.5f)).w) / f32(tmp_3.width));
    }
    (*prd).result = c;
}
