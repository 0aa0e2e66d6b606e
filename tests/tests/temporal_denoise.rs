//! The denoiser's temporal mode (`rt_runtime::postprocess::temporal`)
//! through the context, over a scene traced here on the host: a
//! checkered floor (z = 0) under a bright square (z = 2), both facing the
//! camera. Still frames of noise accumulate towards the noise-free
//! picture; a moved camera finds its history where the floor was seen
//! before and none where the square hid it; a reset drops the history;
//! the CPU and wgpu backends agree; bad setups are typed errors naming
//! the stage and the variable.

use glam::{Vec3, Vec4};
use rt_runtime::{Backend, BufferId, BufferType, Context, PostProcessError, RtError, StageId};

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
    let d = (glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5) / glam::Vec2::new(W as f32, H as f32)) * 2.0 - 1.0;
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
    let mut images: [Vec<Vec4>; 4] = Default::default();
    for y in 0..H {
        for x in 0..W {
            let (p, square) = trace(cam, x, y);
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
    let mut buffer = |_| ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, W, H).unwrap();
    let buffers = [0, 1, 2, 3, 4].map(&mut buffer);
    let stage = ctx.create_builtin_postprocessing_stage("DLDenoiser").unwrap();
    for (name, b) in
        ["input_buffer", "input_albedo_buffer", "input_normal_buffer", "input_position_buffer", "output_buffer"]
            .into_iter()
            .zip(buffers)
    {
        ctx.set_stage_var(stage, name, b).unwrap();
    }
    ctx.set_stage_var(stage, "temporal", 1.0f32).unwrap();
    (stage, buffers)
}

/// Runs `stage` over `images` seen through `cam`; its output.
fn run(
    ctx: &mut Context,
    (stage, buffers): (StageId, [BufferId; 5]),
    cam: Camera,
    images: &[Vec<Vec4>; 4],
) -> Vec<Vec4> {
    for (b, px) in buffers.iter().zip(images) {
        ctx.write_buffer(*b, px).unwrap();
    }
    for (name, v) in [("camera_eye", cam.eye), ("camera_u", cam.u), ("camera_v", cam.v), ("camera_w", cam.w)] {
        ctx.set_stage_var(stage, name, v).unwrap();
    }
    ctx.run_stage(stage, W, H).unwrap();
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
    let mut ctx = Context::new();
    let stage = temporal(&mut ctx);
    let cam = camera(0.0);
    let first = run(&mut ctx, stage, cam, &frame(cam, 0.5, 0));
    run(&mut ctx, stage, cam, &frame(cam, 0.5, 1));
    assert_eq!(ctx.stage_history(stage.0).unwrap().unwrap().2[0].w, 2.0);
    ctx.reset_stage_history(stage.0).unwrap();
    assert_eq!(ctx.stage_history(stage.0).unwrap(), None);
    // The frame after a reset is denoised as a first frame is.
    assert_eq!(run(&mut ctx, stage, cam, &frame(cam, 0.5, 0)), first);
    assert!(ctx.stage_history(stage.0).unwrap().unwrap().2.iter().all(|p| p.w == 1.0));
    // Turning the mode off drops it too; setting it to what it is does not.
    ctx.set_stage_var(stage.0, "temporal", 1.0f32).unwrap();
    assert!(ctx.stage_history(stage.0).unwrap().is_some());
    ctx.set_stage_var(stage.0, "temporal", 0.0f32).unwrap();
    assert_eq!(ctx.stage_history(stage.0).unwrap(), None);
}

/// Five frames, the camera moving, of noise: the CPU and wgpu backends
/// give the same pictures and histories within 1e-4 relative.
#[test]
fn the_cpu_and_wgpu_backends_agree() {
    let frames = |backend| {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        let stage = temporal(&mut ctx);
        let mut outputs = Vec::new();
        for f in 0..5u32 {
            let cam = camera([0.0, 0.0, 0.25, 0.5, 0.5][f as usize]);
            outputs.push(run(&mut ctx, stage, cam, &frame(cam, 0.3, f)));
        }
        outputs.push(ctx.stage_history(stage.0).unwrap().unwrap().2);
        outputs
    };
    let (cpu, gpu) = (frames(Backend::Cpu), frames(Backend::Wgpu));
    for (f, (a, b)) in cpu.iter().zip(&gpu).enumerate() {
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            let tolerance = 1e-4 * x.abs().max_element().max(1.0);
            assert!((*x - *y).abs().max_element() <= tolerance, "image {f} pixel {i}: cpu {x} wgpu {y}");
        }
    }
    assert_ne!(cpu[4], cpu[3], "the frames differ");
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
        text.ends_with(&format!("is buffer {} of 32x23 elements, but the stage runs at 32x24", small.index())),
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
