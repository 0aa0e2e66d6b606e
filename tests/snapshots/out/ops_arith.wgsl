// ray_generation program `ops_arith`

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_bufstore_i32(b: RtBuffer, i: u32, v: i32) {
    if rt_buf_check(b, i) {
        rt_store_i32(b.offset + i * 1u, v);
    }
}

fn rt_bufstore_u32(b: RtBuffer, i: u32, v: u32) {
    if rt_buf_check(b, i) {
        rt_store_u32(b.offset + i * 1u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_heap[w]);
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_heap[w]);
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_heap[w];
}

fn rt_store_f32(w: u32, v: f32) {
    rt_heap[w] = bitcast<u32>(v);
}

fn rt_store_i32(w: u32, v: i32) {
    rt_heap[w] = bitcast<u32>(v);
}

fn rt_store_u32(w: u32, v: u32) {
    rt_heap[w] = v;
}

fn rtp_ops_arith(a: f32, b: f32, n: i32, m: u32, out_f: RtBuffer, out_i: RtBuffer, out_u: RtBuffer) {
    let slot: u32 = rt_launch_index().x;
    let sum: f32 = (a + b);
    let diff: f32 = (a - b);
    let prod: f32 = (a * b);
    let quot: f32 = (a / b);
    let rem: f32 = (a % b);
    let neg: f32 = -a;
    var acc: f32 = sum;
    acc += diff;
    acc -= prod;
    acc *= 0.5f;
    acc /= (quot + 2.0f);
    acc %= 7.0f;
    rt_bufstore_f32(out_f, slot, ((acc + (rem * neg)) - ((a - b) / (a + b))));
    var k: i32 = ((n * 3i) - 7i);
    k += (n / 2i);
    k -= (n % 3i);
    k *= -2i;
    k /= 3i;
    k %= 5i;
    var tmp_1: i32;
    if (n > 0i) {
        tmp_1 = n;
    } else {
        tmp_1 = -n;
    }
    let magnitude: i32 = max(1i, tmp_1);
    rt_bufstore_i32(out_i, slot, (((-k + ((n - 1i) * (n + 1i))) - -n) + magnitude));
    var w: u32 = (m + 1u);
    w *= 2u;
    w -= 1u;
    w /= 3u;
    w %= 100u;
    w += (m % 7u);
    rt_bufstore_u32(out_u, slot, ((w * 3u) + 10u));
}
