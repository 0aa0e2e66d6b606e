//! Bindless samplers: a texture sampler's id as a value a program holds
//! and samples through (OptiX's texture ids: `rtTextureSamplerGetId`,
//! `rtTex2D<float4>(id, u, v)`, `rtTex2DLod`, `rtTex2DGrad`, `rtTex3D`,
//! `rtTexCubemap`).
//!
//! A [`BindlessSampler<S>`] is one `u32` word, the id of a sampler of shape
//! `S` ([`Sampler2d`], [`Sampler3d`] or [`SamplerCube`]): a program may
//! hold it in a `#[var]` variable, a buffer element (a buffer of ids: a
//! material's texture chosen per instance or primitive), a struct or
//! payload field or a callable's argument, compare it with `==`, and sample
//! through it with the methods of `S`: `sample`, `sample_lod`,
//! `sample_grad`, `fetch`, `size` and `levels` for a 2D id, `sample`,
//! `sample_lod`, `sample_grad`, `fetch`, `size` and `levels` for a 3D one,
//! `sample_dir`,
//! `sample_dir_lod`, `size` and `levels` for a cube map.
//! The host gets a sampler's id with `Context::sampler_id::<S>(sampler)`,
//! which checks the sampler's shape, and sets it like any value; a launch
//! checks every id variable against the sampler it names. A program may
//! make ids too: [`BindlessSampler::NONE`], [`BindlessSampler::default()`]
//! and [`BindlessSampler::from_id`].
//!
//! Every read through an id checks it: an id that names no sampler of the
//! launch (zero, [`NONE`](BindlessSampler::NONE), an id from elsewhere) or
//! a sampler of another shape raises
//! [`EXCEPTION_TEXTURE_ID_INVALID`](crate::EXCEPTION_TEXTURE_ID_INVALID)
//! and reads an empty sampler: every sample and fetch is zero, the size 0,
//! one level. Ids are the context's sampler handles plus one, so zero is
//! none. A bounding-box program runs at build time, outside any launch,
//! and samples no texture through an id (the compiler refuses it).
//!
//! The samplers are texels in the runtime's heap on every backend (the
//! megakernel filters them itself, as [`texture`](crate::texture)
//! describes), so ids are not limited by an adapter's sampled-texture
//! bindings: any number of samplers, any number of ids.

use core::fmt;
use core::marker::PhantomData;

use glam::{UVec2, UVec3, Vec2, Vec3, Vec4};

use crate::data::RtData;
use crate::program::{LayoutKind, TypeLayout};
use crate::texture::{Sampler2d, Sampler3d, SamplerCube, WrapMode};

/// The layout every `BindlessSampler<S>` shares (one word): its shape is
/// checked against the sampler an id names at launch and at each read.
pub const BINDLESS_SAMPLER_LAYOUT: TypeLayout =
    TypeLayout { kind: LayoutKind::SamplerId(None), rust: "BindlessSampler", wgsl: "u32", words: 1, fields: &[] };

mod sealed {
    pub trait Sealed {}
    impl Sealed for crate::texture::Sampler2d {}
    impl Sealed for crate::texture::Sampler3d {}
    impl Sealed for crate::texture::SamplerCube {}
}

/// A sampler type a [`BindlessSampler`] may name: [`Sampler2d`],
/// [`Sampler3d`] or [`SamplerCube`].
pub trait SamplerShape: sealed::Sealed + Copy + Send + Sync + 'static {
    /// The type's name, as programs and errors spell it.
    const NAME: &'static str;
    /// The sampler the tracer gives for no sampler of this shape: every
    /// read zero, size 0.
    fn empty() -> Self;
}

impl SamplerShape for Sampler2d {
    const NAME: &'static str = "Sampler2d";
    fn empty() -> Self {
        // SAFETY: a sampler of no texels reads none.
        unsafe { Sampler2d::from_raw_parts(core::ptr::null(), 0, 0, WrapMode::Repeat, Default::default()) }
    }
}

impl SamplerShape for Sampler3d {
    const NAME: &'static str = "Sampler3d";
    fn empty() -> Self {
        // SAFETY: as for `Sampler2d`.
        unsafe { Sampler3d::from_raw_parts(core::ptr::null(), UVec3::ZERO, WrapMode::Repeat, Default::default()) }
    }
}

impl SamplerShape for SamplerCube {
    const NAME: &'static str = "SamplerCube";
    fn empty() -> Self {
        // SAFETY: as for `Sampler2d`.
        unsafe { SamplerCube::from_raw_parts(core::ptr::null(), 0, Default::default()) }
    }
}

/// The id of a texture sampler of shape `S` ([`Sampler2d`], [`Sampler3d`],
/// [`SamplerCube`]): one `u32` word, 0 for none. Sample through it as
/// through an `S`; see the [module docs](self).
///
/// Program kinds: all but bounding_box.
#[doc(alias = "rtTextureId")]
#[doc(alias = "rtTex2D")]
#[repr(transparent)]
pub struct BindlessSampler<S> {
    id: u32,
    shape: PhantomData<fn() -> S>,
}

impl<S> BindlessSampler<S> {
    /// No sampler: reading through it raises
    /// [`EXCEPTION_TEXTURE_ID_INVALID`](crate::EXCEPTION_TEXTURE_ID_INVALID).
    pub const NONE: Self = Self::from_id(0);

    /// The sampler of id `id` (as `Context::sampler_id` gives it, or read
    /// from a buffer of ids). Nothing is checked until a read.
    pub const fn from_id(id: u32) -> Self {
        BindlessSampler { id, shape: PhantomData }
    }

    /// The id.
    pub const fn id(self) -> u32 {
        self.id
    }
}

impl<S: SamplerShape> BindlessSampler<S> {
    /// The sampler the id names, or after raising the invalid-id exception
    /// an empty one.
    fn sampler(self) -> S {
        match crate::cpu::bindless_sampler::<S>(self.id) {
            Some(s) => s,
            None => {
                crate::cpu::raise(crate::EXCEPTION_TEXTURE_ID_INVALID);
                S::empty()
            }
        }
    }
}

impl<S> Clone for BindlessSampler<S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S> Copy for BindlessSampler<S> {}

impl<S> PartialEq for BindlessSampler<S> {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
    }
}

impl<S> Eq for BindlessSampler<S> {}

impl<S> Default for BindlessSampler<S> {
    fn default() -> Self {
        Self::NONE
    }
}

impl<S> fmt::Debug for BindlessSampler<S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "BindlessSampler({})", self.id)
    }
}

impl<S: 'static> RtData for BindlessSampler<S> {
    const LAYOUT: TypeLayout = BINDLESS_SAMPLER_LAYOUT;

    fn write_words(&self, out: &mut [u32]) {
        out[0] = self.id;
    }

    fn read_words(words: &[u32]) -> Self {
        Self::from_id(words[0])
    }
}

/// Reading a 2D texture through its id: [`Sampler2d`]'s methods.
impl BindlessSampler<Sampler2d> {
    /// [`Sampler2d::sample`] of the sampler the id names (zero through an
    /// invalid id, after
    /// [`EXCEPTION_TEXTURE_ID_INVALID`](crate::EXCEPTION_TEXTURE_ID_INVALID)).
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTex2D")]
    pub fn sample(self, uv: Vec2) -> Vec4 {
        self.sampler().sample(uv)
    }

    /// [`Sampler2d::sample_lod`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTex2DLod")]
    pub fn sample_lod(self, uv: Vec2, lod: f32) -> Vec4 {
        self.sampler().sample_lod(uv, lod)
    }

    /// [`Sampler2d::sample_grad`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTex2DGrad")]
    pub fn sample_grad(self, uv: Vec2, dx: Vec2, dy: Vec2) -> Vec4 {
        self.sampler().sample_grad(uv, dx, dy)
    }

    /// [`Sampler2d::fetch`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTex2DFetch")]
    pub fn fetch(self, texel: UVec2) -> Vec4 {
        self.sampler().fetch(texel)
    }

    /// [`Sampler2d::size`] through the id (0 through an invalid one).
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTexSize")]
    pub fn size(self) -> UVec2 {
        self.sampler().size()
    }

    /// [`Sampler2d::levels`] through the id (1 through an invalid one).
    ///
    /// Program kinds: all but bounding_box.
    pub fn levels(self) -> u32 {
        self.sampler().levels()
    }
}

/// Reading a 3D texture through its id: [`Sampler3d`]'s methods.
impl BindlessSampler<Sampler3d> {
    /// [`Sampler3d::sample`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTex3D")]
    pub fn sample(self, uvw: Vec3) -> Vec4 {
        self.sampler().sample(uvw)
    }

    /// [`Sampler3d::sample_lod`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTex3DLod")]
    pub fn sample_lod(self, uvw: Vec3, lod: f32) -> Vec4 {
        self.sampler().sample_lod(uvw, lod)
    }

    /// [`Sampler3d::sample_grad`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTex3DGrad")]
    pub fn sample_grad(self, uvw: Vec3, dx: Vec3, dy: Vec3) -> Vec4 {
        self.sampler().sample_grad(uvw, dx, dy)
    }

    /// [`Sampler3d::levels`] through the id (1 through an invalid one).
    ///
    /// Program kinds: all but bounding_box.
    pub fn levels(self) -> u32 {
        self.sampler().levels()
    }

    /// [`Sampler3d::fetch`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    pub fn fetch(self, texel: UVec3) -> Vec4 {
        self.sampler().fetch(texel)
    }

    /// [`Sampler3d::size`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    pub fn size(self) -> UVec3 {
        self.sampler().size()
    }
}

/// Reading a cube map through its id: [`SamplerCube`]'s methods.
impl BindlessSampler<SamplerCube> {
    /// [`SamplerCube::sample_dir`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTexCubemap")]
    pub fn sample_dir(self, dir: Vec3) -> Vec4 {
        self.sampler().sample_dir(dir)
    }

    /// [`SamplerCube::sample_dir_lod`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    #[doc(alias = "rtTexCubemapLod")]
    pub fn sample_dir_lod(self, dir: Vec3, lod: f32) -> Vec4 {
        self.sampler().sample_dir_lod(dir, lod)
    }

    /// [`SamplerCube::levels`] through the id (1 through an invalid one).
    ///
    /// Program kinds: all but bounding_box.
    pub fn levels(self) -> u32 {
        self.sampler().levels()
    }

    /// [`SamplerCube::size`] through the id.
    ///
    /// Program kinds: all but bounding_box.
    pub fn size(self) -> u32 {
        self.sampler().size()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::{AnyAttributes, ExecutionContext, Tracer, with_context, with_tracer};
    use crate::texture::FilterMode;
    use crate::{EXCEPTION_TEXTURE_ID_INVALID, Object, Ray};
    use std::any::Any;

    /// Id 1 names a 2D sampler, id 2 a cube map: as the CPU backend's lane.
    struct Two {
        flat: Sampler2d,
        cube: SamplerCube,
    }

    impl Tracer for Two {
        fn trace(&self, _: Object, _: &Ray, _: &mut dyn Any, _: u32, _: u32, _: f32) {}
        fn potential_intersection(&self, _: f32) -> bool {
            false
        }
        fn report_intersection(&self, _: u32, _: Option<&dyn AnyAttributes>) -> bool {
            false
        }
        fn print(&self, _: &str) {}
        fn sampler(&self, id: u32) -> Option<&(dyn Any + Send + Sync)> {
            match id {
                1 => Some(&self.flat),
                2 => Some(&self.cube),
                _ => None,
            }
        }
    }

    #[test]
    fn reads_go_through_the_tracers_samplers() {
        let texels: Vec<Vec4> = (0..24).map(|i| Vec4::splat(i as f32)).collect();
        // SAFETY: 2x2 texels (and six 2x2 faces) that outlive the tracer.
        let tracer = unsafe {
            Two {
                flat: Sampler2d::from_raw_parts(texels.as_ptr(), 2, 2, WrapMode::Clamp, FilterMode::Nearest),
                cube: SamplerCube::from_raw_parts(texels.as_ptr(), 2, FilterMode::Nearest),
            }
        };
        let flat = BindlessSampler::<Sampler2d>::from_id(1);
        let (got, ctx) = with_tracer(ExecutionContext::default(), &tracer, || {
            (flat.sample(Vec2::new(0.75, 0.75)), flat.fetch(UVec2::new(1, 0)), flat.size(), flat.levels())
        });
        assert_eq!(got, (Vec4::splat(3.0), Vec4::splat(1.0), UVec2::splat(2), 1));
        assert_eq!(ctx.pending_exception, None);
        let cube = BindlessSampler::<SamplerCube>::from_id(2);
        let (got, ctx) = with_tracer(ExecutionContext::default(), &tracer, || cube.sample_dir(-Vec3::Z));
        // Face -z (texels 20..24), its centre at nearest: texel (1, 1).
        assert_eq!((got.x, ctx.pending_exception), (23.0, None));
        // Another shape, another id, none: invalid, an empty sampler.
        let (got, ctx) = with_tracer(ExecutionContext::default(), &tracer, || {
            BindlessSampler::<Sampler2d>::from_id(2).sample(Vec2::splat(0.5))
        });
        assert_eq!((got, ctx.pending_exception), (Vec4::ZERO, Some(EXCEPTION_TEXTURE_ID_INVALID)));
        let (got, ctx) = with_tracer(ExecutionContext::default(), &tracer, || {
            let s = BindlessSampler::<Sampler2d>::from_id(3);
            (s.size(), s.levels(), s.sample_lod(Vec2::ZERO, 1.0))
        });
        assert_eq!((got, ctx.pending_exception), ((UVec2::ZERO, 1, Vec4::ZERO), Some(EXCEPTION_TEXTURE_ID_INVALID)));
        let (got, ctx) =
            with_tracer(ExecutionContext::default(), &tracer, || BindlessSampler::<Sampler3d>::NONE.size());
        assert_eq!((got, ctx.pending_exception), (UVec3::ZERO, Some(EXCEPTION_TEXTURE_ID_INVALID)));
        // Without a tracer (no launch), every id is invalid.
        let (got, ctx) = with_context(ExecutionContext::default(), || flat.fetch(UVec2::ZERO));
        assert_eq!((got, ctx.pending_exception), (Vec4::ZERO, Some(EXCEPTION_TEXTURE_ID_INVALID)));
    }
}
