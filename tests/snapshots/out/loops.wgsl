// ray_generation program `loops`

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rtf_pop_bit(mask: ptr<function, u32>, bit: ptr<function, u32>) -> bool {
    if ((*mask) == 0u) {
        return false;
    }
    (*bit) = countTrailingZeros((*mask));
    (*mask) &= ((*mask) - 1u);
    return true;
}

fn rtp_loops(n: u32, mask: u32, out: RtBuffer) {
    let slot: u32 = rt_launch_index().x;
    var sum: f32 = 0.0f;
    let end = n;
    for (var i: u32 = 0u; i < end; i++) {
        if ((i % 2u) == 0u) {
            continue;
        }
        sum += f32(i);
    }
    for (var i_1: i32 = 1i; i_1 <= 4i; i_1++) {
        sum *= (0.5f + f32(i_1));
    }
    for (var row: u32 = 0u; row < 3u; row++) {
        let end_1 = (n + 1u);
        {
            var col: u32 = row;
            if col <= end_1 {
                loop {
                    sum += f32((row * col));
                    continuing {
                        let last = col == end_1;
                        col++;
                        break if last;
                    }
                }
            }
        }
    }
    var k: u32 = (slot + 1u);
    var steps: i32 = 0i;
    while (k > 1u) {
        if select((k % select(2u, 1u, 2u == 0u)) == 0u, k == 0u, 2u == 0u) {
            k /= 2u;
        } else {
            k = ((3u * k) + 1u);
        }
        steps += 1i;
    }
    var remaining: u32 = mask;
    var bit: u32 = 0u;
    var bits_seen: u32 = 0u;
    while ((steps > 0i) && rtf_pop_bit(&remaining, &bit)) {
        bits_seen += bit;
    }
    var x: f32 = 1.0f;
    var iters: i32 = 0i;
    loop {
        x = (0.5f * (x + (2.0f / x)));
        iters += 1i;
        if ((iters == 8i) || (abs(((x * x) - 2.0f)) < 1e-6f)) {
            break;
        }
    }
    rt_bufstore_f32(out, slot, (((sum + x) + f32(steps)) + f32(bits_seen)));
}
