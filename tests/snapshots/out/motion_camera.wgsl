// ray_generation program `motion_camera`
fn rt_trace_Radiance(object: u32, ray: RtRay, prd: ptr<function, Radiance>, flags: u32, mask: u32) {}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
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

fn rt_load_vec2f(w: u32) -> vec2<f32> {
    return vec2<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u));
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

const RADIANCE_RAY: u32 = 0u;

fn rtp_motion_camera(top_object: u32, shutter: vec2<f32>, image: RtBuffer) {
    var image_1 = image;
    let idx: vec2<u32> = rt_launch_index();
    let dim: vec2<u32> = rt_launch_dim();
    let u: f32 = (f32((((idx.x * 7u) + (idx.y * 13u)) % 16u)) / 16.0f);
    let time: f32 = (shutter.x + ((shutter.y - shutter.x) * u));
    let d: vec3<f32> = vec3<f32>(((f32(idx.x) / f32(dim.x)) - 0.5f), ((f32(idx.y) / f32(dim.y)) - 0.5f), -1.0f);
    var prd: Radiance = Radiance(vec3<f32>(0.0), 1.0f, 0i);
    let ray: RtRay = RtRay(vec3<f32>(0.0f, 0.0f, 5.0f), normalize(d), RADIANCE_RAY, 0.001f, rt_f32_from_bits(0x7f800000u));
    rt_set_trace_time(time);
    rt_trace_Radiance(top_object, ray, &prd, 0u, 255u);
    let tmp = idx;
    rt_bufstore2_vec4f(image_1, tmp, vec4<f32>(prd.result, time));
}

// ---- resumable form ----
var<private> rt_fr_rtp_motion_camera_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_camera_image_1: array<RtBuffer, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_camera_idx: array<vec2<u32>, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_camera_dim: array<vec2<u32>, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_camera_u: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_camera_time: array<f32, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_camera_d: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_camera_prd: array<Radiance, RT_DEPTHS>;
var<private> rt_fr_rtp_motion_camera_ray: array<RtRay, RT_DEPTHS>;
fn rtp_motion_camera(top_object: u32, shutter: vec2<f32>, image: RtBuffer) {
    var rt_site: u32 = 0u;
    var image_1: RtBuffer;
    var idx: vec2<u32>;
    var dim: vec2<u32>;
    var u: f32;
    var time: f32;
    var d: vec3<f32>;
    var prd: Radiance;
    var ray: RtRay;
    if rt_rs != 0u {
        image_1 = rt_fr_rtp_motion_camera_image_1[rt_d];
        idx = rt_fr_rtp_motion_camera_idx[rt_d];
        dim = rt_fr_rtp_motion_camera_dim[rt_d];
        u = rt_fr_rtp_motion_camera_u[rt_d];
        time = rt_fr_rtp_motion_camera_time[rt_d];
        d = rt_fr_rtp_motion_camera_d[rt_d];
        prd = rt_fr_rtp_motion_camera_prd[rt_d];
        ray = rt_fr_rtp_motion_camera_ray[rt_d];
        rt_site = rt_fr_rtp_motion_camera_rt_site[rt_d];
    }
    if rt_site == 0u {
        image_1 = image;
    }
    if rt_site == 0u {
        idx = rt_launch_index();
        dim = rt_launch_dim();
        u = (f32((((idx.x * 7u) + (idx.y * 13u)) % 16u)) / 16.0f);
        time = (shutter.x + ((shutter.y - shutter.x) * u));
        d = vec3<f32>(((f32(idx.x) / f32(dim.x)) - 0.5f), ((f32(idx.y) / f32(dim.y)) - 0.5f), -1.0f);
        prd = Radiance(vec3<f32>(0.0), 1.0f, 0i);
        ray = RtRay(vec3<f32>(0.0f, 0.0f, 5.0f), normalize(d), RADIANCE_RAY, 0.001f, rt_f32_from_bits(0x7f800000u));
    }
    if rt_site == 0u {
        rt_set_trace_time(time);
        rt_request_Radiance(top_object, ray, prd, 0u, 255u);
        rt_fr_rtp_motion_camera_image_1[rt_d] = image_1;
        rt_fr_rtp_motion_camera_idx[rt_d] = idx;
        rt_fr_rtp_motion_camera_dim[rt_d] = dim;
        rt_fr_rtp_motion_camera_u[rt_d] = u;
        rt_fr_rtp_motion_camera_time[rt_d] = time;
        rt_fr_rtp_motion_camera_d[rt_d] = d;
        rt_fr_rtp_motion_camera_prd[rt_d] = prd;
        rt_fr_rtp_motion_camera_ray[rt_d] = ray;
        rt_fr_rtp_motion_camera_rt_site[rt_d] = 1u;
        rt_rs = 1u;
        return;
    }
    if rt_site == 1u {
        prd = rt_result_Radiance();
        rt_site = 0u;
        rt_rs = 0u;
    }
    if rt_site == 0u {
        let tmp = idx;
        rt_bufstore2_vec4f(image_1, tmp, vec4<f32>(prd.result, time));
    }
}
