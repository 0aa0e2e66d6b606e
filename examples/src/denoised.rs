//! A rendered scene's picture, denoised: the runtime's post-processing
//! stages over the guide outputs (AOVs) a path-traced scene writes
//! ([`Aovs`]), run as one command list: the denoiser over the mean
//! radiance, then the tonemapper over the raw and over the denoised
//! radiance, so the two pictures differ only by the denoising. The
//! tour's `--denoise` writes them side by side. [`Denoiser`] is the
//! denoiser alone, over linear radiance (`render --denoise`), and
//! [`guides`] reads the guides back (`render --aov`). The denoiser is
//! given the scene's per-pixel variance ([`crate::guides`]), so that edges
//! no sample disagrees about stay sharp.

use crate::scene::{Aovs, Error, Image, Scene};
use glam::Vec4;
use rt_runtime::{BufferId, BufferType, CommandList, Context, StageId, StageKind};

/// The exposure the pair's tonemapper applies.
pub const EXPOSURE: f32 = 1.6;

/// The noisy and the denoised pictures (display values: the built-in
/// tonemapper's) of `scene`'s last render, or `None` where the scene
/// writes no guides.
pub fn noisy_and_denoised(scene: &mut Scene) -> Result<Option<(Image, Image)>, Error> {
    let Some(aovs) = scene.aovs else {
        return Ok(None);
    };
    let radiance = aovs.radiance;
    let (w, h) = (scene.width, scene.height);
    let ctx = &mut scene.ctx;
    let mut image = || -> Result<_, Error> { Ok(ctx.create_buffer_2d::<Vec4>(BufferType::Output, w, h)?) };
    let (denoised, noisy_display, denoised_display) = (image()?, image()?, image()?);
    let denoiser = denoiser_stage(ctx, aovs, denoised)?;
    let mut list = CommandList::new();
    list.append_stage(denoiser, w, h)?;
    for (input, output) in [(radiance, noisy_display), (denoised, denoised_display)] {
        append_tonemapper(ctx, &mut list, (input, output), (w, h))?;
    }
    list.finalize(ctx)?;
    list.execute(ctx)?;
    let read = |b| -> Result<Image, Error> { Ok(Image { width: w, height: h, pixels: ctx.read_buffer::<Vec4>(b)? }) };
    Ok(Some((read(noisy_display)?, read(denoised_display)?)))
}

/// The picture of `scene`'s last render through the tonemapper alone (as
/// [`noisy_and_denoised`] shows its pair, to be set beside them), or
/// `None` where the scene writes no guides.
pub fn tonemapped(scene: &mut Scene) -> Result<Option<Image>, Error> {
    let Some(aovs) = scene.aovs else {
        return Ok(None);
    };
    let (width, height) = (scene.width, scene.height);
    let ctx = &mut scene.ctx;
    let output = ctx.create_buffer_2d::<Vec4>(BufferType::Output, width, height)?;
    let mut list = CommandList::new();
    append_tonemapper(ctx, &mut list, (aovs.radiance, output), (width, height))?;
    list.finalize(ctx)?;
    list.execute(ctx)?;
    Ok(Some(Image { width, height, pixels: ctx.read_buffer::<Vec4>(output)? }))
}

/// A denoiser stage over `aovs` (the radiance, guided by the albedo, the
/// normal and the per-pixel variance) into `output`.
pub fn denoiser_stage(ctx: &mut Context, aovs: Aovs, output: BufferId) -> Result<StageId, Error> {
    let denoiser = ctx.create_postprocessing_stage(StageKind::Denoiser);
    ctx.set_stage_var(denoiser, "input_buffer", aovs.radiance)?;
    ctx.set_stage_var(denoiser, "input_albedo_buffer", aovs.albedo)?;
    ctx.set_stage_var(denoiser, "input_normal_buffer", aovs.normal)?;
    ctx.set_stage_var(denoiser, "input_variance_buffer", aovs.variance)?;
    ctx.set_stage_var(denoiser, "output_buffer", output)?;
    Ok(denoiser)
}

/// Appends to `list` a tonemapper (at [`EXPOSURE`]) from `input` to
/// `output`, `width` x `height`.
fn append_tonemapper(
    ctx: &mut Context,
    list: &mut CommandList,
    (input, output): (BufferId, BufferId),
    (width, height): (u32, u32),
) -> Result<(), Error> {
    let tonemapper = ctx.create_postprocessing_stage(StageKind::Tonemapper);
    ctx.set_stage_var(tonemapper, "input_buffer", input)?;
    ctx.set_stage_var(tonemapper, "output_buffer", output)?;
    ctx.set_stage_var(tonemapper, "exposure", EXPOSURE)?;
    list.append_stage(tonemapper, width, height)?;
    Ok(())
}

/// The denoiser stage set up once over a scene's guides, run after each
/// render (a `--frames` run's every frame reuses its output buffer).
pub struct Denoiser {
    list: CommandList,
    output: BufferId,
    size: (u32, u32),
}

impl Denoiser {
    /// The denoiser over `scene`'s guides, or `None` where the scene
    /// writes none.
    pub fn new(scene: &mut Scene) -> Result<Option<Denoiser>, Error> {
        let Some(aovs) = scene.aovs else {
            return Ok(None);
        };
        let (w, h) = (scene.width, scene.height);
        let ctx = &mut scene.ctx;
        let output = ctx.create_buffer_2d::<Vec4>(BufferType::Output, w, h)?;
        let denoiser = denoiser_stage(ctx, aovs, output)?;
        let mut list = CommandList::new();
        list.append_stage(denoiser, w, h)?;
        list.finalize(ctx)?;
        Ok(Some(Denoiser { list, output, size: (w, h) }))
    }

    /// The last render's mean radiance, denoised (linear; alpha the
    /// input's).
    pub fn run(&self, scene: &mut Scene) -> Result<Image, Error> {
        self.list.execute(&mut scene.ctx)?;
        let (width, height) = self.size;
        Ok(Image { width, height, pixels: scene.ctx.read_buffer::<Vec4>(self.output)? })
    }

    /// [`Denoiser::run`] awaiting the device ([`CommandList::execute_async`]),
    /// as a browser page must.
    pub async fn run_async(&self, scene: &mut Scene) -> Result<Image, Error> {
        self.list.execute_async(&mut scene.ctx).await?;
        let (width, height) = self.size;
        Ok(Image { width, height, pixels: scene.ctx.read_buffer_async::<Vec4>(self.output).await? })
    }
}

/// The last render's guides, read back (to be seen in an image viewer,
/// alpha 1): the first hit's albedo and shading normal, each averaged
/// over the samples, and the variance of the mean's luminance (grey; -1
/// where unknown, below two samples); `None` where the scene writes none.
pub fn guides(scene: &Scene) -> Result<Option<Guides>, Error> {
    let Some(aovs) = scene.aovs else {
        return Ok(None);
    };
    let (width, height) = (scene.width, scene.height);
    let read = |b, f: fn(Vec4) -> Vec4| -> Result<Image, Error> {
        let pixels = scene.ctx.read_buffer::<Vec4>(b)?.into_iter().map(f).collect();
        Ok(Image { width, height, pixels })
    };
    let opaque = |p: Vec4| p.truncate().extend(1.0);
    Ok(Some(Guides {
        albedo: read(aovs.albedo, opaque)?,
        normal: read(aovs.normal, opaque)?,
        variance: read(aovs.variance, |p| Vec4::new(p.x, p.x, p.x, 1.0))?,
    }))
}

/// A render's guides as pictures ([`guides`]).
pub struct Guides {
    pub albedo: Image,
    pub normal: Image,
    pub variance: Image,
}
