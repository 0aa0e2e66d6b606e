
// ---- traversal ----
// The fast path is two levels (a group's BVH over instances, each a
// transform over a geometry group's BVH of primitives); deeper graphs
// (groups of groups, transforms above groups, selectors) go through
// rt_search_graph (graph.wgsl, linked only when the scene has them).
// Scene words (see mod.rs `encode`): node table entries [kind, a, b, mask]:
// kind 0: geometry group or transform chain down to one, a = instance;
// kind 1: group of instances only, a = BVH offset, b = leaf table of
// instance indices; kind 2: group with other children, leaves are instance
// indices or node indices | RT_NODE_BIT; kind 3: transform chain above a
// group or selector, a = offset of [object-to-world, world-to-object],
// b = the node below; kind 4: selector, a = offset of [visit case, visit
// record, child count, child nodes...]. mask is the AND of the visibility
// masks of the nodes the entry stands for. Instances of 36 words
// [object-to-world, world-to-object, BVH offset, primitive table, mask,
// node]; BVH nodes of 8 words [min xyz, max xyz, count, first]; geometry
// instances of 8 words [kind, positions, indices, normals, texcoords,
// material indices, material count, hit records].
const RT_NODE_BIT: u32 = 0x80000000u;

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
    var terminate = (rt_s_flags & 1u) != 0u;
    if ah != 0u && (rt_s_flags & 2u) == 0u {
        let saved_ray = rt_ray;
        let saved_t = rt_t;
        let saved_prim = rt_prim;
        rt_ray = rt_s_wray;
        rt_ray.tmax = rt_c_t;
        rt_t = rt_c_t;
        rt_prim = rt_c_prim;
        rt_ignored = false;
        rt_terminated = false;
        rt_anyhit_dispatch(ah, rt_scene[rec + 3u]);
        rt_ray = saved_ray;
        rt_t = saved_t;
        rt_prim = saved_prim;
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
    if rt_scene[g] == 0u {
        let ib = rt_scene[g + 2u] + prim * 3u;
        let pb = rt_scene[g + 1u];
        let a = rt_v3(pb + rt_scene[ib] * 3u);
        let b = rt_v3(pb + rt_scene[ib + 1u] * 3u);
        let c = rt_v3(pb + rt_scene[ib + 2u] * 3u);
        let t = rt_triangle(a, b, c, rt_s_oray, rt_s_tmax);
        if t < 0.0 {
            return;
        }
        if (rt_tri_front && (rt_s_flags & 16u) != 0u) || (!rt_tri_front && (rt_s_flags & 8u) != 0u) {
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
        rt_isect_dispatch(rt_scene[rec], rt_scene[rec + 1u], prim);
        rt_ray = saved_ray;
    }
}

const RT_FAR: f32 = 3.40282347e38;

// The primitives of instance `inst` (a geometry group's BVH, in the
// instance's object space).
fn rt_blas(inst: u32) {
    let ib = rt_scene[1] + inst * 36u;
    rt_o2w = rt_m4(ib);
    rt_w2o = rt_m4(ib + 16u);
    rt_blas_in(inst);
}

// The primitives of instance `inst` with rt_o2w and rt_w2o already set to
// its full transform.
fn rt_blas_in(inst: u32) {
    let ib = rt_scene[1] + inst * 36u;
    rt_s_inst = inst;
    var oray = rt_s_wray;
    oray.origin = (rt_w2o * vec4<f32>(rt_s_wray.origin, 1.0)).xyz;
    oray.direction = (rt_w2o * vec4<f32>(rt_s_wray.direction, 0.0)).xyz;
    rt_s_oray = oray;
    let bvh = rt_scene[ib + 32u];
    let prims = rt_scene[ib + 33u];
    let inv = 1.0 / oray.direction;
    if rt_aabb_hit(bvh, oray.origin, inv, oray.tmin, rt_s_tmax) == RT_FAR {
        return;
    }
    var stack: array<vec2<u32>, RT_BVH_STACK>;
    stack[0] = vec2<u32>(0u, 0u);
    var sp = 1u;
    while sp > 0u && !rt_s_done {
        sp = sp - 1u;
        let e = stack[sp];
        if bitcast<f32>(e.y) > rt_s_tmax {
            continue;
        }
        let n = bvh + e.x * 8u;
        let count = rt_node_word(n + 6u);
        let first = rt_node_word(n + 7u);
        if count > 0u {
            for (var i = first; i < first + count; i++) {
                let p = prims + i * 2u;
                rt_intersect_prim(rt_scene[p], rt_scene[p + 1u]);
                if rt_s_done {
                    break;
                }
            }
            continue;
        }
        let ta = rt_aabb_hit(bvh + first * 8u, oray.origin, inv, oray.tmin, rt_s_tmax);
        let tb = rt_aabb_hit(bvh + (first + 1u) * 8u, oray.origin, inv, oray.tmin, rt_s_tmax);
        var near = vec2<u32>(first, bitcast<u32>(ta));
        var far = vec2<u32>(first + 1u, bitcast<u32>(tb));
        if tb < ta {
            let tmp = near;
            near = far;
            far = tmp;
        }
        if bitcast<f32>(far.y) != RT_FAR && sp < RT_BVH_STACK {
            stack[sp] = far;
            sp = sp + 1u;
        }
        if bitcast<f32>(near.y) != RT_FAR && sp < RT_BVH_STACK {
            stack[sp] = near;
            sp = sp + 1u;
        }
    }
}

// After a search that found a hit: the word offset of the hit's record
// with the hit made the current ray state, or RT_NONE when no closest-hit
// program runs (none set, or the ray's flags disable it).
fn rt_enter_hit(ray: RtRay, flags: u32) -> u32 {
    let g = rt_scene[2] + rt_h_gi * 8u;
    let rec = rt_scene[g + 7u] + (rt_h_mat * rt_scene[4] + ray.ray_type) * 4u;
    if rt_scene[rec] == 0u || (flags & 4u) != 0u {
        return RT_NONE;
    }
    rt_ray = ray;
    rt_ray.tmax = rt_h_t;
    rt_t = rt_h_t;
    rt_prim = rt_h_prim;
    rt_hit_xform();
    return rec;
}

fn rt_search(object: u32, ray: RtRay, flags: u32, mask: u32) {
    rt_s_wray = ray;
    rt_s_flags = flags;
    rt_s_ray_type = ray.ray_type;
    rt_s_done = false;
    rt_s_tmax = ray.tmax;
    rt_h_found = false;
    let node = rt_scene[0] + object * 4u;
    if (rt_scene[node + 3u] & mask) == 0u {
        return;
    }
    let kind = rt_scene[node];
    if kind == 0u {
        rt_blas(rt_scene[node + 1u]);
        return;
    }
    if kind != 1u {
        rt_search_graph(object, mask);
        return;
    }
    let bvh = rt_scene[node + 1u];
    let leaves = rt_scene[node + 2u];
    let inv = 1.0 / ray.direction;
    if rt_aabb_hit(bvh, ray.origin, inv, ray.tmin, rt_s_tmax) == RT_FAR {
        return;
    }
    var stack: array<vec2<u32>, RT_BVH_STACK>;
    stack[0] = vec2<u32>(0u, 0u);
    var sp = 1u;
    while sp > 0u && !rt_s_done {
        sp = sp - 1u;
        let e = stack[sp];
        if bitcast<f32>(e.y) > rt_s_tmax {
            continue;
        }
        let n = bvh + e.x * 8u;
        let count = rt_node_word(n + 6u);
        let first = rt_node_word(n + 7u);
        if count > 0u {
            for (var i = first; i < first + count; i++) {
                let inst = rt_scene[leaves + i];
                if (rt_scene[rt_scene[1] + inst * 36u + 34u] & mask) != 0u {
                    rt_blas(inst);
                }
                if rt_s_done {
                    break;
                }
            }
            continue;
        }
        let ta = rt_aabb_hit(bvh + first * 8u, ray.origin, inv, ray.tmin, rt_s_tmax);
        let tb = rt_aabb_hit(bvh + (first + 1u) * 8u, ray.origin, inv, ray.tmin, rt_s_tmax);
        var near = vec2<u32>(first, bitcast<u32>(ta));
        var far = vec2<u32>(first + 1u, bitcast<u32>(tb));
        if tb < ta {
            let tmp = near;
            near = far;
            far = tmp;
        }
        if bitcast<f32>(far.y) != RT_FAR && sp < RT_BVH_STACK {
            stack[sp] = far;
            sp = sp + 1u;
        }
        if bitcast<f32>(near.y) != RT_FAR && sp < RT_BVH_STACK {
            stack[sp] = near;
            sp = sp + 1u;
        }
    }
}
