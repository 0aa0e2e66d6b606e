//! Post-processing stages through the context: the tonemapper's and the
//! denoiser's output on the CPU backend, and every way a stage's setup
//! can be wrong, each a typed error naming the stage and the variable.

use glam::Vec4;
use rt_runtime::postprocess::tonemap::tonemap_pixel;
use rt_runtime::{BufferId, BufferType, Context, PostProcessError, RtError, StageKind};

fn image(ctx: &mut Context, w: u32, h: u32, f: impl Fn(u32, u32) -> Vec4) -> BufferId {
    let b = ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, w, h).unwrap();
    let px: Vec<Vec4> = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).map(|(x, y)| f(x, y)).collect();
    ctx.write_buffer(b, &px).unwrap();
    b
}

/// A denoiser over `w` x `h` buffers: colour, albedo, normal, output.
fn denoiser(ctx: &mut Context, w: u32, h: u32) -> (rt_runtime::StageId, [BufferId; 4]) {
    let color = image(ctx, w, h, |x, y| Vec4::new(0.5 + 0.01 * x as f32, 0.25, 0.125 * y as f32, 1.0));
    let albedo = image(ctx, w, h, |_, _| Vec4::new(0.8, 0.5, 0.5, 1.0));
    let normal = image(ctx, w, h, |_, _| Vec4::new(0.0, 0.0, 1.0, 0.0));
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, w, h).unwrap();
    let stage = ctx.create_builtin_postprocessing_stage("DLDenoiser").unwrap();
    ctx.set_stage_var(stage, "input_buffer", color).unwrap();
    ctx.set_stage_var(stage, "input_albedo_buffer", albedo).unwrap();
    ctx.set_stage_var(stage, "input_normal_buffer", normal).unwrap();
    ctx.set_stage_var(stage, "output_buffer", out).unwrap();
    (stage, [color, albedo, normal, out])
}

fn stage_error(e: RtError) -> (String, String, String) {
    let text = e.to_string();
    match e {
        RtError::PostProcess(PostProcessError::BadStage { stage, variable, .. }) => (stage, variable, text),
        other => panic!("expected a stage error, got {other:?}"),
    }
}

#[test]
fn the_tonemapper_maps_every_pixel_through_exposure_the_curve_and_gamma() {
    let mut ctx = Context::new();
    let input = image(&mut ctx, 5, 3, |x, y| Vec4::new(x as f32 * 0.7, y as f32 * 2.0, 0.1, 0.5));
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 5, 3).unwrap();
    let stage = ctx.create_postprocessing_stage(StageKind::Tonemapper);
    ctx.set_stage_var(stage, "input_buffer", input).unwrap();
    ctx.set_stage_var(stage, "output_buffer", out).unwrap();
    ctx.set_stage_var(stage, "exposure", 1.5f32).unwrap();
    ctx.run_stage(stage, 5, 3).unwrap();
    let (got, inp) = (ctx.read_buffer::<Vec4>(out).unwrap(), ctx.read_buffer::<Vec4>(input).unwrap());
    for (g, i) in got.iter().zip(&inp) {
        assert_eq!(*g, tonemap_pixel(*i, 1.5, 2.2));
        assert!(g.max_element() <= 1.0 && g.min_element() >= 0.0, "{g}");
    }
    // Bright pixels saturate towards 1, black stays black.
    assert_eq!(got[0].z, tonemap_pixel(Vec4::splat(0.1), 1.5, 2.2).z);
    assert!(got[14].y > 0.95, "{}", got[14]);
}

#[test]
fn the_denoiser_leaves_a_flat_noise_free_image_as_it_is() {
    let mut ctx = Context::new();
    let (stage, [color, .., out]) = denoiser(&mut ctx, 24, 16);
    let flat = vec![Vec4::new(0.3, 0.6, 0.9, 1.0); 24 * 16];
    ctx.write_buffer(color, &flat).unwrap();
    ctx.run_stage(stage, 24, 16).unwrap();
    for p in ctx.read_buffer::<Vec4>(out).unwrap() {
        assert!((p - flat[0]).abs().max_element() < 1e-4, "{p}");
    }
}

#[test]
fn blend_one_gives_back_the_input() {
    let mut ctx = Context::new();
    let (stage, [color, .., out]) = denoiser(&mut ctx, 8, 8);
    ctx.set_stage_var(stage, "blend", 1.0f32).unwrap();
    ctx.run_stage(stage, 8, 8).unwrap();
    assert_eq!(ctx.read_buffer::<Vec4>(out).unwrap(), ctx.read_buffer::<Vec4>(color).unwrap());
}

#[test]
fn a_missing_guide_buffer_is_named() {
    let mut ctx = Context::new();
    let color = image(&mut ctx, 4, 4, |_, _| Vec4::ONE);
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 4, 4).unwrap();
    let stage = ctx.create_postprocessing_stage(StageKind::Denoiser);
    ctx.set_stage_var(stage, "input_buffer", color).unwrap();
    ctx.set_stage_var(stage, "output_buffer", out).unwrap();
    let (stage_name, variable, text) = stage_error(ctx.run_stage(stage, 4, 4).unwrap_err());
    assert_eq!((stage_name.as_str(), variable.as_str()), ("0 (`denoiser`)", "input_albedo_buffer"));
    assert_eq!(
        text,
        "post-processing stage 0 (`denoiser`): variable `input_albedo_buffer` is not set; the denoiser is guided by an albedo and a normal buffer"
    );
    assert_eq!(ctx.read_buffer::<Vec4>(out).unwrap(), vec![Vec4::ZERO; 16], "a failed stage writes nothing");
}

#[test]
fn buffers_smaller_than_the_run_are_named() {
    let mut ctx = Context::new();
    let (stage, _) = denoiser(&mut ctx, 8, 6);
    let small = image(&mut ctx, 8, 5, |_, _| Vec4::Z);
    ctx.set_stage_var(stage, "input_normal_buffer", small).unwrap();
    let (_, variable, text) = stage_error(ctx.run_stage(stage, 8, 6).unwrap_err());
    assert_eq!(variable, "input_normal_buffer");
    assert_eq!(
        text,
        format!(
            "post-processing stage 0 (`denoiser`): variable `input_normal_buffer` is buffer {} of 8x5 elements, but the stage runs at 8x6: its buffers must be at least that large",
            small.index()
        )
    );
    // The optional variance buffer too.
    let (with_variance, _) = denoiser(&mut ctx, 8, 6);
    let narrow = image(&mut ctx, 7, 6, |_, _| Vec4::ZERO);
    ctx.set_stage_var(with_variance, "input_variance_buffer", narrow).unwrap();
    let (stage_name, variable, text) = stage_error(ctx.run_stage(with_variance, 8, 6).unwrap_err());
    assert_eq!((stage_name.as_str(), variable.as_str()), ("1 (`denoiser`)", "input_variance_buffer"));
    assert_eq!(
        text,
        format!(
            "post-processing stage 1 (`denoiser`): variable `input_variance_buffer` is buffer {} of 7x6 elements, but the stage runs at 8x6: its buffers must be at least that large",
            narrow.index()
        )
    );
    // The run's size is checked against the input too.
    let (stage2, _) = denoiser(&mut ctx, 8, 6);
    let (_, variable, _) = stage_error(ctx.run_stage(stage2, 16, 6).unwrap_err());
    assert_eq!(variable, "input_buffer");
}

#[test]
fn a_buffer_that_is_not_float_rgba_is_named() {
    let mut ctx = Context::new();
    let (stage, _) = denoiser(&mut ctx, 4, 4);
    let ints = ctx.create_buffer_2d::<u32>(BufferType::Input, 4, 4).unwrap();
    ctx.set_stage_var(stage, "input_albedo_buffer", ints).unwrap();
    let (_, variable, text) = stage_error(ctx.run_stage(stage, 4, 4).unwrap_err());
    assert_eq!(variable, "input_albedo_buffer");
    assert!(text.ends_with("which holds `u32`; stages take float RGBA (`Vec4`) buffers"), "{text}");
    let (stage2, [.., out]) = denoiser(&mut ctx, 4, 4);
    let floats = ctx.create_buffer_2d::<f32>(BufferType::Input, 4, 4).unwrap();
    ctx.set_stage_var(stage2, "input_variance_buffer", floats).unwrap();
    let (_, variable, text) = stage_error(ctx.run_stage(stage2, 4, 4).unwrap_err());
    assert_eq!(variable, "input_variance_buffer");
    assert!(text.ends_with("which holds `f32`; stages take float RGBA (`Vec4`) buffers"), "{text}");
    assert_eq!(ctx.read_buffer::<Vec4>(out).unwrap(), vec![Vec4::ZERO; 16], "a failed stage writes nothing");
}

#[test]
fn unknown_variables_values_of_the_wrong_sort_and_an_output_over_an_input_are_refused() {
    let mut ctx = Context::new();
    let (stage, [color, ..]) = denoiser(&mut ctx, 4, 4);
    let text = ctx.set_stage_var(stage, "exposure", 2.0f32).unwrap_err().to_string();
    assert_eq!(
        text,
        "post-processing stage 0 (`denoiser`): variable `exposure` is not a variable of the denoiser; it has input_buffer, input_albedo_buffer, input_normal_buffer, input_variance_buffer, input_position_buffer, output_buffer, blend, temporal, alpha_min, camera_eye, camera_u, camera_v, camera_w"
    );
    let (_, variable, _) = stage_error(ctx.set_stage_var(stage, "blend", color).unwrap_err());
    assert_eq!(variable, "blend");
    let (_, variable, _) = stage_error(ctx.set_stage_var(stage, "input_buffer", 1.0f32).unwrap_err());
    assert_eq!(variable, "input_buffer");
    let (_, variable, _) = stage_error(ctx.set_stage_var(stage, "blend", f32::NAN).unwrap_err());
    assert_eq!(variable, "blend");
    ctx.set_stage_var(stage, "output_buffer", color).unwrap();
    let (_, variable, text) = stage_error(ctx.run_stage(stage, 4, 4).unwrap_err());
    assert_eq!(variable, "output_buffer");
    assert!(text.contains("which is also its `input_buffer`"), "{text}");
    let (stage2, [.., out]) = denoiser(&mut ctx, 4, 4);
    ctx.set_stage_var(stage2, "input_variance_buffer", out).unwrap();
    let (_, variable, text) = stage_error(ctx.run_stage(stage2, 4, 4).unwrap_err());
    assert_eq!(variable, "output_buffer");
    assert!(text.contains("which is also its `input_variance_buffer`"), "{text}");
    let e = ctx.create_builtin_postprocessing_stage("SuperDenoiser").unwrap_err().to_string();
    assert!(e.contains("`SuperDenoiser`"), "{e}");
}

/// Both stages on the CPU backend and as WGSL on the wgpu backend, over a
/// noisy picture of two surfaces, the denoiser with and without a
/// per-pixel variance (known in some pixels, unknown in others): the same
/// images within 1e-4 relative.
#[test]
fn the_stages_agree_on_the_cpu_and_wgpu_backends() {
    let spatial = agree(false);
    assert_ne!(agree(true), spatial, "the variance changed the denoised picture");
}

/// The denoised picture on the CPU backend, checked against wgpu's.
fn agree(with_variance: bool) -> Vec<Vec4> {
    let (w, h) = (40, 24);
    let run = |backend: rt_runtime::Backend| {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        let (stage, [color, albedo, normal, out]) = denoiser(&mut ctx, w, h);
        if with_variance {
            let variance = image(&mut ctx, w, h, |x, y| {
                let v = if (x * 7 + y * 3) % 5 == 0 { -1.0 } else { 0.002 * ((x + 2 * y) % 9) as f32 };
                Vec4::new(v, 0.0, 0.0, 0.0)
            });
            ctx.set_stage_var(stage, "input_variance_buffer", variance).unwrap();
        }
        let noise = |x: u32, y: u32| ((x.wrapping_mul(73856093) ^ y.wrapping_mul(19349663)) % 1000) as f32 / 1000.0;
        let px = (0..h).flat_map(|y| (0..w).map(move |x| (x, y)));
        let c: Vec<Vec4> = px.clone().map(|(x, y)| Vec4::new(2.0 * noise(x, y), noise(y, x), 0.5, 1.0)).collect();
        let a: Vec<Vec4> =
            px.clone().map(|(x, _)| if x < w / 2 { Vec4::splat(0.7) } else { Vec4::new(0.6, 0.1, 0.1, 1.0) }).collect();
        let n: Vec<Vec4> = px.map(|(x, y)| if x + y < 30 { Vec4::Z } else { Vec4::new(0.0, 0.6, 0.8, 0.0) }).collect();
        ctx.write_buffer(color, &c).unwrap();
        ctx.write_buffer(albedo, &a).unwrap();
        ctx.write_buffer(normal, &n).unwrap();
        ctx.run_stage(stage, w, h).unwrap();
        let tonemapped = ctx.create_buffer_2d::<Vec4>(BufferType::Output, w, h).unwrap();
        let tm = ctx.create_postprocessing_stage(StageKind::Tonemapper);
        ctx.set_stage_var(tm, "input_buffer", out).unwrap();
        ctx.set_stage_var(tm, "output_buffer", tonemapped).unwrap();
        ctx.set_stage_var(tm, "gamma", 2.4f32).unwrap();
        ctx.run_stage(tm, w, h).unwrap();
        (ctx.read_buffer::<Vec4>(out).unwrap(), ctx.read_buffer::<Vec4>(tonemapped).unwrap(), c)
    };
    let (cpu, cpu_tm, input) = run(rt_runtime::Backend::Cpu);
    let (gpu, gpu_tm, _) = run(rt_runtime::Backend::Wgpu);
    assert_ne!(cpu, input, "the denoiser changed the picture");
    for (name, a, b) in [("denoised", &cpu, &gpu), ("tonemapped", &cpu_tm, &gpu_tm)] {
        for (i, (x, y)) in a.iter().zip(b.iter()).enumerate() {
            let tolerance = 1e-4 * x.abs().max_element().max(1.0);
            assert!((*x - *y).abs().max_element() <= tolerance, "{name} pixel {i}: cpu {x} wgpu {y}");
        }
    }
    cpu
}
