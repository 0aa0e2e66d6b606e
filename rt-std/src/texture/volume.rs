//! [`Sampler3d`]: a 3D texture with its mip levels, sampled as a 2D one
//! with a third axis.

use core::fmt;

use glam::{UVec3, Vec3, Vec4};

use super::{
    FilterMode, IndexMode, MipFilter, SamplerModes, WrapMode, blend_levels, mip_level_count_3d, mip_level_size_3d,
    select_levels,
};
use crate::math::mix;

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
///
/// [`Sampler2d`]: super::Sampler2d
/// [`Sampler2d::sample_lod`]: super::Sampler2d::sample_lod
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
    ///
    /// [`Sampler2d`]: super::Sampler2d
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
    ///
    /// [`Sampler2d::sample_lod`]: super::Sampler2d::sample_lod
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
    ///
    /// [`Sampler2d::sample_grad`]: super::Sampler2d::sample_grad
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

#[cfg(test)]
mod tests {
    use super::super::tests::texel;
    use super::*;

    use FilterMode::*;
    use WrapMode::*;

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
    fn sampler_3d_levels_are_chosen_as_2d_ones() {
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
    }
}
