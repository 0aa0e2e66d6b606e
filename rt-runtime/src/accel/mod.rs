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
//! Files: [`bvh`] builds, refits and walks one tree (obvhs's BVH2, widened
//! to its CWBVH for the wgpu backend); [`wide`] is the CPU backend's SIMD
//! layout of a geometry group's tree (8-wide nodes, 4-triangle leaves) and
//! its walk; [`cache`] keeps a scene's trees across launches, building
//! what is new and refitting what moved, in the forms the launch's backend
//! walks ([`cache::Trees`]).

pub(crate) mod bvh;
pub(crate) mod cache;
pub mod wide;

pub use wide::isa::Isa as CpuSimd;

/// An acceleration builder, by OptiX's names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Builder {
    Bvh,
    Sbvh,
    MedianBvh,
    Lbvh,
    TriangleKdTree,
    NoAccel,
}

impl Builder {
    pub fn name(self) -> &'static str {
        match self {
            Builder::Bvh => "Bvh",
            Builder::Sbvh => "Sbvh",
            Builder::MedianBvh => "MedianBvh",
            Builder::Lbvh => "Lbvh",
            Builder::TriangleKdTree => "TriangleKdTree",
            Builder::NoAccel => "NoAccel",
        }
    }

    /// Parses OptiX's builder names.
    pub fn from_name(name: &str) -> Option<Builder> {
        [Builder::Bvh, Builder::Sbvh, Builder::MedianBvh, Builder::Lbvh, Builder::TriangleKdTree, Builder::NoAccel]
            .into_iter()
            .find(|b| b.name() == name)
    }
}

/// An acceleration structure attached to a geometry group or group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Acceleration {
    pub builder: Builder,
}

impl Acceleration {
    pub fn new(builder: Builder) -> Self {
        Acceleration { builder }
    }
}

impl Default for Acceleration {
    fn default() -> Self {
        Acceleration::new(Builder::Bvh)
    }
}
