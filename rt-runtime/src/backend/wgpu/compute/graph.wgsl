
// ---- general graph traversal: groups of groups, transforms above groups
// and selectors (linked only when the scene has them; the generator
// defines RT_LEVELS, 1 + the deepest nesting of transform entries) ----
//
// One explicit stack of entries vec4(node, BVH node or RT_NONE, entry t,
// level), each with its instance path (rt_s_ipath's form), walks the graph depth first without recursion: RT_NONE entries
// enter a graph node (never pruned by distance: like the CPU backend,
// every child in a leaf the ray reaches is entered), others are BVH nodes
// of group `node`. `level` names
// the transform space the entry lives in: level 0 is world space, a
// transform entry at level l puts its child at level l + 1. Levels on the
// stack never decrease from bottom to top, so entering a transform can
// overwrite level l + 1: every entry of the previous occupant is gone.

// RT_GRAPH_STACK (defined by the linker) is sized from the scene's deepest
// BVH and RT_LEVELS, so no entry is ever dropped.

var<private> rt_g_o2w: array<mat4x4<f32>, RT_LEVELS>;
var<private> rt_g_w2o: array<mat4x4<f32>, RT_LEVELS>;
var<private> rt_g_org: array<vec3<f32>, RT_LEVELS>;
var<private> rt_g_dir: array<vec3<f32>, RT_LEVELS>;
var<private> rt_g_inv: array<vec3<f32>, RT_LEVELS>;
// The committed hit's transforms are kept (KEPT_XFORM in kernel/mod.rs):
// instances under transform entries have no single matrix in the
// instance table.

fn rt_enter_level(level: u32, o2w: mat4x4<f32>, w2o: mat4x4<f32>) {
    rt_g_o2w[level] = o2w;
    rt_g_w2o[level] = w2o;
    rt_g_org[level] = (w2o * vec4<f32>(rt_s_wray.origin, 1.0)).xyz;
    let d = (w2o * vec4<f32>(rt_s_wray.direction, 0.0)).xyz;
    rt_g_dir[level] = d;
    rt_g_inv[level] = rt_safe_inv(d);
}

// Instance `inst` seen from transform level `level`, reached by `path`.
fn rt_graph_instance(inst: u32, level: u32, mask: u32, path: vec2<u32>) {
    let ib = rt_scene[1] + inst * RT_INST_WORDS;
    if !rt_visible(rt_scene[ib + RT_INST_MASK], mask) {
        return;
    }
    rt_s_ipath = path;
    rt_o2w = rt_g_o2w[level] * rt_m4(ib);
    rt_w2o = rt_m4(ib + RT_INST_W2O) * rt_g_w2o[level];
    rt_blas_in(inst);
}

// Runs selector `sel`'s visit program with the ray in the selector's space
// (tmax the closest hit so far): the chosen child, or RT_NONE.
fn rt_visit(sel: u32, level: u32) -> u32 {
    let saved_ray = rt_ray;
    rt_ray = rt_s_wray;
    rt_ray.origin = rt_g_org[level];
    rt_ray.direction = rt_g_dir[level];
    rt_ray.tmax = rt_s_tmax;
    let child = rt_visit_dispatch(rt_scene[sel], rt_scene[sel + 1u]);
    rt_ray = saved_ray;
    return child;
}

fn rt_search_graph(object: u32, mask: u32) {
    let identity = mat4x4<f32>(vec4<f32>(1.0, 0.0, 0.0, 0.0), vec4<f32>(0.0, 1.0, 0.0, 0.0), vec4<f32>(0.0, 0.0, 1.0, 0.0), vec4<f32>(0.0, 0.0, 0.0, 1.0));
    rt_enter_level(0u, identity, identity);
    var stack: array<vec4<u32>, RT_GRAPH_STACK>;
    var paths: array<vec2<u32>, RT_GRAPH_STACK>;
    stack[0] = vec4<u32>(object, RT_NONE, 0u, 0u);
    paths[0] = vec2<u32>(0u, RT_NONE);
    var sp = 1u;
    while sp > 0u && !rt_s_done {
        sp = sp - 1u;
        let e = stack[sp];
        let path = paths[sp];
        if e.y != RT_NONE && bitcast<f32>(e.z) > rt_s_tmax {
            continue;
        }
        let level = e.w;
        let node = rt_scene[0] + e.x * 4u;
        let kind = rt_scene[node];
        let org = rt_g_org[level];
        let inv = rt_g_inv[level];
        if e.y == RT_NONE {
            // Enter graph node e.x.
            if !rt_visible(rt_scene[node + 3u], mask) {
                continue;
            }
            switch kind {
                case RT_NODE_INSTANCE: {
                    rt_graph_instance(rt_scene[node + 1u], level, mask, path);
                }
                case RT_NODE_INSTANCE_GROUP, RT_NODE_GROUP: {
                    let t = rt_aabb_hit(rt_scene[node + 1u], org, inv, rt_s_wray.tmin, rt_s_tmax);
                    if t != RT_FAR && sp < RT_GRAPH_STACK {
                        stack[sp] = vec4<u32>(e.x, 0u, bitcast<u32>(t), level);
                        paths[sp] = path;
                        sp = sp + 1u;
                    }
                }
                case RT_NODE_TRANSFORM: {
                    if level + 1u < RT_LEVELS && sp < RT_GRAPH_STACK {
                        let m = rt_scene[node + 1u];
                        rt_enter_level(level + 1u, rt_g_o2w[level] * rt_m4(m), rt_m4(m + 16u) * rt_g_w2o[level]);
                        stack[sp] = vec4<u32>(rt_scene[node + 2u], RT_NONE, 0u, level + 1u);
                        // The chain's instance id, after its matrices.
                        paths[sp] = path;
                        if rt_scene[m + 32u] != RT_NONE {
                            paths[sp].y = rt_scene[m + 32u];
                        }
                        sp = sp + 1u;
                    }
                }
                case RT_NODE_MOTION_TRANSFORM: {
                    // The transform at the ray's time (motion.wgsl); a
                    // singular instant hides the child.
                    let m = rt_scene[node + 1u];
                    let own = rt_motion_matrix(m);
                    let inv = rt_affine_inverse(own);
                    if inv[3].w == 1.0 && level + 1u < RT_LEVELS && sp < RT_GRAPH_STACK {
                        rt_enter_level(level + 1u, rt_g_o2w[level] * own, inv * rt_g_w2o[level]);
                        stack[sp] = vec4<u32>(rt_scene[node + 2u], RT_NONE, 0u, level + 1u);
                        // The transform's instance id comes first.
                        paths[sp] = path;
                        if rt_scene[m] != RT_NONE {
                            paths[sp].y = rt_scene[m];
                        }
                        sp = sp + 1u;
                    }
                }
                case RT_NODE_SELECTOR: {
                    let sel = rt_scene[node + 1u];
                    let child = rt_visit(sel, level);
                    let count = rt_scene[sel + 2u];
                    if child < count && sp < RT_GRAPH_STACK {
                        stack[sp] = vec4<u32>(rt_scene[sel + 3u + child], RT_NONE, 0u, level);
                        // The children's instance offsets follow them.
                        paths[sp] = vec2<u32>(path.x + rt_scene[sel + 3u + count + child], path.y);
                        sp = sp + 1u;
                    }
                }
                default: {}
            }
            continue;
        }
        // BVH node e.y of group e.x.
        let bvh = rt_scene[node + 1u];
        let leaves = rt_scene[node + 2u];
        let n = bvh + e.y * 8u;
        let count = rt_node_word(n + 6u);
        let first = rt_node_word(n + 7u);
        if count > 0u {
            // Instances now; other children pushed, visited in leaf order.
            // Leaves are [instance or node, its first instance index].
            for (var i = first + count; i > first; i--) {
                let leaf = rt_scene[leaves + (i - 1u) * 2u];
                let below = vec2<u32>(path.x + rt_scene[leaves + (i - 1u) * 2u + 1u], path.y);
                if (leaf & RT_NODE_BIT) == 0u {
                    rt_graph_instance(leaf, level, mask, below);
                    if rt_s_done {
                        break;
                    }
                } else if sp < RT_GRAPH_STACK {
                    stack[sp] = vec4<u32>(leaf & ~RT_NODE_BIT, RT_NONE, 0u, level);
                    paths[sp] = below;
                    sp = sp + 1u;
                }
            }
            continue;
        }
        let ta = rt_aabb_hit(bvh + first * 8u, org, inv, rt_s_wray.tmin, rt_s_tmax);
        let tb = rt_aabb_hit(bvh + (first + 1u) * 8u, org, inv, rt_s_wray.tmin, rt_s_tmax);
        var near = vec4<u32>(e.x, first, bitcast<u32>(ta), level);
        var far = vec4<u32>(e.x, first + 1u, bitcast<u32>(tb), level);
        if tb < ta {
            let tmp = near;
            near = far;
            far = tmp;
        }
        if bitcast<f32>(far.z) != RT_FAR && sp < RT_GRAPH_STACK {
            stack[sp] = far;
            paths[sp] = path;
            sp = sp + 1u;
        }
        if bitcast<f32>(near.z) != RT_FAR && sp < RT_GRAPH_STACK {
            stack[sp] = near;
            paths[sp] = path;
            sp = sp + 1u;
        }
    }
}
