// closest_hit program `motion_shade`
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

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

const SHADOW_RAY: u32 = 1u;

fn rtp_motion_shade(prd: ptr<function, Radiance>, attr: Normals, light_pos: vec3<f32>, top_object: u32) {
    let ray: RtRay = rt_current_ray();
    let p: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    let l: vec3<f32> = normalize((light_pos - p));
    var shadow: Shadow = Shadow(vec3<f32>(1.0));
    let shadow_ray: RtRay = RtRay(p, l, SHADOW_RAY, 0.001f, rt_f32_from_bits(0x7f800000u));
    let flags: u32 = (1u | 4u);
    rt_set_trace_time(rt_current_time());
    rt_trace_Shadow(top_object, shadow_ray, &shadow, flags, 255u);
    let n: vec3<f32> = normalize(rt_transform_normal(0u, attr.shading_normal));
    (*prd).result = (shadow.attenuation * max(dot(n, l), 0.0f));
}

// ---- resumable form ----
var<private> rt_fr_rtp_motion_shade_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_shade_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_shade_p: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_shade_l: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_shade_shadow: array<Shadow, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_shade_shadow_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_shade_flags: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_shade_n: array<vec3<f32>, RT_DEPTHS>;
fn rtp_motion_shade(prd: ptr<function, Radiance>, attr: Normals, light_pos: vec3<f32>, top_object: u32) {
    var rt_site: u32 = 0u;
    var ray: RtRay;
    var p: vec3<f32>;
    var l: vec3<f32>;
    var shadow: Shadow;
    var shadow_ray: RtRay;
    var flags: u32;
    var n: vec3<f32>;
    if rt_rs != 0u {
        ray = rt_fr_rtp_motion_shade_ray[rt_d];
        p = rt_fr_rtp_motion_shade_p[rt_d];
        l = rt_fr_rtp_motion_shade_l[rt_d];
        shadow = rt_fr_rtp_motion_shade_shadow[rt_d];
        shadow_ray = rt_fr_rtp_motion_shade_shadow_ray[rt_d];
        flags = rt_fr_rtp_motion_shade_flags[rt_d];
        n = rt_fr_rtp_motion_shade_n[rt_d];
        rt_site = rt_fr_rtp_motion_shade_rt_site[rt_d];
    }
    if rt_site == 0u {
        ray = rt_current_ray();
        p = (ray.origin + (rt_t_hit() * ray.direction));
        l = normalize((light_pos - p));
        shadow = Shadow(vec3<f32>(1.0));
        shadow_ray = RtRay(p, l, SHADOW_RAY, 0.001f, rt_f32_from_bits(0x7f800000u));
        flags = (1u | 4u);
    }
    if rt_site == 0u {
        rt_set_trace_time(rt_current_time());
        rt_request_Shadow(top_object, shadow_ray, shadow, flags, 255u);
        rt_fr_rtp_motion_shade_ray[rt_d] = ray;
        rt_fr_rtp_motion_shade_p[rt_d] = p;
        rt_fr_rtp_motion_shade_l[rt_d] = l;
        rt_fr_rtp_motion_shade_shadow[rt_d] = shadow;
        rt_fr_rtp_motion_shade_shadow_ray[rt_d] = shadow_ray;
        rt_fr_rtp_motion_shade_flags[rt_d] = flags;
        rt_fr_rtp_motion_shade_n[rt_d] = n;
        rt_fr_rtp_motion_shade_rt_site[rt_d] = 1u;
        rt_rs = 1u;
        return;
    }
    if rt_site == 1u {
        shadow = rt_result_Shadow();
        rt_site = 0u;
        rt_rs = 0u;
    }
    if rt_site == 0u {
        n = normalize(rt_transform_normal(0u, attr.shading_normal));
        (*prd).result = (shadow.attenuation * max(dot(n, l), 0.0f));
    }
}
