
// ---- traversal ----
// The fast path is two levels (a group's BVH over instances, each a
// transform over a geometry group's BVH of primitives); deeper graphs
// (groups of groups, transforms above groups, selectors) go through
// rt_search_graph (graph.wgsl, linked only when the scene has them).
// Scene words (see mod.rs `encode`): node table entries [kind, a, b, mask]
// with kinds RT_NODE_* (rt-abi's NodeEntry, which says what a and b are);
// instances of RT_INST_WORDS words (rt-abi's InstanceRecord, read by the
// RT_INST_* offsets); BVH nodes of 8 words [min xyz, max
// xyz, count, first] in the BVH section; triangle slots of 10 words per
// primitive table entry, in the triangle section: the triangle's vertices
// in object space, then its material index, or RT_NONE when it has none
// (custom primitives, material index past the material count); geometry
// instances of 8 words [kind, positions, indices, normals, texcoords,
// material indices, material count, hit records].
const RT_NODE_BIT: u32 = 0x80000000u;

const RT_FAR: f32 = RT_F32_MAX;

// The primitives of instance `inst` (a geometry group's BVH, in the
// instance's object space).
fn rt_blas(inst: u32) {
    let ib = rt_scene[1] + inst * RT_INST_WORDS;
    rt_o2w = rt_m4(ib);
    rt_w2o = rt_m4(ib + RT_INST_W2O);
    rt_blas_in(inst);
}

// The primitives of instance `inst` with rt_o2w and rt_w2o already set to
// its full transform.
fn rt_blas_in(inst: u32) {
    if RT_TRIANGLES_ONLY {
        if RT_CWBVH {
            rt_blas_cwbvh(inst);
        } else {
            rt_blas_triangles(inst);
        }
        return;
    }
    let ib = rt_scene[1] + inst * RT_INST_WORDS;
    rt_s_inst = inst;
    var oray = rt_s_wray;
    oray.origin = (rt_w2o * vec4<f32>(rt_s_wray.origin, 1.0)).xyz;
    oray.direction = (rt_w2o * vec4<f32>(rt_s_wray.direction, 0.0)).xyz;
    rt_s_oray = oray;
    let bvh = rt_scene[ib + RT_INST_BVH];
    let prims = rt_scene[ib + RT_INST_PRIMS];
    let inv = rt_safe_inv(oray.direction);
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

// Marks a search stack entry that is an instance to search (its leaf in the
// group's leaf table, or RT_ROOT_LEAF: the traced node's own instance), not
// a node of the group's BVH.
const RT_INST_BIT: u32 = 0x80000000u;
const RT_ROOT_LEAF: u32 = 0x7fffffffu;

// One loop for a geometry group (one instance on the stack) and a group of
// instances (its BVH; a leaf pushes its instances, popped in leaf order):
// rt_blas is called from one place, so the kernel holds one copy of the
// instance search per trace. (llvmpipe runs a loop no lane takes, and
// pays for code size: a second copy cost a fifth of the AO workload's
// time.)
fn rt_search(object: u32, ray: RtRay, flags: u32, mask: u32) {
    rt_s_wray = ray;
    rt_s_flags = flags;
    rt_s_ray_type = ray.ray_type;
    rt_s_done = false;
    rt_s_tmax = ray.tmax;
    rt_h_found = false;
    let node = rt_scene[0] + object * 4u;
    if !rt_visible(rt_scene[node + 3u], mask) {
        return;
    }
    let kind = rt_scene[node];
    if kind != RT_NODE_INSTANCE && kind != RT_NODE_INSTANCE_GROUP {
        rt_search_graph(object, mask);
        return;
    }
    if !RT_GROUPS {
        // No group of instances in the scene (the linker's RT_GROUPS): the
        // object is one instance, searched without the loop below (its
        // stack and control flow cost llvmpipe a fifth of a search).
        rt_s_ipath = vec2<u32>(0u, RT_NONE);
        rt_blas(rt_scene[node + 1u]);
        return;
    }
    let bvh = rt_scene[node + 1u];
    let leaves = rt_scene[node + 2u];
    let inv = rt_safe_inv(ray.direction);
    var stack: array<vec2<u32>, RT_TLAS_STACK>;
    var sp = 0u;
    if kind == RT_NODE_INSTANCE {
        stack[0] = vec2<u32>(RT_ROOT_LEAF | RT_INST_BIT, 0u);
        sp = 1u;
    } else if rt_aabb_hit(bvh, ray.origin, inv, ray.tmin, rt_s_tmax) != RT_FAR {
        stack[0] = vec2<u32>(0u, 0u);
        sp = 1u;
    }
    while sp > 0u && !rt_s_done {
        sp = sp - 1u;
        let e = stack[sp];
        if bitcast<f32>(e.y) > rt_s_tmax {
            continue;
        }
        if (e.x & RT_INST_BIT) != 0u {
            // Leaves are [instance, its first instance index].
            let leaf = e.x & ~RT_INST_BIT;
            var inst = rt_scene[node + 1u];
            rt_s_ipath = vec2<u32>(0u, RT_NONE);
            if leaf != RT_ROOT_LEAF {
                inst = rt_scene[leaves + leaf * 2u];
                rt_s_ipath.x = rt_scene[leaves + leaf * 2u + 1u];
            }
            rt_blas(inst);
            continue;
        }
        let n = bvh + e.x * 8u;
        let count = rt_node_word(n + 6u);
        let first = rt_node_word(n + 7u);
        if count > 0u {
            // The leaf's instances, last first: popped in leaf order, each
            // at the leaf's entry distance (its bounds hold theirs).
            for (var i = first + count; i > first; i--) {
                let inst = rt_scene[leaves + (i - 1u) * 2u];
                if rt_visible(rt_scene[rt_scene[1] + inst * RT_INST_WORDS + RT_INST_MASK], mask) && sp < RT_TLAS_STACK {
                    stack[sp] = vec2<u32>((i - 1u) | RT_INST_BIT, e.y);
                    sp = sp + 1u;
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
        if bitcast<f32>(far.y) != RT_FAR && sp < RT_TLAS_STACK {
            stack[sp] = far;
            sp = sp + 1u;
        }
        if bitcast<f32>(near.y) != RT_FAR && sp < RT_TLAS_STACK {
            stack[sp] = near;
            sp = sp + 1u;
        }
    }
}

// ---- triangles without any-hit programs ----
// Kernels with no intersection and no any-hit program (RT_TRIANGLES_ONLY,
// set by the linker) search instances here: every primitive is a
// triangle and every candidate nearer than the closest hit commits, so the
// search keeps its state in locals, reads each triangle's nine vertex
// words and its material word from the triangle section in BVH leaf order,
// and fills the hit state once at the end. Same hits as rt_blas_in's
// general loop (same tests, same order); llvmpipe runs both sides of every
// branch under a lane mask, so the loop body's size is its cost.

// Vertex k (0-2) of the triangle slot at word w of the triangle section.
fn rt_slot_vertex(w: u32, k: u32) -> vec3<f32> {
    let v = w + k * 3u;
    return vec3<f32>(bitcast<f32>(rt_tri_word(v)), bitcast<f32>(rt_tri_word(v + 1u)), bitcast<f32>(rt_tri_word(v + 2u)));
}

// rt_triangle with the shear precomputed, on the triangle slot at word w:
// t (negative on a miss), the barycentrics of vertices 1 and 2 in *bary.
// A slot no hit may commit on (a material index past the instance's
// materials) holds NaN vertices, so it never hits.
fn rt_triangle_sheared(w: u32, o: vec3<f32>, sh: RtShear, tmin: f32, tmax: f32, bary: ptr<function, vec2<f32>>) -> f32 {
    return rt_watertight(rt_slot_vertex(w, 0u), rt_slot_vertex(w, 1u), rt_slot_vertex(w, 2u), o, sh, tmin, tmax, bary);
}

// The triangle slot at word w as a candidate of the lean search: its t
// (negative when the ray misses it, or when the ray's flags cull the side
// it meets: asked only when a cull flag is set), barycentrics in *bary.
fn rt_slot_candidate(w: u32, o: vec3<f32>, d: vec3<f32>, sh: RtShear, tmin: f32, tmax: f32, flags: u32, bary: ptr<function, vec2<f32>>) -> f32 {
    let t = rt_triangle_sheared(w, o, sh, tmin, tmax, bary);
    if t >= 0.0 && (flags & (RT_RAY_FLAG_CULL_FRONT_FACING | RT_RAY_FLAG_CULL_BACK_FACING)) != 0u {
        let front = rt_front(rt_slot_vertex(w, 0u), rt_slot_vertex(w, 1u), rt_slot_vertex(w, 2u), d);
        if (front && (flags & RT_RAY_FLAG_CULL_FRONT_FACING) != 0u) || (!front && (flags & RT_RAY_FLAG_CULL_BACK_FACING) != 0u) {
            return -1.0;
        }
    }
    return t;
}

// Commits the lean search's hit on triangle slot `slot` of instance `inst`
// (its primitive table and triangle slots in the same order).
fn rt_commit_slot(inst: u32, slot: u32, t: f32, bary: vec2<f32>, done: bool) {
    let ib = rt_scene[1] + inst * RT_INST_WORDS;
    let p = rt_scene[ib + RT_INST_PRIMS] + slot * 2u;
    rt_s_inst = inst;
    rt_h_ipath = rt_s_ipath;
    rt_s_tmax = t;
    rt_h_found = true;
    rt_h_t = t;
    rt_h_gi = rt_scene[p];
    rt_h_prim = rt_scene[p + 1u];
    rt_h_mat = rt_tri_word(rt_scene[ib + RT_INST_TRIS] + slot * 10u + 9u);
    rt_h_inst = inst;
    rt_h_custom = false;
    rt_h_bary = bary;
    rt_commit_xform();
    rt_s_done = done;
}

fn rt_blas_triangles(inst: u32) {
    let ib = rt_scene[1] + inst * RT_INST_WORDS;
    let o = (rt_w2o * vec4<f32>(rt_s_wray.origin, 1.0)).xyz;
    let d = (rt_w2o * vec4<f32>(rt_s_wray.direction, 0.0)).xyz;
    let tmin = rt_s_wray.tmin;
    let bvh = rt_scene[ib + RT_INST_BVH];
    let tris = rt_scene[ib + RT_INST_TRIS];
    let inv = rt_safe_inv(d);
    var tmax = rt_s_tmax;
    if rt_aabb_hit(bvh, o, inv, tmin, tmax) == RT_FAR {
        return;
    }
    let sh = rt_shear(d);
    if !sh.ok {
        // A zero direction: rt_triangle misses every triangle.
        return;
    }
    let flags = rt_s_flags;
    let terminate = (flags & RT_RAY_FLAG_TERMINATE_ON_FIRST_HIT) != 0u;
    var hit = RT_NONE;
    var hit_bary = vec2<f32>();
    var done = false;
    var stack: array<u32, RT_BVH_STACK>;
    stack[0] = 0u;
    var sp = 1u;
    while sp > 0u && !done {
        sp = sp - 1u;
        let n = bvh + stack[sp] * 8u;
        let count = rt_node_word(n + 6u);
        let first = rt_node_word(n + 7u);
        if count > 0u {
            for (var i = first; i < first + count; i++) {
                var bary: vec2<f32>;
                let t = rt_slot_candidate(tris + i * 10u, o, d, sh, tmin, tmax, flags, &bary);
                if t >= 0.0 {
                    tmax = t;
                    hit = i;
                    hit_bary = bary;
                    if terminate {
                        done = true;
                        break;
                    }
                }
            }
            continue;
        }
        let ta = rt_aabb_hit(bvh + first * 8u, o, inv, tmin, tmax);
        let tb = rt_aabb_hit(bvh + (first + 1u) * 8u, o, inv, tmin, tmax);
        var near = first;
        var far = first + 1u;
        if tb < ta {
            near = first + 1u;
            far = first;
        }
        if max(ta, tb) != RT_FAR && sp < RT_BVH_STACK {
            stack[sp] = far;
            sp = sp + 1u;
        }
        if min(ta, tb) != RT_FAR && sp < RT_BVH_STACK {
            stack[sp] = near;
            sp = sp + 1u;
        }
    }
    if hit != RT_NONE {
        rt_commit_slot(inst, hit, tmax, hit_bary, done);
    }
}

// ---- triangles without any-hit programs, over 8-wide nodes ----
// Where every geometry group has a CWBVH (obvhs's compressed wide BVH,
// Ylitie et al. 2017: 8 children a node, boxes quantized to a byte per
// plane, up to 3 triangles a leaf; RT_CWBVH, set by the linker), the lean
// search walks it instead of the BVH2: same tests, same commit, a fraction
// of the node visits (on lavapipe about 1.5-2.4x the speed of the BVH2
// kernel, BENCHMARKS.md). The triangle slots are in the CWBVH's primitive
// order then. Nodes are 20 words (mod.rs `cwbvh_node_words`).

// Byte `i` (0-3) of a word, as a float.
fn rt_byte_f(w: u32, i: u32) -> f32 {
    return f32((w >> (i * 8u)) & 0xffu);
}

// The children of the node at word `n` of the BVH nodes that the ray segment
// enters: internal children as bits 24-31 (at the slot the ray's octant
// orders them to), leaf children as their triangles' bits 0-23.
fn rt_cw_node_hits(n: u32, o: vec3<f32>, inv: vec3<f32>, oct_inv4: u32, tmin: f32, tmax: f32) -> u32 {
    let p = rt_node_v3(n);
    let ew = rt_node_word(n + 3u);
    // The node's scale per axis: a power of two with the stored exponent.
    let e = vec3<f32>(
        bitcast<f32>((ew & 0xffu) << 23u),
        bitcast<f32>(((ew >> 8u) & 0xffu) << 23u),
        bitcast<f32>(((ew >> 16u) & 0xffu) << 23u),
    );
    let scale = e * inv;
    let shift = (p - o) * inv;
    var hits = 0u;
    for (var half = 0u; half < 2u; half++) {
        // Per byte of the child meta: internal children have 24-31 (bits 3
        // and 4 set) and take their slot in the octant's order as bit
        // index; a leaf's bit index is its first triangle, its bits the
        // unary triangle count.
        let cm = rt_node_word(n + 6u + half);
        let inner = ((cm & (cm << 1u)) & 0x10101010u) >> 4u;
        let index4 = (cm ^ (oct_inv4 & (inner * 0xffu))) & 0x1f1f1f1fu;
        let bits4 = (cm >> 5u) & 0x07070707u;
        let lox = rt_node_word(n + 8u + half);
        let hix = rt_node_word(n + 10u + half);
        let loy = rt_node_word(n + 12u + half);
        let hiy = rt_node_word(n + 14u + half);
        let loz = rt_node_word(n + 16u + half);
        let hiz = rt_node_word(n + 18u + half);
        for (var i = 0u; i < 4u; i++) {
            let t0 = vec3<f32>(rt_byte_f(lox, i), rt_byte_f(loy, i), rt_byte_f(loz, i)) * scale + shift;
            let t1 = vec3<f32>(rt_byte_f(hix, i), rt_byte_f(hiy, i), rt_byte_f(hiz, i)) * scale + shift;
            let lo = min(t0, t1);
            let hi = max(t0, t1);
            if max(max(max(lo.x, lo.y), lo.z), tmin) <= min(min(min(hi.x, hi.y), hi.z), tmax) {
                let sh = i * 8u;
                hits |= ((bits4 >> sh) & 0xffu) << ((index4 >> sh) & 0xffu);
            }
        }
    }
    return hits;
}

fn rt_blas_cwbvh(inst: u32) {
    let ib = rt_scene[1] + inst * RT_INST_WORDS;
    let cw = rt_scene[ib + RT_INST_BVH];
    if cw == RT_NONE {
        // A geometry group without primitives.
        return;
    }
    let o = (rt_w2o * vec4<f32>(rt_s_wray.origin, 1.0)).xyz;
    let d = (rt_w2o * vec4<f32>(rt_s_wray.direction, 0.0)).xyz;
    let tmin = rt_s_wray.tmin;
    let tris = rt_scene[ib + RT_INST_TRIS];
    let inv = rt_safe_inv(d);
    var tmax = rt_s_tmax;
    let sh = rt_shear(d);
    if !sh.ok {
        // A zero direction: rt_triangle misses every triangle.
        return;
    }
    let flags = rt_s_flags;
    let terminate = (flags & RT_RAY_FLAG_TERMINATE_ON_FIRST_HIT) != 0u;
    let oct_inv4 = select(0x04040404u, 0u, d.x < 0.0) | select(0x02020202u, 0u, d.y < 0.0)
        | select(0x01010101u, 0u, d.z < 0.0);
    var hit = RT_NONE;
    var hit_bary = vec2<f32>();
    var done = false;
    // Groups of (first child node, hit bits 24-31 | the node's imask) and
    // of (first triangle, triangle bits); the root as the one child of a
    // virtual node.
    var stack: array<vec2<u32>, RT_CW_STACK>;
    var sp = 0u;
    var nodes_left = vec2<u32>(0u, 0x80000000u);
    var tris_left = vec2<u32>(0u, 0u);
    loop {
        while tris_left.y != 0u {
            let k = firstLeadingBit(tris_left.y);
            tris_left.y &= ~(1u << k);
            let i = tris_left.x + k;
            var bary: vec2<f32>;
            let t = rt_slot_candidate(tris + i * 10u, o, d, sh, tmin, tmax, flags, &bary);
            if t >= 0.0 {
                tmax = t;
                hit = i;
                hit_bary = bary;
                if terminate {
                    done = true;
                    break;
                }
            }
        }
        if done {
            break;
        }
        if (nodes_left.y & 0xff000000u) != 0u {
            let mask = nodes_left.y;
            let bit = firstLeadingBit(mask);
            nodes_left.y &= ~(1u << bit);
            if (nodes_left.y & 0xff000000u) != 0u && sp < RT_CW_STACK {
                stack[sp] = nodes_left;
                sp += 1u;
            }
            // The child's slot, and its rank among the node's internal
            // children.
            let slot = (bit - 24u) ^ (oct_inv4 & 0xffu);
            let n = cw + (nodes_left.x + countOneBits(mask & ~(0xffffffffu << slot))) * 20u;
            let hits = rt_cw_node_hits(n, o, inv, oct_inv4, tmin, tmax);
            nodes_left = vec2<u32>(rt_node_word(n + 4u), (hits & 0xff000000u) | (rt_node_word(n + 3u) >> 24u));
            tris_left = vec2<u32>(rt_node_word(n + 5u), hits & 0x00ffffffu);
        } else {
            nodes_left = vec2<u32>(0u, 0u);
        }
        if tris_left.y == 0u && (nodes_left.y & 0xff000000u) == 0u {
            if sp == 0u {
                break;
            }
            sp -= 1u;
            nodes_left = stack[sp];
        }
    }
    if hit != RT_NONE {
        rt_commit_slot(inst, hit, tmax, hit_bary, done);
    }
}
