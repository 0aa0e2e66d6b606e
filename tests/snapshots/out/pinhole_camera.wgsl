// ray_generation program `pinhole_camera`
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

const RADIANCE_RAY: u32 = 0u;

fn rtp_pinhole_camera(eye: vec3<f32>, u: vec3<f32>, v: vec3<f32>, w: vec3<f32>, scene_epsilon: f32, top_object: u32, output_buffer: RtBuffer) {
    var output_buffer_1 = output_buffer;
    let idx: vec2<u32> = rt_launch_index();
    let d: vec2<f32> = ((((vec2<f32>(idx) + vec2<f32>(0.5f)) / vec2<f32>(rt_launch_dim())) * 2.0f) - vec2<f32>(1.0));
    let ray_direction: vec3<f32> = normalize((((d.x * u) + (d.y * v)) + w));
    let ray: RtRay = RtRay(eye, ray_direction, RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u));
    var prd: Radiance = Radiance(vec3<f32>(0.0), 1.0f, 0i);
    rt_trace_Radiance(top_object, ray, &prd, 0u, 255u);
    let tmp = idx;
    rt_bufstore2_vec4f(output_buffer_1, tmp, vec4<f32>(prd.result, 1.0f));
}

// ---- resumable form ----
var<private> rt_fr_rtp_pinhole_camera_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_pinhole_camera_output_buffer_1: array<RtBuffer, RT_DEPTHS>;
var<private> rt_fr_rtp_pinhole_camera_idx: array<vec2<u32>, RT_DEPTHS>;
var<private> rt_fr_rtp_pinhole_camera_d: array<vec2<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_pinhole_camera_ray_direction: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_pinhole_camera_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_pinhole_camera_prd: array<Radiance, RT_DEPTHS>;
fn rtp_pinhole_camera(eye: vec3<f32>, u: vec3<f32>, v: vec3<f32>, w: vec3<f32>, scene_epsilon: f32, top_object: u32, output_buffer: RtBuffer) {
    var rt_site: u32 = 0u;
    var output_buffer_1: RtBuffer;
    var idx: vec2<u32>;
    var d: vec2<f32>;
    var ray_direction: vec3<f32>;
    var ray: RtRay;
    var prd: Radiance;
    if rt_rs != 0u {
        output_buffer_1 = rt_fr_rtp_pinhole_camera_output_buffer_1[rt_d];
        idx = rt_fr_rtp_pinhole_camera_idx[rt_d];
        d = rt_fr_rtp_pinhole_camera_d[rt_d];
        ray_direction = rt_fr_rtp_pinhole_camera_ray_direction[rt_d];
        ray = rt_fr_rtp_pinhole_camera_ray[rt_d];
        prd = rt_fr_rtp_pinhole_camera_prd[rt_d];
        rt_site = rt_fr_rtp_pinhole_camera_rt_site[rt_d];
    }
    if rt_site == 0u {
        output_buffer_1 = output_buffer;
    }
    if rt_site == 0u {
        idx = rt_launch_index();
        d = ((((vec2<f32>(idx) + vec2<f32>(0.5f)) / vec2<f32>(rt_launch_dim())) * 2.0f) - vec2<f32>(1.0));
        ray_direction = normalize((((d.x * u) + (d.y * v)) + w));
        ray = RtRay(eye, ray_direction, RADIANCE_RAY, scene_epsilon, rt_f32_from_bits(0x7f800000u));
        prd = Radiance(vec3<f32>(0.0), 1.0f, 0i);
    }
    if rt_site == 0u {
        rt_request_Radiance(top_object, ray, prd, 0u, 255u);
        rt_fr_rtp_pinhole_camera_output_buffer_1[rt_d] = output_buffer_1;
        rt_fr_rtp_pinhole_camera_idx[rt_d] = idx;
        rt_fr_rtp_pinhole_camera_d[rt_d] = d;
        rt_fr_rtp_pinhole_camera_ray_direction[rt_d] = ray_direction;
        rt_fr_rtp_pinhole_camera_ray[rt_d] = ray;
        rt_fr_rtp_pinhole_camera_prd[rt_d] = prd;
        rt_fr_rtp_pinhole_camera_rt_site[rt_d] = 1u;
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
        rt_bufstore2_vec4f(output_buffer_1, tmp, vec4<f32>(prd.result, 1.0f));
    }
}
