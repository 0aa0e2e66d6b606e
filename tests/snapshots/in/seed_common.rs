//! Shared declarations of the seed's worked examples: per-ray data, the
//! attributes triangle meshes and custom primitives report, and lights. The
//! examples' own (`examples/src/common.rs`, whose programs the snapshot
//! corpus lowers as they are): `the_corpus_shares_the_examples_types` fails
//! when the two differ but for their doc comments.
use rt_std::prelude::*;

/// Per-ray data of radiance rays.
#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
    pub importance: f32,
    pub depth: i32,
}

/// Per-ray data of shadow rays.
#[rt_payload]
pub struct Shadow {
    pub attenuation: Vec3,
}

/// What intersection reports to the hit programs.
#[rt_attributes]
pub struct Normals {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
}

/// A point light.
#[rt_struct]
pub struct BasicLight {
    pub pos: Vec3,
    pub color: Vec3,
    pub casts_shadow: i32,
}

/// Ray types of the examples.
#[rt_const]
pub const RADIANCE_RAY: u32 = 0;
#[rt_const]
pub const SHADOW_RAY: u32 = 1;
