// The trace loop: the program on top of the stack runs until it returns or asks for a trace.
// (a template: rt-runtime's kernel/stack.rs fills the {names} in braces).

// ---- the trace loop ----
// Runs the program on top of the stack, from its start (rt_rs == 0) or from
// its site rt_rs.
fn rt_step() {
    let d = rt_d;
    let vars = rt_st_vars[d];
    switch rt_st_case[d] {
{cases}        default: {
            rt_raise(RT_EXC_INVALID_RAY);
        }
    }
}

// Starts the trace requested by the program at depth d: true when a
// closest-hit or miss program is now on top at depth d + 1; false when the
// caller resumes at once (exception, no program to run).
fn rt_begin_trace(d: u32) -> bool {
    let object = rt_rq_obj;
    let ray = rt_rq_ray;
    let flags = rt_rq_flags;
    let mask = rt_rq_mask;
    let ty = rt_rq_type;
    let time = rt_next_time;
    rt_next_time = 0.0;
    if rt_exc != 0u {
        return false;
    }
    if d + 1u >= RT_DEPTHS {
        rt_raise(RT_EXC_TRACE_DEPTH);
        return false;
    }
    if !rt_valid_ray(ray) || object >= rt_scene[7] || ray.ray_type >= rt_scene[4] {
        rt_raise(RT_EXC_INVALID_RAY);
        return false;
    }
    let e = d + 1u;
    rt_st_ray[e] = rt_ray;
    rt_st_t[e] = rt_t;
    rt_st_time[e] = rt_time;
    rt_time = time;
    rt_st_prim[e] = rt_prim;
    rt_st_o2w[e] = rt_o2w;
    rt_st_w2o[e] = rt_w2o;
    rt_st_rs[e] = vec3<u32>(rt_hk, rt_rflags, rt_rmask);
    rt_st_ic[e] = rt_icur;
    rt_rflags = flags;
    rt_rmask = mask & 0xffu;
    rt_rays = rt_rays + 1u;{note_payload}
    switch ty {
{take_request}        default: {}
    }
    rt_search(object, ray, flags, mask);
    switch ty {
{after_search}        default: {}
    }
    var run = false;
    if rt_h_found {
        let rec = rt_enter_hit(ray, flags);
        if rec != RT_NONE {
            rt_st_case[e] = rt_scene[rec];
            rt_st_vars[e] = rt_scene[rec + 1u];
            run = true;
        }
    } else {
        let mr = rt_scene[5] + ray.ray_type * 2u;
        rt_ray = ray;
        rt_hk = 0u;
        rt_st_case[e] = rt_scene[mr];
        rt_st_vars[e] = rt_scene[mr + 1u];
        // Case 0: the ray type has no miss program, and a miss does nothing.
        run = rt_scene[mr] != 0u;
    }
    if !run {
        rt_end_trace(e);
        return false;
    }
    rt_st_type[e] = ty;
    rt_d = e;
    return true;
}

// Ends the trace that started depth d: the caller's ray state comes back.
fn rt_end_trace(d: u32) {
    rt_ray = rt_st_ray[d];
    rt_t = rt_st_t[d];
    rt_time = rt_st_time[d];
    rt_prim = rt_st_prim[d];
    rt_o2w = rt_st_o2w[d];
    rt_w2o = rt_st_w2o[d];
    rt_hk = rt_st_rs[d].x;
    rt_rflags = rt_st_rs[d].y;
    rt_rmask = rt_st_rs[d].z;
    rt_icur = rt_st_ic[d];
}

fn rt_run() {
    rt_d = 0u;
    rt_rs = 0u;
    rt_st_case[0] = {rg_case}u;
    rt_st_vars[0] = rt_launch.ray_generation.y;
    loop {
        rt_step();
        let d = rt_d;
        if rt_rs != 0u {
            rt_rs = 0u;
            if !rt_begin_trace(d) {
                rt_rs = 1u;
            }
            continue;
        }
        if d == 0u {
            break;
        }
        switch rt_st_type[d] {
{deliver}            default: {}
        }
        rt_end_trace(d);
        rt_d = d - 1u;
        rt_rs = 1u;
    }
}
