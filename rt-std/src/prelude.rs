//! Everything a ray program uses: `use rt_std::prelude::*;`.
//!
//! The glam types and constructors programs may use, glam's swizzles, the
//! `f32` constants, the macros, the data traits, and every item of rt-std's
//! vocabulary: [`Ray`], [`Aabb`], the handles, the math helpers, the
//! intrinsics and their constants. [`TransformKind`]'s variants are imported
//! too, so programs write `rt_transform_normal(ObjectToWorld, n)`.

pub use core::f32::consts::{E, FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, LN_2, PI, SQRT_2, TAU};

pub use glam::swizzles::*;
pub use glam::{
    BVec2, BVec3, BVec4, BVec4A, IVec2, IVec3, IVec4, Mat2, Mat3, Mat4, UVec2, UVec3, UVec4, Vec2, Vec3, Vec4, bvec2,
    bvec3, bvec4, ivec2, ivec3, ivec4, uvec2, uvec3, uvec4, vec2, vec3, vec4,
};

pub use rt_macros::{
    rt_attributes, rt_const, rt_enum, rt_function, rt_impl, rt_payload, rt_program, rt_struct, rt_trait, rt_type,
};

pub use crate::rt_printf;

pub use crate::bindless::{BindlessBuffer, RwBindlessBuffer};
pub use crate::bindless_sampler::BindlessSampler;
pub use crate::buffer::{Buffer, Buffer2d, Buffer3d, RwBuffer, RwBuffer2d, RwBuffer3d};
pub use crate::callable::Callable;
pub use crate::data::{Attributes, Payload, RtData};
pub use crate::geometry::Aabb;
pub use crate::intrinsics::*;
pub use crate::math::{GenType, MixFactor, faceforward, mix, reflect, refract, saturate, smoothstep, step};
pub use crate::ray::{
    RAY_FLAG_CULL_BACK_FACING, RAY_FLAG_CULL_FRONT_FACING, RAY_FLAG_DISABLE_ANYHIT, RAY_FLAG_DISABLE_CLOSESTHIT,
    RAY_FLAG_NONE, RAY_FLAG_TERMINATE_ON_FIRST_HIT, RAY_MASK_ALL, Ray,
};
pub use crate::scene::Object;
pub use crate::scene::TransformKind::{self, *};
pub use crate::texture::{FilterMode, IndexMode, MipFilter, Sampler2d, Sampler3d, SamplerCube, WrapMode};
