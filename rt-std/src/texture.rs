//! [`Sampler2d`]: filtered reads of RGBA `f32` textures.
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
//! GPUs filter with a few bits of sub-texel precision (8 in Vulkan's
//! minimum), so compare GPU results with a tolerance, not bit for bit.

use core::fmt;

use glam::{UVec2, Vec2, Vec4};

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

/// A 2D texture of RGBA `f32` texels with its wrap and filter modes, as a
/// variable gives it to a program. Texel `(x, y)` is stored at
/// `x + y * width`. See the [module docs](self) for the sampling rules.
#[doc(alias = "rtTextureSampler")]
#[doc(alias = "tex2D")]
#[derive(Clone, Copy)]
pub struct Sampler2d {
    texels: *const Vec4,
    size: UVec2,
    wrap: WrapMode,
    filter: FilterMode,
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
        Sampler2d { texels, size: UVec2::new(width, height), wrap, filter }
    }

    /// Width and height in texels.
    ///
    /// Program kinds: all.
    pub fn size(&self) -> UVec2 {
        self.size
    }

    /// The texture at normalised coordinates `uv`, filtered and wrapped by
    /// the sampler's modes (see the [module docs](self)). A NaN or infinite
    /// coordinate counts as 0.
    ///
    /// Program kinds: all.
    #[doc(alias = "tex2D")]
    pub fn sample(&self, uv: Vec2) -> Vec4 {
        if self.is_degenerate() {
            return Vec4::ZERO;
        }
        let uv = Vec2::select(uv.is_finite_mask(), uv, Vec2::ZERO);
        let p = uv * self.size.as_vec2();
        match self.filter {
            FilterMode::Nearest => {
                let i = p.floor();
                self.wrapped(i.x as i64, i.y as i64)
            }
            FilterMode::Linear => {
                let p = p - 0.5;
                let i0 = p.floor();
                let f = p - i0;
                // `as` saturates, so huge coordinates cannot overflow;
                // neither can the `+ 1` below.
                let (x0, y0) = (i0.x as i64, i0.y as i64);
                let (x1, y1) = (x0.saturating_add(1), y0.saturating_add(1));
                let top = mix(self.wrapped(x0, y0), self.wrapped(x1, y0), f.x);
                let bottom = mix(self.wrapped(x0, y1), self.wrapped(x1, y1), f.x);
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
        self.texel(t.x as usize, t.y as usize)
    }

    fn is_degenerate(&self) -> bool {
        self.size.x == 0 || self.size.y == 0
    }

    fn wrapped(&self, x: i64, y: i64) -> Vec4 {
        self.texel(self.wrap.apply(x, self.size.x), self.wrap.apply(y, self.size.y))
    }

    fn texel(&self, x: usize, y: usize) -> Vec4 {
        debug_assert!(x < self.size.x as usize && y < self.size.y as usize);
        // SAFETY: `x`, `y` are in range, so the offset is inside the
        // `width * height` texels of the `from_raw_parts` contract.
        unsafe { *self.texels.add(x + y * self.size.x as usize) }
    }
}

impl fmt::Debug for Sampler2d {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Sampler2d")
            .field("size", &self.size)
            .field("wrap", &self.wrap)
            .field("filter", &self.filter)
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
}
