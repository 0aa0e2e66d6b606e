// miss program `printf`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_bool(w: u32) -> bool {
    return rt_hw(w) != 0u;
}

fn rtf_log_ray(tag: u32, ray: RtRay) {
    let tmp = tag;
    let tmp_1 = ray.origin;
    let tmp_2 = ray.direction;
    if rt_printf_begin(3950072924u, 7u) {
        rt_printf_word(tmp);
        rt_printf_word(bitcast<u32>(tmp_1[0]));
        rt_printf_word(bitcast<u32>(tmp_1[1]));
        rt_printf_word(bitcast<u32>(tmp_1[2]));
        rt_printf_word(bitcast<u32>(tmp_2[0]));
        rt_printf_word(bitcast<u32>(tmp_2[1]));
        rt_printf_word(bitcast<u32>(tmp_2[2]));
    }
}

fn rtp_printf(prd: ptr<function, Radiance>, verbose: bool) {
    let ray: RtRay = rt_current_ray();
    if rt_printf_begin(1754405337u, 0u) {
    }
    let tmp = (*prd).depth;
    let tmp_1 = (*prd).importance;
    let tmp_2 = verbose;
    if rt_printf_begin(3280768049u, 3u) {
        rt_printf_word(bitcast<u32>(tmp));
        rt_printf_word(bitcast<u32>(tmp_1));
        rt_printf_word(select(0u, 1u, tmp_2));
    }
    if verbose {
        rtf_log_ray(ray.ray_type, ray);
        let tmp_3 = rt_launch_index();
        let tmp_4 = vec3<i32>(-1i, 0i, 1i);
        let tmp_5 = (ray.tmax > 1.0f);
        if rt_printf_begin(3384038492u, 6u) {
            rt_printf_word(tmp_3[0]);
            rt_printf_word(tmp_3[1]);
            rt_printf_word(bitcast<u32>(tmp_4[0]));
            rt_printf_word(bitcast<u32>(tmp_4[1]));
            rt_printf_word(bitcast<u32>(tmp_4[2]));
            rt_printf_word(select(0u, 1u, tmp_5));
        }
    }
    (*prd).result = vec3<f32>(0.0);
}
