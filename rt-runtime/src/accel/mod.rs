//! Acceleration structures: OptiX's builder names mapped onto obvhs.
//!
//! | builder | obvhs | why |
//! | --- | --- | --- |
//! | `Bvh` | BVH2, `medium_build` (PLOC + reinsertion) | the general-purpose default; refits |
//! | `Sbvh` | BVH2 from triangles, `slow_build` (spatial pre-splits) | highest quality; needs triangles |
//! | `MedianBvh` | BVH2, `fast_build` | fast build, lower quality |
//! | `Lbvh` | BVH2, `fastest_build` (PLOC, minimum search: Morton-order merging, like an LBVH) | fastest build |
//! | `TriangleKdTree` | — | obvhs builds no kd-trees: an error, not a silent remap |
//! | `NoAccel` | a single leaf holding every primitive | linear scan |
//!
//! The descriptor a group carries ([`Acceleration`], [`Builder`]) is the
//! scene's (`scene.rs`), so the scene names it without importing this
//! folder. Files: `bvh` builds, refits and walks one tree (obvhs's BVH2, widened
//! to its CWBVH for the wgpu backend); [`wide`] is the CPU backend's SIMD
//! layout of a geometry group's tree (8-wide nodes, 4-triangle leaves) and
//! its walk; `cache` keeps a scene's trees across launches, building
//! what is new and refitting what moved, in the forms the launch's backend
//! walks (`cache::Trees`).

pub(crate) mod bvh;
pub(crate) mod cache;
pub mod wide;

pub use crate::scene::{Acceleration, Builder};
pub use wide::isa::Isa as CpuSimd;
