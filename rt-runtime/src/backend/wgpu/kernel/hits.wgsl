
// ---- candidates and hits, shared by both traversals ----
// A search (rt_search: the compute traversal's in traverse.wgsl, or the
// ray-query loop in rayquery/search.wgsl) reports each candidate through
// rt_report (custom primitives through their intersection program, from
// rt_intersect_prim), which runs any hit and commits the hit state
// (rt_h_*); rt_enter_hit then makes the hit the current ray state for the
// closest-hit program.
var<private> rt_s_wray: RtRay;

// A candidate at rt_c_t (inside (tmin, closest)) on instance rt_s_inst:
// runs any hit, commits unless ignored.
fn rt_report(m: u32) -> bool {
    let gi = rt_s_gi;
    let g = rt_scene[2] + gi * 8u;
    if m >= rt_scene[g + 6u] {
        return false;
    }
    let rec = rt_scene[g + 7u] + (m * rt_scene[4] + rt_s_ray_type) * 4u;
    let ah = rt_scene[rec + 2u];
    var terminate = (rt_s_flags & RT_RAY_FLAG_TERMINATE_ON_FIRST_HIT) != 0u;
    if ah != 0u && (rt_s_flags & RT_RAY_FLAG_DISABLE_ANYHIT) == 0u {
        let saved_ray = rt_ray;
        let saved_t = rt_t;
        let saved_prim = rt_prim;
        let saved_hk = rt_hk;
        let saved_ic = rt_icur;
        rt_ray = rt_s_wray;
        rt_ray.tmax = rt_c_t;
        rt_t = rt_c_t;
        rt_prim = rt_c_prim;
        rt_hk = rt_hit_kind(rt_c_custom, gi, rt_c_prim, rt_w2o, rt_s_wray.direction);
        rt_icur = vec4<u32>(rt_s_ipath, rt_s_inst, gi);
        rt_ignored = false;
        rt_terminated = false;
        rt_anyhit_dispatch(ah, rt_scene[rec + 3u]);
        rt_ray = saved_ray;
        rt_t = saved_t;
        rt_prim = saved_prim;
        rt_hk = saved_hk;
        rt_icur = saved_ic;
        if rt_ignored {
            return false;
        }
        terminate = terminate || rt_terminated;
    }
    rt_s_tmax = rt_c_t;
    rt_h_found = true;
    rt_h_t = rt_c_t;
    rt_h_gi = gi;
    rt_h_prim = rt_c_prim;
    rt_h_mat = m;
    rt_h_inst = rt_s_inst;
    rt_h_ipath = rt_s_ipath;
    rt_h_custom = rt_c_custom;
    rt_h_bary = rt_c_bary;
    rt_commit_xform();
    if rt_c_custom {
        rt_commit_attributes();
    }
    if terminate {
        rt_s_done = true;
    }
    return true;
}

fn rt_intersect_prim(gi: u32, prim: u32) {
    let g = rt_scene[2] + gi * 8u;
    rt_s_gi = gi;
    rt_c_prim = prim;
    // Kinds 0 and 2: triangles (2 with vertex motion), 1: custom.
    if rt_scene[g] != 1u {
        let ib = rt_scene[g + 2u] + prim * 3u;
        let a = rt_tri_corner(g, rt_scene[ib]);
        let b = rt_tri_corner(g, rt_scene[ib + 1u]);
        let c = rt_tri_corner(g, rt_scene[ib + 2u]);
        let t = rt_triangle(a, b, c, rt_s_oray, rt_s_tmax);
        if t < 0.0 {
            return;
        }
        if (rt_tri_front && (rt_s_flags & RT_RAY_FLAG_CULL_FRONT_FACING) != 0u) || (!rt_tri_front && (rt_s_flags & RT_RAY_FLAG_CULL_BACK_FACING) != 0u) {
            return;
        }
        var m = 0u;
        if rt_scene[g + 5u] != RT_NONE {
            m = rt_scene[rt_scene[g + 5u] + prim];
        }
        rt_c_t = t;
        rt_c_ok = true;
        rt_c_custom = false;
        _ = rt_report(m);
    } else {
        let rec = rt_scene[6] + gi * 2u;
        rt_c_ok = false;
        rt_c_custom = true;
        let saved_ray = rt_ray;
        rt_ray = rt_s_oray;
        rt_ray.tmax = rt_s_tmax;
        rt_prim = prim;
        rt_icur = vec4<u32>(rt_s_ipath, rt_s_inst, gi);
        rt_isect_dispatch(rt_scene[rec], rt_scene[rec + 1u], prim);
        rt_ray = saved_ray;
    }
}

// After a search that found a hit: the word offset of the hit's record
// with the hit made the current ray state, or RT_NONE when no closest-hit
// program runs (none set, or the ray's flags disable it).
fn rt_enter_hit(ray: RtRay, flags: u32) -> u32 {
    let g = rt_scene[2] + rt_h_gi * 8u;
    let rec = rt_scene[g + 7u] + (rt_h_mat * rt_scene[4] + ray.ray_type) * 4u;
    if rt_scene[rec] == 0u || (flags & RT_RAY_FLAG_DISABLE_CLOSESTHIT) != 0u {
        return RT_NONE;
    }
    rt_ray = ray;
    rt_ray.tmax = rt_h_t;
    rt_t = rt_h_t;
    rt_prim = rt_h_prim;
    rt_hit_xform();
    rt_hk = rt_hit_kind(rt_h_custom, rt_h_gi, rt_h_prim, rt_w2o, ray.direction);
    rt_icur = vec4<u32>(rt_h_ipath, rt_h_inst, rt_h_gi);
    return rec;
}

