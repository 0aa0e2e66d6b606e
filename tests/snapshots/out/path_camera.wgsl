// ray_generation program `path_camera`
fn rt_trace_PathState(object: u32, ray: RtRay, prd: ptr<function, PathState>, flags: u32, mask: u32) {}

struct PathState {
    radiance: vec3<f32>,
    throughput: vec3<f32>,
    origin: vec3<f32>,
    direction: vec3<f32>,
    seed: u32,
    done: bool,
}

fn rt_bufload2_vec4f(b: RtBuffer, i: vec2<u32>) -> vec4<f32> {
    if rt_buf_check2(b, i) {
        return rt_load_vec4f(b.offset + (i.y * b.width + i.x) * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore2_vec4f(b: RtBuffer, i: vec2<u32>, v: vec4<f32>) {
    if rt_buf_check2(b, i) {
        rt_store_vec4f(b.offset + (i.y * b.width + i.x) * 4u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_mat3(w: u32) -> mat3x3<f32> {
    return mat3x3<f32>(rt_load_vec3f(w + 0u), rt_load_vec3f(w + 3u), rt_load_vec3f(w + 6u));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_vec4f(w: u32, v: vec4<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
    rt_store_f32(w + 3u, v[3]);
}

const PATH_RAY: u32 = 0u;

fn rtf_lcg_next(seed: ptr<function, u32>) -> f32 {
    (*seed) = (((*seed) * 1664525u) + 1013904223u);
    return (f32(((*seed) >> 8u)) * (1.0f / 16777216.0f));
}

fn rtp_path_camera(eye: vec3<f32>, camera: mat3x3<f32>, frame: u32, spp: u32, max_bounces: u32, scene_epsilon: f32, top_object: u32, accum: RtBuffer) {
    var accum_1 = accum;
    let idx: vec2<u32> = rt_launch_index();
    let dim: vec2<f32> = vec2<f32>(rt_launch_dim());
    var seed: u32 = (((idx.y * rt_launch_dim().x) + idx.x) ^ (frame * 2654435769u));
    var color: vec3<f32> = vec3<f32>(0.0);
    let end = spp;
    for (var i: u32 = 0u; i < end; i++) {
        let jitter: vec2<f32> = vec2<f32>(rtf_lcg_next(&seed), rtf_lcg_next(&seed));
        let d: vec2<f32> = ((((vec2<f32>(idx) + jitter) / dim) * 2.0f) - 1.0f);
        var prd: PathState = PathState(vec3<f32>(0.0), vec3<f32>(1.0), eye, normalize((camera * vec3<f32>(d.x, -d.y, 1.0f))), seed, false);
        var bounce: u32 = 0u;
        while ((bounce < max_bounces) && !prd.done) {
            let ray: RtRay = RtRay(prd.origin, prd.direction, PATH_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u));
            rt_trace_PathState(top_object, ray, &prd, 0u, 255u);
            bounce += 1u;
        }
        seed = prd.seed;
        color += prd.radiance;
    }
    let sample: vec3<f32> = (color / f32(max(spp, 1u)));
    let prev: vec4<f32> = rt_bufload2_vec4f(accum_1, idx);
    let tmp = (1.0f / f32((frame + 1u)));
    let blended: vec3<f32> = (prev.xyz * (1.0 - tmp) + sample * tmp);
    let tmp_1 = idx;
    rt_bufstore2_vec4f(accum_1, tmp_1, vec4<f32>(blended, 1.0f));
}

// ---- resumable form ----
var<private> rt_fr_rtp_path_camera_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_accum_1: array<RtBuffer, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_idx: array<vec2<u32>, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_dim: array<vec2<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_seed: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_color: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_i: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_end: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_jitter: array<vec2<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_d: array<vec2<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_prd: array<PathState, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_bounce: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_sample: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_prev: array<vec4<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_path_camera_blended: array<vec3<f32>, RT_DEPTHS>;
fn rtp_path_camera(eye: vec3<f32>, camera: mat3x3<f32>, frame: u32, spp: u32, max_bounces: u32, scene_epsilon: f32, top_object: u32, accum: RtBuffer) {
    var rt_site: u32 = 0u;
    var accum_1: RtBuffer;
    var idx: vec2<u32>;
    var dim: vec2<f32>;
    var seed: u32;
    var color: vec3<f32>;
    var i: u32;
    var end: u32;
    var jitter: vec2<f32>;
    var d: vec2<f32>;
    var prd: PathState;
    var bounce: u32;
    var ray: RtRay;
    var sample: vec3<f32>;
    var prev: vec4<f32>;
    var blended: vec3<f32>;
    if rt_rs != 0u {
        accum_1 = rt_fr_rtp_path_camera_accum_1[rt_d];
        idx = rt_fr_rtp_path_camera_idx[rt_d];
        dim = rt_fr_rtp_path_camera_dim[rt_d];
        seed = rt_fr_rtp_path_camera_seed[rt_d];
        color = rt_fr_rtp_path_camera_color[rt_d];
        i = rt_fr_rtp_path_camera_i[rt_d];
        end = rt_fr_rtp_path_camera_end[rt_d];
        jitter = rt_fr_rtp_path_camera_jitter[rt_d];
        d = rt_fr_rtp_path_camera_d[rt_d];
        prd = rt_fr_rtp_path_camera_prd[rt_d];
        bounce = rt_fr_rtp_path_camera_bounce[rt_d];
        ray = rt_fr_rtp_path_camera_ray[rt_d];
        sample = rt_fr_rtp_path_camera_sample[rt_d];
        prev = rt_fr_rtp_path_camera_prev[rt_d];
        blended = rt_fr_rtp_path_camera_blended[rt_d];
        rt_site = rt_fr_rtp_path_camera_rt_site[rt_d];
    }
    if rt_site == 0u {
        accum_1 = accum;
    }
    if rt_site == 0u {
        idx = rt_launch_index();
        dim = vec2<f32>(rt_launch_dim());
        seed = (((idx.y * rt_launch_dim().x) + idx.x) ^ (frame * 2654435769u));
        color = vec3<f32>(0.0);
    }
    if rt_site == 0u {
        i = 0u;
        end = spp;
    }
    if rt_site == 0u || rt_site == 1u {
        loop {
            if rt_site == 0u {
                if !(i < end) {
                    break;
                }
            }
            if rt_site == 0u {
                jitter = vec2<f32>(rtf_lcg_next(&seed), rtf_lcg_next(&seed));
                d = ((((vec2<f32>(idx) + jitter) / dim) * 2.0f) - 1.0f);
                prd = PathState(vec3<f32>(0.0), vec3<f32>(1.0), eye, normalize((camera * vec3<f32>(d.x, -d.y, 1.0f))), seed, false);
                bounce = 0u;
            }
            if rt_site == 0u || rt_site == 1u {
                loop {
                    if rt_site == 0u {
                        if !(((bounce < max_bounces) && !prd.done)) {
                            break;
                        }
                    }
                    if rt_site == 0u {
                        ray = RtRay(prd.origin, prd.direction, PATH_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u));
                    }
                    if rt_site == 0u {
                        rt_request_PathState(top_object, ray, prd, 0u, 255u);
                        rt_fr_rtp_path_camera_accum_1[rt_d] = accum_1;
                        rt_fr_rtp_path_camera_idx[rt_d] = idx;
                        rt_fr_rtp_path_camera_dim[rt_d] = dim;
                        rt_fr_rtp_path_camera_seed[rt_d] = seed;
                        rt_fr_rtp_path_camera_color[rt_d] = color;
                        rt_fr_rtp_path_camera_i[rt_d] = i;
                        rt_fr_rtp_path_camera_end[rt_d] = end;
                        rt_fr_rtp_path_camera_jitter[rt_d] = jitter;
                        rt_fr_rtp_path_camera_d[rt_d] = d;
                        rt_fr_rtp_path_camera_prd[rt_d] = prd;
                        rt_fr_rtp_path_camera_bounce[rt_d] = bounce;
                        rt_fr_rtp_path_camera_ray[rt_d] = ray;
                        rt_fr_rtp_path_camera_sample[rt_d] = sample;
                        rt_fr_rtp_path_camera_prev[rt_d] = prev;
                        rt_fr_rtp_path_camera_blended[rt_d] = blended;
                        rt_fr_rtp_path_camera_rt_site[rt_d] = 1u;
                        rt_rs = 1u;
                        return;
                    }
                    if rt_site == 1u {
                        prd = rt_result_PathState();
                        rt_site = 0u;
                        rt_rs = 0u;
                    }
                    if rt_site == 0u {
                        bounce += 1u;
                    }
                }
            }
            if rt_site == 0u {
                seed = prd.seed;
                color += prd.radiance;
            }
            continuing {
                i++;
            }
        }
    }
    if rt_site == 0u {
        sample = (color / f32(max(spp, 1u)));
        prev = rt_bufload2_vec4f(accum_1, idx);
        let tmp = (1.0f / f32((frame + 1u)));
        blended = (prev.xyz * (1.0 - tmp) + sample * tmp);
        let tmp_1 = idx;
        rt_bufstore2_vec4f(accum_1, tmp_1, vec4<f32>(blended, 1.0f));
    }
}
