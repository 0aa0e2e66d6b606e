// closest_hit program `glass`
fn rt_trace_Radiance(object: u32, ray: RtRay, prd: ptr<function, Radiance>, flags: u32, mask: u32) {}

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

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_powi(x: f32, n: i32) -> f32 {
    var base = x;
    var e = n;
    var r = 1.0f;
    loop {
        if (e & 1i) != 0i {
            r *= base;
        }
        e /= 2i;
        if e == 0i {
            break;
        }
        base *= base;
    }
    return select(r, 1.0f / r, n < 0i);
}

const RADIANCE_RAY: u32 = 0u;

fn rtf_fresnel_schlick(cos_theta: f32, f0: f32) -> f32 {
    return (f0 + ((1.0f - f0) * pow(clamp((1.0f - cos_theta), 0.0f, 1.0f), 5.0f)));
}

fn rtp_glass(prd: ptr<function, Radiance>, attr: Normals, refraction_index: f32, glass_color: vec3<f32>, max_depth: i32, importance_cutoff: f32, scene_epsilon: f32, top_object: u32) {
    let ray: RtRay = rt_current_ray();
    let hit_point: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    let n: vec3<f32> = normalize(rt_transform_normal(0u, attr.shading_normal));
    let entering: bool = (dot(ray.direction, n) < 0.0f);
    var tmp: vec3<f32>;
    if entering {
        tmp = n;
    } else {
        tmp = -n;
    }
    let ffn: vec3<f32> = tmp;
    var tmp_1: f32;
    if entering {
        tmp_1 = (1.0f / refraction_index);
    } else {
        tmp_1 = refraction_index;
    }
    let eta: f32 = tmp_1;
    let cos_i: f32 = -dot(ray.direction, ffn);
    let refract_dir: vec3<f32> = refract(ray.direction, ffn, eta);
    let f0: f32 = rt_powi(((1.0f - refraction_index) / (1.0f + refraction_index)), 2i);
    var cos_thin: f32 = cos_i;
    if !entering {
        cos_thin = -dot(refract_dir, ffn);
    }
    var fresnel: f32 = rtf_fresnel_schlick(cos_thin, f0);
    if (dot(refract_dir, refract_dir) == 0.0f) {
        fresnel = 1.0f;
    }
    var result: vec3<f32> = vec3<f32>(0.0);
    if ((*prd).depth < max_depth) {
        let reflect_importance: f32 = ((*prd).importance * fresnel);
        if (reflect_importance > importance_cutoff) {
            var refl: Radiance = Radiance(vec3<f32>(0.0), reflect_importance, ((*prd).depth + 1i));
            let r: vec3<f32> = reflect(ray.direction, ffn);
            rt_trace_Radiance(top_object, RtRay(hit_point, r, RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u)), &refl, 0u, 255u);
            result += (fresnel * refl.result);
        }
        let refract_importance: f32 = ((*prd).importance * (1.0f - fresnel));
        if (refract_importance > importance_cutoff) {
            var refr: Radiance = Radiance(vec3<f32>(0.0), refract_importance, ((*prd).depth + 1i));
            let t: RtRay = RtRay(hit_point, refract_dir, RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u));
            rt_trace_Radiance(top_object, t, &refr, 0u, 255u);
            result += (((1.0f - fresnel) * glass_color) * refr.result);
        }
    }
    (*prd).result = result;
}

// ---- resumable form ----
var<private> rt_fr_rtp_glass_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_hit_point: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_n: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_entering: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_ffn: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_eta: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_cos_i: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_refract_dir: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_f0: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_cos_thin: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_fresnel: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_result: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_cond: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_reflect_importance: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_cond_1: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_refl: array<Radiance, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_r: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_refract_importance: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_cond_2: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_refr: array<Radiance, RT_DEPTHS>;
var<private> rt_fr_rtp_glass_t: array<RtRay, RT_DEPTHS>;
fn rtp_glass(prd: ptr<function, Radiance>, attr: Normals, refraction_index: f32, glass_color: vec3<f32>, max_depth: i32, importance_cutoff: f32, scene_epsilon: f32, top_object: u32) {
    var rt_site: u32 = 0u;
    var ray: RtRay;
    var hit_point: vec3<f32>;
    var n: vec3<f32>;
    var entering: bool;
    var ffn: vec3<f32>;
    var eta: f32;
    var cos_i: f32;
    var refract_dir: vec3<f32>;
    var f0: f32;
    var cos_thin: f32;
    var fresnel: f32;
    var result: vec3<f32>;
    var cond: bool;
    var reflect_importance: f32;
    var cond_1: bool;
    var refl: Radiance;
    var r: vec3<f32>;
    var refract_importance: f32;
    var cond_2: bool;
    var refr: Radiance;
    var t: RtRay;
    if rt_rs != 0u {
        ray = rt_fr_rtp_glass_ray[rt_d];
        hit_point = rt_fr_rtp_glass_hit_point[rt_d];
        n = rt_fr_rtp_glass_n[rt_d];
        entering = rt_fr_rtp_glass_entering[rt_d];
        ffn = rt_fr_rtp_glass_ffn[rt_d];
        eta = rt_fr_rtp_glass_eta[rt_d];
        cos_i = rt_fr_rtp_glass_cos_i[rt_d];
        refract_dir = rt_fr_rtp_glass_refract_dir[rt_d];
        f0 = rt_fr_rtp_glass_f0[rt_d];
        cos_thin = rt_fr_rtp_glass_cos_thin[rt_d];
        fresnel = rt_fr_rtp_glass_fresnel[rt_d];
        result = rt_fr_rtp_glass_result[rt_d];
        cond = rt_fr_rtp_glass_cond[rt_d];
        reflect_importance = rt_fr_rtp_glass_reflect_importance[rt_d];
        cond_1 = rt_fr_rtp_glass_cond_1[rt_d];
        refl = rt_fr_rtp_glass_refl[rt_d];
        r = rt_fr_rtp_glass_r[rt_d];
        refract_importance = rt_fr_rtp_glass_refract_importance[rt_d];
        cond_2 = rt_fr_rtp_glass_cond_2[rt_d];
        refr = rt_fr_rtp_glass_refr[rt_d];
        t = rt_fr_rtp_glass_t[rt_d];
        rt_site = rt_fr_rtp_glass_rt_site[rt_d];
    }
    if rt_site == 0u {
        ray = rt_current_ray();
        hit_point = (ray.origin + (rt_t_hit() * ray.direction));
        n = normalize(rt_transform_normal(0u, attr.shading_normal));
        entering = (dot(ray.direction, n) < 0.0f);
        var tmp: vec3<f32>;
        if entering {
            tmp = n;
        } else {
            tmp = -n;
        }
        ffn = tmp;
        var tmp_1: f32;
        if entering {
            tmp_1 = (1.0f / refraction_index);
        } else {
            tmp_1 = refraction_index;
        }
        eta = tmp_1;
        cos_i = -dot(ray.direction, ffn);
        refract_dir = refract(ray.direction, ffn, eta);
        f0 = rt_powi(((1.0f - refraction_index) / (1.0f + refraction_index)), 2i);
        cos_thin = cos_i;
        if !entering {
            cos_thin = -dot(refract_dir, ffn);
        }
        fresnel = rtf_fresnel_schlick(cos_thin, f0);
        if (dot(refract_dir, refract_dir) == 0.0f) {
            fresnel = 1.0f;
        }
        result = vec3<f32>(0.0);
    }
    if rt_site == 0u {
        cond = ((*prd).depth < max_depth);
    }
    if rt_site == 0u || (rt_site >= 1u && rt_site <= 2u) {
        if cond {
            if rt_site == 0u {
                reflect_importance = ((*prd).importance * fresnel);
            }
            if rt_site == 0u {
                cond_1 = (reflect_importance > importance_cutoff);
            }
            if rt_site == 0u || rt_site == 1u {
                if cond_1 {
                    if rt_site == 0u {
                        refl = Radiance(vec3<f32>(0.0), reflect_importance, ((*prd).depth + 1i));
                        r = reflect(ray.direction, ffn);
                    }
                    if rt_site == 0u {
                        rt_request_Radiance(top_object, RtRay(hit_point, r, RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u)), refl, 0u, 255u);
                        rt_fr_rtp_glass_ray[rt_d] = ray;
                        rt_fr_rtp_glass_hit_point[rt_d] = hit_point;
                        rt_fr_rtp_glass_n[rt_d] = n;
                        rt_fr_rtp_glass_entering[rt_d] = entering;
                        rt_fr_rtp_glass_ffn[rt_d] = ffn;
                        rt_fr_rtp_glass_eta[rt_d] = eta;
                        rt_fr_rtp_glass_cos_i[rt_d] = cos_i;
                        rt_fr_rtp_glass_refract_dir[rt_d] = refract_dir;
                        rt_fr_rtp_glass_f0[rt_d] = f0;
                        rt_fr_rtp_glass_cos_thin[rt_d] = cos_thin;
                        rt_fr_rtp_glass_fresnel[rt_d] = fresnel;
                        rt_fr_rtp_glass_result[rt_d] = result;
                        rt_fr_rtp_glass_cond[rt_d] = cond;
                        rt_fr_rtp_glass_reflect_importance[rt_d] = reflect_importance;
                        rt_fr_rtp_glass_cond_1[rt_d] = cond_1;
                        rt_fr_rtp_glass_refl[rt_d] = refl;
                        rt_fr_rtp_glass_r[rt_d] = r;
                        rt_fr_rtp_glass_refract_importance[rt_d] = refract_importance;
                        rt_fr_rtp_glass_cond_2[rt_d] = cond_2;
                        rt_fr_rtp_glass_refr[rt_d] = refr;
                        rt_fr_rtp_glass_t[rt_d] = t;
                        rt_fr_rtp_glass_rt_site[rt_d] = 1u;
                        rt_rs = 1u;
                        return;
                    }
                    if rt_site == 1u {
                        refl = rt_result_Radiance();
                        rt_site = 0u;
                        rt_rs = 0u;
                    }
                    if rt_site == 0u {
                        result += (fresnel * refl.result);
                    }
                }
            }
            if rt_site == 0u {
                refract_importance = ((*prd).importance * (1.0f - fresnel));
            }
            if rt_site == 0u {
                cond_2 = (refract_importance > importance_cutoff);
            }
            if rt_site == 0u || rt_site == 2u {
                if cond_2 {
                    if rt_site == 0u {
                        refr = Radiance(vec3<f32>(0.0), refract_importance, ((*prd).depth + 1i));
                        t = RtRay(hit_point, refract_dir, RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u));
                    }
                    if rt_site == 0u {
                        rt_request_Radiance(top_object, t, refr, 0u, 255u);
                        rt_fr_rtp_glass_ray[rt_d] = ray;
                        rt_fr_rtp_glass_hit_point[rt_d] = hit_point;
                        rt_fr_rtp_glass_n[rt_d] = n;
                        rt_fr_rtp_glass_entering[rt_d] = entering;
                        rt_fr_rtp_glass_ffn[rt_d] = ffn;
                        rt_fr_rtp_glass_eta[rt_d] = eta;
                        rt_fr_rtp_glass_cos_i[rt_d] = cos_i;
                        rt_fr_rtp_glass_refract_dir[rt_d] = refract_dir;
                        rt_fr_rtp_glass_f0[rt_d] = f0;
                        rt_fr_rtp_glass_cos_thin[rt_d] = cos_thin;
                        rt_fr_rtp_glass_fresnel[rt_d] = fresnel;
                        rt_fr_rtp_glass_result[rt_d] = result;
                        rt_fr_rtp_glass_cond[rt_d] = cond;
                        rt_fr_rtp_glass_reflect_importance[rt_d] = reflect_importance;
                        rt_fr_rtp_glass_cond_1[rt_d] = cond_1;
                        rt_fr_rtp_glass_refl[rt_d] = refl;
                        rt_fr_rtp_glass_r[rt_d] = r;
                        rt_fr_rtp_glass_refract_importance[rt_d] = refract_importance;
                        rt_fr_rtp_glass_cond_2[rt_d] = cond_2;
                        rt_fr_rtp_glass_refr[rt_d] = refr;
                        rt_fr_rtp_glass_t[rt_d] = t;
                        rt_fr_rtp_glass_rt_site[rt_d] = 2u;
                        rt_rs = 1u;
                        return;
                    }
                    if rt_site == 2u {
                        refr = rt_result_Radiance();
                        rt_site = 0u;
                        rt_rs = 0u;
                    }
                    if rt_site == 0u {
                        result += (((1.0f - fresnel) * glass_color) * refr.result);
                    }
                }
            }
        }
    }
    if rt_site == 0u {
        (*prd).result = result;
    }
}
