// ray_generation program `helpers_refs`

struct Accum {
    mean: vec3<f32>,
    count: u32,
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

fn rt_f2u(x: f32) -> u32 {
    return select(select(u32(x), u32(4294967295u), x >= f32(4294967296.0)), u32(0), (bitcast<u32>(x) & u32(0x7fffffffu)) > u32(0x7f800000u));
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
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

fn rtf_accumulate(acc: ptr<function, Accum>, sample: vec3<f32>) {
    (*acc).count += 1u;
    (*acc).mean += ((sample - (*acc).mean) / f32((*acc).count));
}

fn rtf_accumulate_noise(acc: ptr<function, Accum>, state: ptr<function, u32>, n: u32) {
    var n_1 = n;
    while (n_1 > 0u) {
        let v: f32 = rtf_rand(state);
        rtf_accumulate(acc, vec3<f32>(v));
        n_1 -= 1u;
    }
}

fn rtf_rand(state: ptr<function, u32>) -> f32 {
    var x: u32 = (*state);
    x ^= (x << 13u);
    x ^= (x >> 17u);
    x ^= (x << 5u);
    (*state) = x;
    return (f32((x >> 8u)) / 16777216.0f);
}

fn rtf_scaled(acc: Accum, by: f32) -> Accum {
    return Accum((acc.mean * by), acc.count);
}

fn rtp_helpers_refs(frame: u32, samples: u32, out: RtBuffer) {
    var out_1 = out;
    let idx: vec2<u32> = rt_launch_index();
    var seed: u32 = ((((idx.x * 1973u) + (idx.y * 9277u)) + (frame * 26699u)) | 1u);
    var acc: Accum = Accum(vec3<f32>(0.0), 0u);
    let end = samples;
    for (var i: u32 = 0u; i < end; i++) {
        let c: vec3<f32> = vec3<f32>(rtf_rand(&seed), rtf_rand(&seed), rtf_rand(&seed));
        rtf_accumulate(&acc, c);
    }
    rtf_accumulate_noise(&acc, &seed, 4u);
    let half: Accum = rtf_scaled(acc, 0.5f);
    let tmp = (rtf_rand(&seed) * 8.0f);
    let jitter: f32 = (tmp - trunc(tmp));
    let tmp_1 = rt_f2u((rtf_rand(&seed) * 4.0f));
    let tmp_2 = vec3<f32>(rtf_rand(&seed));
    let swapped: Accum = Accum(tmp_2, tmp_1);
    let scrutinee = rt_f2u((rtf_rand(&seed) * 3.0f));
    var tmp_3: f32;
    switch scrutinee {
        case 0u: {
            tmp_3 = 0.25f;
        }
        default: {
            let k = scrutinee;
            tmp_3 = f32(k);
        }
    }
    let lobe: f32 = tmp_3;
    let tmp_4 = idx;
    rt_bufstore2_vec4f(out_1, tmp_4, vec4<f32>(((half.mean + (jitter * 0.01f)) + (swapped.mean * lobe)), f32((half.count + swapped.count))));
}
