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
    return bitcast<f32>(rt_heap[w]);
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_heap[w]);
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

fn rtp_glass(prd: ptr<function, Radiance>, attr: Normals, refraction_index: f32, glass_color: vec3<f32>, max_depth: i32, scene_epsilon: f32, top_object: u32) {
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
    let reflect_dir: vec3<f32> = reflect(ray.direction, ffn);
    let refract_dir: vec3<f32> = refract(ray.direction, ffn, eta);
    let f0: f32 = rt_powi(((1.0f - refraction_index) / (1.0f + refraction_index)), 2i);
    var fresnel: f32 = rtf_fresnel_schlick(cos_i, f0);
    if (dot(refract_dir, refract_dir) == 0.0f) {
        fresnel = 1.0f;
    }
    var result: vec3<f32> = vec3<f32>(0.0);
    if ((*prd).depth < max_depth) {
        var refl: Radiance = Radiance(vec3<f32>(0.0), ((*prd).importance * fresnel), ((*prd).depth + 1i));
        rt_trace_Radiance(top_object, RtRay(hit_point, reflect_dir, RADIANCE_RAY, scene_epsilon, bitcast<f32>(0x7f800000u)), &refl, 0u, 255u);
        result += (fresnel * refl.result);
        if (fresnel < 1.0f) {
            var refr: Radiance = Radiance(vec3<f32>(0.0), ((*prd).importance * (1.0f - fresnel)), ((*prd).depth + 1i));
            rt_trace_Radiance(top_object, RtRay(hit_point, refract_dir, RADIANCE_RAY, scene_epsilon, bitcast<f32>(0x7f800000u)), &refr, 0u, 255u);
            result += (((1.0f - fresnel) * glass_color) * refr.result);
        }
    }
    (*prd).result = result;
}
