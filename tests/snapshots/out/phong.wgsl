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
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
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

// ---- resumable form ----
var<private> rt_fr_rtp_phong_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_n: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_g: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_ffnormal: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_hit_point: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_color: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_i: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_end: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_light: array<BasicLight, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_to_light: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_light_dist: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_l: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_n_dot_l: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_cond: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadow: array<Shadow, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_cond_1: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadow_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_light_attenuation: array<vec3<f32>, RT_DEPTHS>;
fn rtp_phong(prd: ptr<function, Radiance>, attr: Normals, ka: vec3<f32>, kd: vec3<f32>, ks: vec3<f32>, phong_exp: f32, ambient_light_color: vec3<f32>, lights: RtBuffer, scene_epsilon: f32, top_shadower: u32) {
    var rt_site: u32 = 0u;
    var ray: RtRay;
    var n: vec3<f32>;
    var g: vec3<f32>;
    var ffnormal: vec3<f32>;
    var hit_point: vec3<f32>;
    var color: vec3<f32>;
    var i: u32;
    var end: u32;
    var light: BasicLight;
    var to_light: vec3<f32>;
    var light_dist: f32;
    var l: vec3<f32>;
    var n_dot_l: f32;
    var cond: bool;
    var shadow: Shadow;
    var cond_1: bool;
    var shadow_ray: RtRay;
    var light_attenuation: vec3<f32>;
    if rt_rs != 0u {
        ray = rt_fr_rtp_phong_ray[rt_d];
        n = rt_fr_rtp_phong_n[rt_d];
        g = rt_fr_rtp_phong_g[rt_d];
        ffnormal = rt_fr_rtp_phong_ffnormal[rt_d];
        hit_point = rt_fr_rtp_phong_hit_point[rt_d];
        color = rt_fr_rtp_phong_color[rt_d];
        i = rt_fr_rtp_phong_i[rt_d];
        end = rt_fr_rtp_phong_end[rt_d];
        light = rt_fr_rtp_phong_light[rt_d];
        to_light = rt_fr_rtp_phong_to_light[rt_d];
        light_dist = rt_fr_rtp_phong_light_dist[rt_d];
        l = rt_fr_rtp_phong_l[rt_d];
        n_dot_l = rt_fr_rtp_phong_n_dot_l[rt_d];
        cond = rt_fr_rtp_phong_cond[rt_d];
        shadow = rt_fr_rtp_phong_shadow[rt_d];
        cond_1 = rt_fr_rtp_phong_cond_1[rt_d];
        shadow_ray = rt_fr_rtp_phong_shadow_ray[rt_d];
        light_attenuation = rt_fr_rtp_phong_light_attenuation[rt_d];
        rt_site = rt_fr_rtp_phong_rt_site[rt_d];
    }
    if rt_site == 0u {
        ray = rt_current_ray();
        n = normalize(rt_transform_normal(0u, attr.shading_normal));
        g = normalize(rt_transform_normal(0u, attr.geometric_normal));
        ffnormal = faceForward(n, ray.direction, g);
        hit_point = (ray.origin + (rt_t_hit() * ray.direction));
        color = (ka * ambient_light_color);
    }
    if rt_site == 0u {
        i = 0u;
        end = lights.len;
    }
    if rt_site == 0u || rt_site == 1u {
        loop {
            if rt_site == 0u {
                if !(i < end) {
                    break;
                }
            }
            if rt_site == 0u {
                light = rt_bufload_BasicLight(lights, i);
                to_light = (light.pos - hit_point);
                light_dist = length(to_light);
                l = (to_light / light_dist);
                n_dot_l = dot(ffnormal, l);
            }
            if rt_site == 0u {
                cond = (n_dot_l > 0.0f);
            }
            if rt_site == 0u || rt_site == 1u {
                if cond {
                    if rt_site == 0u {
                        shadow = Shadow(vec3<f32>(1.0));
                    }
                    if rt_site == 0u {
                        cond_1 = (light.casts_shadow != 0i);
                    }
                    if rt_site == 0u || rt_site == 1u {
                        if cond_1 {
                            if rt_site == 0u {
                                shadow_ray = RtRay(hit_point, l, SHADOW_RAY, scene_epsilon, light_dist);
                            }
                            if rt_site == 0u {
                                rt_request_Shadow(top_shadower, shadow_ray, shadow, 0u, 255u);
                                rt_fr_rtp_phong_ray[rt_d] = ray;
                                rt_fr_rtp_phong_n[rt_d] = n;
                                rt_fr_rtp_phong_g[rt_d] = g;
                                rt_fr_rtp_phong_ffnormal[rt_d] = ffnormal;
                                rt_fr_rtp_phong_hit_point[rt_d] = hit_point;
                                rt_fr_rtp_phong_color[rt_d] = color;
                                rt_fr_rtp_phong_i[rt_d] = i;
                                rt_fr_rtp_phong_end[rt_d] = end;
                                rt_fr_rtp_phong_light[rt_d] = light;
                                rt_fr_rtp_phong_to_light[rt_d] = to_light;
                                rt_fr_rtp_phong_light_dist[rt_d] = light_dist;
                                rt_fr_rtp_phong_l[rt_d] = l;
                                rt_fr_rtp_phong_n_dot_l[rt_d] = n_dot_l;
                                rt_fr_rtp_phong_cond[rt_d] = cond;
                                rt_fr_rtp_phong_shadow[rt_d] = shadow;
                                rt_fr_rtp_phong_cond_1[rt_d] = cond_1;
                                rt_fr_rtp_phong_shadow_ray[rt_d] = shadow_ray;
                                rt_fr_rtp_phong_light_attenuation[rt_d] = light_attenuation;
                                rt_fr_rtp_phong_rt_site[rt_d] = 1u;
                                rt_rs = 1u;
                                return;
                            }
                            if rt_site == 1u {
                                shadow = rt_result_Shadow();
                                rt_site = 0u;
                                rt_rs = 0u;
                            }
                        }
                    }
                    if rt_site == 0u {
                        light_attenuation = shadow.attenuation;
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
            }
            continuing {
                i++;
            }
        }
    }
    if rt_site == 0u {
        (*prd).result = color;
    }
}
