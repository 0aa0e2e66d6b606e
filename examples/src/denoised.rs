//! A rendered scene's picture, denoised: the runtime's post-processing
//! stages over the guide outputs (AOVs) a path-traced scene writes
//! ([`Aovs`]), run as one command list: the denoiser over the mean
//! radiance, then the tonemapper over the raw and over the denoised
//! radiance, so the two pictures differ only by the denoising. The
//! tour's `--denoise` writes them side by side.

use crate::scene::{Aovs, Error, Image, Scene};
use glam::Vec4;
use rt_runtime::{BufferType, CommandList, StageKind};

/// The exposure the pair's tonemapper applies.
pub const EXPOSURE: f32 = 1.6;

/// The noisy and the denoised pictures (display values: the built-in
/// tonemapper's) of `scene`'s last render, or `None` where the scene
/// writes no guides.
pub fn noisy_and_denoised(scene: &mut Scene) -> Result<Option<(Image, Image)>, Error> {
    let Some(Aovs { radiance, albedo, normal }) = scene.aovs else {
        return Ok(None);
    };
    let (w, h) = (scene.width, scene.height);
    let ctx = &mut scene.ctx;
    let mut image = || -> Result<_, Error> { Ok(ctx.create_buffer_2d::<Vec4>(BufferType::Output, w, h)?) };
    let (denoised, noisy_display, denoised_display) = (image()?, image()?, image()?);
    let denoiser = ctx.create_postprocessing_stage(StageKind::Denoiser);
    ctx.set_stage_var(denoiser, "input_buffer", radiance)?;
    ctx.set_stage_var(denoiser, "input_albedo_buffer", albedo)?;
    ctx.set_stage_var(denoiser, "input_normal_buffer", normal)?;
    ctx.set_stage_var(denoiser, "output_buffer", denoised)?;
    let mut list = CommandList::new();
    list.append_stage(denoiser, w, h)?;
    for (input, output) in [(radiance, noisy_display), (denoised, denoised_display)] {
        let tonemapper = ctx.create_postprocessing_stage(StageKind::Tonemapper);
        ctx.set_stage_var(tonemapper, "input_buffer", input)?;
        ctx.set_stage_var(tonemapper, "output_buffer", output)?;
        ctx.set_stage_var(tonemapper, "exposure", EXPOSURE)?;
        list.append_stage(tonemapper, w, h)?;
    }
    list.finalize(ctx)?;
    list.execute(ctx)?;
    let read = |b| -> Result<Image, Error> { Ok(Image { width: w, height: h, pixels: ctx.read_buffer::<Vec4>(b)? }) };
    Ok(Some((read(noisy_display)?, read(denoised_display)?)))
}
