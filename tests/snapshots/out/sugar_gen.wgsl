// ray_generation program `sugar_gen`

struct Depths {
    near: f32,
    far: f32,
}

struct Weights {
    f0: f32,
    f1: f32,
}

struct rt_option_f32_ {
    some: bool,
    value: f32,
}

struct rt_tuple_u32_f32_ {
    f0: u32,
    f1: f32,
}

fn rt_bufload_f32(b: RtBuffer, i: u32) -> f32 {
    if rt_buf_check(b, i) {
        return rt_load_f32(b.offset + i * 1u);
    }
    return f32();
}

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rtf_sugar_blend(a: f32, b: f32, t: f32) -> f32 {
    return (a + ((b - a) * t));
}

fn rtp_sugar_gen(sugar_out: RtBuffer, sugar_k: f32) {
    var sugar_out_1 = sugar_out;
    let i: u32 = rt_launch_index().x;
    let x: f32 = f32(i);
    let span: Depths = Depths(x, (x + 1.0f));
    var tmp: f32;
    {
        let v: f32 = x;
        tmp = (v * sugar_k);
    }
    var tmp_3: f32;
    {
        let x_rt_inl1: f32 = x;
        var tmp_1: f32;
        {
            let v_1: f32 = x_rt_inl1;
            tmp_1 = (v_1 + sugar_k);
        }
        let once_rt_inl1: f32 = tmp_1;
        var tmp_2: f32;
        {
            let v_2: f32 = once_rt_inl1;
            tmp_2 = (v_2 + sugar_k);
        }
        tmp_3 = tmp_2;
    }
    var tmp_6: f32;
    {
        let self_rt_inl2: Depths = span;
        var tmp_4: f32;
        {
            let d: f32 = self_rt_inl2.near;
            tmp_4 = (d * d);
        }
        var tmp_5: f32;
        {
            let d_1: f32 = self_rt_inl2.far;
            tmp_5 = (d_1 * d_1);
        }
        tmp_6 = (tmp_4 + tmp_5);
    }
    var acc: f32 = ((tmp + tmp_3) + tmp_6);
    var ws: array<f32, 3> = array<f32, 3>(0.25f, 0.5f, 0.75f);
    var tmp_8: f32;
    {
        var rt_sugar_array2_: array<f32, 3> = ws;
        var rt_sugar_acc5_: f32 = -0.0f;
        let end = 3u;
        for (var rt_sugar_k3_: u32 = 0u; rt_sugar_k3_ < end; rt_sugar_k3_++) {
            var tmp_7: f32;
            {
                let tuple: rt_tuple_u32_f32_ = rt_tuple_u32_f32_(rt_sugar_k3_, rt_sugar_array2_[rt_sugar_k3_]);
                let j: u32 = tuple.f0;
                let w: f32 = tuple.f1;
                tmp_7 = (w * f32(j));
            }
            let rt_sugar_v4_: f32 = tmp_7;
            rt_sugar_acc5_ += rt_sugar_v4_;
        }
        tmp_8 = rt_sugar_acc5_;
    }
    acc += tmp_8;
    var tmp_12: f32;
    {
        let rt_sugar_start6_: u32 = 0u;
        let rt_sugar_end7_: u32 = 8u;
        var tmp_9: u32;
        if (rt_sugar_start6_ < rt_sugar_end7_) {
            tmp_9 = (rt_sugar_end7_ - rt_sugar_start6_);
        } else {
            tmp_9 = 0u;
        }
        let rt_sugar_n8_: u32 = tmp_9;
        let rt_sugar_n9_: u32 = rt_sugar_n8_;
        let rt_sugar_step10_: u32 = 2u;
        var tmp_10: u32;
        if (rt_sugar_n9_ == 0u) {
            tmp_10 = 0u;
        } else {
            tmp_10 = (((rt_sugar_n9_ - 1u) / rt_sugar_step10_) + 1u);
        }
        let rt_sugar_n11_: u32 = tmp_10;
        let rt_sugar_n12_: u32 = rt_sugar_n11_;
        var rt_sugar_acc15_: f32 = 0.0f;
        let end_1 = rt_sugar_n12_;
        for (var rt_sugar_k13_: u32 = 0u; rt_sugar_k13_ < end_1; rt_sugar_k13_++) {
            let rt_sugar_v14_: u32 = (rt_sugar_start6_ + (((rt_sugar_n12_ - 1u) - rt_sugar_k13_) * rt_sugar_step10_));
            var tmp_11: f32;
            {
                let a: f32 = rt_sugar_acc15_;
                let j_1: u32 = rt_sugar_v14_;
                tmp_11 = (a + f32(j_1));
            }
            rt_sugar_acc15_ = tmp_11;
        }
        tmp_12 = rt_sugar_acc15_;
    }
    acc += tmp_12;
    var tmp_14: bool;
    {
        var rt_sugar_array16_: array<f32, 3> = ws;
        var rt_sugar_acc19_: bool = false;
        let end_2 = 3u;
        for (var rt_sugar_k17_: u32 = 0u; rt_sugar_k17_ < end_2; rt_sugar_k17_++) {
            let rt_sugar_v18_: f32 = rt_sugar_array16_[rt_sugar_k17_];
            var tmp_13: bool;
            {
                let w_1: f32 = rt_sugar_v18_;
                tmp_13 = (w_1 > x);
            }
            if tmp_13 {
                rt_sugar_acc19_ = true;
                break;
            }
        }
        tmp_14 = rt_sugar_acc19_;
    }
    if tmp_14 {
        acc += 1.0f;
    }
    var tmp_15: rt_option_f32_;
    if ((i % 2u) == 0u) {
        tmp_15 = rt_option_f32_(true, x);
    } else {
        tmp_15 = rt_option_f32_();
    }
    let first: rt_option_f32_ = tmp_15;
    let scrutinee = first;
    if (scrutinee.some) {
        let f = scrutinee.value;
        {
            acc += f;
        }
    } else {
        {
        }
    }
    let scrutinee_1 = first;
    var tmp_17: rt_option_f32_;
    if (scrutinee_1.some) {
        let rt_sugar_some20_ = scrutinee_1.value;
        var tmp_18: f32;
        {
            let f_1: f32 = rt_sugar_some20_;
            tmp_18 = (f_1 * 2.0f);
        }
        tmp_17 = rt_option_f32_(true, tmp_18);
    } else if (!scrutinee_1.some) {
        tmp_17 = rt_option_f32_();
    }
    let opt = tmp_17;
    var tmp_19: f32 = 0.5f;
    if opt.some {
        tmp_19 = opt.value;
    }
    acc += tmp_19;
    let scrutinee_2 = first;
    var tmp_20: rt_option_f32_;
    if (scrutinee_2.some) {
        let rt_sugar_some21_ = scrutinee_2.value;
        var tmp_21: bool;
        {
            let f_2: f32 = rt_sugar_some21_;
            tmp_21 = (f_2 > 1.0f);
        }
        var tmp_22: rt_option_f32_;
        if tmp_21 {
            tmp_22 = rt_option_f32_(true, rt_sugar_some21_);
        } else {
            tmp_22 = rt_option_f32_();
        }
        tmp_20 = tmp_22;
    } else if (!scrutinee_2.some) {
        tmp_20 = rt_option_f32_();
    }
    let scrutinee_3 = tmp_20;
    var tmp_23: f32;
    if (scrutinee_3.some) {
        let g = scrutinee_3.value;
        tmp_23 = g;
    } else {
        {
            let tmp_24 = i;
            rt_bufstore_f32(sugar_out_1, tmp_24, acc);
            return;
        }
    }
    let g_1: f32 = tmp_23;
    var tmp_31: f32;
    {
        let rt_sugar_match22_: u32 = i;
        var tmp_30: f32;
        if ((rt_sugar_match22_ >= 0u) && (rt_sugar_match22_ <= 3u)) {
            tmp_30 = g_1;
        } else {
            var tmp_29: f32;
            if ((rt_sugar_match22_ == 4u) || (rt_sugar_match22_ == 5u)) {
                tmp_29 = -g_1;
            } else {
                var tmp_26: bool = true;
                if tmp_26 {
                    var tmp_25: bool;
                    {
                        let n: u32 = rt_sugar_match22_;
                        tmp_25 = (n > 100u);
                    }
                    tmp_26 = tmp_25;
                }
                var tmp_28: f32;
                if tmp_26 {
                    let n_1: u32 = rt_sugar_match22_;
                    tmp_28 = 0.0f;
                } else {
                    var tmp_27: f32;
                    {
                        tmp_27 = 1.0f;
                    }
                    tmp_28 = tmp_27;
                }
                tmp_29 = tmp_28;
            }
            tmp_30 = tmp_29;
        }
        tmp_31 = tmp_30;
    }
    acc += tmp_31;
    var tmp_32: bool;
    switch (i % 4u) {
        case 1u, 3u: {
            tmp_32 = true;
        }
        default: {
            tmp_32 = false;
        }
    }
    if tmp_32 {
        acc *= 0.5f;
    }
    var found: u32 = 0u;
    {
        var rt_sugar_jump1_: u32 = 0u;
        for (var r: u32 = 0u; r < 4u; r++) {
            for (var c: u32 = 0u; c < 4u; c++) {
                if ((r * c) > i) {
                    found = r;
                    {
                        rt_sugar_jump1_ = 1u;
                        break;
                    }
                }
            }
            if (rt_sugar_jump1_ != 0u) {
                if (rt_sugar_jump1_ == 1u) {
                    break;
                }
                rt_sugar_jump1_ = 0u;
                continue;
            }
        }
    }
    var n_2: u32 = 0u;
    var loop_value: u32;
    loop {
        n_2 += 1u;
        if (n_2 > found) {
            loop_value = (n_2 * 2u);
            break;
        }
    }
    let steps: u32 = loop_value;
    let tint: vec3<f32> = vec3<f32>(acc);
    let tuple_1: Weights = Weights(0.5f, 0.25f);
    let wa: f32 = tuple_1.f0;
    let wb: f32 = tuple_1.f1;
    let tmp_33 = i;
    rt_bufstore_f32(sugar_out_1, tmp_33, (rtf_sugar_blend(tint.x, f32(steps), wa) + wb));
}
