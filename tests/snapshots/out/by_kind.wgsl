// closest_hit program `by_kind`
fn rt_trace_Shade(object: u32, ray: RtRay, prd: ptr<function, Shade>, flags: u32, mask: u32) {}

struct Shade {
    color: vec3<f32>,
    depth: u32,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtf_seen_above(top_object: u32, p: vec3<f32>, depth: u32) -> vec3<f32> {
    var up: Shade = Shade(vec3<f32>(0.0), (depth + 1u));
    var tmp: vec3<f32>;
    {
        let r: RtRay = RtRay(p, vec3<f32>(0.0f, 1.0f, 0.0f), 0u, 0.001f, rt_f32_from_bits(0x7f800000u));
        rt_trace_Shade(top_object, r, &up, 0u, 255u);
        tmp = (up.color * 0.5f);
    }
    return tmp;
}

fn rtp_by_kind(prd: ptr<function, Shade>, kind: u32, top_object: u32, tint: vec3<f32>) {
    let ray: RtRay = rt_current_ray();
    let p: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    var next: Shade = Shade(vec3<f32>(0.0), ((*prd).depth + 1u));
    switch kind {
        case 0u: {
            {
                let d: vec3<f32> = vec3<f32>(ray.direction.x, -ray.direction.y, ray.direction.z);
                rt_trace_Shade(top_object, RtRay(p, d, 0u, 0.001f, rt_f32_from_bits(0x7f800000u)), &next, 0u, 255u);
                (*prd).color = (next.color * tint);
            }
        }
        case 1u, 2u: {
            rt_trace_Shade(top_object, RtRay(p, ray.direction, 0u, 0.001f, rt_f32_from_bits(0x7f800000u)), &next, 0u, 255u);
        }
        default: {
            let k = kind;
            {
                (*prd).color = (tint * f32(k));
                return;
            }
        }
    }
    (*prd).color += ((next.color * 0.5f) + rtf_seen_above(top_object, p, (*prd).depth));
}

// ---- resumable form ----
var<private> rt_fr_rtf_seen_above_rs_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtf_seen_above_rs_up: array<Shade, RT_DEPTHS>;
var<private> rt_fr_rtf_seen_above_rs_r: array<RtRay, RT_DEPTHS>;
fn rtf_seen_above_rs(top_object: u32, p: vec3<f32>, depth: u32) -> vec3<f32> {
    var rt_site: u32 = 0u;
    var up: Shade;
    var r: RtRay;
    if rt_rs != 0u {
        up = rt_fr_rtf_seen_above_rs_up[rt_d];
        r = rt_fr_rtf_seen_above_rs_r[rt_d];
        rt_site = rt_fr_rtf_seen_above_rs_rt_site[rt_d];
    }
    if rt_site == 0u {
        up = Shade(vec3<f32>(0.0), (depth + 1u));
        r = RtRay(p, vec3<f32>(0.0f, 1.0f, 0.0f), 0u, 0.001f, rt_f32_from_bits(0x7f800000u));
    }
    if rt_site == 0u {
        rt_request_Shade(top_object, r, up, 0u, 255u);
        rt_fr_rtf_seen_above_rs_up[rt_d] = up;
        rt_fr_rtf_seen_above_rs_r[rt_d] = r;
        rt_fr_rtf_seen_above_rs_rt_site[rt_d] = 1u;
        rt_rs = 1u;
        return vec3<f32>();
    }
    if rt_site == 1u {
        up = rt_result_Shade();
        rt_site = 0u;
        rt_rs = 0u;
    }
    if rt_site == 0u {
        return (up.color * 0.5f);
    }
    return vec3<f32>();
}
var<private> rt_fr_rtp_by_kind_rt_site: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_p: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_next: array<Shade, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_sel: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_d: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_arg: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_arg_1: array<vec3<f32>, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_arg_2: array<u32, RT_DEPTHS>;
var<private> rt_fr_rtp_by_kind_rt_call_0_: array<vec3<f32>, RT_DEPTHS>;
fn rtp_by_kind(prd: ptr<function, Shade>, kind: u32, top_object: u32, tint: vec3<f32>) {
    var rt_site: u32 = 0u;
    var ray: RtRay;
    var p: vec3<f32>;
    var next: Shade;
    var sel: u32;
    var d: vec3<f32>;
    var arg: u32;
    var arg_1: vec3<f32>;
    var arg_2: u32;
    var rt_call_0_: vec3<f32>;
    if rt_rs != 0u {
        ray = rt_fr_rtp_by_kind_ray[rt_d];
        p = rt_fr_rtp_by_kind_p[rt_d];
        next = rt_fr_rtp_by_kind_next[rt_d];
        sel = rt_fr_rtp_by_kind_sel[rt_d];
        d = rt_fr_rtp_by_kind_d[rt_d];
        arg = rt_fr_rtp_by_kind_arg[rt_d];
        arg_1 = rt_fr_rtp_by_kind_arg_1[rt_d];
        arg_2 = rt_fr_rtp_by_kind_arg_2[rt_d];
        rt_call_0_ = rt_fr_rtp_by_kind_rt_call_0_[rt_d];
        rt_site = rt_fr_rtp_by_kind_rt_site[rt_d];
    }
    if rt_site == 0u {
        ray = rt_current_ray();
        p = (ray.origin + (rt_t_hit() * ray.direction));
        next = Shade(vec3<f32>(0.0), ((*prd).depth + 1u));
    }
    if rt_site == 0u {
        sel = kind;
    }
    if rt_site == 0u || (rt_site >= 1u && rt_site <= 2u) {
        switch sel {
            case 0u: {
                if rt_site == 0u {
                    d = vec3<f32>(ray.direction.x, -ray.direction.y, ray.direction.z);
                }
                if rt_site == 0u {
                    rt_request_Shade(top_object, RtRay(p, d, 0u, 0.001f, rt_f32_from_bits(0x7f800000u)), next, 0u, 255u);
                    rt_fr_rtp_by_kind_ray[rt_d] = ray;
                    rt_fr_rtp_by_kind_p[rt_d] = p;
                    rt_fr_rtp_by_kind_next[rt_d] = next;
                    rt_fr_rtp_by_kind_sel[rt_d] = sel;
                    rt_fr_rtp_by_kind_d[rt_d] = d;
                    rt_fr_rtp_by_kind_arg[rt_d] = arg;
                    rt_fr_rtp_by_kind_arg_1[rt_d] = arg_1;
                    rt_fr_rtp_by_kind_arg_2[rt_d] = arg_2;
                    rt_fr_rtp_by_kind_rt_call_0_[rt_d] = rt_call_0_;
                    rt_fr_rtp_by_kind_rt_site[rt_d] = 1u;
                    rt_rs = 1u;
                    return;
                }
                if rt_site == 1u {
                    next = rt_result_Shade();
                    rt_site = 0u;
                    rt_rs = 0u;
                }
                if rt_site == 0u {
                    (*prd).color = (next.color * tint);
                }
            }
            case 1u, 2u: {
                if rt_site == 0u {
                    rt_request_Shade(top_object, RtRay(p, ray.direction, 0u, 0.001f, rt_f32_from_bits(0x7f800000u)), next, 0u, 255u);
                    rt_fr_rtp_by_kind_ray[rt_d] = ray;
                    rt_fr_rtp_by_kind_p[rt_d] = p;
                    rt_fr_rtp_by_kind_next[rt_d] = next;
                    rt_fr_rtp_by_kind_sel[rt_d] = sel;
                    rt_fr_rtp_by_kind_d[rt_d] = d;
                    rt_fr_rtp_by_kind_arg[rt_d] = arg;
                    rt_fr_rtp_by_kind_arg_1[rt_d] = arg_1;
                    rt_fr_rtp_by_kind_arg_2[rt_d] = arg_2;
                    rt_fr_rtp_by_kind_rt_call_0_[rt_d] = rt_call_0_;
                    rt_fr_rtp_by_kind_rt_site[rt_d] = 2u;
                    rt_rs = 1u;
                    return;
                }
                if rt_site == 2u {
                    next = rt_result_Shade();
                    rt_site = 0u;
                    rt_rs = 0u;
                }
            }
            default: {
                if rt_site == 0u {
                    (*prd).color = (tint * f32(sel));
                    return;
                }
            }
        }
    }
    if rt_site == 0u || rt_site == 3u {
        if rt_site == 0u {
            arg = top_object;
            arg_1 = p;
            arg_2 = (*prd).depth;
        }
        let tmp = rtf_seen_above_rs(arg, arg_1, arg_2);
        if rt_rs != 0u {
            rt_fr_rtp_by_kind_ray[rt_d] = ray;
            rt_fr_rtp_by_kind_p[rt_d] = p;
            rt_fr_rtp_by_kind_next[rt_d] = next;
            rt_fr_rtp_by_kind_sel[rt_d] = sel;
            rt_fr_rtp_by_kind_d[rt_d] = d;
            rt_fr_rtp_by_kind_arg[rt_d] = arg;
            rt_fr_rtp_by_kind_arg_1[rt_d] = arg_1;
            rt_fr_rtp_by_kind_arg_2[rt_d] = arg_2;
            rt_fr_rtp_by_kind_rt_call_0_[rt_d] = rt_call_0_;
            rt_fr_rtp_by_kind_rt_site[rt_d] = 3u;
            rt_rs = 1u;
            return;
        }
        rt_site = 0u;
        rt_call_0_ = tmp;
    }
    if rt_site == 0u {
        (*prd).color += ((next.color * 0.5f) + rt_call_0_);
    }
}
