
// ---- traversal: hardware ray queries ----
// Each traced root is a TLAS (bound as rt_tlas<slot>; rt_search, generated
// by the linker, picks the root's slot from the side table
// rt_query_side), each
// geometry group one or two BLASes (its triangles, its custom primitives'
// boxes). The loop below is OptiX's program model over a ray query, as
// Vulkan runs any-hit and intersection code inline: a triangle candidate
// (only non-opaque geometry: it has an any-hit program, or a material index
// out of range) goes to rt_report, which runs any hit and says whether to
// confirm it; a box candidate runs the intersection program, whose
// accepted reports generate the intersection. Opaque triangles commit in
// the hardware without a candidate. Afterwards a committed triangle fills
// the hit state from the query; a generated one filled it when reported.
//
// Side table rt_query_side: [0] the node count n; [1] the ray type count r;
// [2 + ray type] 1 where no traced geometry needs a candidate for that ray
// type (no any-hit program of the type, every material index in range):
// its traces force the query opaque; [2 + r + 2 node] the node's TLAS slot
// (RT_NONE: not a root) and [+ 1] where its TLAS instances' paths are (two
// words per TLAS instance index, rt_s_ipath's form); [2 + r + 2 n + custom]
// (custom = instance record * 2 + part, the TLAS instance's custom data)
// where the part's geometry instances start, one word per BLAS geometry
// index.

// Where the traced root's paths are in the side table.
var<private> rt_q_paths: u32;

// The committed hit's transforms are kept (KEPT_XFORM in kernel/mod.rs):
// a triangle's come from the committed intersection.

fn rt_query_m43(m: mat4x3<f32>) -> mat4x4<f32> {
    return mat4x4<f32>(vec4<f32>(m[0], 0.0), vec4<f32>(m[1], 0.0), vec4<f32>(m[2], 0.0), vec4<f32>(m[3], 1.0));
}

// Where the side table's node slots start.
fn rt_query_nodes() -> u32 {
    return 2u + rt_query_side[1];
}

// The TLAS slot of node `object` (RT_NONE: not a root).
fn rt_query_slot(object: u32) -> u32 {
    if object >= rt_query_side[0] {
        return RT_NONE;
    }
    return rt_query_side[rt_query_nodes() + object * 2u];
}

// The path (rt_s_ipath) of TLAS instance `i` of the traced root.
fn rt_query_path(i: u32) -> vec2<u32> {
    return vec2<u32>(rt_query_side[rt_q_paths + i * 2u], rt_query_side[rt_q_paths + i * 2u + 1u]);
}

// The geometry instance of BLAS geometry `geometry` of the TLAS instance
// with custom data `custom`.
fn rt_query_gi(custom: u32, geometry: u32) -> u32 {
    return rt_query_side[rt_query_side[rt_query_nodes() + rt_query_side[0] * 2u + custom] + geometry];
}

// Triangle `prim`'s material index in geometry instance `gi`.
fn rt_query_material(gi: u32, prim: u32) -> u32 {
    let g = rt_scene[2] + gi * 8u;
    if rt_scene[g + 5u] == RT_NONE {
        return 0u;
    }
    return rt_scene[rt_scene[g + 5u] + prim];
}

// The query's flags for a ray of type `ray_type` with RT_RAY_FLAG_* flags
// `flags`.
fn rt_query_flags(flags: u32, ray_type: u32) -> u32 {
    var q = RAY_FLAG_NONE;
    let opaque_type = ray_type < rt_query_side[1] && rt_query_side[2u + ray_type] != 0u;
    if (flags & RT_RAY_FLAG_DISABLE_ANYHIT) != 0u || opaque_type {
        q = q | RAY_FLAG_FORCE_OPAQUE;
    }
    if (flags & RT_RAY_FLAG_TERMINATE_ON_FIRST_HIT) != 0u {
        q = q | RAY_FLAG_TERMINATE_ON_FIRST_HIT;
    }
    if (flags & RT_RAY_FLAG_CULL_BACK_FACING) != 0u {
        q = q | RAY_FLAG_CULL_BACK_FACING;
    }
    if (flags & RT_RAY_FLAG_CULL_FRONT_FACING) != 0u {
        q = q | RAY_FLAG_CULL_FRONT_FACING;
    }
    return q;
}

fn rt_query_search(acs: acceleration_structure, ray: RtRay, flags: u32, mask: u32) {
    var rq: ray_query;
    rayQueryInitialize(&rq, acs, RayDesc(rt_query_flags(flags, ray.ray_type), mask & 0xffu, ray.tmin, ray.tmax, ray.origin, ray.direction));
    // The t of the last generated intersection (the closest: each is
    // generated only nearer than what is committed). Lavapipe does not
    // report a committed generated intersection as one (its kind and t read
    // otherwise), so the loop keeps its own and reads the query only for
    // triangles.
    var generated = ray.tmax;
    while rayQueryProceed(&rq) {
        let c = rayQueryGetCandidateIntersection(&rq);
        let committed = rayQueryGetCommittedIntersection(&rq);
        rt_s_tmax = generated;
        if committed.kind == RAY_QUERY_INTERSECTION_TRIANGLE {
            rt_s_tmax = min(committed.t, generated);
        }
        rt_s_inst = c.instance_custom_data >> 1u;
        rt_s_ipath = rt_query_path(c.instance_index);
        rt_o2w = rt_query_m43(c.object_to_world);
        rt_w2o = rt_query_m43(c.world_to_object);
        let gi = rt_query_gi(c.instance_custom_data, c.geometry_index);
        if c.kind == RAY_QUERY_INTERSECTION_TRIANGLE {
            if !(c.t < rt_s_tmax) {
                continue;
            }
            rt_s_gi = gi;
            rt_c_prim = c.primitive_index;
            rt_c_t = c.t;
            rt_c_bary = c.barycentrics;
            rt_c_ok = true;
            rt_c_custom = false;
            if rt_report(rt_query_material(gi, c.primitive_index)) {
                rayQueryConfirmIntersection(&rq);
            }
        } else {
            var oray = ray;
            oray.origin = (rt_w2o * vec4<f32>(ray.origin, 1.0)).xyz;
            oray.direction = (rt_w2o * vec4<f32>(ray.direction, 0.0)).xyz;
            rt_s_oray = oray;
            let before = rt_s_tmax;
            rt_intersect_prim(gi, c.primitive_index);
            // (A named value: naga 30 does not emit an expression written
            // in the call itself before the call.)
            let reported = rt_s_tmax;
            if reported < before {
                rayQueryGenerateIntersection(&rq, reported);
                generated = reported;
            }
        }
        if rt_s_done {
            rayQueryTerminate(&rq);
        }
    }
    let h = rayQueryGetCommittedIntersection(&rq);
    if h.kind == RAY_QUERY_INTERSECTION_TRIANGLE && h.t < generated {
        let gi = rt_query_gi(h.instance_custom_data, h.geometry_index);
        rt_h_found = true;
        rt_h_t = h.t;
        rt_h_gi = gi;
        rt_h_prim = h.primitive_index;
        rt_h_mat = rt_query_material(gi, h.primitive_index);
        rt_h_inst = h.instance_custom_data >> 1u;
        rt_h_ipath = rt_query_path(h.instance_index);
        rt_h_custom = false;
        rt_h_bary = h.barycentrics;
        rt_h_o2w = rt_query_m43(h.object_to_world);
        rt_h_w2o = rt_query_m43(h.world_to_object);
    } else if !(generated < ray.tmax) {
        rt_h_found = false;
    }
    // Else a generated intersection is the closest: rt_report filled the
    // hit state when it was reported.
}

// The search state for a trace of `ray` (rt_search, generated with the
// slots, calls this, then rt_query_search on the root's TLAS).
fn rt_query_begin(ray: RtRay, flags: u32) {
    rt_s_wray = ray;
    rt_s_flags = flags;
    rt_s_ray_type = ray.ray_type;
    rt_s_done = false;
    rt_s_tmax = ray.tmax;
    rt_h_found = false;
}
