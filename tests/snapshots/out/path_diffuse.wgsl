// closest_hit program `path_diffuse`

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

struct PathState {
    radiance: vec3<f32>,
    throughput: vec3<f32>,
    origin: vec3<f32>,
    direction: vec3<f32>,
    seed: u32,
    done: bool,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtf_cosine_sample_hemisphere(n: vec3<f32>, u1: f32, u2: f32) -> vec3<f32> {
    let r: f32 = sqrt(u1);
    let phi: f32 = (6.2831855f * u2);
    let local: vec3<f32> = vec3<f32>((r * cos(phi)), (r * sin(phi)), sqrt(max((1.0f - u1), 0.0f)));
    var tmp: f32;
    if (n.z >= 0.0f) {
        tmp = 1.0f;
    } else {
        tmp = -1.0f;
    }
    let sign_: f32 = tmp;
    let a: f32 = (-1.0f / (sign_ + n.z));
    let b: f32 = ((n.x * n.y) * a);
    let t: vec3<f32> = vec3<f32>((1.0f + (((sign_ * n.x) * n.x) * a)), (sign_ * b), (-sign_ * n.x));
    let bt: vec3<f32> = vec3<f32>(b, (sign_ + ((n.y * n.y) * a)), -n.y);
    return normalize((((t * local.x) + (bt * local.y)) + (n * local.z)));
}

fn rtf_lcg_next(seed: ptr<function, u32>) -> f32 {
    (*seed) = (((*seed) * 1664525u) + 1013904223u);
    return (f32(((*seed) >> 8u)) * (1.0f / 16777216.0f));
}

fn rtp_path_diffuse(prd: ptr<function, PathState>, attr: Normals, albedo: vec3<f32>, emission: vec3<f32>) {
    let ray: RtRay = rt_current_ray();
    let n: vec3<f32> = normalize(rt_transform_normal(0u, attr.shading_normal));
    var tmp: vec3<f32>;
    if (dot(n, ray.direction) > 0.0f) {
        tmp = -n;
    } else {
        tmp = n;
    }
    let n_1: vec3<f32> = tmp;
    (*prd).radiance += ((*prd).throughput * emission);
    (*prd).throughput *= albedo;
    let tmp_1 = (*prd).throughput;
    let p: f32 = max(max(tmp_1.x, tmp_1.y), tmp_1.z);
    var tmp_2: u32 = (*prd).seed;
    let tmp_3 = rtf_lcg_next(&tmp_2);
    (*prd).seed = tmp_2;
    if (tmp_3 > p) {
        (*prd).done = true;
        return;
    }
    (*prd).throughput /= p;
    var tmp_4: u32 = (*prd).seed;
    let tmp_5 = rtf_lcg_next(&tmp_4);
    (*prd).seed = tmp_4;
    let u1: f32 = tmp_5;
    var tmp_6: u32 = (*prd).seed;
    let tmp_7 = rtf_lcg_next(&tmp_6);
    (*prd).seed = tmp_6;
    let u2: f32 = tmp_7;
    (*prd).origin = (ray.origin + (rt_t_hit() * ray.direction));
    (*prd).direction = rtf_cosine_sample_hemisphere(n_1, u1, u2);
}
