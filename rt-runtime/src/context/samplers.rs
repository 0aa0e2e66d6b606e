//! Texture samplers: 2D, 3D and cube maps, one level or a mip chain
//! (given or generated), from RGBA texels, texels of any format, images
//! and files. Every constructor is [`Context::create_sampler_with`] over a
//! [`SamplerDescriptor`]; the OptiX-shaped `create_sampler_*` names are
//! thin wrappers that fill one in.

use super::Context;
use crate::buffer::{SamplerRec, SamplerShape};
use crate::error::{IoError, Result, RtError, SceneError};
use crate::scene::*;
use glam::{UVec2, UVec3, Vec4};
use rt_std::{FilterMode, IndexMode, MipFilter, SamplerModes, WrapMode};

/// The size of a sampler's level 0, and so its shape: the program type
/// that reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerExtent {
    /// A 2D texture of `width x height` texels, read by a `Sampler2d`.
    Flat {
        /// Texels per row.
        width: u32,
        /// Rows.
        height: u32,
    },
    /// A 3D texture, read by a `Sampler3d`; texel `(x, y, z)` at
    /// `x + y * width + z * width * height`.
    Volume(UVec3),
    /// A cube map of six `size x size` faces, read by a `SamplerCube`.
    Cube(u32),
}

/// Where a sampler's mip levels come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MipLevels {
    /// One level: [`SamplerDescriptor::images`] holds level 0.
    One,
    /// The levels given, level 0 first, from one to the full chain (down
    /// to 1x1, or 1x1x1).
    Given,
    /// Level 0 given; the rest of the full chain generated on the host by
    /// a box filter ([`generate_mip_levels`](crate::generate_mip_levels),
    /// [`generate_mip_levels_3d`](crate::generate_mip_levels_3d); a cube
    /// map's within each face).
    Generated,
}

/// Everything a sampler is made of: [`Context::create_sampler_with`]'s one
/// argument.
#[derive(Clone, Debug)]
pub struct SamplerDescriptor {
    /// Level 0's size and the sampler's shape.
    pub extent: SamplerExtent,
    /// RGBA texels, row-major: one image per level (level 0 first), and
    /// for a cube map six per level (+x, -x, +y, -y, +z, -z, Vulkan's
    /// layer order, each row-major as Vulkan lays a face out: `s` along a
    /// row, `t` down the rows).
    pub images: Vec<Vec<Vec4>>,
    /// Whether `images` holds one level, the levels, or level 0 of a chain
    /// to generate.
    pub levels: MipLevels,
    /// Wrap, filter, mip filter and index modes. A cube map clamps to its
    /// faces' edges whatever `wrap` says; [`IndexMode::ArrayIndex`] needs
    /// [`WrapMode::Clamp`] (GPUs' unnormalised coordinates clamp).
    pub modes: SamplerModes,
}

const FACES: [&str; 6] = ["+x", "-x", "+y", "-y", "+z", "-z"];

impl SamplerExtent {
    /// `WxH`, `WxHxD`, or a cube map's `SxS` faces, as messages name it.
    fn name(self) -> String {
        match self {
            SamplerExtent::Flat { width, height } => format!("{width}x{height}"),
            SamplerExtent::Volume(s) => format!("{}x{}x{}", s.x, s.y, s.z),
            SamplerExtent::Cube(size) => format!("{size}x{size}"),
        }
    }

    /// Images a level has: six for a cube map, else one.
    fn faces(self) -> usize {
        if matches!(self, SamplerExtent::Cube(_)) { 6 } else { 1 }
    }

    /// Levels in the full chain, down to 1x1 (or 1x1x1).
    fn chain(self) -> u32 {
        match self {
            SamplerExtent::Flat { width, height } => rt_std::mip_level_count(width, height),
            SamplerExtent::Volume(s) => rt_std::mip_level_count_3d(s),
            SamplerExtent::Cube(size) => rt_std::mip_level_count(size, size),
        }
    }

    /// Level `l`'s size, as a volume (depth 1 in 2D, a face's in a cube).
    fn level(self, l: u32) -> UVec3 {
        match self {
            SamplerExtent::Flat { width, height } => rt_std::mip_level_size(UVec2::new(width, height), l).extend(1),
            SamplerExtent::Volume(s) => rt_std::mip_level_size_3d(s, l),
            SamplerExtent::Cube(size) => UVec3::new((size >> l).max(1), (size >> l).max(1), 1),
        }
    }

    fn texels(self) -> u64 {
        let s = self.level(0);
        s.x as u64 * s.y as u64 * s.z as u64
    }

    /// Level 0 (six faces for a cube map) of the right texel counts, or
    /// the problem with it.
    fn check_level_zero(self, images: &[Vec<Vec4>]) -> std::result::Result<(), String> {
        if images.len() != self.faces() {
            return Err(format!(
                "{} images for one level of a {} sampler (it takes {})",
                images.len(),
                self.name(),
                self.faces()
            ));
        }
        for (image, face) in images.iter().zip(FACES) {
            if image.len() as u64 != self.texels() || image.is_empty() {
                return Err(match self {
                    SamplerExtent::Cube(_) => {
                        format!("cube face {face} has {} texels for a {} face", image.len(), self.name())
                    }
                    _ => format!("{} texels for a {} texture", image.len(), self.name()),
                });
            }
        }
        Ok(())
    }

    /// Level 0 and the rest of its full chain, generated by a box filter.
    fn generate(self, images: Vec<Vec<Vec4>>) -> std::result::Result<Vec<Vec<Vec4>>, String> {
        match self {
            SamplerExtent::Flat { width, height } => {
                self.check_level_zero(&images)?;
                Ok(crate::buffer::generate_mip_levels(&images[0], width, height))
            }
            SamplerExtent::Volume(size) => {
                self.check_level_zero(&images)?;
                Ok(crate::buffer::generate_mip_levels_3d(&images[0], size))
            }
            SamplerExtent::Cube(size) => {
                let lens: Vec<usize> = images.iter().map(Vec::len).collect();
                let chains: Vec<_> = images.iter().map(|f| crate::buffer::generate_mip_levels(f, size, size)).collect();
                let count = chains.iter().map(Vec::len).min().unwrap_or(0);
                if count == 0 || chains.len() != 6 {
                    return Err(format!("cube faces of {lens:?} texels (+x to -z) for {size}x{size} faces"));
                }
                // Level by level, each level's six faces in order.
                let mut chains: Vec<_> = chains.into_iter().map(Vec::into_iter).collect();
                Ok((0..count).flat_map(|_| chains.iter_mut().filter_map(Iterator::next).collect::<Vec<_>>()).collect())
            }
        }
    }

    /// Levels (six images each for a cube map) from one to the full
    /// chain, each of its level's texel count, or the problem with them.
    fn check_chain(self, images: &[Vec<Vec4>]) -> std::result::Result<(), String> {
        let name = self.name();
        let levels = images.len() / self.faces();
        let (empty, bottom) = match self {
            SamplerExtent::Flat { .. } => (format!("no mip levels for a {name} texture (level 0 is needed)"), "1x1"),
            SamplerExtent::Volume(_) => {
                (format!("no mip levels for a {name} texture (level 0 is needed, not empty)"), "1x1x1")
            }
            SamplerExtent::Cube(_) => {
                (format!("no mip levels for a cube map of {name} faces (level 0 is needed)"), "1x1")
            }
        };
        let zero_sized = match self {
            SamplerExtent::Flat { .. } => false,
            _ => self.texels() == 0,
        };
        if images.is_empty() || zero_sized {
            return Err(empty);
        }
        if !images.len().is_multiple_of(self.faces()) {
            return Err(format!("{} images for a cube map's levels (six faces a level)", images.len()));
        }
        let chain = self.chain();
        if levels > chain as usize {
            let what = match self {
                SamplerExtent::Cube(_) => format!("a cube map of {name} faces"),
                _ => format!("a {name} texture"),
            };
            return Err(format!("{levels} mip levels for {what}, whose full chain has {chain} (down to {bottom})"));
        }
        for (i, image) in images.iter().enumerate() {
            let l = i / self.faces();
            let s = self.level(l as u32);
            let n = s.x as usize * s.y as usize * s.z as usize;
            if image.len() != n {
                return Err(match self {
                    SamplerExtent::Flat { .. } => format!(
                        "mip level {l} has {} texels; level {l} of a {name} texture is {}x{} ({n} texels)",
                        image.len(),
                        s.x,
                        s.y
                    ),
                    SamplerExtent::Volume(_) => format!(
                        "mip level {l} has {} texels; level {l} of a {name} texture is {}x{}x{} ({n} texels)",
                        image.len(),
                        s.x,
                        s.y,
                        s.z
                    ),
                    SamplerExtent::Cube(_) => format!(
                        "cube face {} of mip level {l} has {} texels for a {}x{} face",
                        FACES[i % 6],
                        image.len(),
                        s.x,
                        s.y
                    ),
                });
            }
        }
        Ok(())
    }
}

impl Context {
    /// A sampler from its descriptor: the one constructor every
    /// `create_sampler_*` calls. The texel counts are checked against the
    /// extent (level by level, face by face), the levels against the full
    /// chain, the modes against each other; an error names the sampler,
    /// and the level and face at fault.
    #[doc(alias = "rtTextureSamplerCreate")]
    pub fn create_sampler_with(&mut self, desc: SamplerDescriptor) -> Result<SamplerId> {
        let fail =
            |problem: String| SceneError::BadSampler { sampler: self.scene.samplers.len() as u32, problem }.into();
        let SamplerDescriptor { extent, images, levels, mut modes } = desc;
        let images = match levels {
            MipLevels::One => {
                extent.check_level_zero(&images).map_err(fail)?;
                images
            }
            MipLevels::Given => images,
            MipLevels::Generated => extent.generate(images).map_err(fail)?,
        };
        extent.check_chain(&images).map_err(fail)?;
        if modes.index == IndexMode::ArrayIndex && modes.wrap != WrapMode::Clamp {
            return Err(fail(format!(
                "array-index coordinates (RT_TEXTURE_INDEX_ARRAY_INDEX) clamp to the edge, as GPUs' unnormalised coordinates do: use WrapMode::Clamp, not {:?}",
                modes.wrap
            )));
        }
        let (width, height, shape) = match extent {
            SamplerExtent::Flat { width, height } => (width, height, SamplerShape::Flat),
            SamplerExtent::Volume(s) => (s.x, s.y, SamplerShape::Volume(s.z)),
            SamplerExtent::Cube(size) => {
                modes.wrap = WrapMode::Clamp;
                (size, size, SamplerShape::Cube)
            }
        };
        let rec = SamplerRec {
            levels: (images.len() / extent.faces()) as u32,
            texels: images.concat().into_boxed_slice(),
            width,
            height,
            modes,
            shape,
        };
        self.scene.samplers.push(rec);
        Ok(SamplerId(self.scene.samplers.len() as u32 - 1))
    }

    /// A sampler over RGBA texels (row-major, `width * height` of them).
    /// The wrong texel count is refused naming the sampler's place among
    /// the buffers and samplers (`buffer N`).
    pub fn create_sampler(
        &mut self,
        texels: Vec<Vec4>,
        width: u32,
        height: u32,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Result<SamplerId> {
        let modes = SamplerModes { wrap, filter, ..SamplerModes::default() };
        let extent = SamplerExtent::Flat { width, height };
        let desc = SamplerDescriptor { extent, images: vec![texels], levels: MipLevels::One, modes };
        self.create_sampler_with(desc).map_err(|e| match e {
            RtError::Scene(SceneError::BadSampler { sampler, problem }) => {
                RtError::Scene(SceneError::BadBuffer { buffer: sampler, problem })
            }
            e => e,
        })
    }

    /// A mipmapped sampler (OptiX's mip levels of an `RTtexturesampler`):
    /// `levels[0]` holds the `width * height` texels of level 0 (row-major),
    /// `levels[l]` those of level `l`, `max(1, width >> l)` by
    /// `max(1, height >> l)` texels ([`rt_std::mip_level_size`]); any number of levels
    /// from 1 to the full chain ([`rt_std::mip_level_count`], down to 1x1).
    /// `mip` says how [`Sampler2d::sample_lod`](rt_std::Sampler2d) and
    /// `sample_grad` combine levels. A level of the wrong texel count, or
    /// more levels than the chain has, is refused naming the sampler and
    /// the level.
    pub fn create_sampler_mipmapped(
        &mut self,
        levels: Vec<Vec<Vec4>>,
        width: u32,
        height: u32,
        wrap: WrapMode,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let modes = SamplerModes { wrap, filter, mip, index: IndexMode::NormalizedCoordinates };
        let extent = SamplerExtent::Flat { width, height };
        self.create_sampler_with(SamplerDescriptor { extent, images: levels, levels: MipLevels::Given, modes })
    }

    /// A mipmapped sampler whose levels are generated on the host: the full
    /// chain of [`generate_mip_levels`](crate::generate_mip_levels) (a 2x2
    /// box filter, down to 1x1) over level 0's `width * height` texels.
    pub fn create_sampler_with_mips(
        &mut self,
        texels: Vec<Vec4>,
        width: u32,
        height: u32,
        wrap: WrapMode,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let modes = SamplerModes { wrap, filter, mip, index: IndexMode::NormalizedCoordinates };
        let extent = SamplerExtent::Flat { width, height };
        self.create_sampler_with(SamplerDescriptor {
            extent,
            images: vec![texels],
            levels: MipLevels::Generated,
            modes,
        })
    }

    /// A sampler over texels of any supported format (OptiX's buffer
    /// formats, read and index modes): the host decodes them to RGBA `f32`
    /// on upload as [`TexelData::decode`](crate::TexelData::decode) says
    /// (the texture takes 16 bytes a texel), `width * height` of them,
    /// row-major, one level. With [`IndexMode::ArrayIndex`] coordinates are
    /// in texels and, as GPUs' unnormalised coordinates, clamp to the edge:
    /// another wrap mode is refused. Errors name the sampler.
    pub fn create_sampler_from_texels(
        &mut self,
        texels: crate::TexelData,
        width: u32,
        height: u32,
        options: crate::SamplerOptions,
    ) -> Result<SamplerId> {
        self.check_texel_count(&texels, width as u64 * height as u64, &format!("{width}x{height}"))?;
        let extent = SamplerExtent::Flat { width, height };
        self.create_sampler_with(SamplerDescriptor {
            extent,
            images: vec![texels.decode(options.read)],
            levels: MipLevels::One,
            modes: options_modes(options),
        })
    }

    /// A 3D sampler (OptiX `rtTextureSampler<float4, 3>`, read by a
    /// program's `Sampler3d` variable) over `width * height * depth` RGBA
    /// texels, texel `(x, y, z)` at `x + y * width + z * width * height`;
    /// one level. The wrong texel count is refused naming the sampler.
    pub fn create_sampler_3d(
        &mut self,
        texels: Vec<Vec4>,
        size: UVec3,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Result<SamplerId> {
        let modes = SamplerModes { wrap, filter, ..SamplerModes::default() };
        let extent = SamplerExtent::Volume(size);
        self.create_sampler_with(SamplerDescriptor { extent, images: vec![texels], levels: MipLevels::One, modes })
    }

    /// A mipmapped 3D sampler (OptiX's mip levels of a 3D
    /// `RTtexturesampler`, read by `Sampler3d::sample_lod`): `levels[0]`
    /// holds level 0's `size` texels (texel `(x, y, z)` at
    /// `x + y * width + z * width * height`), `levels[l]` those of level
    /// `l`, [`rt_std::mip_level_size_3d`]; from 1 level to the full chain
    /// ([`rt_std::mip_level_count_3d`], down to 1x1x1). A level of the
    /// wrong texel count, or more levels than the chain has, is refused
    /// naming the sampler and the level.
    pub fn create_sampler_3d_mipmapped(
        &mut self,
        levels: Vec<Vec<Vec4>>,
        size: UVec3,
        wrap: WrapMode,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let modes = SamplerModes { wrap, filter, mip, index: IndexMode::NormalizedCoordinates };
        let extent = SamplerExtent::Volume(size);
        self.create_sampler_with(SamplerDescriptor { extent, images: levels, levels: MipLevels::Given, modes })
    }

    /// A mipmapped 3D sampler whose levels are generated on the host: the
    /// full chain of [`generate_mip_levels_3d`](crate::generate_mip_levels_3d)
    /// (a 2x2x2 box filter, down to 1x1x1) over level 0's texels.
    pub fn create_sampler_3d_with_mips(
        &mut self,
        texels: Vec<Vec4>,
        size: UVec3,
        wrap: WrapMode,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let modes = SamplerModes { wrap, filter, mip, index: IndexMode::NormalizedCoordinates };
        let extent = SamplerExtent::Volume(size);
        self.create_sampler_with(SamplerDescriptor {
            extent,
            images: vec![texels],
            levels: MipLevels::Generated,
            modes,
        })
    }

    /// A 3D sampler over texels of any supported format (OptiX's buffer
    /// formats and read modes behind a 3D sampler): the host decodes them
    /// to RGBA `f32` on upload as [`TexelData::decode`](crate::TexelData::decode)
    /// says, `size` of them (texel `(x, y, z)` at
    /// `x + y * width + z * width * height`), one level (for levels, decode
    /// them and pass them to
    /// [`create_sampler_3d_mipmapped`](Self::create_sampler_3d_mipmapped)).
    /// With [`IndexMode::ArrayIndex`] coordinates are in texels and clamp to
    /// the edge, as [`create_sampler_from_texels`](Self::create_sampler_from_texels)'s:
    /// another wrap mode is refused, as is the wrong texel count, naming
    /// the sampler.
    pub fn create_sampler_3d_from_texels(
        &mut self,
        texels: crate::TexelData,
        size: UVec3,
        options: crate::SamplerOptions,
    ) -> Result<SamplerId> {
        let count = size.x as u64 * size.y as u64 * size.z as u64;
        self.check_texel_count(&texels, count, &format!("{}x{}x{}", size.x, size.y, size.z))?;
        self.create_sampler_with(SamplerDescriptor {
            extent: SamplerExtent::Volume(size),
            images: vec![texels.decode(options.read)],
            levels: MipLevels::One,
            modes: options_modes(options),
        })
    }

    /// A cube map (OptiX's cube-map textures, read by a program's
    /// `SamplerCube` variable with `sample_dir`): six `size x size` faces
    /// of RGBA texels, `faces[0..6]` being +x, -x, +y, -y, +z, -z (Vulkan's
    /// layer order), each row-major as Vulkan lays a face out (`s` along a
    /// row, `t` down the rows; see `SamplerCube::face_coordinates`). Faces
    /// clamp to their edges. A face of the wrong texel count is refused
    /// naming the sampler and the face.
    pub fn create_sampler_cube(&mut self, faces: [Vec<Vec4>; 6], size: u32, filter: FilterMode) -> Result<SamplerId> {
        let modes = SamplerModes { wrap: WrapMode::Clamp, filter, ..SamplerModes::default() };
        let extent = SamplerExtent::Cube(size);
        self.create_sampler_with(SamplerDescriptor { extent, images: faces.into(), levels: MipLevels::One, modes })
    }

    /// A mipmapped cube map (read by `SamplerCube::sample_dir_lod`):
    /// `levels[l]` holds level `l`'s six faces (+x, -x, +y, -y, +z, -z, as
    /// [`create_sampler_cube`](Self::create_sampler_cube) has them) of side
    /// `max(1, size >> l)`; from 1 level to the full chain (down to 1x1
    /// faces). A face of the wrong texel count, or more levels than the
    /// chain has, is refused naming the sampler, the level and the face.
    pub fn create_sampler_cube_mipmapped(
        &mut self,
        levels: Vec<[Vec<Vec4>; 6]>,
        size: u32,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let modes = SamplerModes { wrap: WrapMode::Clamp, filter, mip, ..SamplerModes::default() };
        let images = levels.into_iter().flat_map(<[Vec<Vec4>; 6]>::into_iter).collect();
        let extent = SamplerExtent::Cube(size);
        self.create_sampler_with(SamplerDescriptor { extent, images, levels: MipLevels::Given, modes })
    }

    /// A mipmapped cube map whose levels are generated on the host: each
    /// face's full chain of [`generate_mip_levels`](crate::generate_mip_levels)
    /// (a 2x2 box filter within the face, down to 1x1).
    pub fn create_sampler_cube_with_mips(
        &mut self,
        faces: [Vec<Vec4>; 6],
        size: u32,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let modes = SamplerModes { wrap: WrapMode::Clamp, filter, mip, ..SamplerModes::default() };
        let extent = SamplerExtent::Cube(size);
        self.create_sampler_with(SamplerDescriptor {
            extent,
            images: faces.into(),
            levels: MipLevels::Generated,
            modes,
        })
    }

    /// A cube map over faces of any supported format, decoded to RGBA
    /// `f32` on upload as [`TexelData::decode`](crate::TexelData::decode)
    /// says with read mode `read`: `faces[0..6]` (+x, -x, +y, -y, +z, -z)
    /// of `size * size` texels each, one level (for levels, decode them
    /// and pass them to
    /// [`create_sampler_cube_mipmapped`](Self::create_sampler_cube_mipmapped)).
    /// A face of the wrong texel count is refused naming the sampler, the
    /// face and its format.
    pub fn create_sampler_cube_from_texels(
        &mut self,
        faces: [crate::TexelData; 6],
        size: u32,
        filter: FilterMode,
        read: crate::ReadMode,
    ) -> Result<SamplerId> {
        let n = size as usize * size as usize;
        for (face, name) in faces.iter().zip(FACES) {
            if face.len() != n || n == 0 {
                return Err(SceneError::BadSampler {
                    sampler: self.scene.samplers.len() as u32,
                    problem: format!(
                        "cube face {name} has {} {} texels for a {size}x{size} face",
                        face.len(),
                        face.format_name()
                    ),
                }
                .into());
            }
        }
        self.create_sampler_cube(faces.map(|f| f.decode(read)), size, filter)
    }

    /// A sampler from an image (8-bit channels map to `[0, 1]`, float
    /// channels are kept as they are).
    pub fn create_sampler_from_image(
        &mut self,
        image: &image::DynamicImage,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Result<SamplerId> {
        let rgba = image.to_rgba32f();
        let (w, h) = rgba.dimensions();
        let texels = rgba.pixels().map(|p| Vec4::from_array(p.0)).collect();
        self.create_sampler(texels, w, h, wrap, filter)
    }

    /// A sampler from an image file (PNG or Radiance HDR, by content). A
    /// file of another format, or one that does not decode, is refused with
    /// the path and the reason.
    pub fn create_sampler_from_file(
        &mut self,
        path: impl AsRef<std::path::Path>,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Result<SamplerId> {
        let path = path.as_ref();
        let fail = |problem: String| IoError::Texture { path: path.display().to_string(), problem }.into();
        let reader = image::ImageReader::open(path)
            .map_err(|e| fail(e.to_string()))?
            .with_guessed_format()
            .map_err(|e| fail(e.to_string()))?;
        let Some(format) = reader.format() else {
            return Err(fail("not an image format this build reads (PNG, Radiance HDR)".into()));
        };
        if !matches!(format, image::ImageFormat::Png | image::ImageFormat::Hdr) {
            return Err(fail(format!(
                "{} images are not supported (supported: PNG, Radiance HDR)",
                format.extensions_str().first().unwrap_or(&"this kind of").to_uppercase()
            )));
        }
        let image = reader.decode().map_err(|e| fail(format!("does not decode as {format:?}: {e}")))?;
        self.create_sampler_from_image(&image, wrap, filter)
    }

    /// `texels` are `count` of them, or an error naming the sampler, the
    /// texels' format and the texture's `size`.
    fn check_texel_count(&self, texels: &crate::TexelData, count: u64, size: &str) -> Result<()> {
        if texels.len() as u64 != count || texels.is_empty() {
            return Err(SceneError::BadSampler {
                sampler: self.scene.samplers.len() as u32,
                problem: format!("{} {} texels for a {size} texture", texels.len(), texels.format_name()),
            }
            .into());
        }
        Ok(())
    }
}

/// A texel sampler's options as modes (one level: the mip filter is
/// linear, as every sampler's default).
fn options_modes(options: crate::SamplerOptions) -> SamplerModes {
    SamplerModes { wrap: options.wrap, filter: options.filter, mip: MipFilter::Linear, index: options.index }
}
