// ray_generation program `tuples`

struct PolarSample {
    angles: rt_tuple_f32_f32_,
    index: u32,
}

struct rt_tuple_f32_f32_ {
    f0: f32,
    f1: f32,
}

struct rt_tuple_f32_rt_tuple_f32_u32__ {
    f0: f32,
    f1: rt_tuple_f32_u32_,
}

struct rt_tuple_f32_u32_ {
    f0: f32,
    f1: u32,
}

struct rt_tuple_i32_i32_ {
    f0: i32,
    f1: i32,
}

fn rt_bufload_PolarSample(b: RtBuffer, i: u32) -> PolarSample {
    if rt_buf_check(b, i) {
        return rt_load_PolarSample(b.offset + i * 3u);
    }
    return PolarSample();
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

fn rt_load_PolarSample(w: u32) -> PolarSample {
    return PolarSample(rt_load_rt_tuple_f32_f32_(w + 0u), rt_load_u32(w + 2u));
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_rt_tuple_f32_f32_(w: u32) -> rt_tuple_f32_f32_ {
    return rt_tuple_f32_f32_(rt_load_f32(w + 0u), rt_load_f32(w + 1u));
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

fn rtf_disk(u: f32, v: f32) -> rt_tuple_f32_f32_ {
    let tmp = (u * 3.1415927f);
    let tuple: rt_tuple_f32_f32_ = rt_tuple_f32_f32_(sin(tmp), cos(tmp));
    let s: f32 = tuple.f0;
    let c: f32 = tuple.f1;
    return rt_tuple_f32_f32_((s * v), (c * v));
}

fn rtf_quadrant(cell: rt_tuple_i32_i32_) -> u32 {
    let scrutinee = cell;
    var tmp: u32;
    if ((scrutinee.f0 == 0i) && (scrutinee.f1 == 0i)) {
        tmp = 0u;
    } else if ((scrutinee.f0 == 0i)) || ((scrutinee.f1 == 0i)) {
        tmp = 1u;
    } else if ((scrutinee.f1 == 1i)) {
        let x = scrutinee.f0;
        tmp = (u32(x) + 10u);
    } else {
        tmp = 99u;
    }
    return tmp;
}

fn rtp_tuples(samples: RtBuffer, out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let sample: PolarSample = rt_bufload_PolarSample(samples, i);
    let tuple: rt_tuple_f32_f32_ = rtf_disk(sample.angles.f0, sample.angles.f1);
    var x: f32 = tuple.f0;
    let y: f32 = tuple.f1;
    x += 1.0f;
    var pair: rt_tuple_f32_rt_tuple_f32_u32__ = rt_tuple_f32_rt_tuple_f32_u32__(x, rt_tuple_f32_u32_(y, sample.index));
    pair.f0 *= 2.0f;
    let tuple_1: rt_tuple_f32_rt_tuple_f32_u32__ = pair;
    let a: f32 = tuple_1.f0;
    let n: u32 = tuple_1.f1.f1;
    let q: u32 = rtf_quadrant(rt_tuple_i32_i32_((i32(n) % 3i), (i32(i) % 2i)));
    let tmp = i;
    rt_bufstore_vec3f(out_1, tmp, vec3<f32>(a, pair.f1.f0, f32((q + n))));
}
