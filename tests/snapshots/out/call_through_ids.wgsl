// ray_generation program `call_through_ids`
fn rt_call_f32__f32_(id: u32, a0: f32) -> f32 {
    var r: f32;
    return r;
}
fn rt_call_vec3f_vec3f_vec3f__vec3f_(id: u32, a0: vec3<f32>, a1: vec3<f32>, a2: vec3<f32>) -> vec3<f32> {
    var r: vec3<f32>;
    return r;
}

struct Shader {
    brdf: u32,
    tint: vec3<f32>,
}

fn rt_bufload_u32(b: RtBuffer, i: u32) -> u32 {
    if rt_buf_check(b, i) {
        return rt_load_u32(b.offset + i * 1u);
    }
    return u32();
}

fn rt_bufload_vec3f(b: RtBuffer, i: u32) -> vec3<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec3f(b.offset + i * 3u);
    }
    return vec3<f32>();
}

fn rt_bufstore_vec3f(b: RtBuffer, i: u32, v: vec3<f32>) {
    if rt_buf_check(b, i) {
        rt_store_vec3f(b.offset + i * 3u, v);
    }
}

fn rt_load_Shader(w: u32) -> Shader {
    return Shader(rt_load_u32(w + 0u), rt_load_vec3f(w + 1u));
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_vec3f(w: u32, v: vec3<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
}

fn rtp_call_through_ids(shader: Shader, brdfs: RtBuffer, exponent: u32, out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let n: vec3<f32> = vec3<f32>(0.0f, 0.0f, 1.0f);
    let l: vec3<f32> = vec3<f32>(0.6f, 0.0f, 0.8f);
    let v: vec3<f32> = vec3<f32>(-0.6f, 0.0f, 0.8f);
    let tmp = rt_call_vec3f_vec3f_vec3f__vec3f_(rt_bufload_u32(brdfs, (i % brdfs.len)), n, l, v);
    let by_buffer: vec3<f32> = tmp;
    let tmp_1 = rt_call_vec3f_vec3f_vec3f__vec3f_(shader.brdf, n, l, v);
    let by_struct: vec3<f32> = (tmp_1 * shader.tint);
    let tmp_2 = rt_call_f32__f32_((i + 1u), 0.25f);
    let picked: f32 = tmp_2;
    let tmp_3 = rt_call_f32__f32_(exponent, 0.5f);
    let tmp_4 = i;
    rt_bufstore_vec3f(out_1, tmp_4, ((by_buffer + by_struct) + vec3<f32>((tmp_3 + picked))));
}
