//! The intrinsics: what rt-std offers programs beyond plain math, which
//! kinds may call each, and the WGSL function each lowers to.

use crate::kinds::{Callers, Kind, Kind::*};

/// A type at the compiler-runtime boundary, as both sides spell it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AbiTy {
    Unit,
    Bool,
    U32,
    F32,
    UVec2,
    UVec3,
    Vec2,
    Vec3,
    Vec4,
    Mat4,
    /// `rt_std::Ray`, WGSL `RtRay`.
    Ray,
    /// `rt_std::TransformKind`, passed as `u32` (0 object to world, 1 world
    /// to object).
    TransformKind,
    /// A buffer handle, WGSL `RtBuffer`.
    Buffer,
    /// A sampler handle, WGSL `RtSampler`.
    Sampler,
    /// A 3D sampler handle, WGSL `RtSampler3d`.
    Sampler3d,
}

impl AbiTy {
    /// The WGSL type.
    pub fn wgsl(self) -> &'static str {
        match self {
            AbiTy::Unit => "",
            AbiTy::Bool => "bool",
            AbiTy::U32 | AbiTy::TransformKind => "u32",
            AbiTy::F32 => "f32",
            AbiTy::UVec2 => "vec2<u32>",
            AbiTy::UVec3 => "vec3<u32>",
            AbiTy::Vec2 => "vec2<f32>",
            AbiTy::Vec3 => "vec3<f32>",
            AbiTy::Vec4 => "vec4<f32>",
            AbiTy::Mat4 => "mat4x4<f32>",
            AbiTy::Ray => "RtRay",
            AbiTy::Buffer => "RtBuffer",
            AbiTy::Sampler => "RtSampler",
            AbiTy::Sampler3d => "RtSampler3d",
        }
    }

    /// The Rust type rt-std's CPU body takes or returns.
    pub fn rust(self) -> &'static str {
        match self {
            AbiTy::Unit => "()",
            AbiTy::Bool => "bool",
            AbiTy::U32 => "u32",
            AbiTy::F32 => "f32",
            AbiTy::UVec2 => "UVec2",
            AbiTy::UVec3 => "UVec3",
            AbiTy::Vec2 => "Vec2",
            AbiTy::Vec3 => "Vec3",
            AbiTy::Vec4 => "Vec4",
            AbiTy::Mat4 => "Mat4",
            AbiTy::Ray => "Ray",
            AbiTy::TransformKind => "TransformKind",
            AbiTy::Buffer => "RtBuffer",
            AbiTy::Sampler => "Sampler2d",
            AbiTy::Sampler3d => "Sampler3d",
        }
    }
}

/// A WGSL function the runtime's prelude defines and lowered programs call.
#[derive(Clone, Copy, Debug)]
pub struct WgslFn {
    pub name: &'static str,
    /// Parameter names and types.
    pub params: &'static [(&'static str, AbiTy)],
    pub ret: AbiTy,
}

/// How the compiler lowers a call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// An expression: the WGSL function called with the arguments, checked
    /// against its parameters.
    Value,
    /// A statement of its own (it has an effect and returns nothing).
    Statement,
    /// Lowered by the compiler's own code (the trace, the report, printf):
    /// its WGSL function, if any, has per-type variants.
    Special,
}

/// One intrinsic of rt-std that depends on the program kind.
#[derive(Clone, Copy, Debug)]
pub struct Intrinsic {
    /// Rust name in rt-std.
    pub name: &'static str,
    /// OptiX's name (rt-std carries it as `#[doc(alias)]`).
    pub optix: &'static str,
    pub callers: Callers,
    pub form: Form,
    /// The runtime function a call lowers to.
    pub wgsl: Option<WgslFn>,
}

const NOT_BOUNDS: &[Kind] = &[RayGeneration, Exception, ClosestHit, AnyHit, Miss, Intersection, Visit, Callable];
const RAY_KINDS: &[Kind] = &[ClosestHit, AnyHit, Miss, Intersection, Visit];
const HITS: &[Kind] = &[ClosestHit, AnyHit];
const TRACERS: &[Kind] = &[RayGeneration, ClosestHit, Miss];
const THROWERS: &[Kind] = &[RayGeneration, ClosestHit, AnyHit, Miss, Intersection, Visit, Callable];
const TRANSFORMERS: &[Kind] = &[ClosestHit, AnyHit, Intersection];
/// Kinds that run for one traced ray, whose flags and mask they may read.
const RAY_STATE: &[Kind] = &[ClosestHit, AnyHit, Miss, Intersection];

use AbiTy::*;

const fn row(
    name: &'static str,
    optix: &'static str,
    callers: &'static [Kind],
    form: Form,
    wgsl: &'static str,
    params: &'static [(&'static str, AbiTy)],
    ret: AbiTy,
) -> Intrinsic {
    Intrinsic { name, optix, callers: Callers::Only(callers), form, wgsl: Some(WgslFn { name: wgsl, params, ret }) }
}

/// Kind-restricted intrinsics. Math helpers, buffer and sampler methods are
/// callable from every kind and are not listed (their runtime functions are
/// in [`RUNTIME_FUNCTIONS`]).
pub const INTRINSICS: &[Intrinsic] = &[
    row("launch_index", "rtLaunchIndex", NOT_BOUNDS, Form::Value, "rt_launch_index", &[], UVec2),
    row("launch_dim", "rtLaunchDim", NOT_BOUNDS, Form::Value, "rt_launch_dim", &[], UVec2),
    row("launch_index_3d", "rtLaunchIndex", NOT_BOUNDS, Form::Value, "rt_launch_index_3d", &[], UVec3),
    row("launch_dim_3d", "rtLaunchDim", NOT_BOUNDS, Form::Value, "rt_launch_dim_3d", &[], UVec3),
    row("current_ray", "rtCurrentRay", RAY_KINDS, Form::Value, "rt_current_ray", &[], Ray),
    row("t_hit", "rtIntersectionDistance", HITS, Form::Value, "rt_t_hit", &[], F32),
    row("current_time", "rtCurrentTime", RAY_KINDS, Form::Value, "rt_current_time", &[], F32),
    row(
        "primitive_index",
        "rtPrimitiveIndex",
        &[ClosestHit, AnyHit, Intersection],
        Form::Value,
        "rt_primitive_index",
        &[],
        U32,
    ),
    row("exception_code", "rtGetExceptionCode", &[Exception], Form::Value, "rt_exception_code", &[], U32),
    Intrinsic { name: "rt_trace", optix: "rtTrace", callers: Callers::Only(TRACERS), form: Form::Special, wgsl: None },
    Intrinsic {
        name: "rt_trace_with",
        optix: "rtTrace",
        callers: Callers::Only(TRACERS),
        form: Form::Special,
        wgsl: None,
    },
    // `rt_trace_with` at a ray time: lowered as `rt_set_trace_time(time)`
    // (a runtime function) before the trace.
    Intrinsic {
        name: "rt_trace_at",
        optix: "rtTrace",
        callers: Callers::Only(TRACERS),
        form: Form::Special,
        wgsl: None,
    },
    row(
        "rt_potential_intersection",
        "rtPotentialIntersection",
        &[Intersection],
        Form::Value,
        "rt_potential_intersection",
        &[("t", F32)],
        Bool,
    ),
    row(
        "rt_report_intersection",
        "rtReportIntersection",
        &[Intersection],
        Form::Special,
        "rt_report_intersection",
        &[("material", U32)],
        Bool,
    ),
    row(
        "rt_ignore_intersection",
        "rtIgnoreIntersection",
        &[AnyHit],
        Form::Statement,
        "rt_ignore_intersection",
        &[],
        Unit,
    ),
    row("rt_terminate_ray", "rtTerminateRay", &[AnyHit], Form::Statement, "rt_terminate_ray", &[], Unit),
    row("rt_throw", "rtThrow", THROWERS, Form::Statement, "rt_throw", &[("code", U32)], Unit),
    row(
        "rt_transform_point",
        "rtTransformPoint",
        TRANSFORMERS,
        Form::Value,
        "rt_transform_point",
        &[("kind", TransformKind), ("p", Vec3)],
        Vec3,
    ),
    row(
        "rt_transform_vector",
        "rtTransformVector",
        TRANSFORMERS,
        Form::Value,
        "rt_transform_vector",
        &[("kind", TransformKind), ("v", Vec3)],
        Vec3,
    ),
    row(
        "rt_transform_normal",
        "rtTransformNormal",
        TRANSFORMERS,
        Form::Value,
        "rt_transform_normal",
        &[("kind", TransformKind), ("n", Vec3)],
        Vec3,
    ),
    row(
        "rt_get_transform",
        "rtGetTransform",
        TRANSFORMERS,
        Form::Value,
        "rt_get_transform",
        &[("kind", TransformKind)],
        Mat4,
    ),
    row("is_triangle_hit", "rtIsTriangleHit", HITS, Form::Value, "rt_is_triangle_hit", &[], Bool),
    row(
        "is_triangle_hit_front_face",
        "rtIsTriangleHitFrontFace",
        HITS,
        Form::Value,
        "rt_is_triangle_hit_front_face",
        &[],
        Bool,
    ),
    row(
        "is_triangle_hit_back_face",
        "rtIsTriangleHitBackFace",
        HITS,
        Form::Value,
        "rt_is_triangle_hit_back_face",
        &[],
        Bool,
    ),
    row("instance_index", "optixGetInstanceIndex", TRANSFORMERS, Form::Value, "rt_instance_index", &[], U32),
    row("instance_id", "optixGetInstanceId", TRANSFORMERS, Form::Value, "rt_instance_id", &[], U32),
    row("ray_flags", "rtGetRayFlags", RAY_STATE, Form::Value, "rt_ray_flags", &[], U32),
    row("ray_mask", "rtGetRayMask", RAY_STATE, Form::Value, "rt_ray_mask", &[], U32),
    Intrinsic { name: "rt_printf", optix: "rtPrintf", callers: Callers::All, form: Form::Special, wgsl: None },
];

/// The runtime functions lowered code calls that are not intrinsics of
/// their own: buffer bounds checks, texture reads, debug output.
pub const RUNTIME_FUNCTIONS: &[WgslFn] = &[
    WgslFn { name: "rt_buf_check", params: &[("b", Buffer), ("i", U32)], ret: Bool },
    WgslFn { name: "rt_buf_check2", params: &[("b", Buffer), ("i", UVec2)], ret: Bool },
    // Bindless ids (`BindlessBuffer<T>`): whether `id` names a buffer of
    // element tag `tag` (and writable, if asked), raising the invalid-id
    // exception if not; the buffer of an id that passed.
    WgslFn { name: "rt_bufid_ok", params: &[("id", U32), ("tag", U32), ("writable", Bool)], ret: Bool },
    WgslFn { name: "rt_bufid", params: &[("id", U32)], ret: Buffer },
    WgslFn { name: "rt_buf_check3", params: &[("b", Buffer), ("i", UVec3)], ret: Bool },
    WgslFn { name: "rt_buf_size3", params: &[("b", Buffer)], ret: UVec3 },
    WgslFn { name: "rt_tex_sample", params: &[("s", Sampler), ("uv", Vec2)], ret: Vec4 },
    WgslFn { name: "rt_tex_fetch", params: &[("s", Sampler), ("texel", UVec2)], ret: Vec4 },
    WgslFn { name: "rt_tex_sample_lod", params: &[("s", Sampler), ("uv", Vec2), ("lod", F32)], ret: Vec4 },
    WgslFn {
        name: "rt_tex_sample_grad",
        params: &[("s", Sampler), ("uv", Vec2), ("dx", Vec2), ("dy", Vec2)],
        ret: Vec4,
    },
    WgslFn { name: "rt_tex3_sample", params: &[("s", Sampler3d), ("uvw", Vec3)], ret: Vec4 },
    WgslFn { name: "rt_tex3_fetch", params: &[("s", Sampler3d), ("texel", UVec3)], ret: Vec4 },
    WgslFn { name: "rt_tex3_sample_lod", params: &[("s", Sampler3d), ("uvw", Vec3), ("lod", F32)], ret: Vec4 },
    WgslFn {
        name: "rt_tex3_sample_grad",
        params: &[("s", Sampler3d), ("uvw", Vec3), ("dx", Vec3), ("dy", Vec3)],
        ret: Vec4,
    },
    // A cube map (`SamplerCube`) is an `RtSampler` of six square faces.
    WgslFn { name: "rt_texcube_sample", params: &[("s", Sampler), ("dir", Vec3)], ret: Vec4 },
    WgslFn { name: "rt_texcube_sample_lod", params: &[("s", Sampler), ("dir", Vec3), ("lod", F32)], ret: Vec4 },
    // Bindless sampler ids (`BindlessSampler<S>`): the sampler `id` names
    // if it is of shape `shape` (`SamplerTable::SHAPE_*`), else an empty
    // one (every sample zero) after raising the invalid-texture-id
    // exception; `rt_texid3` for 3D samplers.
    WgslFn { name: "rt_texid", params: &[("id", U32), ("shape", U32)], ret: Sampler },
    WgslFn { name: "rt_texid3", params: &[("id", U32)], ret: Sampler3d },
    WgslFn { name: "rt_printf_begin", params: &[("format", U32), ("words", U32)], ret: Bool },
    WgslFn { name: "rt_printf_word", params: &[("word", U32)], ret: Unit },
    // The time of the next trace (`rt_trace_at`); every trace takes it and
    // puts it back to 0, so a trace without one is at time 0.
    WgslFn { name: "rt_set_trace_time", params: &[("time", F32)], ret: Unit },
];

/// The row of the intrinsic rt-std calls `name`.
pub fn intrinsic(name: &str) -> Option<&'static Intrinsic> {
    INTRINSICS.iter().find(|i| i.name == name)
}

/// Every WGSL function of the contract: the intrinsics' and the others.
pub fn wgsl_functions() -> impl Iterator<Item = &'static WgslFn> {
    INTRINSICS.iter().filter_map(|i| i.wgsl.as_ref()).chain(RUNTIME_FUNCTIONS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        let mut rust: Vec<&str> = INTRINSICS.iter().map(|i| i.name).collect();
        rust.sort();
        rust.dedup();
        assert_eq!(rust.len(), INTRINSICS.len());
        let mut wgsl: Vec<&str> = wgsl_functions().map(|f| f.name).collect();
        wgsl.sort();
        wgsl.dedup();
        assert_eq!(wgsl.len(), wgsl_functions().count());
    }

    #[test]
    fn lowered_rows_have_a_function() {
        for i in INTRINSICS.iter().filter(|i| i.form != Form::Special) {
            let f = i.wgsl.unwrap_or_else(|| panic!("`{}` has no WGSL function", i.name));
            assert_eq!(i.form == Form::Statement, f.ret == AbiTy::Unit, "`{}`", i.name);
        }
    }
}
