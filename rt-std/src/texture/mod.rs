//! [`Sampler2d`], [`Sampler3d`] and [`SamplerCube`], each with mip levels:
//! filtered reads of RGBA `f32` textures. (Texel formats are decoded to
//! RGBA `f32` by the host when it creates a sampler.)
//!
//! A program may also hold a sampler's id, a
//! [`BindlessSampler<S>`](crate::BindlessSampler), and sample through it
//! with the same methods and the same results (OptiX's `rtTex2D<float4>(id,
//! ..)`; see [`bindless_sampler`](crate::bindless_sampler)).
//!
//! The CPU implementation here is the reference for the GPU one, written to
//! the rules of WebGPU/Vulkan sampling with explicit level 0:
//!
//! - Texture coordinates are normalised: `uv = (0, 0)` is the start of the
//!   first texel row in memory, `(1, 1)` the end of the last; texel `(i, j)`
//!   has its centre at `((i + 0.5) / width, (j + 0.5) / height)`.
//! - Wrapping applies to integer texel coordinates, per axis, after they are
//!   computed ([`WrapMode`]).
//! - A NaN or infinite coordinate counts as 0.
//! - [`FilterMode::Nearest`] reads texel `floor(uv * size)`.
//!   [`FilterMode::Linear`] takes `p = uv * size - 0.5`, the four texels
//!   around it, `i0 = floor(p)` and `i0 + 1` in each axis (each wrapped on
//!   its own), and blends them with `f = p - floor(p)`: first along x, then
//!   along y, each blend being [`mix`]'s `a * (1 - f) + b * f`.
//!
//! Mip levels (OptiX `tex2DLod`, `tex2DGrad`): level `l` of a `w x h`
//! texture is `max(1, w >> l) x max(1, h >> l)` texels, and a texture has
//! at most `floor(log2(max(w, h))) + 1` levels ([`mip_level_count`]). Level
//! selection follows Vulkan's "Level-of-Detail Operation" with no bias and
//! no LOD clamps beyond the levels there are:
//!
//! - [`Sampler2d::sample_lod`] takes the LOD `λ` as given;
//!   [`Sampler2d::sample_grad`] computes it from the derivatives of `uv`
//!   along the screen's x and y: with `ρx = |dx * size|` and
//!   `ρy = |dy * size|` (the footprint's lengths in level-0 texels),
//!   `λ = log2(max(ρx, ρy))`. A footprint of 1, 2 or 4 texels is LOD 0, 1
//!   or 2.
//! - `d = clamp(λ, 0, levels - 1)`; a NaN LOD counts as 0 (`λ = -∞`, a
//!   zero footprint, is level 0, `+∞` the last level).
//! - [`MipFilter::Nearest`] samples level `ceil(d + 0.5) - 1` (the nearest
//!   level, a half rounding down, Vulkan's preferred rule);
//!   [`MipFilter::Linear`] samples levels `floor(d)` and
//!   `min(floor(d) + 1, levels - 1)` and blends them with
//!   `δ = d - floor(d)` as [`mix`] does (at `δ = 0`, level `floor(d)`
//!   alone). Each level is sampled with the sampler's [`FilterMode`] and
//!   [`WrapMode`] at its own size: linear filter and linear mip filter are
//!   trilinear filtering.
//!
//! [`Sampler3d::sample_lod`] and [`SamplerCube::sample_dir_lod`] choose
//! and blend levels by the same rules (a cube map's level is filtered on
//! the selected face alone); [`Sampler3d::sample_grad`] computes `λ` as
//! `sample_grad` does with three axes.
//!
//! [`Sampler2d::sample`] reads level 0 only: programs run in compute shaders,
//! which have no screen-space derivatives to choose a level from (WGSL's
//! `textureSample` is for fragment shaders only), so a program that wants
//! filtering across levels says which level (`sample_lod`) or gives the
//! footprint (`sample_grad`), e.g. from a ray differential.
//!
//! GPUs filter with a few bits of sub-texel precision (8 in Vulkan's
//! minimum), so compare GPU results with a tolerance, not bit for bit.

mod cube;
mod flat;
mod volume;

pub use cube::SamplerCube;
pub use flat::Sampler2d;
pub use volume::Sampler3d;

use glam::{UVec2, UVec3, Vec4};

use crate::math::mix;

/// How texel coordinates outside `[0, size)` map back into the texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum WrapMode {
    /// Tile: coordinate `i` reads `i mod size` (WebGPU `repeat`).
    #[default]
    Repeat,
    /// Clamp to the edge texel: `clamp(i, 0, size - 1)` (WebGPU
    /// `clamp-to-edge`).
    Clamp,
    /// Tile, mirroring every other copy: with `m = i mod 2 size`, reads `m`
    /// if `m < size`, else `2 size - 1 - m` (WebGPU `mirror-repeat`).
    Mirror,
}

impl WrapMode {
    /// Maps texel coordinate `i` into `[0, size)`; `size > 0`.
    fn apply(self, i: i64, size: u32) -> usize {
        let n = i64::from(size);
        let wrapped = match self {
            WrapMode::Repeat => i.rem_euclid(n),
            WrapMode::Clamp => i.clamp(0, n - 1),
            WrapMode::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        };
        wrapped as usize
    }
}

/// How [`Sampler2d::sample`] turns texels into a value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum FilterMode {
    /// The texel that contains the sample point.
    Nearest,
    /// Bilinear blend of the four texels whose centres surround the point.
    #[default]
    Linear,
}

/// How [`Sampler2d::sample_lod`] and [`Sampler2d::sample_grad`] combine
/// mip levels (OptiX's mipmap filter mode, Vulkan's `mipmapMode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum MipFilter {
    /// The level nearest to the LOD.
    Nearest,
    /// A blend of the two levels around the LOD (trilinear filtering with
    /// [`FilterMode::Linear`]).
    #[default]
    Linear,
}

/// How a sampler reads its coordinates (OptiX's
/// `rtTextureSamplerSetIndexingMode`, Vulkan's `unnormalizedCoordinates`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum IndexMode {
    /// `uv` in `[0, 1]` spans the texture (`RT_TEXTURE_INDEX_NORMALIZED_COORDINATES`).
    #[default]
    NormalizedCoordinates,
    /// `uv` in texels: `[0, width] x [0, height]` spans the texture, texel
    /// `(i, j)` has its centre at `(i + 0.5, j + 0.5)`
    /// (`RT_TEXTURE_INDEX_ARRAY_INDEX`, CUDA's unnormalised coordinates).
    /// As on GPUs, such a sampler has one level and clamps to the edge
    /// (the host refuses other wrap modes).
    ArrayIndex,
}

/// A sampler's modes: wrap, filter, mip filter and index mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct SamplerModes {
    /// Where coordinates outside the texture read.
    pub wrap: WrapMode,
    /// How a level's texels are filtered.
    pub filter: FilterMode,
    /// How levels are combined.
    pub mip: MipFilter,
    /// Whether coordinates are normalised or in texels.
    pub index: IndexMode,
}

/// How many levels a full mip chain of a `width x height` texture has:
/// `floor(log2(max(width, height))) + 1`, the last level being 1x1 (0 for
/// an empty texture).
pub fn mip_level_count(width: u32, height: u32) -> u32 {
    32 - width.max(height).leading_zeros()
}

/// The size of level `level` of a texture of level-0 size `size`:
/// `max(1, size >> level)` per axis (a level past the chain is 1x1).
pub fn mip_level_size(size: UVec2, level: u32) -> UVec2 {
    UVec2::new(size.x.checked_shr(level).unwrap_or(0), size.y.checked_shr(level).unwrap_or(0)).max(UVec2::ONE)
}

/// How many levels a full mip chain of a 3D texture of `size` has:
/// `floor(log2(max(width, height, depth))) + 1`, the last level being
/// 1x1x1 (0 for an empty texture).
pub fn mip_level_count_3d(size: UVec3) -> u32 {
    32 - size.max_element().leading_zeros()
}

/// The size of level `level` of a 3D texture of level-0 size `size`:
/// `max(1, size >> level)` per axis.
pub fn mip_level_size_3d(size: UVec3, level: u32) -> UVec3 {
    let shr = |n: u32| n.checked_shr(level).unwrap_or(0);
    UVec3::new(shr(size.x), shr(size.y), shr(size.z)).max(UVec3::ONE)
}

/// Vulkan's level selection, as [`Sampler2d::sample_lod`] makes it (see the
/// [module docs](self)): the levels LOD `lod` reads from `levels` levels,
/// `(lo, hi, t)`, level `lo` blended with level `hi` by `t` (`t = 0`: `lo`
/// alone).
fn select_levels(levels: u32, mip: MipFilter, lod: f32) -> (u32, u32, f32) {
    let last = (levels.max(1) - 1) as f32;
    let d = if lod.is_nan() { 0.0 } else { lod.clamp(0.0, last) };
    match mip {
        MipFilter::Nearest => {
            let l = ((d + 0.5).ceil() - 1.0) as u32;
            (l, l, 0.0)
        }
        MipFilter::Linear => {
            let lo = d.floor();
            (lo as u32, (lo + 1.0).min(last) as u32, d - lo)
        }
    }
}

/// Level `lo`'s sample, blended with level `hi`'s by `t` as [`mix`] does
/// (`hi` is not sampled at `t = 0`).
fn blend_levels(lo: Vec4, hi: impl FnOnce() -> Vec4, t: f32) -> Vec4 {
    if t == 0.0 { lo } else { mix(lo, hi(), t) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A texel whose every channel is an affine function of `v`, shared by
    /// the samplers' tests.
    pub(super) const fn texel(v: f32) -> Vec4 {
        Vec4::new(v, -v, 0.5 * v, 1.0)
    }

    #[test]
    fn mip_chain_sizes() {
        assert_eq!(mip_level_count(4, 2), 3);
        assert_eq!(mip_level_count(5, 1), 3);
        assert_eq!(mip_level_count(1, 1), 1);
        assert_eq!(mip_level_count(0, 0), 0);
        assert_eq!(mip_level_size(UVec2::new(5, 2), 1), UVec2::new(2, 1));
        assert_eq!(mip_level_size(UVec2::new(5, 2), 40), UVec2::ONE);
    }
}
