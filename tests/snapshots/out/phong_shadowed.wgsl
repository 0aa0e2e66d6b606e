// closest_hit program `phong_shadowed`
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

fn rtf_direct_light(hit_point: vec3<f32>, n: vec3<f32>, ray_direction: vec3<f32>, kd: vec3<f32>, ks: vec3<f32>, phong_exp: f32, lights: RtBuffer, scene_epsilon: f32, top_shadower: u32) -> vec3<f32> {
    var color: vec3<f32> = vec3<f32>(0.0);
    let end = lights.len;
    for (var i: u32 = 0u; i < end; i++) {
        let light: BasicLight = rt_bufload_BasicLight(lights, i);
        let to_light: vec3<f32> = (light.pos - hit_point);
        let light_dist: f32 = length(to_light);
        let l: vec3<f32> = (to_light / light_dist);
        if (dot(n, l) > 0.0f) {
            var shadow: Shadow = Shadow(vec3<f32>(1.0));
            if (light.casts_shadow != 0i) {
                let shadow_ray: RtRay = RtRay(hit_point, l, SHADOW_RAY, scene_epsilon, light_dist);
                rt_trace_Shadow(top_shadower, shadow_ray, &shadow, 0u, 255u);
            }
            if (max(max(shadow.attenuation.x, shadow.attenuation.y), shadow.attenuation.z) > 0.0f) {
                color += rtf_blinn_phong(kd, ks, phong_exp, n, l, ray_direction, (light.color * shadow.attenuation));
            }
        }
    }
    return color;
}

fn rtf_facing_normal(shading_normal: vec3<f32>, geometric_normal: vec3<f32>, ray_direction: vec3<f32>) -> vec3<f32> {
    let n: vec3<f32> = normalize(rt_transform_normal(0u, shading_normal));
    let g: vec3<f32> = normalize(rt_transform_normal(0u, geometric_normal));
    return faceForward(n, ray_direction, g);
}

fn rtp_phong_shadowed(prd: ptr<function, Radiance>, attr: Normals, ka: vec3<f32>, kd: vec3<f32>, ks: vec3<f32>, phong_exp: f32, ambient_light_color: vec3<f32>, lights: RtBuffer, scene_epsilon: f32, top_shadower: u32) {
    let ray: RtRay = rt_current_ray();
    let ffnormal: vec3<f32> = rtf_facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    (*prd).result = ((ka * ambient_light_color) + rtf_direct_light(hit_point, ffnormal, ray.direction, kd, ks, phong_exp, lights, scene_epsilon, top_shadower));
}

// ---- resumable form ----
var<private> rt_fr_rtf_direct_light_rs_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_color: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_i: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_end: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_light: array<BasicLight, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_to_light: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_light_dist: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_l: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_cond: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_shadow: array<Shadow, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_cond_1: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtf_direct_light_rs_shadow_ray: array<RtRay, RT_DEPTHS>;
fn rtf_direct_light_rs(hit_point: vec3<f32>, n: vec3<f32>, ray_direction: vec3<f32>, kd: vec3<f32>, ks: vec3<f32>, phong_exp: f32, lights: RtBuffer, scene_epsilon: f32, top_shadower: u32) -> vec3<f32> {
    var rt_site: u32 = 0u;
    var color: vec3<f32>;
    var i: u32;
    var end: u32;
    var light: BasicLight;
    var to_light: vec3<f32>;
    var light_dist: f32;
    var l: vec3<f32>;
    var cond: bool;
    var shadow: Shadow;
    var cond_1: bool;
    var shadow_ray: RtRay;
    if rt_rs != 0u {
        color = rt_fr_rtf_direct_light_rs_color[rt_d];
        i = rt_fr_rtf_direct_light_rs_i[rt_d];
        end = rt_fr_rtf_direct_light_rs_end[rt_d];
        light = rt_fr_rtf_direct_light_rs_light[rt_d];
        to_light = rt_fr_rtf_direct_light_rs_to_light[rt_d];
        light_dist = rt_fr_rtf_direct_light_rs_light_dist[rt_d];
        l = rt_fr_rtf_direct_light_rs_l[rt_d];
        cond = rt_fr_rtf_direct_light_rs_cond[rt_d];
        shadow = rt_fr_rtf_direct_light_rs_shadow[rt_d];
        cond_1 = rt_fr_rtf_direct_light_rs_cond_1[rt_d];
        shadow_ray = rt_fr_rtf_direct_light_rs_shadow_ray[rt_d];
        rt_site = rt_fr_rtf_direct_light_rs_rt_site[rt_d];
    }
    if rt_site == 0u {
        color = vec3<f32>(0.0);
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
            }
            if rt_site == 0u {
                cond = (dot(n, l) > 0.0f);
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
                                rt_fr_rtf_direct_light_rs_color[rt_d] = color;
                                rt_fr_rtf_direct_light_rs_i[rt_d] = i;
                                rt_fr_rtf_direct_light_rs_end[rt_d] = end;
                                rt_fr_rtf_direct_light_rs_light[rt_d] = light;
                                rt_fr_rtf_direct_light_rs_to_light[rt_d] = to_light;
                                rt_fr_rtf_direct_light_rs_light_dist[rt_d] = light_dist;
                                rt_fr_rtf_direct_light_rs_l[rt_d] = l;
                                rt_fr_rtf_direct_light_rs_cond[rt_d] = cond;
                                rt_fr_rtf_direct_light_rs_shadow[rt_d] = shadow;
                                rt_fr_rtf_direct_light_rs_cond_1[rt_d] = cond_1;
                                rt_fr_rtf_direct_light_rs_shadow_ray[rt_d] = shadow_ray;
                                rt_fr_rtf_direct_light_rs_rt_site[rt_d] = 1u;
                                rt_rs = 1u;
                                return vec3<f32>();
                            }
                            if rt_site == 1u {
                                shadow = rt_result_Shadow();
                                rt_site = 0u;
                                rt_rs = 0u;
                            }
                        }
                    }
                    if rt_site == 0u {
                        if (max(max(shadow.attenuation.x, shadow.attenuation.y), shadow.attenuation.z) > 0.0f) {
                            color += rtf_blinn_phong(kd, ks, phong_exp, n, l, ray_direction, (light.color * shadow.attenuation));
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
        return color;
    }
    return vec3<f32>();
}
var<private> rt_fr_rtp_phong_shadowed_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_ffnormal: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_hit_point: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg_1: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg_2: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg_3: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg_4: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg_5: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg_6: array<RtBuffer, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg_7: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_arg_8: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_phong_shadowed_rt_call_0_: array<vec3<f32>, RT_DEPTHS>;
fn rtp_phong_shadowed(prd: ptr<function, Radiance>, attr: Normals, ka: vec3<f32>, kd: vec3<f32>, ks: vec3<f32>, phong_exp: f32, ambient_light_color: vec3<f32>, lights: RtBuffer, scene_epsilon: f32, top_shadower: u32) {
    var rt_site: u32 = 0u;
    var ray: RtRay;
    var ffnormal: vec3<f32>;
    var hit_point: vec3<f32>;
    var arg: vec3<f32>;
    var arg_1: vec3<f32>;
    var arg_2: vec3<f32>;
    var arg_3: vec3<f32>;
    var arg_4: vec3<f32>;
    var arg_5: f32;
    var arg_6: RtBuffer;
    var arg_7: f32;
    var arg_8: u32;
    var rt_call_0_: vec3<f32>;
    if rt_rs != 0u {
        ray = rt_fr_rtp_phong_shadowed_ray[rt_d];
        ffnormal = rt_fr_rtp_phong_shadowed_ffnormal[rt_d];
        hit_point = rt_fr_rtp_phong_shadowed_hit_point[rt_d];
        arg = rt_fr_rtp_phong_shadowed_arg[rt_d];
        arg_1 = rt_fr_rtp_phong_shadowed_arg_1[rt_d];
        arg_2 = rt_fr_rtp_phong_shadowed_arg_2[rt_d];
        arg_3 = rt_fr_rtp_phong_shadowed_arg_3[rt_d];
        arg_4 = rt_fr_rtp_phong_shadowed_arg_4[rt_d];
        arg_5 = rt_fr_rtp_phong_shadowed_arg_5[rt_d];
        arg_6 = rt_fr_rtp_phong_shadowed_arg_6[rt_d];
        arg_7 = rt_fr_rtp_phong_shadowed_arg_7[rt_d];
        arg_8 = rt_fr_rtp_phong_shadowed_arg_8[rt_d];
        rt_call_0_ = rt_fr_rtp_phong_shadowed_rt_call_0_[rt_d];
        rt_site = rt_fr_rtp_phong_shadowed_rt_site[rt_d];
    }
    if rt_site == 0u {
        ray = rt_current_ray();
        ffnormal = rtf_facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
        hit_point = (ray.origin + (rt_t_hit() * ray.direction));
    }
    if rt_site == 0u || rt_site == 1u {
        if rt_site == 0u {
            arg = hit_point;
            arg_1 = ffnormal;
            arg_2 = ray.direction;
            arg_3 = kd;
            arg_4 = ks;
            arg_5 = phong_exp;
            arg_6 = lights;
            arg_7 = scene_epsilon;
            arg_8 = top_shadower;
        }
        let tmp = rtf_direct_light_rs(arg, arg_1, arg_2, arg_3, arg_4, arg_5, arg_6, arg_7, arg_8);
        if rt_rs != 0u {
            rt_fr_rtp_phong_shadowed_ray[rt_d] = ray;
            rt_fr_rtp_phong_shadowed_ffnormal[rt_d] = ffnormal;
            rt_fr_rtp_phong_shadowed_hit_point[rt_d] = hit_point;
            rt_fr_rtp_phong_shadowed_arg[rt_d] = arg;
            rt_fr_rtp_phong_shadowed_arg_1[rt_d] = arg_1;
            rt_fr_rtp_phong_shadowed_arg_2[rt_d] = arg_2;
            rt_fr_rtp_phong_shadowed_arg_3[rt_d] = arg_3;
            rt_fr_rtp_phong_shadowed_arg_4[rt_d] = arg_4;
            rt_fr_rtp_phong_shadowed_arg_5[rt_d] = arg_5;
            rt_fr_rtp_phong_shadowed_arg_6[rt_d] = arg_6;
            rt_fr_rtp_phong_shadowed_arg_7[rt_d] = arg_7;
            rt_fr_rtp_phong_shadowed_arg_8[rt_d] = arg_8;
            rt_fr_rtp_phong_shadowed_rt_call_0_[rt_d] = rt_call_0_;
            rt_fr_rtp_phong_shadowed_rt_site[rt_d] = 1u;
            rt_rs = 1u;
            return;
        }
        rt_site = 0u;
        rt_call_0_ = tmp;
    }
    if rt_site == 0u {
        (*prd).result = ((ka * ambient_light_color) + rt_call_0_);
    }
}
