// ray_generation program `methods_balls`

struct Ball {
    center: vec3<f32>,
    radius: f32,
}

struct BallPair {
    a: Ball,
    b: Ball,
}

fn rt_bufload_Ball(b: RtBuffer, i: u32) -> Ball {
    if rt_buf_check(b, i) {
        return rt_load_Ball(b.offset + i * 4u);
    }
    return Ball();
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

fn rt_load_Ball(w: u32) -> Ball {
    return Ball(rt_load_vec3f(w + 0u), rt_load_f32(w + 3u));
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

const Ball__DOUBLE: f32 = (Ball__UNIT * 2.0f);

const Ball__UNIT: f32 = 1.0f;

fn rtf_ball_rand(state: ptr<function, u32>) -> f32 {
    var x: u32 = (*state);
    x ^= (x << 13u);
    x ^= (x >> 17u);
    x ^= (x << 5u);
    (*state) = x;
    return (f32((x >> 8u)) / 16777216.0f);
}

fn rtf_total_volume(a: Ball, b: Ball) -> f32 {
    return (rtm_Ball__volume(a) + rtm_Ball__volume(b));
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

fn rtp_methods_balls(balls: RtBuffer, out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    var b: Ball = rt_bufload_Ball(balls, i);
    rtm_Ball__grow(&b, 0.5f);
    var seed: u32 = ((i * 7u) + 1u);
    let j: Ball = rtm_Ball__jittered(b, &seed);
    var pair: BallPair = BallPair(b, rtm_Ball__unit());
    var tmp: Ball = pair.b;
    rtm_Ball__grow(&tmp, Ball__UNIT);
    pair.b = tmp;
    let grown: Ball = rtm_Ball__moved(rtm_Ball__new(vec3<f32>(1.0), 0.25f), vec3<f32>(1.0, 0.0, 0.0));
    var t: Ball = rtm_Ball__new(vec3<f32>(0.0), 1.0f);
    rtm_Ball__grow(&t, rtm_Ball__area(grown));
    var tmp_1: f32;
    if rtm_Ball__contains(pair.a, j.center) {
        tmp_1 = 1.0f;
    } else {
        tmp_1 = 0.0f;
    }
    let inside: f32 = tmp_1;
    let tmp_2 = i;
    rt_bufstore_vec4f(out_1, tmp_2, vec4<f32>(rtf_total_volume(pair.a, pair.b), t.radius, inside, (grown.center.x + Ball__DOUBLE)));
}
