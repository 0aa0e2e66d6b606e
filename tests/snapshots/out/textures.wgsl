// closest_hit program `textures`

struct MeshHit {
    normal: vec3<f32>,
    uv: vec2<f32>,
}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_f2u2(x: vec2<f32>) -> vec2<u32> {
    return select(select(vec2<u32>(x), vec2<u32>(4294967295u), x >= vec2<f32>(4294967296.0)), vec2<u32>(0), (bitcast<vec2<u32>>(x) & vec2<u32>(0x7fffffffu)) > vec2<u32>(0x7f800000u));
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rtp_textures(prd: ptr<function, Radiance>, attr: MeshHit, albedo: RtSampler, normal_map: RtSampler, palette: RtSampler, tiling: f32) {
    let uv: vec2<f32> = (attr.uv * tiling);
    let base: vec4<f32> = rt_tex_sample(albedo, uv);
    let texel: vec2<u32> = rt_f2u2(((uv - trunc(uv)) * vec2<f32>(vec2<u32>(normal_map.width, normal_map.height))));
    let bump: vec3<f32> = ((rt_tex_fetch(normal_map, texel).xyz * 2.0f) - 1.0f);
    let n: vec3<f32> = normalize((attr.normal + (bump * 0.25f)));
    let last: vec2<u32> = (vec2<u32>(palette.width, palette.height) - 1u);
    let entry: vec4<f32> = rt_tex_fetch(palette, vec2<u32>((rt_primitive_index() % (last.x + 1u)), last.y));
    let light: f32 = max(dot(n, vec3<f32>(0.0f, 1.0f, 0.0f)), 0.0f);
    (*prd).result = (((base.xyz * entry.xyz) * light) * base.w);
}
