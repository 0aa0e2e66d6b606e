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

use core::fmt;

use glam::{UVec2, UVec3, Vec2, Vec3, Vec4};

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

/// A 2D texture of RGBA `f32` texels with its wrap and filter modes and its
/// mip levels, as a variable gives it to a program. Texel `(x, y)` of a
/// level is stored at `x + y * width` of that level, the levels one after
/// the other from level 0. See the [module docs](self) for the sampling
/// rules.
#[doc(alias = "rtTextureSampler")]
#[doc(alias = "tex2D")]
#[derive(Clone, Copy)]
pub struct Sampler2d {
    texels: *const Vec4,
    size: UVec2,
    levels: u32,
    wrap: WrapMode,
    filter: FilterMode,
    mip: MipFilter,
    index: IndexMode,
}

// SAFETY: a sampler only reads its texels, which the `from_raw_parts`
// contract keeps unchanged while the handle is used.
unsafe impl Send for Sampler2d {}
// SAFETY: as for `Send`.
unsafe impl Sync for Sampler2d {}

impl Sampler2d {
    /// A sampler over the `width * height` texels at `texels`, row-major.
    /// Host side only: the runtime creates samplers, programs receive them as
    /// variables.
    ///
    /// # Safety
    /// `texels` points to `width * height` initialised `Vec4`s that stay
    /// valid and unchanged while any copy of the handle is used. (A sampler
    /// of width or height 0 reads nothing and samples to zero.)
    pub unsafe fn from_raw_parts(
        texels: *const Vec4,
        width: u32,
        height: u32,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Self {
        let modes = SamplerModes { wrap, filter, ..SamplerModes::default() };
        // SAFETY: one level, as the caller promises.
        unsafe { Sampler2d::from_raw_mip_parts(texels, width, height, 1, modes) }
    }

    /// A sampler over a mip chain of `levels` levels at `texels`: level 0
    /// (`width * height` texels, row-major), then each next level of
    /// [`mip_level_size`]. Host side only, as [`Sampler2d::from_raw_parts`].
    /// `levels` is clamped to `1..=mip_level_count(width, height)` (to 1
    /// with [`IndexMode::ArrayIndex`]).
    ///
    /// # Safety
    /// `texels` points to the texels of those levels, initialised, valid
    /// and unchanged while any copy of the handle is used.
    pub unsafe fn from_raw_mip_parts(
        texels: *const Vec4,
        width: u32,
        height: u32,
        levels: u32,
        modes: SamplerModes,
    ) -> Self {
        let chain = if modes.index == IndexMode::ArrayIndex { 1 } else { mip_level_count(width, height).max(1) };
        let SamplerModes { wrap, filter, mip, index } = modes;
        Sampler2d { texels, size: UVec2::new(width, height), levels: levels.clamp(1, chain), wrap, filter, mip, index }
    }

    /// Width and height in texels.
    ///
    /// Program kinds: all.
    pub fn size(&self) -> UVec2 {
        self.size
    }

    /// How many mip levels the sampler has (1 without mips).
    ///
    /// Program kinds: all.
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// Level 0 of the texture at normalised coordinates `uv`, filtered and
    /// wrapped by the sampler's modes (see the [module docs](self)). A NaN
    /// or infinite coordinate counts as 0. Programs run in compute shaders,
    /// which have no derivatives to pick a mip level from: use
    /// [`Sampler2d::sample_lod`] or [`Sampler2d::sample_grad`] for the
    /// others.
    ///
    /// Program kinds: all.
    #[doc(alias = "tex2D")]
    pub fn sample(&self, uv: Vec2) -> Vec4 {
        if self.is_degenerate() {
            return Vec4::ZERO;
        }
        self.sample_level(uv, 0)
    }

    /// The texture at `uv` at level of detail `lod` (0 is level 0, 1 level
    /// 1, a fraction between them with [`MipFilter::Linear`]), clamped to
    /// the levels there are; a NaN LOD counts as 0. See the
    /// [module docs](self).
    ///
    /// Program kinds: all.
    #[doc(alias = "tex2DLod")]
    pub fn sample_lod(&self, uv: Vec2, lod: f32) -> Vec4 {
        if self.is_degenerate() {
            return Vec4::ZERO;
        }
        let last = (self.levels - 1) as f32;
        let d = if lod.is_nan() { 0.0 } else { lod.clamp(0.0, last) };
        match self.mip {
            MipFilter::Nearest => self.sample_level(uv, ((d + 0.5).ceil() - 1.0) as u32),
            MipFilter::Linear => {
                let hi = d.floor();
                let delta = d - hi;
                let a = self.sample_level(uv, hi as u32);
                if delta == 0.0 {
                    return a;
                }
                let b = self.sample_level(uv, (hi + 1.0).min(last) as u32);
                mix(a, b, delta)
            }
        }
    }

    /// The texture at `uv` at the level of detail of a footprint whose
    /// sides are `dx` and `dy` in normalised coordinates (the derivatives
    /// of `uv` along the screen's x and y): `log2` of the longer side in
    /// level-0 texels, as OpenGL and Vulkan define it, then as
    /// [`Sampler2d::sample_lod`].
    ///
    /// Program kinds: all.
    #[doc(alias = "tex2DGrad")]
    pub fn sample_grad(&self, uv: Vec2, dx: Vec2, dy: Vec2) -> Vec4 {
        let size = self.size.as_vec2();
        let rho = (dx * size).length().max((dy * size).length());
        self.sample_lod(uv, rho.log2())
    }

    /// Level `level` (< `levels`) at `uv`; the sampler is not degenerate.
    fn sample_level(&self, uv: Vec2, level: u32) -> Vec4 {
        let (start, size) = self.level(level);
        let uv = Vec2::select(uv.is_finite_mask(), uv, Vec2::ZERO);
        let p = match self.index {
            IndexMode::NormalizedCoordinates => uv * size.as_vec2(),
            IndexMode::ArrayIndex => uv,
        };
        let wrapped = |x: i64, y: i64| {
            let (x, y) = (self.wrap.apply(x, size.x), self.wrap.apply(y, size.y));
            self.texel(start + x + y * size.x as usize)
        };
        match self.filter {
            FilterMode::Nearest => {
                let i = p.floor();
                wrapped(i.x as i64, i.y as i64)
            }
            FilterMode::Linear => {
                let p = p - 0.5;
                let i0 = p.floor();
                let f = p - i0;
                // `as` saturates, so huge coordinates cannot overflow;
                // neither can the `+ 1` below.
                let (x0, y0) = (i0.x as i64, i0.y as i64);
                let (x1, y1) = (x0.saturating_add(1), y0.saturating_add(1));
                let top = mix(wrapped(x0, y0), wrapped(x1, y0), f.x);
                let bottom = mix(wrapped(x0, y1), wrapped(x1, y1), f.x);
                mix(top, bottom, f.y)
            }
        }
    }

    /// Texel `texel`, unfiltered, each coordinate clamped to the last texel.
    ///
    /// Program kinds: all.
    pub fn fetch(&self, texel: UVec2) -> Vec4 {
        if self.is_degenerate() {
            return Vec4::ZERO;
        }
        let t = texel.min(self.size - 1);
        self.texel(t.x as usize + t.y as usize * self.size.x as usize)
    }

    fn is_degenerate(&self) -> bool {
        self.size.x == 0 || self.size.y == 0
    }

    /// The index of level `level`'s first texel, and the level's size.
    fn level(&self, level: u32) -> (usize, UVec2) {
        let mut start = 0;
        for l in 0..level {
            let s = mip_level_size(self.size, l);
            start += s.x as usize * s.y as usize;
        }
        (start, mip_level_size(self.size, level))
    }

    fn texel(&self, i: usize) -> Vec4 {
        debug_assert!(i < self.level(self.levels).0);
        // SAFETY: `i` is inside the levels' texels (callers index a level
        // below `levels` within its size) of the `from_raw_parts` contract.
        unsafe { *self.texels.add(i) }
    }
}

impl fmt::Debug for Sampler2d {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Sampler2d")
            .field("size", &self.size)
            .field("wrap", &self.wrap)
            .field("filter", &self.filter)
            .field("levels", &self.levels)
            .field("mip", &self.mip)
            .field("index", &self.index)
            .finish()
    }
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

/// A 3D texture of RGBA `f32` texels with its wrap and filter modes and its
/// mip levels, as a variable gives it to a program (OptiX
/// `rtTextureSampler<float4, 3>`). Texel `(x, y, z)` of a level is stored
/// at `x + y * width + z * width * height` of that level, the levels one
/// after the other from level 0, level `l` of [`mip_level_size_3d`];
/// `uvw = (0, 0, 0)` is the start of the first texel, `(1, 1, 1)` the end of
/// the last, and the rules are [`Sampler2d`]'s with a third axis: the
/// [`WrapMode`] per axis on texel indices, [`FilterMode::Nearest`] reads
/// texel `floor(uvw * size)`, [`FilterMode::Linear`] blends the eight
/// texels around `uvw * size - 0.5` along x, then y, then z (trilinear);
/// levels are chosen as [`Sampler2d::sample_lod`] chooses them.
/// A NaN or infinite coordinate counts as 0.
#[doc(alias = "tex3D")]
#[derive(Clone, Copy)]
pub struct Sampler3d {
    texels: *const Vec4,
    size: UVec3,
    levels: u32,
    wrap: WrapMode,
    filter: FilterMode,
    mip: MipFilter,
    index: IndexMode,
}

// SAFETY: as for `Sampler2d`.
unsafe impl Send for Sampler3d {}
// SAFETY: as for `Sampler2d`.
unsafe impl Sync for Sampler3d {}

impl Sampler3d {
    /// A sampler over the `width * height * depth` texels at `texels`, one
    /// level. Host side only.
    ///
    /// # Safety
    /// `texels` points to `width * height * depth` initialised `Vec4`s that
    /// stay valid and unchanged while any copy of the handle is used (an
    /// empty size reads nothing and samples to zero).
    pub unsafe fn from_raw_parts(texels: *const Vec4, size: UVec3, wrap: WrapMode, filter: FilterMode) -> Self {
        let modes = SamplerModes { wrap, filter, ..SamplerModes::default() };
        // SAFETY: one level, as the caller promises.
        unsafe { Sampler3d::from_raw_mip_parts(texels, size, 1, modes) }
    }

    /// A sampler over a mip chain of `levels` levels at `texels`: level 0
    /// (`size` texels), then each next level of [`mip_level_size_3d`].
    /// Host side only. `levels` is clamped to `1..=mip_level_count_3d(size)`
    /// (to 1 with [`IndexMode::ArrayIndex`], whose coordinates are in
    /// texels, as [`Sampler2d`]'s).
    ///
    /// # Safety
    /// `texels` points to the texels of those levels, initialised, valid
    /// and unchanged while any copy of the handle is used.
    pub unsafe fn from_raw_mip_parts(texels: *const Vec4, size: UVec3, levels: u32, modes: SamplerModes) -> Self {
        let chain = if modes.index == IndexMode::ArrayIndex { 1 } else { mip_level_count_3d(size).max(1) };
        let SamplerModes { wrap, filter, mip, index } = modes;
        Sampler3d { texels, size, levels: levels.clamp(1, chain), wrap, filter, mip, index }
    }

    /// Width, height and depth in texels.
    ///
    /// Program kinds: all.
    pub fn size(&self) -> UVec3 {
        self.size
    }

    /// How many mip levels the sampler has (1 without mips).
    ///
    /// Program kinds: all.
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// Level 0 of the texture at coordinates `uvw` (normalised, or in
    /// texels with [`IndexMode::ArrayIndex`]), filtered and wrapped by the
    /// sampler's modes.
    ///
    /// Program kinds: all.
    #[doc(alias = "tex3D")]
    pub fn sample(&self, uvw: Vec3) -> Vec4 {
        if self.size.min_element() == 0 {
            return Vec4::ZERO;
        }
        self.sample_level(uvw, 0)
    }

    /// The texture at `uvw` at level of detail `lod`, the levels chosen and
    /// blended as [`Sampler2d::sample_lod`] does (clamped to the levels
    /// there are; a NaN LOD counts as 0).
    ///
    /// Program kinds: all.
    #[doc(alias = "tex3DLod")]
    pub fn sample_lod(&self, uvw: Vec3, lod: f32) -> Vec4 {
        if self.size.min_element() == 0 {
            return Vec4::ZERO;
        }
        let (lo, hi, t) = select_levels(self.levels, self.mip, lod);
        blend_levels(self.sample_level(uvw, lo), || self.sample_level(uvw, hi), t)
    }

    /// The texture at `uvw` at the level of detail of the footprint `dx`,
    /// `dy` (the derivatives of `uvw` across a pixel): log2 of its longer
    /// side in level-0 texels, as [`Sampler2d::sample_grad`] (isotropic,
    /// as OpenGL and Vulkan define it for 3D textures).
    ///
    /// Program kinds: all.
    #[doc(alias = "tex3DGrad")]
    pub fn sample_grad(&self, uvw: Vec3, dx: Vec3, dy: Vec3) -> Vec4 {
        let size = self.size.as_vec3();
        let rho = (dx * size).length().max((dy * size).length());
        self.sample_lod(uvw, rho.log2())
    }

    /// Level `level` (< `levels`) at `uvw`; the sampler is not degenerate.
    fn sample_level(&self, uvw: Vec3, level: u32) -> Vec4 {
        let (start, size) = self.level(level);
        let uvw = Vec3::select(uvw.is_finite_mask(), uvw, Vec3::ZERO);
        let p = match self.index {
            IndexMode::NormalizedCoordinates => uvw * size.as_vec3(),
            IndexMode::ArrayIndex => uvw,
        };
        let wrapped = |x: i64, y: i64, z: i64| {
            let (x, y, z) = (self.wrap.apply(x, size.x), self.wrap.apply(y, size.y), self.wrap.apply(z, size.z));
            self.texel(start, size, x, y, z)
        };
        match self.filter {
            FilterMode::Nearest => {
                let i = p.floor();
                wrapped(i.x as i64, i.y as i64, i.z as i64)
            }
            FilterMode::Linear => {
                let p = p - 0.5;
                let i0 = p.floor();
                let f = p - i0;
                let (x0, y0, z0) = (i0.x as i64, i0.y as i64, i0.z as i64);
                let (x1, y1, z1) = (x0.saturating_add(1), y0.saturating_add(1), z0.saturating_add(1));
                let plane = |z: i64| {
                    let top = mix(wrapped(x0, y0, z), wrapped(x1, y0, z), f.x);
                    let bottom = mix(wrapped(x0, y1, z), wrapped(x1, y1, z), f.x);
                    mix(top, bottom, f.y)
                };
                mix(plane(z0), plane(z1), f.z)
            }
        }
    }

    /// Texel `texel` of level 0, unfiltered, each coordinate clamped to the
    /// last texel.
    ///
    /// Program kinds: all.
    pub fn fetch(&self, texel: UVec3) -> Vec4 {
        if self.size.min_element() == 0 {
            return Vec4::ZERO;
        }
        let t = texel.min(self.size - 1);
        self.texel(0, self.size, t.x as usize, t.y as usize, t.z as usize)
    }

    /// The index of level `level`'s first texel, and the level's size.
    fn level(&self, level: u32) -> (usize, UVec3) {
        let mut start = 0;
        for l in 0..level {
            let s = mip_level_size_3d(self.size, l);
            start += s.x as usize * s.y as usize * s.z as usize;
        }
        (start, mip_level_size_3d(self.size, level))
    }

    fn texel(&self, start: usize, size: UVec3, x: usize, y: usize, z: usize) -> Vec4 {
        let (w, h) = (size.x as usize, size.y as usize);
        debug_assert!(x < w && y < h && z < size.z as usize);
        // SAFETY: in range of a level below `levels`, so inside the texels
        // of the contract.
        unsafe { *self.texels.add(start + x + y * w + z * w * h) }
    }
}

impl fmt::Debug for Sampler3d {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Sampler3d")
            .field("size", &self.size)
            .field("wrap", &self.wrap)
            .field("filter", &self.filter)
            .field("levels", &self.levels)
            .field("mip", &self.mip)
            .field("index", &self.index)
            .finish()
    }
}

/// A cube map: six square faces of RGBA `f32` texels, read by direction
/// (OptiX `texCubemap`, a layered texture of six faces), with mip levels.
/// Faces are stored in Vulkan's layer order, +x, -x, +y, -y, +z, -z, each
/// `size x size` texels row-major; level `l` holds six faces of side
/// `max(1, size >> l)`, the levels one after the other from level 0. See
/// [`SamplerCube::sample_dir`] for the face selection; levels are chosen as
/// [`Sampler2d::sample_lod`] chooses them.
#[doc(alias = "texCubemap")]
#[derive(Clone, Copy)]
pub struct SamplerCube {
    texels: *const Vec4,
    size: u32,
    levels: u32,
    filter: FilterMode,
    mip: MipFilter,
}

// SAFETY: as for `Sampler2d`.
unsafe impl Send for SamplerCube {}
// SAFETY: as for `Sampler2d`.
unsafe impl Sync for SamplerCube {}

impl SamplerCube {
    /// A cube map over the `6 * size * size` texels at `texels`, one level.
    /// Host side only.
    ///
    /// # Safety
    /// `texels` points to `6 * size * size` initialised `Vec4`s that stay
    /// valid and unchanged while any copy of the handle is used.
    pub unsafe fn from_raw_parts(texels: *const Vec4, size: u32, filter: FilterMode) -> Self {
        // SAFETY: one level, as the caller promises.
        unsafe { SamplerCube::from_raw_mip_parts(texels, size, 1, filter, MipFilter::Linear) }
    }

    /// A cube map over `levels` levels at `texels`, each six faces of side
    /// `max(1, size >> l)`. Host side only. `levels` is clamped to
    /// `1..=mip_level_count(size, size)`.
    ///
    /// # Safety
    /// `texels` points to the texels of those levels, initialised, valid
    /// and unchanged while any copy of the handle is used.
    pub unsafe fn from_raw_mip_parts(
        texels: *const Vec4,
        size: u32,
        levels: u32,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Self {
        let chain = mip_level_count(size, size).max(1);
        SamplerCube { texels, size, levels: levels.clamp(1, chain), filter, mip }
    }

    /// The side of a face in texels.
    ///
    /// Program kinds: all.
    pub fn size(&self) -> u32 {
        self.size
    }

    /// How many mip levels the cube map has (1 without mips).
    ///
    /// Program kinds: all.
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// The face (0 to 5: +x, -x, +y, -y, +z, -z) and the face coordinates
    /// `(s, t)` direction `dir` reads, as Vulkan's "Cube Map Face
    /// Selection" table says: the major axis is the component of largest
    /// magnitude (ties go to z, then y, then x), and with `(sc, tc, rc)`
    /// from the table, `s = 0.5 sc / |rc| + 0.5`, `t = 0.5 tc / |rc| + 0.5`.
    /// A NaN or infinite component counts as 0; the zero direction reads
    /// the centre of face +z.
    pub fn face_coordinates(dir: Vec3) -> (u32, Vec2) {
        let d = Vec3::select(dir.is_finite_mask(), dir, Vec3::ZERO);
        let a = d.abs();
        let (face, sc, tc, rc) = if a.z >= a.x && a.z >= a.y {
            if d.z >= 0.0 { (4, d.x, -d.y, a.z) } else { (5, -d.x, -d.y, a.z) }
        } else if a.y >= a.x {
            if d.y >= 0.0 { (2, d.x, d.z, a.y) } else { (3, d.x, -d.z, a.y) }
        } else if d.x >= 0.0 {
            (0, -d.z, -d.y, a.x)
        } else {
            (1, d.z, -d.y, a.x)
        };
        if rc == 0.0 {
            return (face, Vec2::splat(0.5));
        }
        (face, Vec2::new(0.5 * (sc / rc) + 0.5, 0.5 * (tc / rc) + 0.5))
    }

    /// Level 0 of the cube map in direction `dir` (any length): the face
    /// and coordinates of [`SamplerCube::face_coordinates`], sampled on
    /// that face with the sampler's filter, clamped to the face's edge
    /// (filtering does not reach across to the next face, unlike Vulkan's
    /// seamless cube maps: a linear sample within half a texel of an edge
    /// differs).
    ///
    /// Program kinds: all.
    #[doc(alias = "texCubemap")]
    pub fn sample_dir(&self, dir: Vec3) -> Vec4 {
        if self.size == 0 {
            return Vec4::ZERO;
        }
        let (face, st) = Self::face_coordinates(dir);
        self.face(0, face).sample(st)
    }

    /// The cube map in direction `dir` at level of detail `lod`: the face
    /// of [`SamplerCube::sample_dir`], its levels chosen and blended as
    /// [`Sampler2d::sample_lod`] does (clamped to the levels there are; a
    /// NaN LOD counts as 0).
    ///
    /// Program kinds: all.
    #[doc(alias = "texCubemapLod")]
    pub fn sample_dir_lod(&self, dir: Vec3, lod: f32) -> Vec4 {
        if self.size == 0 {
            return Vec4::ZERO;
        }
        let (face, st) = Self::face_coordinates(dir);
        let (lo, hi, t) = select_levels(self.levels, self.mip, lod);
        blend_levels(self.face(lo, face).sample(st), || self.face(hi, face).sample(st), t)
    }

    /// Face `face` (< 6) of level `level` (< `levels`) as a one-level 2D
    /// sampler clamped to its edges.
    fn face(&self, level: u32, face: u32) -> Sampler2d {
        let side = |l: u32| (self.size >> l).max(1) as usize;
        let start: usize =
            (0..level).map(|l| 6 * side(l) * side(l)).sum::<usize>() + face as usize * side(level).pow(2);
        let n = side(level) as u32;
        // SAFETY: the face lies inside the levels' texels of the contract.
        unsafe { Sampler2d::from_raw_parts(self.texels.add(start), n, n, WrapMode::Clamp, self.filter) }
    }
}

impl fmt::Debug for SamplerCube {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SamplerCube")
            .field("size", &self.size)
            .field("filter", &self.filter)
            .field("levels", &self.levels)
            .field("mip", &self.mip)
            .finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2x2 texture: `t(x, y) = texel(v)` with v = 0, 1 in the first row and
    /// 2, 4 in the second.
    const TEXELS: [Vec4; 4] = [texel(0.0), texel(1.0), texel(2.0), texel(4.0)];

    const fn texel(v: f32) -> Vec4 {
        Vec4::new(v, -v, 0.5 * v, 1.0)
    }

    fn sampler(wrap: WrapMode, filter: FilterMode) -> Sampler2d {
        unsafe { Sampler2d::from_raw_parts(TEXELS.as_ptr(), 2, 2, wrap, filter) }
    }

    fn sample(wrap: WrapMode, filter: FilterMode, u: f32, v: f32) -> f32 {
        let s = sampler(wrap, filter).sample(Vec2::new(u, v));
        // Every channel is an affine function of the first one.
        assert_eq!(s, texel(s.x), "channels of ({u}, {v})");
        s.x
    }

    use FilterMode::*;
    use WrapMode::*;

    #[test]
    fn nearest_reads_the_containing_texel() {
        for wrap in [Repeat, Clamp, Mirror] {
            assert_eq!(sample(wrap, Nearest, 0.25, 0.25), 0.0);
            assert_eq!(sample(wrap, Nearest, 0.75, 0.25), 1.0);
            assert_eq!(sample(wrap, Nearest, 0.25, 0.75), 2.0);
            assert_eq!(sample(wrap, Nearest, 0.99, 0.5), 4.0);
            assert_eq!(sample(wrap, Nearest, 0.0, 0.0), 0.0);
        }
    }

    #[test]
    fn nearest_wraps_per_mode() {
        // u = -0.25, 1.25, 1.75, -0.75 are texel columns -1, 2, 3, -2.
        let cases =
            [(-0.25, [1.0, 0.0, 0.0]), (1.25, [0.0, 1.0, 1.0]), (1.75, [1.0, 1.0, 0.0]), (-0.75, [0.0, 0.0, 1.0])];
        for (u, [repeat, clamp, mirror]) in cases {
            assert_eq!(sample(Repeat, Nearest, u, 0.25), repeat, "repeat u={u}");
            assert_eq!(sample(Clamp, Nearest, u, 0.25), clamp, "clamp u={u}");
            assert_eq!(sample(Mirror, Nearest, u, 0.25), mirror, "mirror u={u}");
        }
        // And along v: row 2 is row 0 (repeat), row 1 (clamp, mirror).
        assert_eq!(sample(Repeat, Nearest, 0.75, 1.25), 1.0);
        assert_eq!(sample(Clamp, Nearest, 0.75, 1.25), 4.0);
        assert_eq!(sample(Mirror, Nearest, 0.75, 1.25), 4.0);
    }

    #[test]
    fn linear_is_exact_at_texel_centres_and_blends_between() {
        for wrap in [Repeat, Clamp, Mirror] {
            assert_eq!(sample(wrap, Linear, 0.25, 0.25), 0.0);
            assert_eq!(sample(wrap, Linear, 0.75, 0.25), 1.0);
            assert_eq!(sample(wrap, Linear, 0.25, 0.75), 2.0);
            assert_eq!(sample(wrap, Linear, 0.75, 0.75), 4.0);
            // The centre of the texture: the average of all four.
            assert_eq!(sample(wrap, Linear, 0.5, 0.5), 1.75);
            // p = (0.25, 0.75): rows blend to 0.25 and 2.5, then 1.9375.
            assert_eq!(sample(wrap, Linear, 0.375, 0.625), 1.9375);
        }
    }

    #[test]
    fn linear_wraps_each_neighbour() {
        // uv = (0, 0): p = (-0.5, -0.5), neighbours -1 and 0 in each axis.
        assert_eq!(sample(Repeat, Linear, 0.0, 0.0), 1.75);
        assert_eq!(sample(Clamp, Linear, 0.0, 0.0), 0.0);
        assert_eq!(sample(Mirror, Linear, 0.0, 0.0), 0.0);
        // u = 1: columns 1 and 2, half way.
        assert_eq!(sample(Repeat, Linear, 1.0, 0.25), 0.5);
        assert_eq!(sample(Clamp, Linear, 1.0, 0.25), 1.0);
        assert_eq!(sample(Mirror, Linear, 1.0, 0.25), 1.0);
        // u = 0.125: p.x = -0.25, columns -1 and 0 with f = 0.75.
        assert_eq!(sample(Repeat, Linear, 0.125, 0.25), 0.25);
        assert_eq!(sample(Clamp, Linear, 0.125, 0.25), 0.0);
        assert_eq!(sample(Mirror, Linear, 0.125, 0.25), 0.0);
        // u = 1.25: p.x = 2 exactly, column 2 alone.
        assert_eq!(sample(Repeat, Linear, 1.25, 0.25), 0.0);
        assert_eq!(sample(Clamp, Linear, 1.25, 0.25), 1.0);
        assert_eq!(sample(Mirror, Linear, 1.25, 0.25), 1.0);
    }

    #[test]
    fn extreme_coordinates_stay_in_the_texture() {
        for wrap in [Repeat, Clamp, Mirror] {
            for filter in [Nearest, Linear] {
                for u in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1e30, -1e30] {
                    let s = sampler(wrap, filter).sample(Vec2::new(u, 0.25));
                    let at_zero = sampler(wrap, filter).sample(Vec2::new(0.0, 0.25));
                    if u.is_finite() {
                        assert!(s.is_finite(), "{wrap:?} {filter:?} {u}: {s}");
                    } else {
                        assert_eq!(s, at_zero, "{wrap:?} {filter:?} {u}");
                    }
                }
            }
        }
    }

    #[test]
    fn fetch_clamps_and_size() {
        let s = sampler(Repeat, Linear);
        assert_eq!(s.size(), UVec2::new(2, 2));
        assert_eq!(s.fetch(UVec2::new(1, 0)), texel(1.0));
        assert_eq!(s.fetch(UVec2::new(5, 0)), texel(1.0));
        assert_eq!(s.fetch(UVec2::new(0, 9)), texel(2.0));
        let empty = unsafe { Sampler2d::from_raw_parts(core::ptr::null(), 0, 3, Repeat, Linear) };
        assert_eq!(empty.sample(Vec2::splat(0.5)), Vec4::ZERO);
        assert_eq!(empty.fetch(UVec2::ZERO), Vec4::ZERO);
    }

    /// A 4x2 texture with three levels (4x2, 2x1, 1x1), each of one colour:
    /// level l is `texel(10^l)`.
    fn mipped(filter: FilterMode, mip: MipFilter) -> (Sampler2d, Vec<Vec4>) {
        let texels: Vec<Vec4> = [vec![texel(1.0); 8], vec![texel(10.0); 2], vec![texel(100.0)]].concat();
        let modes = SamplerModes { wrap: Repeat, filter, mip, ..SamplerModes::default() };
        let s = unsafe { Sampler2d::from_raw_mip_parts(texels.as_ptr(), 4, 2, 3, modes) };
        (s, texels)
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

    #[test]
    fn sample_lod_picks_and_blends_levels() {
        for filter in [Nearest, Linear] {
            let (s, _t) = mipped(filter, MipFilter::Linear);
            let at = |lod: f32| s.sample_lod(Vec2::new(0.3, 0.7), lod);
            assert_eq!(s.levels(), 3);
            assert_eq!(at(0.0), texel(1.0));
            assert_eq!(at(1.0), texel(10.0));
            assert_eq!(at(2.0), texel(100.0));
            assert_eq!(at(0.5), texel(5.5));
            assert_eq!(at(1.25), texel(32.5));
            assert_eq!(at(7.0), texel(100.0));
            assert_eq!(at(f32::INFINITY), texel(100.0));
            assert_eq!(at(-3.0), texel(1.0));
            assert_eq!(at(f32::NEG_INFINITY), texel(1.0));
            assert_eq!(at(f32::NAN), texel(1.0));
            assert_eq!(s.sample(Vec2::new(0.3, 0.7)), texel(1.0));
            let (n, _t) = mipped(filter, MipFilter::Nearest);
            let at = |lod: f32| n.sample_lod(Vec2::new(0.3, 0.7), lod);
            assert_eq!(at(0.5), texel(1.0));
            assert_eq!(at(0.51), texel(10.0));
            assert_eq!(at(1.5), texel(10.0));
            assert_eq!(at(1.6), texel(100.0));
        }
    }

    #[test]
    fn sample_grad_takes_log2_of_the_longer_footprint() {
        let (s, _t) = mipped(Linear, MipFilter::Linear);
        let uv = Vec2::new(0.6, 0.2);
        // One texel of level 0 is 1/4 in u and 1/2 in v.
        let du = Vec2::new(0.25, 0.0);
        assert_eq!(s.sample_grad(uv, du, Vec2::ZERO), texel(1.0));
        assert_eq!(s.sample_grad(uv, du * 2.0, Vec2::new(0.0, 0.5)), texel(10.0));
        assert_eq!(s.sample_grad(uv, Vec2::ZERO, Vec2::new(0.0, 2.0)), texel(100.0));
        assert_eq!(s.sample_grad(uv, Vec2::ZERO, Vec2::ZERO), texel(1.0));
        assert_eq!(s.sample_grad(uv, Vec2::NAN, Vec2::ZERO), texel(1.0));
        assert_eq!(s.sample_grad(uv, Vec2::INFINITY, Vec2::ZERO), texel(100.0));
    }

    #[test]
    fn levels_clamp_to_the_chain() {
        let texels = [texel(1.0), texel(2.0)];
        let modes = SamplerModes { wrap: Clamp, filter: Nearest, ..SamplerModes::default() };
        let s = unsafe { Sampler2d::from_raw_mip_parts(texels.as_ptr(), 1, 1, 9, modes) };
        assert_eq!(s.levels(), 1);
        assert_eq!(s.sample_lod(Vec2::ZERO, 5.0), texel(1.0));
        // Array-index samplers have one level.
        let (_s, mips) = mipped(Nearest, MipFilter::Linear);
        let modes = SamplerModes { index: IndexMode::ArrayIndex, ..SamplerModes::default() };
        let s = unsafe { Sampler2d::from_raw_mip_parts(mips.as_ptr(), 4, 2, 3, modes) };
        assert_eq!(s.levels(), 1);
    }

    #[test]
    fn array_index_coordinates_are_in_texels() {
        for filter in [Nearest, Linear] {
            let modes = SamplerModes { wrap: Clamp, filter, index: IndexMode::ArrayIndex, ..SamplerModes::default() };
            let s = unsafe { Sampler2d::from_raw_mip_parts(TEXELS.as_ptr(), 2, 2, 1, modes) };
            assert_eq!(s.sample(Vec2::new(1.5, 0.5)).x, 1.0);
            assert_eq!(s.sample(Vec2::new(0.5, 1.5)).x, 2.0);
            assert_eq!(s.sample(Vec2::new(9.0, 9.0)).x, 4.0);
        }
        let modes = SamplerModes { wrap: Clamp, filter: Linear, index: IndexMode::ArrayIndex, ..Default::default() };
        let s = unsafe { Sampler2d::from_raw_mip_parts(TEXELS.as_ptr(), 2, 2, 1, modes) };
        assert_eq!(s.sample(Vec2::new(1.0, 0.5)).x, 0.5);
    }

    #[test]
    fn sampler_3d_reads_and_blends_eight_texels() {
        // A 2x2x2 cube: texel (x, y, z) is texel(x + 2y + 4z).
        let texels: Vec<Vec4> = (0..8).map(|i| texel(i as f32)).collect();
        for wrap in [Repeat, Clamp, Mirror] {
            let n = unsafe { Sampler3d::from_raw_parts(texels.as_ptr(), UVec3::splat(2), wrap, Nearest) };
            assert_eq!(n.sample(Vec3::new(0.75, 0.25, 0.75)), texel(5.0));
            assert_eq!(n.fetch(UVec3::new(1, 1, 9)), texel(7.0));
            let l = unsafe { Sampler3d::from_raw_parts(texels.as_ptr(), UVec3::splat(2), wrap, Linear) };
            assert_eq!(l.sample(Vec3::new(0.25, 0.75, 0.25)), texel(2.0));
            // The centre: the mean of all eight, 3.5.
            assert_eq!(l.sample(Vec3::splat(0.5)), texel(3.5));
        }
        // Past the far z face: repeat wraps to z = 0, clamp stays at 1.
        let r = unsafe { Sampler3d::from_raw_parts(texels.as_ptr(), UVec3::splat(2), Repeat, Nearest) };
        assert_eq!(r.sample(Vec3::new(0.25, 0.25, 1.25)), texel(0.0));
        let c = unsafe { Sampler3d::from_raw_parts(texels.as_ptr(), UVec3::splat(2), Clamp, Nearest) };
        assert_eq!(c.sample(Vec3::new(0.25, 0.25, 1.25)), texel(4.0));
        assert_eq!(c.sample(Vec3::new(f32::NAN, 0.25, 0.75)), texel(4.0));
        let empty = unsafe { Sampler3d::from_raw_parts(core::ptr::null(), UVec3::new(2, 0, 2), Clamp, Linear) };
        assert_eq!(empty.sample(Vec3::ONE), Vec4::ZERO);
        assert_eq!(empty.fetch(UVec3::ONE), Vec4::ZERO);
    }

    #[test]
    fn sampler_3d_and_cube_levels_are_chosen_as_2d_ones() {
        // A 4x2x2 volume of three levels (4x2x2, 2x1x1, 1x1x1), level l
        // all texel(10^l).
        let texels: Vec<Vec4> = [vec![texel(1.0); 16], vec![texel(10.0); 2], vec![texel(100.0)]].concat();
        assert_eq!(mip_level_count_3d(UVec3::new(4, 2, 2)), 3);
        assert_eq!(mip_level_size_3d(UVec3::new(4, 2, 2), 1), UVec3::new(2, 1, 1));
        let modes = SamplerModes { wrap: Repeat, filter: Linear, mip: MipFilter::Linear, ..SamplerModes::default() };
        let v = unsafe { Sampler3d::from_raw_mip_parts(texels.as_ptr(), UVec3::new(4, 2, 2), 9, modes) };
        let uvw = Vec3::new(0.3, 0.6, 0.2);
        assert_eq!(v.levels(), 3);
        assert_eq!(v.sample(uvw), texel(1.0));
        assert_eq!(v.sample_lod(uvw, 1.0), texel(10.0));
        assert_eq!(v.sample_lod(uvw, 1.25), texel(32.5));
        assert_eq!(v.sample_lod(uvw, f32::NAN), texel(1.0));
        assert_eq!(v.sample_lod(uvw, 8.0), texel(100.0));
        let nearest = SamplerModes { mip: MipFilter::Nearest, ..modes };
        let n = unsafe { Sampler3d::from_raw_mip_parts(texels.as_ptr(), UVec3::new(4, 2, 2), 3, nearest) };
        assert_eq!(n.sample_lod(uvw, 0.5), texel(1.0));
        assert_eq!(n.sample_lod(uvw, 0.51), texel(10.0));
        // A cube of side 2 with two levels: level 0's face k is texel(k),
        // level 1's (1x1 faces) texel(10 + k).
        let cube: Vec<Vec4> =
            (0..24).map(|i| texel((i / 4) as f32)).chain((0..6).map(|k| texel(10.0 + k as f32))).collect();
        let c = unsafe { SamplerCube::from_raw_mip_parts(cube.as_ptr(), 2, 2, Nearest, MipFilter::Linear) };
        assert_eq!(c.levels(), 2);
        assert_eq!(c.sample_dir(-Vec3::Y), texel(3.0));
        assert_eq!(c.sample_dir_lod(-Vec3::Y, 1.0), texel(13.0));
        assert_eq!(c.sample_dir_lod(Vec3::Z, 0.5), texel(9.0));
        assert_eq!(c.sample_dir_lod(Vec3::Z, -1.0), texel(4.0));
    }

    #[test]
    fn cube_faces_follow_vulkans_table() {
        let f = SamplerCube::face_coordinates;
        assert_eq!(f(Vec3::X), (0, Vec2::splat(0.5)));
        assert_eq!(f(-Vec3::X), (1, Vec2::splat(0.5)));
        assert_eq!(f(Vec3::Y), (2, Vec2::splat(0.5)));
        assert_eq!(f(-Vec3::Y), (3, Vec2::splat(0.5)));
        assert_eq!(f(Vec3::Z), (4, Vec2::splat(0.5)));
        assert_eq!(f(-Vec3::Z), (5, Vec2::splat(0.5)));
        // +x: sc = -rz, tc = -ry.
        assert_eq!(f(Vec3::new(2.0, 1.0, -1.0)), (0, Vec2::new(0.75, 0.25)));
        // -y: sc = rx, tc = -rz.
        assert_eq!(f(Vec3::new(0.5, -2.0, 1.0)), (3, Vec2::new(0.625, 0.25)));
        // Ties: z over y over x.
        assert_eq!(f(Vec3::new(1.0, 1.0, 1.0)).0, 4);
        assert_eq!(f(Vec3::new(1.0, -1.0, 0.5)).0, 3);
        assert_eq!(f(Vec3::ZERO), (4, Vec2::splat(0.5)));
        assert_eq!(f(Vec3::new(f32::NAN, f32::INFINITY, -1.0)), (5, Vec2::splat(0.5)));
    }

    #[test]
    fn cube_samples_the_selected_face() {
        // 2x2 faces; face k's texel i is texel(10k + i).
        let texels: Vec<Vec4> = (0..24).map(|i| texel((10 * (i / 4) + i % 4) as f32)).collect();
        let c = unsafe { SamplerCube::from_raw_parts(texels.as_ptr(), 2, Nearest) };
        assert_eq!(c.sample_dir(Vec3::new(2.0, 1.0, -1.0)), texel(1.0));
        assert_eq!(c.sample_dir(Vec3::new(-0.5, -0.5, -1.0)), texel(53.0));
        let l = unsafe { SamplerCube::from_raw_parts(texels.as_ptr(), 2, Linear) };
        // A face's centre: the mean of its four texels.
        assert_eq!(l.sample_dir(Vec3::Y), texel(21.5));
        let empty = unsafe { SamplerCube::from_raw_parts(core::ptr::null(), 0, Linear) };
        assert_eq!(empty.sample_dir(Vec3::X), Vec4::ZERO);
    }
}
