// ray_generation program `fuzz_eval_order`

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_bufstore_u32(b: RtBuffer, i: u32, v: u32) {
    if rt_buf_check(b, i) {
        rt_store_u32(b.offset + i * 1u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

const SLOTS: u32 = 8u;

fn rtf_fuzz_bump(state: ptr<function, u32>) -> u32 {
    (*state) += 10u;
    return 1u;
}

fn rtp_fuzz_eval_order(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    var n: u32 = a;
    let tmp_1 = n;
    var tmp: u32;
    if (b > 0i) {
        n += 1u;
        tmp = 2u;
    } else {
        tmp = 3u;
    }
    let product: u32 = (tmp_1 * tmp);
    rt_bufstore_u32(out_u, slot, product);
    var m: u32 = a;
    let sum: u32 = ((m + rtf_fuzz_bump(&m)) + m);
    rt_bufstore_u32(out_u, (slot + 1u), sum);
    var v: vec2<f32> = vec2<f32>(x, 1.0f);
    let tmp_4 = v.x;
    var tmp_2: f32;
    switch (b & 1i) {
        case 0i: {
            var tmp_3: f32;
            {
                v.x = 5.0f;
                tmp_3 = v.y;
            }
            tmp_2 = tmp_3;
        }
        default: {
            tmp_2 = 2.0f;
        }
    }
    let w: vec2<f32> = vec2<f32>(tmp_4, tmp_2);
    rt_bufstore_f32(out_f, slot, (w.x + w.y));
    var k: u32 = a;
    let tmp_7 = k;
    var tmp_5: u32;
    switch (b & 3i) {
        case 1i: {
            var tmp_6: u32;
            {
                k = 100u;
                tmp_6 = 1u;
            }
            tmp_5 = tmp_6;
        }
        default: {
            tmp_5 = 2u;
        }
    }
    rt_bufstore_u32(out_u, (slot + 2u), (tmp_7 + tmp_5));
    rt_bufstore_u32(out_u, (slot + 3u), ((n + m) + k));
}
