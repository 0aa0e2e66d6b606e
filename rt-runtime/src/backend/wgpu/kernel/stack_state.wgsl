// The trace stack's state: the request slot and one frame per trace depth.
// (a template: rt-runtime's kernel/stack.rs fills the {names} in braces).
const RT_DEPTHS: u32 = {depths}u;
var<private> rt_rs: u32;
var<private> rt_d: u32;
var<private> rt_rq_obj: u32;
var<private> rt_rq_ray: RtRay;
var<private> rt_rq_flags: u32;
var<private> rt_rq_mask: u32;
var<private> rt_rq_type: u32;
var<private> rt_st_case: array<u32, RT_DEPTHS>;
var<private> rt_st_vars: array<u32, RT_DEPTHS>;
var<private> rt_st_type: array<u32, RT_DEPTHS>;
var<private> rt_st_ray: array<RtRay, RT_DEPTHS>;
var<private> rt_st_t: array<f32, RT_DEPTHS>;
var<private> rt_st_time: array<f32, RT_DEPTHS>;
var<private> rt_st_prim: array<u32, RT_DEPTHS>;
var<private> rt_st_o2w: array<mat4x4<f32>, RT_DEPTHS>;
var<private> rt_st_w2o: array<mat4x4<f32>, RT_DEPTHS>;
// The caller's rt_hk, rt_rflags and rt_rmask.
var<private> rt_st_rs: array<vec3<u32>, RT_DEPTHS>;
// The caller's rt_icur.
var<private> rt_st_ic: array<vec4<u32>, RT_DEPTHS>;
