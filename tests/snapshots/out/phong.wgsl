// closest_hit program `phong`

struct BasicLight {
    pos: vec3<f32>,
    color: vec3<f32>,
    casts_shadow: i32,
}

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_bufload_BasicLight(b: RtBuffer, i: u32) -> BasicLight {
    if rt_buf_check(b, i) {
        return rt_load_BasicLight(b.offset + i * 7u);
    }
    return BasicLight();
}

fn rt_load_BasicLight(w: u32) -> BasicLight {
    return BasicLight(rt_load_vec3f(w + 0u), rt_load_vec3f(w + 3u), rt_load_i32(w + 6u));
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtf_blinn_phong(kd: vec3<f32>, ks: vec3<f32>, phong_exp: f32, n: vec3<f32>, l: vec3<f32>, ray_direction: vec3<f32>, light_color: vec3<f32>) -> vec3<f32> {
    let n_dot_l: f32 = dot(n, l);
    var color: vec3<f32> = vec3<f32>(0.0);
    if (n_dot_l > 0.0f) {
        color = ((kd * n_dot_l) * light_color);
        let h: vec3<f32> = normalize((l - ray_direction));
        let n_dot_h: f32 = dot(n, h);
        if (n_dot_h > 0.0f) {
            color += ((ks * light_color) * pow(n_dot_h, phong_exp));
        }
    }
    return color;
}

fn rtf_facing_normal(shading_normal: vec3<f32>, geometric_normal: vec3<f32>, ray_direction: vec3<f32>) -> vec3<f32> {
    let n: vec3<f32> = normalize(rt_transform_normal(0u, shading_normal));
    let g: vec3<f32> = normalize(rt_transform_normal(0u, geometric_normal));
    return faceForward(n, ray_direction, g);
}

fn rtp_phong(prd: ptr<function, Radiance>, attr: Normals, ka: vec3<f32>, kd: vec3<f32>, ks: vec3<f32>, phong_exp: f32, ambient_light_color: vec3<f32>, lights: RtBuffer) {
    let ray: RtRay = rt_current_ray();
    let ffnormal: vec3<f32> = rtf_facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    var color: vec3<f32> = (ka * ambient_light_color);
    let end = lights.len;
    for (var i: u32 = 0u; i < end; i++) {
        let light: BasicLight = rt_bufload_BasicLight(lights, i);
        let l: vec3<f32> = normalize((light.pos - hit_point));
        color += rtf_blinn_phong(kd, ks, phong_exp, ffnormal, l, ray.direction, light.color);
    }
    (*prd).result = color;
}
