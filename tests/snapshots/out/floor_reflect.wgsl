// closest_hit program `floor_reflect`
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

const RADIANCE_RAY: u32 = 0u;

fn rtf_luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.3f, 0.59f, 0.11f));
}

fn rtp_floor_reflect(prd: ptr<function, Radiance>, attr: Normals, floor_color: vec3<f32>, reflectivity: vec3<f32>, max_depth: i32, importance_cutoff: f32, scene_epsilon: f32, top_object: u32) {
    let ray: RtRay = rt_current_ray();
    let n: vec3<f32> = normalize(rt_transform_normal(0u, attr.shading_normal));
    let hit_point: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    var result: vec3<f32> = floor_color;
    let importance: f32 = ((*prd).importance * rtf_luminance(reflectivity));
    if ((importance > importance_cutoff) && ((*prd).depth < max_depth)) {
        var refl: Radiance = Radiance(vec3<f32>(0.0), importance, ((*prd).depth + 1i));
        let r: vec3<f32> = reflect(ray.direction, n);
        rt_trace_Radiance(top_object, RtRay(hit_point, r, RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u)), &refl, 0u, 255u);
        result += (reflectivity * refl.result);
    }
    (*prd).result = result;
}

// ---- resumable form ----
var<private> rt_fr_rtp_floor_reflect_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_floor_reflect_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_floor_reflect_n: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_floor_reflect_hit_point: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_floor_reflect_result: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_floor_reflect_importance: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_floor_reflect_cond: array<bool, RT_DEPTHS>;
var<private> rt_fr_rtp_floor_reflect_refl: array<Radiance, RT_DEPTHS>;
var<private> rt_fr_rtp_floor_reflect_r: array<vec3<f32>, RT_DEPTHS>;
fn rtp_floor_reflect(prd: ptr<function, Radiance>, attr: Normals, floor_color: vec3<f32>, reflectivity: vec3<f32>, max_depth: i32, importance_cutoff: f32, scene_epsilon: f32, top_object: u32) {
    var rt_site: u32 = 0u;
    var ray: RtRay;
    var n: vec3<f32>;
    var hit_point: vec3<f32>;
    var result: vec3<f32>;
    var importance: f32;
    var cond: bool;
    var refl: Radiance;
    var r: vec3<f32>;
    if rt_rs != 0u {
        ray = rt_fr_rtp_floor_reflect_ray[rt_d];
        n = rt_fr_rtp_floor_reflect_n[rt_d];
        hit_point = rt_fr_rtp_floor_reflect_hit_point[rt_d];
        result = rt_fr_rtp_floor_reflect_result[rt_d];
        importance = rt_fr_rtp_floor_reflect_importance[rt_d];
        cond = rt_fr_rtp_floor_reflect_cond[rt_d];
        refl = rt_fr_rtp_floor_reflect_refl[rt_d];
        r = rt_fr_rtp_floor_reflect_r[rt_d];
        rt_site = rt_fr_rtp_floor_reflect_rt_site[rt_d];
    }
    if rt_site == 0u {
        ray = rt_current_ray();
        n = normalize(rt_transform_normal(0u, attr.shading_normal));
        hit_point = (ray.origin + (rt_t_hit() * ray.direction));
        result = floor_color;
        importance = ((*prd).importance * rtf_luminance(reflectivity));
    }
    if rt_site == 0u {
        cond = ((importance > importance_cutoff) && ((*prd).depth < max_depth));
    }
    if rt_site == 0u || rt_site == 1u {
        if cond {
            if rt_site == 0u {
                refl = Radiance(vec3<f32>(0.0), importance, ((*prd).depth + 1i));
                r = reflect(ray.direction, n);
            }
            if rt_site == 0u {
                rt_request_Radiance(top_object, RtRay(hit_point, r, RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u)), refl, 0u, 255u);
                rt_fr_rtp_floor_reflect_ray[rt_d] = ray;
                rt_fr_rtp_floor_reflect_n[rt_d] = n;
                rt_fr_rtp_floor_reflect_hit_point[rt_d] = hit_point;
                rt_fr_rtp_floor_reflect_result[rt_d] = result;
                rt_fr_rtp_floor_reflect_importance[rt_d] = importance;
                rt_fr_rtp_floor_reflect_cond[rt_d] = cond;
                rt_fr_rtp_floor_reflect_refl[rt_d] = refl;
                rt_fr_rtp_floor_reflect_r[rt_d] = r;
                rt_fr_rtp_floor_reflect_rt_site[rt_d] = 1u;
                rt_rs = 1u;
                return;
            }
            if rt_site == 1u {
                refl = rt_result_Radiance();
                rt_site = 0u;
                rt_rs = 0u;
            }
            if rt_site == 0u {
                result += (reflectivity * refl.result);
            }
        }
    }
    if rt_site == 0u {
        (*prd).result = result;
    }
}
