// ray_generation program `methods_trace`
fn rt_trace_Glow(object: u32, ray: RtRay, prd: ptr<function, Glow>, flags: u32, mask: u32) {}

struct Ball {
    center: vec3<f32>,
    radius: f32,
}

struct Glow {
    color: vec3<f32>,
    bounces: u32,
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

const Ball__DOUBLE: f32 = (Ball__UNIT * 2.0f);

const Ball__UNIT: f32 = 1.0f;

const Glow__MAX_BOUNCES: u32 = 4u;

fn rtf_ball_rand(state: ptr<function, u32>) -> f32 {
    var x: u32 = (*state);
    x ^= (x << 13u);
    x ^= (x >> 17u);
    x ^= (x << 5u);
    (*state) = x;
    return (f32((x >> 8u)) / 16777216.0f);
}

fn rtm_Ball__area(self_: Ball) -> f32 {
    return (((4.0f * 3.1415927f) * self_.radius) * self_.radius);
}

fn rtm_Ball__contains(self_: Ball, p: vec3<f32>) -> bool {
    let tmp = (p - self_.center);
    return (dot(tmp, tmp) <= (self_.radius * self_.radius));
}

fn rtm_Ball__grow(self_: ptr<function, Ball>, by: f32) {
    (*self_).radius += by;
    if ((*self_).radius > (Ball__DOUBLE * 4.0f)) {
        (*self_).radius = (Ball__DOUBLE * 4.0f);
    }
}

fn rtm_Ball__jittered(self_: Ball, state: ptr<function, u32>) -> Ball {
    let j: f32 = (rtf_ball_rand(state) * 0.01f);
    return rtm_Ball__moved(self_, vec3<f32>(j));
}

fn rtm_Ball__moved(self_: Ball, by: vec3<f32>) -> Ball {
    var self__1 = self_;
    self__1.center += by;
    return self__1;
}

fn rtm_Ball__new(center: vec3<f32>, radius: f32) -> Ball {
    return Ball(center, radius);
}

fn rtm_Ball__unit() -> Ball {
    return rtm_Ball__new(vec3<f32>(0.0), Ball__UNIT);
}

fn rtm_Ball__volume(self_: Ball) -> f32 {
    return ((rtm_Ball__area(self_) * self_.radius) / 3.0f);
}

fn rtm_Glow__add(self_: ptr<function, Glow>, c: vec3<f32>) {
    if ((*self_).bounces < Glow__MAX_BOUNCES) {
        (*self_).color += c;
        (*self_).bounces += 1u;
    }
}

fn rtm_Glow__luminance(self_: Glow) -> f32 {
    return dot(self_.color, vec3<f32>(0.2126f, 0.7152f, 0.0722f));
}

fn rtp_methods_trace(top: u32, out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    var prd: Glow = Glow(vec3<f32>(0.0), 0u);
    rtm_Glow__add(&prd, vec3<f32>(0.1f));
    let b: Ball = rtm_Ball__new(vec3<f32>(0.0), 2.0f);
    rt_trace_Glow(top, RtRay(b.center, vec3<f32>(0.0, 0.0, 1.0), 0u, 0.001f, (b.radius * 10.0f)), &prd, 0u, 255u);
    rtm_Glow__add(&prd, vec3<f32>(1.0, 0.0, 0.0));
    let tmp = i;
    rt_bufstore_vec4f(out_1, tmp, vec4<f32>(prd.color, rtm_Glow__luminance(prd)));
}

// ---- resumable form ----
var<private> rt_fr_rtp_methods_trace_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_methods_trace_out_1: array<RtBuffer, RT_DEPTHS>;
var<private> rt_fr_rtp_methods_trace_i: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_methods_trace_prd: array<Glow, RT_DEPTHS>;
var<private> rt_fr_rtp_methods_trace_b: array<Ball, RT_DEPTHS>;
fn rtp_methods_trace(top: u32, out: RtBuffer) {
    var rt_site: u32 = 0u;
    var out_1: RtBuffer;
    var i: u32;
    var prd: Glow;
    var b: Ball;
    if rt_rs != 0u {
        out_1 = rt_fr_rtp_methods_trace_out_1[rt_d];
        i = rt_fr_rtp_methods_trace_i[rt_d];
        prd = rt_fr_rtp_methods_trace_prd[rt_d];
        b = rt_fr_rtp_methods_trace_b[rt_d];
        rt_site = rt_fr_rtp_methods_trace_rt_site[rt_d];
    }
    if rt_site == 0u {
        out_1 = out;
    }
    if rt_site == 0u {
        i = rt_launch_index().x;
        prd = Glow(vec3<f32>(0.0), 0u);
        rtm_Glow__add(&prd, vec3<f32>(0.1f));
        b = rtm_Ball__new(vec3<f32>(0.0), 2.0f);
    }
    if rt_site == 0u {
        rt_request_Glow(top, RtRay(b.center, vec3<f32>(0.0, 0.0, 1.0), 0u, 0.001f, (b.radius * 10.0f)), prd, 0u, 255u);
        rt_fr_rtp_methods_trace_out_1[rt_d] = out_1;
        rt_fr_rtp_methods_trace_i[rt_d] = i;
        rt_fr_rtp_methods_trace_prd[rt_d] = prd;
        rt_fr_rtp_methods_trace_b[rt_d] = b;
        rt_fr_rtp_methods_trace_rt_site[rt_d] = 1u;
        rt_rs = 1u;
        return;
    }
    if rt_site == 1u {
        prd = rt_result_Glow();
        rt_site = 0u;
        rt_rs = 0u;
    }
    if rt_site == 0u {
        rtm_Glow__add(&prd, vec3<f32>(1.0, 0.0, 0.0));
        let tmp = i;
        rt_bufstore_vec4f(out_1, tmp, vec4<f32>(prd.color, rtm_Glow__luminance(prd)));
    }
}
