// ray_generation program `generic_intervals`

struct rt_Interval__f32 {
    lo: f32,
    hi: f32,
}

struct rt_Interval__Vec3 {
    lo: vec3<f32>,
    hi: vec3<f32>,
}

struct rt_Labelled__f32 {
    range: rt_Interval__f32,
    label: u32,
}

fn rt_bufload_vec4f(b: RtBuffer, i: u32) -> vec4<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec4f(b.offset + i * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore_vec4f(b: RtBuffer, i: u32, v: vec4<f32>) {
    if rt_buf_check(b, i) {
        rt_store_vec4f(b.offset + i * 4u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
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

fn rtf_clamp_into(x: f32, r: rt_Interval__f32) -> f32 {
    return clamp(x, r.lo, r.hi);
}

fn rtm_Interval__new__Vec3(lo: vec3<f32>, hi: vec3<f32>) -> rt_Interval__Vec3 {
    return rt_Interval__Vec3(lo, hi);
}

fn rtm_Interval__width__Vec3(self_: rt_Interval__Vec3) -> vec3<f32> {
    return (self_.hi - self_.lo);
}

fn rtm_Interval__width__f32(self_: rt_Interval__f32) -> f32 {
    return (self_.hi - self_.lo);
}

fn rtp_generic_intervals(out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let x: f32 = f32(i);
    let unit: rt_Interval__f32 = rt_Interval__f32(0.0f, 1.0f);
    let boxed: rt_Interval__Vec3 = rtm_Interval__new__Vec3(vec3<f32>(0.0), vec3<f32>(x));
    let tagged: rt_Labelled__f32 = rt_Labelled__f32(rt_Interval__f32(-x, x), i);
    let tmp = i;
    rt_bufstore_vec4f(out_1, tmp, vec4<f32>(rtf_clamp_into(x, unit), rtm_Interval__width__Vec3(boxed).y, rtm_Interval__width__f32(tagged.range), f32(tagged.label)));
}
