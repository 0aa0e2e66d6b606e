//! The denoiser's temporal mode (`rt_runtime::postprocess::temporal`)
//! through the context, over a scene traced here on the host: a
//! checkered floor (z = 0) under a bright square (z = 2), both facing the
//! camera. Still frames of noise accumulate towards the noise-free
//! picture; a moved camera finds its history where the floor was seen
//! before and none where the square hid it; a reset drops the history;
//! the CPU and wgpu backends agree, frame by frame; on wgpu the history
//! stays on the device (no run moves it to or from the host), moves with
//! a switch of backends and is dropped with a lost device; bad setups are
//! typed errors naming the stage and the variable.

use glam::{Vec3, Vec4};
use rt_runtime::{
    Backend, BufferId, BufferType, CommandList, Context, DeviceError, PostProcessError, RtError, Scope, StageId,
};
use rt_std::prelude::{RwBuffer2d, launch_index, rt_program};

const W: u32 = 32;
const H: u32 = 24;

/// The camera at `eye` looking down -z, a picture 8 x 6 units wide at
/// z = 0 from z = 5 (a floor pixel is 0.25 units).
#[derive(Clone, Copy)]
struct Camera {
    eye: Vec3,
    u: Vec3,
    v: Vec3,
    w: Vec3,
}

fn camera(x: f32) -> Camera {
    Camera { eye: Vec3::new(x, 0.0, 5.0), u: Vec3::new(0.8, 0.0, 0.0), v: Vec3::new(0.0, 0.6, 0.0), w: Vec3::NEG_Z }
}

/// The floor's checker (cells one unit wide) and the square's colour.
fn floor_color(p: Vec3) -> f32 {
    if (p.x.floor() as i32 + p.y.floor() as i32).rem_euclid(2) == 0 { 0.2 } else { 0.8 }
}

const SQUARE: f32 = 0.9;

/// What pixel `(x, y)` sees through `cam`: the point, and whether it is
/// the square's.
fn trace(cam: Camera, x: u32, y: u32) -> (Vec3, bool) {
    trace_sized(cam, x, y, (W, H))
}

/// [`trace`] in a picture of `size`.
fn trace_sized(cam: Camera, x: u32, y: u32, (w, h): (u32, u32)) -> (Vec3, bool) {
    let d = (glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5) / glam::Vec2::new(w as f32, h as f32)) * 2.0 - 1.0;
    let dir = d.x * cam.u + d.y * cam.v + cam.w;
    let on_square = cam.eye + dir * ((cam.eye.z - 2.0) / -dir.z);
    if on_square.x.abs() <= 1.0 && on_square.y.abs() <= 1.0 {
        return (on_square, true);
    }
    (cam.eye + dir * (cam.eye.z / -dir.z), false)
}

/// A frame through `cam`: colour (the clean picture plus `noise` times a
/// hash of the pixel and `frame` in [-1, 1)), albedo, normal, position.
fn frame(cam: Camera, noise: f32, frame: u32) -> [Vec<Vec4>; 4] {
    frame_sized(cam, noise, frame, (W, H))
}

/// [`frame`] of `size` pixels.
fn frame_sized(cam: Camera, noise: f32, frame: u32, size: (u32, u32)) -> [Vec<Vec4>; 4] {
    let mut images: [Vec<Vec4>; 4] = Default::default();
    for y in 0..size.1 {
        for x in 0..size.0 {
            let (p, square) = trace_sized(cam, x, y, size);
            let clean = if square { SQUARE } else { floor_color(p) };
            let mut h = (x.wrapping_mul(73856093) ^ y.wrapping_mul(19349663) ^ frame.wrapping_mul(83492791))
                .wrapping_mul(1274126177);
            h ^= h >> 16;
            let n = (h & 0xffff) as f32 / 32768.0 - 1.0;
            images[0].push(Vec4::new(clean + noise * n, clean + noise * n, clean + noise * n, 1.0));
            images[1].push(Vec4::ONE);
            images[2].push(Vec4::Z);
            images[3].push(p.extend(1.0));
        }
    }
    images
}

fn clean(cam: Camera) -> Vec<Vec4> {
    frame(cam, 0.0, 0)[0].clone()
}

/// A temporal denoiser over fresh buffers: its stage, its four inputs
/// and output.
fn temporal(ctx: &mut Context) -> (StageId, [BufferId; 5]) {
    let stage = ctx.create_builtin_postprocessing_stage("DLDenoiser").unwrap();
    ctx.set_stage_var(stage, "temporal", 1.0f32).unwrap();
    (stage, images_of(ctx, stage, (W, H)))
}

/// Fresh buffers of `size` as `stage`'s four inputs and output.
fn images_of(ctx: &mut Context, stage: StageId, (w, h): (u32, u32)) -> [BufferId; 5] {
    let mut buffer = |_| ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, w, h).unwrap();
    let buffers = [0, 1, 2, 3, 4].map(&mut buffer);
    bind(ctx, stage, buffers);
    buffers
}

/// Sets `buffers` as `stage`'s four inputs and output.
fn bind(ctx: &mut Context, stage: StageId, buffers: [BufferId; 5]) {
    for (name, b) in
        ["input_buffer", "input_albedo_buffer", "input_normal_buffer", "input_position_buffer", "output_buffer"]
            .into_iter()
            .zip(buffers)
    {
        ctx.set_stage_var(stage, name, b).unwrap();
    }
}

/// Runs `stage` over `images` seen through `cam`; its output.
fn run(ctx: &mut Context, stage: (StageId, [BufferId; 5]), cam: Camera, images: &[Vec<Vec4>; 4]) -> Vec<Vec4> {
    run_sized(ctx, stage, cam, images, (W, H))
}

/// [`run`] over images of `size`.
fn run_sized(
    ctx: &mut Context,
    (stage, buffers): (StageId, [BufferId; 5]),
    cam: Camera,
    images: &[Vec<Vec4>; 4],
    (w, h): (u32, u32),
) -> Vec<Vec4> {
    for (b, px) in buffers.iter().zip(images) {
        ctx.write_buffer(*b, px).unwrap();
    }
    for (name, v) in [("camera_eye", cam.eye), ("camera_u", cam.u), ("camera_v", cam.v), ("camera_w", cam.w)] {
        ctx.set_stage_var(stage, name, v).unwrap();
    }
    ctx.run_stage(stage, w, h).unwrap();
    ctx.read_buffer::<Vec4>(buffers[4]).unwrap()
}

fn squared_error(a: &[Vec4], b: &[Vec4]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x.truncate() - y.truncate()).length_squared()).sum()
}

#[test]
fn still_frames_of_noise_accumulate_towards_the_clean_picture() {
    let mut ctx = Context::new();
    let stage = temporal(&mut ctx);
    let cam = camera(0.0);
    let reference = clean(cam);
    let mut errors = Vec::new();
    for f in 0..16 {
        let out = run(&mut ctx, stage, cam, &frame(cam, 0.5, f));
        errors.push(squared_error(&out, &reference));
    }
    eprintln!("squared error by frame: {errors:?}");
    // The spatial filter alone (the first frame) against frames blended:
    // from the fourth the moments give the variance (no longer the
    // spatial estimate, which takes the checker's edges for noise), and
    // alpha_min 0.2 keeps about nine frames' worth (measured: 111, 19.3
    // at the fourth, 9.5 at the sixteenth).
    assert!(errors[1] < errors[0] && errors[2] < errors[1], "{errors:?}");
    assert!(errors[3] < errors[0] * 0.25, "{errors:?}");
    assert!(errors[15] < errors[0] * 0.12, "{errors:?}");
    let (w, h, history) = ctx.stage_history(stage.0).unwrap().unwrap();
    assert_eq!((w, h), (W, H));
    assert!(history.iter().all(|p| p.w == 16.0), "every pixel holds all 16 frames");
}

/// Two frames: the clean picture from `camera(0)`, then a black one
/// from `camera(0.5)` (the floor 2 pixels to the left, the square 3.33):
/// each pixel's history is half the colour it saw first, found where the
/// point it sees was seen then; a floor point the square hid then, or
/// outside the first picture, starts again (black, one frame).
#[test]
fn a_moved_camera_finds_the_history_where_each_point_was_seen() {
    let (before, after) = (camera(0.0), camera(0.5));
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        let stage = temporal(&mut ctx);
        run(&mut ctx, stage, before, &frame(before, 0.0, 0));
        let mut black = frame(after, 0.0, 0);
        black[0].fill(Vec4::new(0.0, 0.0, 0.0, 1.0));
        run(&mut ctx, stage, after, &black);
        let (_, _, history) = ctx.stage_history(stage.0).unwrap().unwrap();
        let first = clean(before);
        let (mut kept, mut disoccluded, mut moved) = (0, 0, 0);
        for y in 0..H {
            for x in 0..W {
                let got = history[(y * W + x) as usize];
                let (p, square) = trace(after, x, y);
                let seen = pixel_of(before, p).filter(|&(qx, qy)| trace(before, qx, qy).1 == square);
                match seen {
                    Some((qx, qy)) => {
                        let want = first[(qy * W + qx) as usize].x * 0.5;
                        assert!((got.x - want).abs() < 1e-5 && got.w == 2.0, "{backend:?} ({x}, {y}): {got} vs {want}");
                        kept += 1;
                        moved += (want != first[(y * W + x) as usize].x * 0.5) as u32;
                    }
                    None => {
                        assert_eq!(got, Vec4::new(0.0, 0.0, 0.0, 1.0), "{backend:?} ({x}, {y}) starts again");
                        disoccluded += (pixel_of(before, p).is_some() && !square) as u32;
                    }
                }
            }
        }
        eprintln!("{backend:?}: kept {kept}, disoccluded {disoccluded}, moved {moved}");
        assert!(moved > 100, "the test tells a moved history from one kept in place: {moved}");
        assert!(disoccluded >= 20 && kept > 600, "{backend:?}: kept {kept}, disoccluded {disoccluded}");
    }
}

/// The pixel of a `W` x `H` picture through `cam` where `p` appears.
fn pixel_of(cam: Camera, p: Vec3) -> Option<(u32, u32)> {
    let d = p - cam.eye;
    let depth = d.dot(cam.w);
    let s = glam::Vec2::new(d.dot(cam.u) / cam.u.length_squared(), d.dot(cam.v) / cam.v.length_squared()) / depth;
    let px = (s + 1.0) * 0.5 * glam::Vec2::new(W as f32, H as f32);
    (px.x >= 0.0 && px.y >= 0.0 && px.x < W as f32 && px.y < H as f32).then_some((px.x as u32, px.y as u32))
}

#[test]
fn a_reset_drops_the_history() {
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        let stage = temporal(&mut ctx);
        let cam = camera(0.0);
        let first = run(&mut ctx, stage, cam, &frame(cam, 0.5, 0));
        run(&mut ctx, stage, cam, &frame(cam, 0.5, 1));
        assert_eq!(ctx.stage_history(stage.0).unwrap().unwrap().2[0].w, 2.0, "{backend:?}");
        ctx.reset_stage_history(stage.0).unwrap();
        assert_eq!(ctx.stage_history(stage.0).unwrap(), None, "{backend:?}");
        // The frame after a reset is denoised as a first frame is.
        assert_eq!(run(&mut ctx, stage, cam, &frame(cam, 0.5, 0)), first, "{backend:?}");
        assert!(ctx.stage_history(stage.0).unwrap().unwrap().2.iter().all(|p| p.w == 1.0), "{backend:?}");
        // Turning the mode off drops it too; setting it to what it is does not.
        ctx.set_stage_var(stage.0, "temporal", 1.0f32).unwrap();
        assert!(ctx.stage_history(stage.0).unwrap().is_some(), "{backend:?}");
        ctx.set_stage_var(stage.0, "temporal", 0.0f32).unwrap();
        assert_eq!(ctx.stage_history(stage.0).unwrap(), None, "{backend:?}");
    }
}

/// Where the camera is at frame `f` of the agreement tests: still, then
/// moving.
fn path(f: usize) -> Camera {
    camera([0.0, 0.0, 0.25, 0.5, 0.5, 0.75, 1.0][f % 7])
}

/// Seven frames, the camera moving, of noise: the CPU and wgpu backends
/// give the same pictures and histories, frame by frame, within 1e-4
/// relative.
#[test]
fn the_cpu_and_wgpu_backends_agree() {
    let frames = |backend| {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        let stage = temporal(&mut ctx);
        let mut images = Vec::new();
        for f in 0..7 {
            images.push(run(&mut ctx, stage, path(f), &frame(path(f), 0.3, f as u32)));
            images.push(ctx.stage_history(stage.0).unwrap().unwrap().2);
        }
        images
    };
    let (cpu, gpu) = (frames(Backend::Cpu), frames(Backend::Wgpu));
    assert_close(&cpu, &gpu, "wgpu");
    assert_ne!(cpu[8], cpu[6], "the frames differ");
    assert!(cpu[13].iter().any(|p| p.w == 7.0), "some pixels hold every frame");
}

/// Images `a` (the CPU's) and `b` agree within 1e-4 relative, pixel by
/// pixel.
fn assert_close(a: &[Vec<Vec4>], b: &[Vec<Vec4>], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (f, (a, b)) in a.iter().zip(b).enumerate() {
        assert_eq!(a.len(), b.len(), "{what}: image {f}");
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            let tolerance = 1e-4 * x.abs().max_element().max(1.0);
            assert!((*x - *y).abs().max_element() <= tolerance, "{what}: image {f} pixel {i}: cpu {x}, {what} {y}");
        }
    }
}

/// On wgpu a temporal denoiser's history stays on the device, frame
/// after frame: each run uploads its four images and reads back its
/// output, nothing more, in one submission; `stage_history` reads the
/// history when asked.
#[test]
fn on_wgpu_no_run_moves_the_history_to_or_from_the_host() {
    let mut ctx = Context::new();
    ctx.set_backend(Backend::Wgpu);
    let stage = temporal(&mut ctx);
    let image = (W * H) as u64 * 16;
    for f in 0..5 {
        let (up, down, submits) = (ctx.stage_upload_bytes(), ctx.stage_read_back_bytes(), ctx.wgpu_submissions());
        run(&mut ctx, stage, path(f), &frame(path(f), 0.3, f as u32));
        assert_eq!(ctx.stage_upload_bytes() - up, 4 * image, "frame {f}: its colour, albedo, normal and position");
        assert_eq!(ctx.stage_read_back_bytes() - down, image, "frame {f}: its output alone");
        assert_eq!(ctx.wgpu_submissions() - submits, 1, "frame {f}");
    }
    let (submits, down) = (ctx.wgpu_submissions(), ctx.stage_read_back_bytes());
    let (w, h, history) = ctx.stage_history(stage.0).unwrap().unwrap();
    assert_eq!((w, h), (W, H));
    assert!(history.iter().any(|p| p.w == 5.0) && history.iter().all(|p| p.w >= 1.0));
    assert_eq!(ctx.wgpu_submissions(), submits + 1, "a read of the history");
    assert_eq!(ctx.stage_read_back_bytes(), down, "not a run's");
}

/// A history moves with a switch of backends: frames alternating between
/// wgpu and the CPU give what the CPU alone gives, frame by frame; the
/// first wgpu run after CPU runs uploads the CPU's history, once.
#[test]
fn a_switch_of_backends_takes_the_history_along() {
    let order = [Backend::Wgpu, Backend::Wgpu, Backend::Cpu, Backend::Wgpu, Backend::Cpu, Backend::Cpu, Backend::Wgpu];
    let mut cpu = Context::new();
    let alone = temporal(&mut cpu);
    let mut ctx = Context::new();
    let stage = temporal(&mut ctx);
    let image = (W * H) as u64 * 16;
    let (mut want, mut got) = (Vec::new(), Vec::new());
    for (f, &backend) in order.iter().enumerate() {
        let images = frame(path(f), 0.3, f as u32);
        ctx.set_backend(backend);
        let up = ctx.stage_upload_bytes();
        got.push(run(&mut ctx, stage, path(f), &images));
        want.push(run(&mut cpu, alone, path(f), &images));
        if backend == Backend::Wgpu {
            let history = if f > 0 && order[f - 1] == Backend::Cpu { 4 * image } else { 0 };
            assert_eq!(ctx.stage_upload_bytes() - up, 4 * image + history, "frame {f}");
        }
    }
    got.push(ctx.stage_history(stage.0).unwrap().unwrap().2);
    want.push(cpu.stage_history(alone.0).unwrap().unwrap().2);
    assert_close(&want, &got, "switching");
    assert!(want[7].iter().any(|p| p.w == 7.0), "some pixels hold every frame");
}

/// A run of another size than the history's starts again, as a first
/// run does, on both backends; its history is of its size, and a run at
/// the first size after it starts again too.
#[test]
fn a_run_of_another_size_starts_again() {
    let small = (W / 2, H / 2);
    let cam = camera(0.0);
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let fresh = |size| {
            let mut ctx = Context::new();
            ctx.set_backend(backend);
            let stage = ctx.create_builtin_postprocessing_stage("DLDenoiser").unwrap();
            ctx.set_stage_var(stage, "temporal", 1.0f32).unwrap();
            let buffers = images_of(&mut ctx, stage, size);
            (ctx, (stage, buffers))
        };
        let (mut ctx, (stage, large)) = fresh((W, H));
        for f in 0..2 {
            run(&mut ctx, (stage, large), cam, &frame(cam, 0.5, f));
        }
        let images = frame_sized(cam, 0.5, 2, small);
        let buffers = images_of(&mut ctx, stage, small);
        let got = run_sized(&mut ctx, (stage, buffers), cam, &images, small);
        let (mut first, first_stage) = fresh(small);
        assert_eq!(got, run_sized(&mut first, first_stage, cam, &images, small), "{backend:?}: a first run");
        let (w, h, history) = ctx.stage_history(stage).unwrap().unwrap();
        assert_eq!((w, h), small, "{backend:?}");
        assert!(history.iter().all(|p| p.w == 1.0), "{backend:?}");
        bind(&mut ctx, stage, large);
        let images = frame(cam, 0.5, 3);
        let (mut first, first_stage) = fresh((W, H));
        let want = run(&mut first, first_stage, cam, &images);
        assert_eq!(run(&mut ctx, (stage, large), cam, &images), want, "{backend:?}: back at the first size");
    }
}

/// Writes `marks` (a launch to lose the device in).
#[rt_program(ray_generation)]
pub fn mark(#[var] mut marks: RwBuffer2d<Vec4>) {
    marks[launch_index()] = Vec4::ONE;
}

/// A device lost (here in a launch) takes the history it held along:
/// the next run on a new device, alone or riding in a command list's
/// launch, is a first run, neither a panic nor a blend with what the lost
/// device held.
#[test]
fn a_lost_device_drops_the_history() {
    for listed in [false, true] {
        let mut ctx = Context::new();
        ctx.set_backend(Backend::Wgpu);
        ctx.set_ray_type_count(0);
        let p = ctx.create_program(&mark::PROGRAM);
        ctx.set_ray_generation_program(0, p).unwrap();
        let marks = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 4, 4).unwrap();
        ctx.set_var(Scope::Context, "marks", marks).unwrap();
        let stage = temporal(&mut ctx);
        let cam = camera(0.0);
        let first = run(&mut ctx, stage, cam, &frame(cam, 0.5, 0));
        assert_ne!(run(&mut ctx, stage, cam, &frame(cam, 0.5, 1)), first);
        ctx.simulate_device_loss_in_next_launch();
        let e = ctx.launch(0, 4, 4).unwrap_err();
        assert!(matches!(e, RtError::Device(DeviceError::DeviceLost { .. })), "{e:?}");
        assert_eq!(ctx.stage_history(stage.0).unwrap(), None, "the history was the lost device's");
        let again = if listed {
            let mut list = CommandList::new();
            list.append_launch_2d(0, 4, 4).unwrap();
            list.append_stage(stage.0, W, H).unwrap();
            list.finalize(&ctx).unwrap();
            for (b, px) in stage.1.iter().zip(&frame(cam, 0.5, 0)) {
                ctx.write_buffer(*b, px).unwrap();
            }
            list.execute(&mut ctx).unwrap();
            assert_eq!(ctx.read_buffer::<Vec4>(marks).unwrap(), vec![Vec4::ONE; 16]);
            ctx.read_buffer::<Vec4>(stage.1[4]).unwrap()
        } else {
            run(&mut ctx, stage, cam, &frame(cam, 0.5, 0))
        };
        assert_eq!(again, first, "listed {listed}: a first run");
        assert!(ctx.stage_history(stage.0).unwrap().unwrap().2.iter().all(|p| p.w == 1.0), "listed {listed}");
        // And the history goes on from there on the new device.
        run(&mut ctx, stage, cam, &frame(cam, 0.5, 1));
        assert!(ctx.stage_history(stage.0).unwrap().unwrap().2.iter().all(|p| p.w == 2.0), "listed {listed}");
    }
}

fn stage_error(e: RtError) -> (String, String) {
    let text = e.to_string();
    match e {
        RtError::PostProcess(PostProcessError::BadStage { variable, .. }) => (variable, text),
        other => panic!("expected a stage error, got {other:?}"),
    }
}

#[test]
fn a_missing_guide_or_camera_a_wrong_size_or_setting_is_named() {
    let mut ctx = Context::new();
    let (stage, buffers) = temporal(&mut ctx);
    // No camera yet.
    let (variable, text) = stage_error(ctx.run_stage(stage, W, H).unwrap_err());
    assert_eq!(variable, "camera_eye");
    assert_eq!(
        text,
        "post-processing stage 0 (`denoiser`): variable `camera_eye` is not set; the temporal denoiser reprojects its history through the camera (`camera_eye`, `camera_u`, `camera_v`, `camera_w`)"
    );
    let cam = camera(0.0);
    run(&mut ctx, (stage, buffers), cam, &frame(cam, 0.0, 0));
    // No position guide.
    let bare = ctx.create_builtin_postprocessing_stage("denoiser").unwrap();
    for (name, b) in ["input_buffer", "input_albedo_buffer", "input_normal_buffer", "output_buffer"]
        .into_iter()
        .zip([buffers[0], buffers[1], buffers[2], buffers[4]])
    {
        ctx.set_stage_var(bare, name, b).unwrap();
    }
    ctx.run_stage(bare, W, H).unwrap(); // spatial only: no position needed
    ctx.set_stage_var(bare, "temporal", 1.0f32).unwrap();
    let (variable, text) = stage_error(ctx.run_stage(bare, W, H).unwrap_err());
    assert_eq!(variable, "input_position_buffer");
    assert_eq!(
        text,
        "post-processing stage 1 (`denoiser`): variable `input_position_buffer` is not set; the temporal denoiser reprojects each pixel by its world position"
    );
    // A position guide of another size.
    let small = ctx.create_buffer_2d::<Vec4>(BufferType::Input, W, H - 1).unwrap();
    ctx.set_stage_var(stage, "input_position_buffer", small).unwrap();
    let (variable, text) = stage_error(ctx.run_stage(stage, W, H).unwrap_err());
    assert_eq!(variable, "input_position_buffer");
    assert!(
        text.ends_with(&format!(
            "is buffer {} of 32x23 elements, but the stage runs at 32x24: its buffers must be at least that large",
            small.index()
        )),
        "{text}"
    );
    // Settings of the wrong sort or out of range; a degenerate camera.
    let e = |r: rt_runtime::Result<()>| stage_error(r.unwrap_err()).1;
    assert_eq!(
        e(ctx.set_stage_var(stage, "camera_u", 1.0f32)),
        "post-processing stage 0 (`denoiser`): variable `camera_u` is a vector, but was given the number 1"
    );
    assert!(e(ctx.set_stage_var(stage, "temporal", 0.5f32)).ends_with("`temporal` is 1 (on) or 0 (off), not 0.5"));
    assert!(
        e(ctx.set_stage_var(stage, "alpha_min", 0.0f32)).ends_with("`alpha_min` is a blend weight in (0, 1], not 0")
    );
    assert!(e(ctx.set_stage_var(stage, "camera_w", Vec3::new(f32::NAN, 0.0, 1.0))).contains("must be finite"));
    assert!(
        e(ctx.set_stage_var(stage, "temporal", Vec3::ONE)).ends_with("is a number, but was given the vector [1, 1, 1]")
    );
    ctx.set_stage_var(stage, "input_position_buffer", buffers[3]).unwrap();
    ctx.set_stage_var(stage, "camera_v", Vec3::ZERO).unwrap();
    let (variable, text) = stage_error(ctx.run_stage(stage, W, H).unwrap_err());
    assert_eq!(variable, "camera_u");
    assert!(text.contains("spans no picture"), "{text}");
}
