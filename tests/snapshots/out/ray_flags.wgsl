// closest_hit program `ray_flags`
fn rt_trace_Radiance(object: u32, ray: RtRay, prd: ptr<function, Radiance>, flags: u32, mask: u32) {}
fn rt_trace_Shadow(object: u32, ray: RtRay, prd: ptr<function, Shadow>, flags: u32, mask: u32) {}

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

fn rt_load_bool(w: u32) -> bool {
    return rt_heap[w] != 0u;
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_heap[w]);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

const MASK_CASTERS: u32 = (1u << 1u);

const RADIANCE_RAY: u32 = 0u;

const SHADOW_RAY: u32 = 1u;

fn rtp_ray_flags(prd: ptr<function, Radiance>, attr: Normals, light_pos: vec3<f32>, cull_back: bool, scene_epsilon: f32, top_object: u32) {
    let ray: RtRay = rt_current_ray();
    let p: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    let n: vec3<f32> = normalize(rt_transform_normal(0u, attr.shading_normal));
    let to_light: vec3<f32> = (light_pos - p);
    let dist: f32 = length(to_light);
    let l: vec3<f32> = (to_light / dist);
    var shadow: Shadow = Shadow(vec3<f32>(1.0));
    var flags: u32 = (1u | 4u);
    if cull_back {
        flags |= 8u;
    } else {
        flags |= 0u;
    }
    let shadow_ray: RtRay = RtRay(p, l, SHADOW_RAY, scene_epsilon, dist);
    rt_trace_Shadow(top_object, shadow_ray, &shadow, flags, MASK_CASTERS);
    var bounce: Radiance = Radiance(vec3<f32>(0.0), ((*prd).importance * 0.5f), ((*prd).depth + 1i));
    if ((*prd).depth < 2i) {
        let r: RtRay = RtRay(p, reflect(ray.direction, n), RADIANCE_RAY, scene_epsilon, bitcast<f32>(0x7f800000u));
        rt_trace_Radiance(top_object, r, &bounce, (16u | 2u), (255u & ~MASK_CASTERS));
        rt_trace_Radiance(top_object, r, &bounce, 0u, 255u);
    }
    (*prd).result = ((shadow.attenuation * max(dot(n, l), 0.0f)) + (bounce.result * 0.5f));
}
