// A payload type's request slot, its stack of payloads and its request and result functions.
// (a template: rt-runtime's kernel/stack.rs fills the {names} in braces).
var<private> rt_rq_{w}: {w};
var<private> rt_pl_{w}: array<{w}, RT_DEPTHS>;
fn rt_request_{w}(object: u32, ray: RtRay, prd: {w}, flags: u32, mask: u32) {
    rt_rq_obj = object;
    rt_rq_ray = ray;
    rt_rq_flags = flags;
    rt_rq_mask = mask;
    rt_rq_type = {id}u;
    rt_rq_{w} = prd;
}
fn rt_result_{w}() -> {w} {
    return rt_rq_{w};
}
