//! [`SamplerCube`]: a cube map of six square faces with their mip levels,
//! read by direction, each face sampled as a 2D texture.

use core::fmt;

use glam::{Vec2, Vec3, Vec4};

use super::{FilterMode, MipFilter, Sampler2d, WrapMode, blend_levels, mip_level_count, select_levels};

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
    use super::super::tests::texel;
    use super::*;

    use FilterMode::*;

    #[test]
    fn cube_levels_are_chosen_as_2d_ones() {
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
