// miss program `fog_miss`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_fog_miss(prd: ptr<function, Radiance>, fog: RtSampler3d, bounds: vec3<f32>) {
    let ray: RtRay = rt_current_ray();
    let uvw: vec3<f32> = ((ray.origin + ray.direction) / bounds);
    let density: f32 = rt_tex3_sample(fog, uvw).x;
    let last: vec3<u32> = (vec3<u32>(fog.width, fog.height, fog.depth) - 1u);
    let corner: vec4<f32> = rt_tex3_fetch(fog, vec3<u32>(last.x, 0u, last.z));
    (*prd).result = (corner.xyz * density);
}
