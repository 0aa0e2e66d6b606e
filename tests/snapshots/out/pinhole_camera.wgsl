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
    return bitcast<f32>(rt_heap[w]);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_heap[w] = bitcast<u32>(v);
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
    let dim: vec2<u32> = rt_launch_dim();
    let d: vec2<f32> = ((((vec2<f32>(idx) + vec2<f32>(0.5f)) / vec2<f32>(dim)) * 2.0f) - vec2<f32>(1.0));
    let ray_direction: vec3<f32> = normalize((((d.x * u) + (d.y * v)) + w));
    let ray: RtRay = RtRay(eye, ray_direction, RADIANCE_RAY, scene_epsilon, bitcast<f32>(0x7f800000u));
    var prd: Radiance = Radiance(vec3<f32>(0.0), 1.0f, 0i);
    rt_trace_Radiance(top_object, ray, &prd, 0u, 255u);
    let tmp = idx;
    rt_bufstore2_vec4f(output_buffer_1, tmp, vec4<f32>(prd.result, 1.0f));
}
