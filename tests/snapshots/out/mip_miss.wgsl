// miss program `mip_miss`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

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

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rtp_mip_miss(prd: ptr<function, Radiance>, sky: RtSampler, bias: f32, lods: RtBuffer) {
    var lods_1 = lods;
    let d: vec3<f32> = rt_current_ray().direction;
    let uv: vec2<f32> = vec2<f32>(((d.x * 0.5f) + 0.5f), ((d.y * 0.5f) + 0.5f));
    let blurred: vec4<f32> = rt_tex_sample_lod(sky, uv, (bias + f32((*prd).depth)));
    let footprint: vec2<f32> = vec2<f32>(((*prd).importance / f32(vec2<u32>(sky.width, sky.height).x)), 0.0f);
    let sharp: vec4<f32> = rt_tex_sample_grad(sky, uv, footprint, footprint.yx);
    let tmp_2 = rt_bufload_f32(lods_1, 0u);
    var tmp_1: f32;
    {
        let tmp = 0u;
        rt_bufstore_f32(lods_1, tmp, f32(max(sky.mode >> 24u, 1u)));
        tmp_1 = 1.0f;
    }
    let last: vec4<f32> = rt_tex_sample_lod(sky, (uv * 2.0f), (tmp_2 + tmp_1));
    (*prd).result = (((blurred + sharp) + last) + rt_tex_sample(sky, uv)).xyz;
}
