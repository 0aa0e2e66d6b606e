// The baseline kernel's traversal as a hardware ray query (after
// handwritten_common.wgsl, with `enable wgpu_ray_query;` before both): one
// TLAS instance over one opaque triangle BLAS, triangles by index.
@group(0) @binding(0) var acc: acceleration_structure;

fn closest(o: vec3<f32>, d: vec3<f32>, tmin: f32) -> f32 {
    var rq: ray_query;
    rayQueryInitialize(&rq, acc, RayDesc(RAY_FLAG_FORCE_OPAQUE, 0xffu, tmin, FAR, o, d));
    while rayQueryProceed(&rq) {}
    let h = rayQueryGetCommittedIntersection(&rq);
    hit_prim = 0xffffffffu;
    if h.kind == RAY_QUERY_INTERSECTION_TRIANGLE {
        hit_prim = h.primitive_index;
        return h.t;
    }
    return FAR;
}
