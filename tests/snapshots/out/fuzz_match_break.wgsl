// ray_generation program `fuzz_match_break`

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

fn rtp_fuzz_match_break(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    var n: u32 = 0u;
    var i: u32 = 0u;
    while (i < 10u) {
        i += 1u;
        var brk = false;
        switch ((i + a) % 4u) {
            case 3u: {
                brk = true;
                break;
            }
            default: {
                n += i;
            }
        }
        if brk {
            break;
        }
    }
    rt_bufstore_u32(out_u, slot, n);
    rt_bufstore_u32(out_u, (slot + 1u), i);
    var steps: i32 = 0i;
    for (var j: i32 = 0i; j < 8i; j++) {
        steps += 1i;
        var brk_1 = false;
        switch (j & 1i) {
            case 1i: {
                var brk_2 = false;
                switch ((j + b) & 3i) {
                    case 0i: {
                        brk_2 = true;
                        break;
                    }
                    case 1i: {
                        steps += 100i;
                    }
                    default: {
                        {
                        }
                    }
                }
                if brk_2 {
                    brk_1 = true;
                    break;
                }
            }
            default: {
                continue;
            }
        }
        if brk_1 {
            break;
        }
        steps += 10i;
    }
    rt_bufstore_u32(out_u, (slot + 2u), u32(steps));
    rt_bufstore_f32(out_f, slot, x);
}
