//! The one table of program kinds and of the intrinsics they may call.
//! The checker reads it to reject, say, `rt_terminate_ray` in a closest-hit
//! program; a test checks rt-std's doc comments against it.

/// A program kind, as written in `#[rt_program(kind)]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    RayGeneration,
    Exception,
    ClosestHit,
    AnyHit,
    Miss,
    Intersection,
    BoundingBox,
    Visit,
}

use Kind::*;

/// Every kind, in OptiX's order.
pub const ALL_KINDS: [Kind; 8] = [RayGeneration, Exception, ClosestHit, AnyHit, Miss, Intersection, BoundingBox, Visit];

impl Kind {
    /// The `#[rt_program(...)]` spelling.
    pub fn name(self) -> &'static str {
        match self {
            RayGeneration => "ray_generation",
            Exception => "exception",
            ClosestHit => "closest_hit",
            AnyHit => "any_hit",
            Miss => "miss",
            Intersection => "intersection",
            BoundingBox => "bounding_box",
            Visit => "visit",
        }
    }

    /// The `rt_std::program::ProgramKind` variant name.
    pub fn variant(self) -> &'static str {
        match self {
            RayGeneration => "RayGeneration",
            Exception => "Exception",
            ClosestHit => "ClosestHit",
            AnyHit => "AnyHit",
            Miss => "Miss",
            Intersection => "Intersection",
            BoundingBox => "BoundingBox",
            Visit => "Visit",
        }
    }

    /// "a miss program", "an any_hit program": for messages.
    pub fn a_program(self) -> String {
        let article = if matches!(self, Exception | AnyHit | Intersection) { "an" } else { "a" };
        format!("{article} {} program", self.name())
    }

    pub fn from_name(name: &str) -> Option<Kind> {
        ALL_KINDS.into_iter().find(|k| k.name() == name)
    }

    /// The parameters a program of this kind may take besides `#[var]`s.
    pub fn signature_help(self) -> &'static str {
        match self {
            RayGeneration | Exception => "only `#[var]` parameters",
            ClosestHit | AnyHit => "`prd: &mut Payload`, `attr: &Attributes` and `#[var]` parameters",
            Miss => "`prd: &mut Payload` and `#[var]` parameters",
            Intersection => "`prim: u32`, `attr: &mut Attributes` and `#[var]` parameters",
            BoundingBox => "`prim: u32` and `#[var]` parameters, returning `Aabb`",
            Visit => "`prd: &Payload` and `#[var]` parameters, returning the child index as `u32`",
        }
    }
}

/// Which kinds may call an intrinsic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Callers {
    All,
    Only(&'static [Kind]),
}

impl Callers {
    pub fn allows(self, kind: Kind) -> bool {
        match self {
            Callers::All => true,
            Callers::Only(kinds) => kinds.contains(&kind),
        }
    }

    /// The list as rt-std's docs spell it: `Program kinds: a, b.`
    pub fn doc_line(self) -> String {
        match self {
            Callers::All => "Program kinds: all.".into(),
            Callers::Only(k) => {
                format!("Program kinds: {}.", k.iter().map(|k| k.name()).collect::<Vec<_>>().join(", "))
            }
        }
    }
}

const NOT_BOUNDS: &[Kind] = &[RayGeneration, Exception, ClosestHit, AnyHit, Miss, Intersection, Visit];
const RAY_KINDS: &[Kind] = &[ClosestHit, AnyHit, Miss, Intersection, Visit];
const HITS: &[Kind] = &[ClosestHit, AnyHit];
const TRACERS: &[Kind] = &[RayGeneration, ClosestHit, Miss];
const THROWERS: &[Kind] = &[RayGeneration, ClosestHit, AnyHit, Miss, Intersection, Visit];
const TRANSFORMERS: &[Kind] = &[ClosestHit, AnyHit, Intersection];

/// One intrinsic of rt-std that depends on the program kind.
#[derive(Clone, Copy, Debug)]
pub struct Intrinsic {
    /// Rust name in rt-std.
    pub name: &'static str,
    /// OptiX's name (rt-std carries it as `#[doc(alias)]`).
    pub optix: &'static str,
    pub callers: Callers,
}

/// Kind-restricted intrinsics. Math helpers, buffer and sampler methods and
/// `rt_printf!` are callable from every kind and are not listed.
pub const INTRINSICS: &[Intrinsic] = &[
    Intrinsic { name: "launch_index", optix: "rtLaunchIndex", callers: Callers::Only(NOT_BOUNDS) },
    Intrinsic { name: "launch_dim", optix: "rtLaunchDim", callers: Callers::Only(NOT_BOUNDS) },
    Intrinsic { name: "current_ray", optix: "rtCurrentRay", callers: Callers::Only(RAY_KINDS) },
    Intrinsic { name: "t_hit", optix: "rtIntersectionDistance", callers: Callers::Only(HITS) },
    Intrinsic {
        name: "primitive_index",
        optix: "rtPrimitiveIndex",
        callers: Callers::Only(&[ClosestHit, AnyHit, Intersection]),
    },
    Intrinsic { name: "exception_code", optix: "rtGetExceptionCode", callers: Callers::Only(&[Exception]) },
    Intrinsic { name: "rt_trace", optix: "rtTrace", callers: Callers::Only(TRACERS) },
    Intrinsic { name: "rt_trace_with", optix: "rtTrace", callers: Callers::Only(TRACERS) },
    Intrinsic {
        name: "rt_potential_intersection",
        optix: "rtPotentialIntersection",
        callers: Callers::Only(&[Intersection]),
    },
    Intrinsic {
        name: "rt_report_intersection",
        optix: "rtReportIntersection",
        callers: Callers::Only(&[Intersection]),
    },
    Intrinsic { name: "rt_ignore_intersection", optix: "rtIgnoreIntersection", callers: Callers::Only(&[AnyHit]) },
    Intrinsic { name: "rt_terminate_ray", optix: "rtTerminateRay", callers: Callers::Only(&[AnyHit]) },
    Intrinsic { name: "rt_throw", optix: "rtThrow", callers: Callers::Only(THROWERS) },
    Intrinsic { name: "rt_transform_point", optix: "rtTransformPoint", callers: Callers::Only(TRANSFORMERS) },
    Intrinsic { name: "rt_transform_vector", optix: "rtTransformVector", callers: Callers::Only(TRANSFORMERS) },
    Intrinsic { name: "rt_transform_normal", optix: "rtTransformNormal", callers: Callers::Only(TRANSFORMERS) },
    Intrinsic { name: "rt_printf", optix: "rtPrintf", callers: Callers::All },
];

pub fn intrinsic(name: &str) -> Option<&'static Intrinsic> {
    INTRINSICS.iter().find(|i| i.name == name)
}

/// Constants rt-std exports that programs may name, with their WGSL value.
pub const CONSTANTS: &[(&str, crate::types::Scalar, &str)] = {
    use crate::types::Scalar::U32;
    &[
        ("RAY_FLAG_NONE", U32, "0u"),
        ("RAY_FLAG_TERMINATE_ON_FIRST_HIT", U32, "1u"),
        ("RAY_FLAG_DISABLE_ANYHIT", U32, "2u"),
        ("RAY_FLAG_DISABLE_CLOSESTHIT", U32, "4u"),
        ("RAY_FLAG_CULL_BACK_FACING", U32, "8u"),
        ("RAY_FLAG_CULL_FRONT_FACING", U32, "16u"),
        ("RAY_MASK_ALL", U32, "255u"),
        ("EXCEPTION_TRACE_DEPTH_EXCEEDED", U32, "1020u"),
        ("EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS", U32, "1019u"),
        ("EXCEPTION_INVALID_RAY", U32, "1014u"),
        ("EXCEPTION_USER", U32, "1024u"),
    ]
};

/// `core::f32::consts` the subset knows, with their f32 values.
pub const F32_CONSTS: &[(&str, f32)] = &[
    ("PI", std::f32::consts::PI),
    ("TAU", std::f32::consts::TAU),
    ("FRAC_PI_2", std::f32::consts::FRAC_PI_2),
    ("FRAC_PI_3", std::f32::consts::FRAC_PI_3),
    ("FRAC_PI_4", std::f32::consts::FRAC_PI_4),
    ("FRAC_PI_6", std::f32::consts::FRAC_PI_6),
    ("FRAC_PI_8", std::f32::consts::FRAC_PI_8),
    ("FRAC_1_PI", std::f32::consts::FRAC_1_PI),
    ("FRAC_2_PI", std::f32::consts::FRAC_2_PI),
    ("FRAC_1_SQRT_2", std::f32::consts::FRAC_1_SQRT_2),
    ("E", std::f32::consts::E),
    ("SQRT_2", std::f32::consts::SQRT_2),
    ("LN_2", std::f32::consts::LN_2),
    ("LN_10", std::f32::consts::LN_10),
];
