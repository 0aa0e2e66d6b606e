//! [`Sampler2d`]: a 2D texture with its mip levels, sampled by normalised
//! or texel coordinates, at level 0, a given LOD or a footprint.

use core::fmt;

use glam::{UVec2, Vec2, Vec4};

use super::{FilterMode, IndexMode, MipFilter, SamplerModes, WrapMode, mip_level_count, mip_level_size};
use crate::math::mix;

/// A 2D texture of RGBA `f32` texels with its wrap and filter modes and its
/// mip levels, as a variable gives it to a program. Texel `(x, y)` of a
/// level is stored at `x + y * width` of that level, the levels one after
/// the other from level 0. See the [module docs](super) for the sampling
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
    /// wrapped by the sampler's modes (see the [module docs](super)). A NaN
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
    /// [module docs](super).
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

#[cfg(test)]
mod tests {
    use super::super::tests::texel;
    use super::*;

    /// A 2x2 texture: `t(x, y) = texel(v)` with v = 0, 1 in the first row and
    /// 2, 4 in the second.
    const TEXELS: [Vec4; 4] = [texel(0.0), texel(1.0), texel(2.0), texel(4.0)];

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
}
