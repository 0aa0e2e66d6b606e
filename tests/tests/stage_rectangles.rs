//! Post-processing stages run over the top-left part of larger buffers
//! (a renderer's buffers that only grow): on the CPU and wgpu backends a
//! run over `w` x `h` of larger buffers writes, in that rectangle of its
//! output, what the same run over buffers cropped to it writes, and
//! leaves the output's other texels as they were; the denoiser (with a
//! variance, and temporal, frame after frame), the tonemapper, and a run
//! of stages whose second reads beyond the first's rectangle. On wgpu a
//! run sends and reads back the rectangle only. A buffer smaller than the
//! run is an error naming the stage and the variable.

use glam::{Vec3, Vec4};
use rt_runtime::{Backend, BufferId, BufferType, CommandList, Context, PostProcessError, RtError, StageId, StageKind};

/// The buffers' size, and the run's.
const BIG: (u32, u32) = (37, 26);
const RUN: (u32, u32) = (29, 17);

/// A picture of `size` from `f`, row by row.
fn picture(size: (u32, u32), f: impl Fn(u32, u32) -> Vec4) -> Vec<Vec4> {
    (0..size.1).flat_map(|y| (0..size.0).map(move |x| (x, y))).map(|(x, y)| f(x, y)).collect()
}

/// A hash of `(x, y, seed)` in [0, 1).
fn noise(x: u32, y: u32, seed: u32) -> f32 {
    let mut h = x.wrapping_mul(73856093) ^ y.wrapping_mul(19349663) ^ seed.wrapping_mul(83492791);
    h = (h ^ (h >> 13)).wrapping_mul(1274126177);
    ((h ^ (h >> 16)) & 0xffff) as f32 / 65536.0
}

/// The temporal denoiser's camera: eye, u, v, w.
const CAMERA: [Vec3; 4] = [Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.8, 0.0, 0.0), Vec3::new(0.0, 0.6, 0.0), Vec3::NEG_Z];

/// The images of frame `seed` at pixel `(x, y)`: colour, albedo, normal,
/// variance (unknown in some pixels), position (where the pixel's ray
/// through [`CAMERA`], in a picture of `RUN`, meets the plane z = 0).
fn images(x: u32, y: u32, seed: u32) -> [Vec4; 5] {
    let left = x + y < 20;
    let color = Vec4::new(2.0 * noise(x, y, seed), noise(y, x, seed), 0.5, 1.0);
    let albedo = if left { Vec4::splat(0.7) } else { Vec4::new(0.6, 0.1, 0.1, 1.0) };
    let normal = if left { Vec4::Z } else { Vec4::new(0.0, 0.6, 0.8, 0.0) };
    let variance = if (x * 7 + y * 3).is_multiple_of(5) { -1.0 } else { 0.002 * ((x + 2 * y) % 9) as f32 };
    let [eye, u, v, w] = CAMERA;
    let d = (glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5) / glam::Vec2::new(RUN.0 as f32, RUN.1 as f32)) * 2.0 - 1.0;
    let position = (eye + (d.x * u + d.y * v + w) * 5.0).extend(1.0);
    [color, albedo, normal, Vec4::new(variance, 0.0, 0.0, 0.0), position]
}

/// Texels outside the run's rectangle: what the output holds before.
fn sentinel(x: u32, y: u32) -> Vec4 {
    Vec4::new(-7.0, x as f32, y as f32, 42.0)
}

/// Which stage a case runs.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Case {
    Spatial,
    Temporal,
    Tonemapper,
}

/// A stage of `case` over fresh buffers of `size` (colour, albedo,
/// normal, variance, position, output), the output filled with
/// [`sentinel`].
fn stage(ctx: &mut Context, case: Case, size: (u32, u32)) -> (StageId, [BufferId; 6]) {
    let mut buffer = |_| ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, size.0, size.1).unwrap();
    let buffers = [0, 1, 2, 3, 4, 5].map(&mut buffer);
    ctx.write_buffer(buffers[5], &picture(size, sentinel)).unwrap();
    let kind = if case == Case::Tonemapper { StageKind::Tonemapper } else { StageKind::Denoiser };
    let stage = ctx.create_postprocessing_stage(kind);
    let names: &[(&str, usize)] = match case {
        Case::Tonemapper => &[("input_buffer", 0), ("output_buffer", 5)],
        _ => &[
            ("input_buffer", 0),
            ("input_albedo_buffer", 1),
            ("input_normal_buffer", 2),
            ("input_variance_buffer", 3),
            ("input_position_buffer", 4),
            ("output_buffer", 5),
        ],
    };
    for &(name, i) in names {
        ctx.set_stage_var(stage, name, buffers[i]).unwrap();
    }
    if case == Case::Temporal {
        ctx.set_stage_var(stage, "temporal", 1.0f32).unwrap();
    }
    (stage, buffers)
}

/// Frame `f` into `buffers` of `size` (the pixels outside `RUN` hold a
/// frame of their own, which the run must not see), and the camera set
/// on the temporal stage.
fn load(ctx: &mut Context, (stage, buffers): (StageId, [BufferId; 6]), size: (u32, u32), f: u32, case: Case) {
    for (i, &b) in buffers[..5].iter().enumerate() {
        let px = picture(size, |x, y| {
            let inside = x < RUN.0 && y < RUN.1;
            images(x, y, if inside { f } else { f + 1000 })[i] * if inside { 1.0 } else { 3.0 }
        });
        ctx.write_buffer(b, &px).unwrap();
    }
    if case == Case::Temporal {
        for (name, x) in ["camera_eye", "camera_u", "camera_v", "camera_w"].into_iter().zip(CAMERA) {
            ctx.set_stage_var(stage, name, x).unwrap();
        }
    }
}

/// The top-left `RUN` of `all`, an image `width` pixels wide.
fn crop(all: &[Vec4], width: u32) -> Vec<Vec4> {
    (0..RUN.1 as usize).flat_map(|y| &all[y * width as usize..][..RUN.0 as usize]).copied().collect()
}

/// Over frames (three for the temporal denoiser, one else): the output's
/// rectangle after a run over `RUN` of `BIG` buffers equals the output
/// of the same run over buffers of `RUN`, bit for bit, and its other
/// texels are as they were; the temporal denoiser's history is of the
/// run's size and the same.
fn rectangle_is_the_cropped_run(backend: Backend, case: Case) {
    let (mut big, mut small) = (Context::new(), Context::new());
    big.set_backend(backend);
    small.set_backend(backend);
    let (on_big, on_small) = (stage(&mut big, case, BIG), stage(&mut small, case, RUN));
    let frames = if case == Case::Temporal { 3 } else { 1 };
    for f in 0..frames {
        load(&mut big, on_big, BIG, f, case);
        load(&mut small, on_small, RUN, f, case);
        let (read, uploaded) = (big.stage_read_back_bytes(), big.stage_upload_bytes());
        big.run_stage(on_big.0, RUN.0, RUN.1).unwrap();
        small.run_stage(on_small.0, RUN.0, RUN.1).unwrap();
        let rect_bytes = (RUN.0 * RUN.1 * 16) as u64;
        if backend == Backend::Wgpu {
            assert_eq!(big.stage_read_back_bytes() - read, rect_bytes, "{case:?}: the rectangle alone comes back");
            let images = match case {
                Case::Tonemapper => 1,
                Case::Spatial => 4,
                Case::Temporal => 5,
            };
            assert_eq!(
                big.stage_upload_bytes() - uploaded,
                images * rect_bytes,
                "{case:?}: its rectangles alone go up"
            );
        }
        let got = big.read_buffer::<Vec4>(on_big.1[5]).unwrap();
        let want = small.read_buffer::<Vec4>(on_small.1[5]).unwrap();
        assert_ne!(want, picture(RUN, sentinel), "{case:?}: the run wrote its output");
        assert_eq!(crop(&got, BIG.0), want, "{backend:?} {case:?} frame {f}: the rectangle");
        for (i, (p, s)) in got.iter().zip(picture(BIG, sentinel)).enumerate() {
            let (x, y) = (i as u32 % BIG.0, i as u32 / BIG.0);
            if x >= RUN.0 || y >= RUN.1 {
                assert_eq!(*p, s, "{backend:?} {case:?}: texel ({x}, {y}) outside the run");
            }
        }
    }
    if case == Case::Temporal {
        let (got, want) = (big.stage_history(on_big.0).unwrap(), small.stage_history(on_small.0).unwrap());
        assert_eq!(got, want, "{backend:?}: the history");
        assert_eq!(got.unwrap().2.iter().map(|t| t.w).fold(0.0, f32::max), 3.0, "the history holds the frames");
    }
}

#[test]
fn the_denoiser_over_part_of_larger_buffers_is_the_denoiser_over_that_part() {
    for backend in [Backend::Cpu, Backend::Wgpu] {
        rectangle_is_the_cropped_run(backend, Case::Spatial);
    }
}

#[test]
fn the_temporal_denoiser_over_part_of_larger_buffers_is_it_over_that_part() {
    for backend in [Backend::Cpu, Backend::Wgpu] {
        rectangle_is_the_cropped_run(backend, Case::Temporal);
    }
}

#[test]
fn the_tonemapper_over_part_of_larger_buffers_is_the_tonemapper_over_that_part() {
    for backend in [Backend::Cpu, Backend::Wgpu] {
        rectangle_is_the_cropped_run(backend, Case::Tonemapper);
    }
}

/// A list of the denoiser over `RUN` of `BIG` buffers, then the
/// tonemapper over all of the denoiser's output (beyond the rectangle
/// the denoiser wrote, where the output holds [`sentinel`]): the
/// tonemapper sees the denoiser's rectangle and the sentinel around it,
/// on both backends.
#[test]
fn a_stage_reading_beyond_an_earlier_ones_rectangle_sees_the_buffer_around_it() {
    let run = |backend| {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        let denoiser = stage(&mut ctx, Case::Spatial, BIG);
        load(&mut ctx, denoiser, BIG, 0, Case::Spatial);
        let display = ctx.create_buffer_2d::<Vec4>(BufferType::Output, BIG.0, BIG.1).unwrap();
        let tonemapper = ctx.create_postprocessing_stage(StageKind::Tonemapper);
        ctx.set_stage_var(tonemapper, "input_buffer", denoiser.1[5]).unwrap();
        ctx.set_stage_var(tonemapper, "output_buffer", display).unwrap();
        let mut list = CommandList::new();
        list.append_stage(denoiser.0, RUN.0, RUN.1).unwrap();
        list.append_stage(tonemapper, BIG.0, BIG.1).unwrap();
        list.finalize(&ctx).unwrap();
        list.execute(&mut ctx).unwrap();
        (ctx.read_buffer::<Vec4>(denoiser.1[5]).unwrap(), ctx.read_buffer::<Vec4>(display).unwrap())
    };
    let (cpu_denoised, cpu) = run(Backend::Cpu);
    let (gpu_denoised, gpu) = run(Backend::Wgpu);
    let tonemapped = |p: Vec4| rt_runtime::postprocess::tonemap::tonemap_pixel(p, 1.0, 2.2);
    for (i, ((c, g), d)) in cpu.iter().zip(&gpu).zip(&cpu_denoised).enumerate() {
        let (x, y) = (i as u32 % BIG.0, i as u32 / BIG.0);
        if x >= RUN.0 || y >= RUN.1 {
            assert_eq!(*d, sentinel(x, y), "({x}, {y}) outside the denoiser's run");
        }
        assert_eq!(*c, tonemapped(*d), "cpu ({x}, {y})");
        let tolerance = 1e-4 * c.abs().max_element().max(1.0);
        assert!((*c - *g).abs().max_element() <= tolerance, "({x}, {y}): cpu {c}, wgpu {g}");
        let d_tolerance = 1e-4 * d.abs().max_element().max(1.0);
        assert!((*d - gpu_denoised[i]).abs().max_element() <= d_tolerance, "denoised ({x}, {y})");
    }
}

/// A buffer narrower or shorter than the run is an error naming the
/// stage and the variable; one larger is not.
#[test]
fn a_buffer_smaller_than_the_run_is_named() {
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        let (stage, buffers) = stage(&mut ctx, Case::Spatial, BIG);
        load(&mut ctx, (stage, buffers), BIG, 0, Case::Spatial);
        let narrow = ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, RUN.0 - 1, BIG.1).unwrap();
        ctx.set_stage_var(stage, "input_normal_buffer", narrow).unwrap();
        let e = ctx.run_stage(stage, RUN.0, RUN.1).unwrap_err();
        let text = e.to_string();
        let RtError::PostProcess(PostProcessError::BadStage { stage: name, variable, .. }) = e else {
            panic!("expected a stage error, got {e:?}");
        };
        assert_eq!((name.as_str(), variable.as_str()), ("0 (`denoiser`)", "input_normal_buffer"));
        assert_eq!(
            text,
            format!(
                "post-processing stage 0 (`denoiser`): variable `input_normal_buffer` is buffer {} of 28x26 elements, but the stage runs at 29x17: its buffers must be at least that large",
                narrow.index()
            )
        );
        assert_eq!(ctx.read_buffer::<Vec4>(buffers[5]).unwrap(), picture(BIG, sentinel), "a failed run writes nothing");
        let short = ctx.create_buffer_2d::<Vec4>(BufferType::Output, BIG.0, RUN.1 - 1).unwrap();
        ctx.set_stage_var(stage, "input_normal_buffer", buffers[2]).unwrap();
        ctx.set_stage_var(stage, "output_buffer", short).unwrap();
        let e = ctx.run_stage(stage, RUN.0, RUN.1).unwrap_err().to_string();
        assert!(e.contains("variable `output_buffer` is buffer"), "{e}");
        ctx.set_stage_var(stage, "output_buffer", buffers[5]).unwrap();
        ctx.run_stage(stage, RUN.0, RUN.1).unwrap();
    }
}
