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
    return rt_hw(w) != 0u;
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
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
        let r: RtRay = RtRay(p, reflect(ray.direction, n), RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u));
        rt_trace_Radiance(top_object, r, &bounce, (16u | 2u), (255u & ~MASK_CASTERS));
        rt_trace_Radiance(top_object, r, &bounce, 0u, 255u);
    }
    (*prd).result = ((shadow.attenuation * max(dot(n, l), 0.0f)) + (bounce.result * 0.5f));
}

// ---- resumable form ----
var<private> rt_fr_rtp_ray_flags_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_p: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_n: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_to_light: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_dist: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_l: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_shadow: array<Shadow, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_flags: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_shadow_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_bounce: array<Radiance, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_cond: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtp_ray_flags_r: array<RtRay, RT_DEPTHS>;
fn rtp_ray_flags(prd: ptr<function, Radiance>, attr: Normals, light_pos: vec3<f32>, cull_back: bool, scene_epsilon: f32, top_object: u32) {
    var rt_site: u32 = 0u;
    var ray: RtRay;
    var p: vec3<f32>;
    var n: vec3<f32>;
    var to_light: vec3<f32>;
    var dist: f32;
    var l: vec3<f32>;
    var shadow: Shadow;
    var flags: u32;
    var shadow_ray: RtRay;
    var bounce: Radiance;
    var cond: bool;
    var r: RtRay;
    if rt_rs != 0u {
        ray = rt_fr_rtp_ray_flags_ray[rt_d];
        p = rt_fr_rtp_ray_flags_p[rt_d];
        n = rt_fr_rtp_ray_flags_n[rt_d];
        to_light = rt_fr_rtp_ray_flags_to_light[rt_d];
        dist = rt_fr_rtp_ray_flags_dist[rt_d];
        l = rt_fr_rtp_ray_flags_l[rt_d];
        shadow = rt_fr_rtp_ray_flags_shadow[rt_d];
        flags = rt_fr_rtp_ray_flags_flags[rt_d];
        shadow_ray = rt_fr_rtp_ray_flags_shadow_ray[rt_d];
        bounce = rt_fr_rtp_ray_flags_bounce[rt_d];
        cond = rt_fr_rtp_ray_flags_cond[rt_d];
        r = rt_fr_rtp_ray_flags_r[rt_d];
        rt_site = rt_fr_rtp_ray_flags_rt_site[rt_d];
    }
    if rt_site == 0u {
        ray = rt_current_ray();
        p = (ray.origin + (rt_t_hit() * ray.direction));
        n = normalize(rt_transform_normal(0u, attr.shading_normal));
        to_light = (light_pos - p);
        dist = length(to_light);
        l = (to_light / dist);
        shadow = Shadow(vec3<f32>(1.0));
        flags = (1u | 4u);
        if cull_back {
            flags |= 8u;
        } else {
            flags |= 0u;
        }
        shadow_ray = RtRay(p, l, SHADOW_RAY, scene_epsilon, dist);
    }
    if rt_site == 0u {
        rt_request_Shadow(top_object, shadow_ray, shadow, flags, MASK_CASTERS);
        rt_fr_rtp_ray_flags_ray[rt_d] = ray;
        rt_fr_rtp_ray_flags_p[rt_d] = p;
        rt_fr_rtp_ray_flags_n[rt_d] = n;
        rt_fr_rtp_ray_flags_to_light[rt_d] = to_light;
        rt_fr_rtp_ray_flags_dist[rt_d] = dist;
        rt_fr_rtp_ray_flags_l[rt_d] = l;
        rt_fr_rtp_ray_flags_shadow[rt_d] = shadow;
        rt_fr_rtp_ray_flags_flags[rt_d] = flags;
        rt_fr_rtp_ray_flags_shadow_ray[rt_d] = shadow_ray;
        rt_fr_rtp_ray_flags_bounce[rt_d] = bounce;
        rt_fr_rtp_ray_flags_cond[rt_d] = cond;
        rt_fr_rtp_ray_flags_r[rt_d] = r;
        rt_fr_rtp_ray_flags_rt_site[rt_d] = 1u;
        rt_rs = 1u;
        return;
    }
    if rt_site == 1u {
        shadow = rt_result_Shadow();
        rt_site = 0u;
        rt_rs = 0u;
    }
    if rt_site == 0u {
        bounce = Radiance(vec3<f32>(0.0), ((*prd).importance * 0.5f), ((*prd).depth + 1i));
    }
    if rt_site == 0u {
        cond = ((*prd).depth < 2i);
    }
    if rt_site == 0u || (rt_site >= 2u && rt_site <= 3u) {
        if cond {
            if rt_site == 0u {
                r = RtRay(p, reflect(ray.direction, n), RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u));
            }
            if rt_site == 0u {
                rt_request_Radiance(top_object, r, bounce, (16u | 2u), (255u & ~MASK_CASTERS));
                rt_fr_rtp_ray_flags_ray[rt_d] = ray;
                rt_fr_rtp_ray_flags_p[rt_d] = p;
                rt_fr_rtp_ray_flags_n[rt_d] = n;
                rt_fr_rtp_ray_flags_to_light[rt_d] = to_light;
                rt_fr_rtp_ray_flags_dist[rt_d] = dist;
                rt_fr_rtp_ray_flags_l[rt_d] = l;
                rt_fr_rtp_ray_flags_shadow[rt_d] = shadow;
                rt_fr_rtp_ray_flags_flags[rt_d] = flags;
                rt_fr_rtp_ray_flags_shadow_ray[rt_d] = shadow_ray;
                rt_fr_rtp_ray_flags_bounce[rt_d] = bounce;
                rt_fr_rtp_ray_flags_cond[rt_d] = cond;
                rt_fr_rtp_ray_flags_r[rt_d] = r;
                rt_fr_rtp_ray_flags_rt_site[rt_d] = 2u;
                rt_rs = 1u;
                return;
            }
            if rt_site == 2u {
                bounce = rt_result_Radiance();
                rt_site = 0u;
                rt_rs = 0u;
            }
            if rt_site == 0u {
                rt_request_Radiance(top_object, r, bounce, 0u, 255u);
                rt_fr_rtp_ray_flags_ray[rt_d] = ray;
                rt_fr_rtp_ray_flags_p[rt_d] = p;
                rt_fr_rtp_ray_flags_n[rt_d] = n;
                rt_fr_rtp_ray_flags_to_light[rt_d] = to_light;
                rt_fr_rtp_ray_flags_dist[rt_d] = dist;
                rt_fr_rtp_ray_flags_l[rt_d] = l;
                rt_fr_rtp_ray_flags_shadow[rt_d] = shadow;
                rt_fr_rtp_ray_flags_flags[rt_d] = flags;
                rt_fr_rtp_ray_flags_shadow_ray[rt_d] = shadow_ray;
                rt_fr_rtp_ray_flags_bounce[rt_d] = bounce;
                rt_fr_rtp_ray_flags_cond[rt_d] = cond;
                rt_fr_rtp_ray_flags_r[rt_d] = r;
                rt_fr_rtp_ray_flags_rt_site[rt_d] = 3u;
                rt_rs = 1u;
                return;
            }
            if rt_site == 3u {
                bounce = rt_result_Radiance();
                rt_site = 0u;
                rt_rs = 0u;
            }
        }
    }
    if rt_site == 0u {
        (*prd).result = ((shadow.attenuation * max(dot(n, l), 0.0f)) + (bounce.result * 0.5f));
    }
}
