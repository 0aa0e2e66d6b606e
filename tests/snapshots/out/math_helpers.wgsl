// closest_hit program `math_helpers`

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

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

fn rtp_math_helpers(prd: ptr<function, Radiance>, attr: Normals, base_color: vec3<f32>, rim_color: vec3<f32>, light_dir: vec3<f32>, ior: f32) {
    let ray: RtRay = rt_current_ray();
    let n: vec3<f32> = faceForward(attr.shading_normal, ray.direction, attr.geometric_normal);
    let r: vec3<f32> = reflect(ray.direction, n);
    let tr: vec3<f32> = refract(ray.direction, n, (1.0f / ior));
    let n_dot_l: f32 = saturate(dot(n, light_dir));
    let band: f32 = ((select(0.0f, 1.0f, n_dot_l >= 0.5f) * 0.5f) + (select(0.0f, 1.0f, n_dot_l >= 0.9f) * 0.5f));
    let rim: f32 = smoothstep(0.6f, 1.0f, (1.0f - saturate(dot(n, -ray.direction))));
    let spec: vec3<f32> = smoothstep(vec3<f32>(0.9f), vec3<f32>(1.0), (r * light_dir));
    let edges: vec3<f32> = (select(vec3<f32>(0.0), vec3<f32>(1.0), abs(tr) >= vec3<f32>(0.25f)) + saturate((tr * 4.0f)));
    let lit: vec3<f32> = ((base_color * 0.2f) * (1.0 - band) + base_color * band);
    let toned: vec3<f32> = ((lit * (1.0 - vec3<f32>(rim)) + rim_color * vec3<f32>(rim)) + ((0.0f * (1.0 - rim) + 0.1f * rim) * spec));
    (*prd).result = (toned * (1.0 - vec3<f32>(0.0f, 0.05f, 0.1f)) + edges * vec3<f32>(0.0f, 0.05f, 0.1f));
}
