// miss program `maybe_t_miss`

struct MaybeT {
    t: f32,
    has: bool,
}

struct rt_option_f32_ {
    some: bool,
    value: f32,
}

fn rtp_maybe_t_miss(prd: ptr<function, MaybeT>) {
    var tmp: rt_option_f32_;
    if (*prd).has {
        tmp = rt_option_f32_(true, (*prd).t);
    } else {
        tmp = rt_option_f32_();
    }
    let o: rt_option_f32_ = tmp;
    let unwrap = o;
    if !unwrap.some {
        rt_throw(1011u);
    }
    let unwrap_1 = rt_option_f32_(true, 1.0f);
    if !unwrap_1.some {
        rt_throw(1011u);
    }
    (*prd).t = ((unwrap.value * 2.0f) + unwrap_1.value);
}
