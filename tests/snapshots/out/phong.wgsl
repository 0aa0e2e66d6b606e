// closest_hit program `phong`
fn rt_trace_Shadow(object: u32, ray: RtRay, prd: ptr<function, Shadow>, flags: u32, mask: u32) {}

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

struct Shadow {
    attenuation: vec3<f32>,
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
    return bitcast<f32>(rt_heap[w]);
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_heap[w]);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

const SHADOW_RAY: u32 = 1u;

fn rtp_phong(prd: ptr<function, Radiance>, attr: Normals, ka: vec3<f32>, kd: vec3<f32>, ks: vec3<f32>, phong_exp: f32, ambient_light_color: vec3<f32>, lights: RtBuffer, scene_epsilon: f32, top_shadower: u32) {
    let ray: RtRay = rt_current_ray();
    let n: vec3<f32> = normalize(rt_transform_normal(0u, attr.shading_normal));
    let g: vec3<f32> = normalize(rt_transform_normal(0u, attr.geometric_normal));
    let ffnormal: vec3<f32> = faceForward(n, ray.direction, g);
    let hit_point: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    var color: vec3<f32> = (ka * ambient_light_color);
    let end = lights.len;
    for (var i: u32 = 0u; i < end; i++) {
        let light: BasicLight = rt_bufload_BasicLight(lights, i);
        let to_light: vec3<f32> = (light.pos - hit_point);
        let light_dist: f32 = length(to_light);
        let l: vec3<f32> = (to_light / light_dist);
        let n_dot_l: f32 = dot(ffnormal, l);
        if (n_dot_l > 0.0f) {
            var shadow: Shadow = Shadow(vec3<f32>(1.0));
            if (light.casts_shadow != 0i) {
                let shadow_ray: RtRay = RtRay(hit_point, l, SHADOW_RAY, scene_epsilon, light_dist);
                rt_trace_Shadow(top_shadower, shadow_ray, &shadow, 0u, 255u);
            }
            let light_attenuation: vec3<f32> = shadow.attenuation;
            if (max(max(light_attenuation.x, light_attenuation.y), light_attenuation.z) > 0.0f) {
                let lc: vec3<f32> = (light.color * light_attenuation);
                color += ((kd * n_dot_l) * lc);
                let h: vec3<f32> = normalize((l - ray.direction));
                let n_dot_h: f32 = dot(ffnormal, h);
                if (n_dot_h > 0.0f) {
                    color += ((ks * lc) * pow(n_dot_h, phong_exp));
                }
            }
        }
    }
    (*prd).result = color;
}
