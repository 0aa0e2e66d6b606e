// closest_hit program `albedo_by_material`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

struct TexturedMaterial {
    albedo: u32,
    roughness: f32,
}

fn rt_bufload_TexturedMaterial(b: RtBuffer, i: u32) -> TexturedMaterial {
    if rt_buf_check(b, i) {
        return rt_load_TexturedMaterial(b.offset + i * 2u);
    }
    return TexturedMaterial();
}

fn rt_load_TexturedMaterial(w: u32) -> TexturedMaterial {
    return TexturedMaterial(rt_load_u32(w + 0u), rt_load_f32(w + 1u));
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rtp_albedo_by_material(prd: ptr<function, Radiance>, material: u32, materials: RtBuffer) {
    let m: TexturedMaterial = rt_bufload_TexturedMaterial(materials, material);
    let uv: vec2<f32> = vec2<f32>((rt_t_hit() * 0.1f), m.roughness);
    let tmp = rt_texid(m.albedo, 1u);
    let base: vec4<f32> = rt_tex_sample(tmp, uv);
    let tmp_1 = rt_texid(m.albedo, 1u);
    let tmp_2 = rt_texid(m.albedo, 1u);
    let blurred: vec4<f32> = rt_tex_sample_lod(tmp_1, uv, (m.roughness * f32(max(tmp_2.mode >> 24u, 1u))));
    let tmp_3 = rt_texid(m.albedo, 1u);
    let texel: vec2<f32> = (vec2<f32>(1.0f, 1.0f) / vec2<f32>(vec2<u32>(tmp_3.width, tmp_3.height)));
    let tmp_4 = rt_texid(m.albedo, 1u);
    let filtered: vec4<f32> = rt_tex_sample_grad(tmp_4, uv, vec2<f32>(texel.x, 0.0f), vec2<f32>(0.0f, texel.y));
    (*prd).result = (((base + blurred) + filtered).xyz / 3.0f);
}
