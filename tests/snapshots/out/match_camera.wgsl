// ray_generation program `match_camera`
fn rt_trace_Shade(object: u32, ray: RtRay, prd: ptr<function, Shade>, flags: u32, mask: u32) {}

struct Shade {
    color: vec3<f32>,
    depth: u32,
}

fn rt_bufload2_vec4f(b: RtBuffer, i: vec2<u32>) -> vec4<f32> {
    if rt_buf_check2(b, i) {
        return rt_load_vec4f(b.offset + (i.y * b.width + i.x) * 4u);
    }
    return vec4<f32>();
}

fn rt_bufload_i32(b: RtBuffer, i: u32) -> i32 {
    if rt_buf_check(b, i) {
        return rt_load_i32(b.offset + i * 1u);
    }
    return i32();
}

fn rt_bufstore2_vec4f(b: RtBuffer, i: vec2<u32>, v: vec4<f32>) {
    if rt_buf_check2(b, i) {
        rt_store_vec4f(b.offset + (i.y * b.width + i.x) * 4u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
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

fn rtp_match_camera(top_object: u32, out: RtBuffer, plan: RtBuffer) {
    var out_1 = out;
    let idx: vec2<u32> = rt_launch_index();
    var total: vec3<f32> = vec3<f32>(0.0);
    var step_: u32 = 0u;
    loop {
        var prd: Shade = Shade(vec3<f32>(0.0), 0u);
        var brk = false;
        switch rt_bufload_i32(plan, step_) {
            case -1i: {
                brk = true;
                break;
            }
            case 0i: {
                {
                }
            }
            default: {
                let n = rt_bufload_i32(plan, step_);
                {
                    let o: vec3<f32> = vec3<f32>(f32(idx.x), f32(idx.y), f32(n));
                    rt_trace_Shade(top_object, RtRay(o, vec3<f32>(0.0f, 0.0f, -1.0f), 0u, 0.0f, rt_f32_from_bits(0x7f800000u)), &prd, 0u, 255u);
                    total += prd.color;
                }
            }
        }
        if brk {
            break;
        }
        step_ += 1u;
        if (step_ >= 4u) {
            break;
        }
    }
    let tmp_1 = idx;
    rt_bufstore2_vec4f(out_1, tmp_1, vec4<f32>(total, 1.0f));
}

// ---- resumable form ----
var<private> rt_fr_rtp_match_camera_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_match_camera_out_1: array<RtBuffer, RT_DEPTHS>;
var<private> rt_fr_rtp_match_camera_idx: array<vec2<u32>, RT_DEPTHS>;
var<private> rt_fr_rtp_match_camera_total: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_match_camera_step_: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_match_camera_prd: array<Shade, RT_DEPTHS>;
var<private> rt_fr_rtp_match_camera_sel: array<i32, RT_DEPTHS>;
var<private> rt_fr_rtp_match_camera_o: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_match_camera_brk: array<bool, RT_DEPTHS>;
fn rtp_match_camera(top_object: u32, out: RtBuffer, plan: RtBuffer) {
    var rt_site: u32 = 0u;
    var out_1: RtBuffer;
    var idx: vec2<u32>;
    var total: vec3<f32>;
    var step_: u32;
    var prd: Shade;
    var sel: i32;
    var o: vec3<f32>;
    var brk: bool;
    if rt_rs != 0u {
        out_1 = rt_fr_rtp_match_camera_out_1[rt_d];
        idx = rt_fr_rtp_match_camera_idx[rt_d];
        total = rt_fr_rtp_match_camera_total[rt_d];
        step_ = rt_fr_rtp_match_camera_step_[rt_d];
        prd = rt_fr_rtp_match_camera_prd[rt_d];
        sel = rt_fr_rtp_match_camera_sel[rt_d];
        o = rt_fr_rtp_match_camera_o[rt_d];
        brk = rt_fr_rtp_match_camera_brk[rt_d];
        rt_site = rt_fr_rtp_match_camera_rt_site[rt_d];
    }
    if rt_site == 0u {
        out_1 = out;
    }
    if rt_site == 0u {
        idx = rt_launch_index();
        total = vec3<f32>(0.0);
        step_ = 0u;
    }
    if rt_site == 0u || rt_site == 1u {
        loop {
            if rt_site == 0u {
                prd = Shade(vec3<f32>(0.0), 0u);
            }
            if rt_site == 0u {
                sel = rt_bufload_i32(plan, step_);
                brk = false;
            }
            if rt_site == 0u || rt_site == 1u {
                switch sel {
                    case -1i: {
                        if rt_site == 0u {
                            brk = true;
                            break;
                        }
                    }
                    case 0i: {
                    }
                    default: {
                        if rt_site == 0u {
                            o = vec3<f32>(f32(idx.x), f32(idx.y), f32(sel));
                        }
                        if rt_site == 0u {
                            rt_request_Shade(top_object, RtRay(o, vec3<f32>(0.0f, 0.0f, -1.0f), 0u, 0.0f, rt_f32_from_bits(0x7f800000u)), prd, 0u, 255u);
                            rt_fr_rtp_match_camera_out_1[rt_d] = out_1;
                            rt_fr_rtp_match_camera_idx[rt_d] = idx;
                            rt_fr_rtp_match_camera_total[rt_d] = total;
                            rt_fr_rtp_match_camera_step_[rt_d] = step_;
                            rt_fr_rtp_match_camera_prd[rt_d] = prd;
                            rt_fr_rtp_match_camera_sel[rt_d] = sel;
                            rt_fr_rtp_match_camera_o[rt_d] = o;
                            rt_fr_rtp_match_camera_brk[rt_d] = brk;
                            rt_fr_rtp_match_camera_rt_site[rt_d] = 1u;
                            rt_rs = 1u;
                            return;
                        }
                        if rt_site == 1u {
                            prd = rt_result_Shade();
                            rt_site = 0u;
                            rt_rs = 0u;
                        }
                        if rt_site == 0u {
                            total += prd.color;
                        }
                    }
                }
                if brk {
                    break;
                }
            }
            if rt_site == 0u {
                step_ += 1u;
                if (step_ >= 4u) {
                    break;
                }
            }
        }
    }
    if rt_site == 0u {
        let tmp = idx;
        rt_bufstore2_vec4f(out_1, tmp, vec4<f32>(total, 1.0f));
    }
}
