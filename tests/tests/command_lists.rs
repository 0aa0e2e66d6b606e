//! Command lists (OptiX 6's `RTcommandlist`): a list of a launch, the
//! denoiser and the tonemapper gives what running them one by one gives,
//! bit for bit, on every backend (on wgpu a launch and the stages after
//! it in one submission, the stages reading the launch's outputs on the
//! device); launches in it are tiled, report progress and are cancelled
//! as any; and a list used out of order, or holding a command that does
//! not fit, is refused with an error naming the command, stage and
//! variable. `CommandList::execute_async` and `Context::run_stage_async`,
//! which a browser page awaits, are natively the blocking calls, ready at
//! their first poll.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;
use std::future::Future;
use std::pin::pin;
use std::task::{Context as TaskContext, Poll, Waker};

/// A noisy picture of two surfaces (left half and right half): colour
/// from a hash of the launch index and `frame`, albedo and normal per
/// half.
#[rt_program(ray_generation)]
pub fn noisy(
    #[var] frame: u32,
    #[var] mut color: RwBuffer2d<Vec4>,
    #[var] mut albedo: RwBuffer2d<Vec4>,
    #[var] mut normal: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let dim = launch_dim();
    let mut h = (idx.x * 73856093) ^ (idx.y * 19349663) ^ (frame * 83492791);
    h = (h ^ (h >> 13)) * 1274126177;
    h = h ^ (h >> 16);
    let noise = (h & 1023) as f32 / 1023.0;
    let left = idx.x < dim.x / 2;
    let mut base = 0.8;
    let mut n = Vec3::Y;
    if left {
        base = 0.2;
        n = Vec3::X;
    }
    color[idx] = Vec4::new(base * 2.0 * noise, base, base * noise, 1.0);
    albedo[idx] = Vec4::new(0.5, 0.5, 0.5, 1.0);
    normal[idx] = n.extend(0.0);
}

const W: u32 = 24;
const H: u32 = 16;

struct Frame {
    ctx: Context,
    buffers: [BufferId; 5],
    denoiser: StageId,
    tonemapper: StageId,
}

/// A frame's list, finalized: the launch, then the denoiser and the
/// tonemapper.
fn frame_list(ctx: &Context, denoiser: StageId, tonemapper: StageId) -> CommandList {
    let mut list = CommandList::new();
    list.append_launch_2d(0, W, H).unwrap();
    list.append_stage(denoiser, W, H).unwrap();
    list.append_stage(tonemapper, W, H).unwrap();
    list.finalize(ctx).unwrap();
    list
}

/// A context with `noisy` as entry point 0 and a denoiser and tonemapper
/// over its buffers (colour, albedo, normal, denoised, display).
fn frame(on: On) -> Frame {
    frame_with(on, false)
}

/// [`frame`], its launch's outputs kept on the device when `device_local`.
fn frame_with(on: On, device_local: bool) -> Frame {
    frame_over(on, device_local, (W, H))
}

/// [`frame_with`] over buffers of `size` (at least `W` x `H`).
fn frame_over(on: On, device_local: bool, (w, h): (u32, u32)) -> Frame {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let p = ctx.create_program(&noisy::PROGRAM);
    ctx.set_ray_generation_program(0, p).unwrap();
    ctx.set_var(Scope::Context, "frame", 3u32).unwrap();
    let mut image = || ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, w, h).unwrap();
    let buffers = [image(), image(), image(), image(), image()];
    let [color, albedo, normal, denoised, display] = buffers;
    for (name, b) in [("color", color), ("albedo", albedo), ("normal", normal)] {
        ctx.set_var(Scope::Context, name, b).unwrap();
        ctx.set_buffer_device_local(b, device_local).unwrap();
    }
    let denoiser = ctx.create_postprocessing_stage(StageKind::Denoiser);
    ctx.set_stage_var(denoiser, "input_buffer", color).unwrap();
    ctx.set_stage_var(denoiser, "input_albedo_buffer", albedo).unwrap();
    ctx.set_stage_var(denoiser, "input_normal_buffer", normal).unwrap();
    ctx.set_stage_var(denoiser, "output_buffer", denoised).unwrap();
    let tonemapper = ctx.create_builtin_postprocessing_stage("TonemapperSimple").unwrap();
    ctx.set_stage_var(tonemapper, "input_buffer", denoised).unwrap();
    ctx.set_stage_var(tonemapper, "output_buffer", display).unwrap();
    ctx.set_stage_var(tonemapper, "exposure", 2.0f32).unwrap();
    Frame { ctx, buffers, denoiser, tonemapper }
}

fn read(ctx: &Context, buffers: &[BufferId]) -> Vec<Vec<Vec4>> {
    buffers.iter().map(|&b| ctx.read_buffer::<Vec4>(b).unwrap()).collect()
}

#[test]
fn a_list_gives_what_its_commands_give_one_by_one() {
    for on in On::ALL {
        let mut one_by_one = frame(on);
        one_by_one.ctx.launch(0, W, H).unwrap();
        one_by_one.ctx.run_stage(one_by_one.denoiser, W, H).unwrap();
        one_by_one.ctx.run_stage(one_by_one.tonemapper, W, H).unwrap();
        let want = read(&one_by_one.ctx, &one_by_one.buffers);
        // On wgpu a stage run alone is a submission; the list's stages
        // ride in its launch's last one. The CPU backend submits nothing.
        let submissions = |n: u64| if on == On::CPU { 0 } else { n };
        assert_eq!(one_by_one.ctx.stage_submissions(), submissions(2), "{}", on.name());

        let Frame { mut ctx, buffers, denoiser, tonemapper } = frame(on);
        // Small tiles: a list's launches are cut as any launch is.
        ctx.set_tile_budget(TileBudget::Indices(64));
        let list = frame_list(&ctx, denoiser, tonemapper);
        let mut tiles_seen = 0;
        let reports = list
            .execute_with_progress(&mut ctx, |p| {
                assert_eq!((p.command, p.commands), (0, 3));
                tiles_seen += 1;
                LaunchControl::Continue
            })
            .unwrap();
        assert_eq!(reports.len(), 1);
        let tiles = reports[0].tiles;
        assert!(tiles > 1, "{tiles} tiles");
        assert_eq!(tiles_seen, tiles, "progress after every tile");
        // One submission a tile, the stages in the last: nothing else.
        assert_eq!(ctx.wgpu_submissions(), submissions(tiles as u64), "{}", on.name());
        let got = read(&ctx, &buffers);
        assert_eq!(got, want, "{}", on.name());
        assert_eq!(ctx.stage_submissions(), 0, "{}", on.name());
        // The stages did something: the display is the tonemapped denoised colour.
        assert_ne!(got[3], got[0]);
        assert!(got[4].iter().all(|p| p.max_element() <= 1.0));
        // Executed again, it gives the same.
        list.execute(&mut ctx).unwrap();
        assert_eq!(read(&ctx, &buffers), want, "{}", on.name());
        assert_eq!(ctx.stage_submissions(), 0, "{}", on.name());
    }
}

/// Polls `f` once, as an executor that never blocks would.
fn first_poll<F: Future>(f: F) -> Poll<F::Output> {
    let mut f = pin!(f);
    f.as_mut().poll(&mut TaskContext::from_waker(Waker::noop()))
}

#[test]
fn an_awaited_list_and_stage_give_what_the_blocking_ones_give() {
    for on in On::ALL {
        let Frame { mut ctx, buffers, denoiser, tonemapper } = frame(on);
        frame_list(&ctx, denoiser, tonemapper).execute(&mut ctx).unwrap();
        let want = read(&ctx, &buffers);

        let Frame { mut ctx, buffers, denoiser, tonemapper } = frame(on);
        let list = frame_list(&ctx, denoiser, tonemapper);
        let Poll::Ready(reports) = first_poll(list.execute_async(&mut ctx)) else { panic!("{}: pending", on.name()) };
        assert_eq!(reports.unwrap().len(), 1, "{}", on.name());
        assert_eq!(read(&ctx, &buffers), want, "{}: the awaited list", on.name());

        let Frame { mut ctx, buffers, denoiser, tonemapper } = frame(on);
        ctx.launch(0, W, H).unwrap();
        for stage in [denoiser, tonemapper] {
            let Poll::Ready(ran) = first_poll(ctx.run_stage_async(stage, W, H)) else {
                panic!("{}: pending", on.name())
            };
            ran.unwrap();
        }
        assert_eq!(read(&ctx, &buffers), want, "{}: the awaited stages", on.name());
        let submissions = if on == On::CPU { 0 } else { 2 };
        assert_eq!(ctx.stage_submissions(), submissions, "{}", on.name());
    }
}

/// On wgpu, a list of a launch of one tile, the denoiser and the
/// tonemapper is one submission, where the commands one by one are three;
/// the launch's outputs the stages read stay on the device (the list reads
/// back only the stages' outputs and the log's header), and a read of one
/// copies it then (one submission each); the pictures are the same, bit
/// for bit.
#[test]
fn on_wgpu_a_launch_and_its_stages_are_one_submission() {
    let images = 4 * (W * H) as u64 * 4;
    let mut one_by_one = frame(On::COMPUTE);
    one_by_one.ctx.set_tile_budget(TileBudget::Whole);
    let report = one_by_one.ctx.launch(0, W, H).unwrap();
    assert_eq!(report.tiles, 1);
    let launch_read_back = one_by_one.ctx.last_read_back_bytes();
    one_by_one.ctx.run_stage(one_by_one.denoiser, W, H).unwrap();
    one_by_one.ctx.run_stage(one_by_one.tonemapper, W, H).unwrap();
    assert_eq!(one_by_one.ctx.wgpu_submissions(), 3);
    // The launch read back its five images (every one is writable) and
    // the log's header (and timestamps, where the device has them).
    let log = launch_read_back - 5 * images;
    assert!(log == 16 || log == 32, "{launch_read_back} bytes read back");
    let want = read(&one_by_one.ctx, &one_by_one.buffers);

    let Frame { mut ctx, buffers, denoiser, tonemapper } = frame(On::COMPUTE);
    ctx.set_tile_budget(TileBudget::Whole);
    let list = frame_list(&ctx, denoiser, tonemapper);
    for frame in 1..=2 {
        let before = ctx.wgpu_submissions();
        let reports = list.execute(&mut ctx).unwrap();
        assert_eq!(reports[0].tiles, 1);
        assert_eq!(ctx.wgpu_submissions() - before, 1, "frame {frame}: the launch and both stages in one");
        assert_eq!(ctx.last_read_back_bytes(), 2 * images + log, "frame {frame}: the stages' two outputs and the log");
        assert_eq!(ctx.stage_submissions(), 0);
        // The denoiser's colour, albedo and normal came from the heap.
        assert_eq!(ctx.stage_inputs_read_on_device(), 3 * frame);
    }
    // The denoised and displayed images are on the host; reading them
    // submits nothing.
    let before = ctx.wgpu_submissions();
    assert_eq!(ctx.read_buffer::<Vec4>(buffers[3]).unwrap(), want[3]);
    assert_eq!(ctx.read_buffer::<Vec4>(buffers[4]).unwrap(), want[4]);
    assert_eq!(ctx.wgpu_submissions(), before);
    // The launch's images are the device's: each read is a copy.
    for b in 0..3 {
        assert_eq!(ctx.read_buffer::<Vec4>(buffers[b]).unwrap(), want[b], "buffer {b}");
    }
    assert_eq!(ctx.wgpu_submissions(), before + 3);
}

/// A list launched and its stages run over the top-left `W` x `H` of
/// larger buffers gives there what the list over buffers of that size
/// gives, bit for bit, on every backend (on wgpu the stages reading the
/// launch's outputs in the heap, rows of the buffers' width), and leaves
/// the stages' outputs as they were around it.
#[test]
fn a_list_over_part_of_larger_buffers_gives_what_it_gives_over_buffers_of_its_size() {
    let big = (W + 7, H + 5);
    let before = |x: u32, y: u32| Vec4::new(-1.0, x as f32, y as f32, 3.0);
    for on in On::ALL {
        if !on.available() {
            continue;
        }
        for device_local in [false, true] {
            let Frame { mut ctx, buffers, denoiser, tonemapper } = frame_with(on, device_local);
            frame_list(&ctx, denoiser, tonemapper).execute(&mut ctx).unwrap();
            let want = read(&ctx, &buffers);

            let Frame { mut ctx, buffers, denoiser, tonemapper } = frame_over(on, device_local, big);
            let around: Vec<Vec4> = (0..big.1).flat_map(|y| (0..big.0).map(move |x| before(x, y))).collect();
            for b in &buffers[3..] {
                ctx.write_buffer(*b, &around).unwrap();
            }
            frame_list(&ctx, denoiser, tonemapper).execute(&mut ctx).unwrap();
            let what = format!("{} device_local {device_local}", on.name());
            if on != On::CPU {
                assert_eq!(ctx.stage_inputs_read_on_device(), 3, "{what}: the launch's outputs, read in the heap");
            }
            for (i, (got, want)) in read(&ctx, &buffers).iter().zip(&want).enumerate() {
                let rect: Vec<Vec4> =
                    (0..H as usize).flat_map(|y| &got[y * big.0 as usize..][..W as usize]).copied().collect();
                assert_eq!(&rect, want, "{what}: image {i}");
                if i >= 3 {
                    for (k, p) in got.iter().enumerate() {
                        let (x, y) = (k as u32 % big.0, k as u32 / big.0);
                        if x >= W || y >= H {
                            assert_eq!(*p, before(x, y), "{what}: image {i} at ({x}, {y}), outside the run");
                        }
                    }
                }
            }
        }
    }
}

/// A list whose tonemapper, after the launch and the denoiser over the
/// top-left `W` x `H`, runs over all of larger buffers: it sees the
/// denoiser's rectangle and the denoised buffer's texels around it, on
/// every backend (on wgpu it cannot ride with the denoiser in the
/// launch's submission, and runs in one of its own after it).
#[test]
fn a_stage_after_a_launch_reading_beyond_the_denoisers_rectangle_sees_the_buffer_around_it() {
    let big = (W + 3, H + 2);
    let around = |x: u32, y: u32| Vec4::new(0.25, x as f32 * 0.01, y as f32 * 0.02, 1.0);
    let run = |on: On| {
        let Frame { mut ctx, buffers, denoiser, tonemapper } = frame_over(on, false, big);
        let before: Vec<Vec4> = (0..big.1).flat_map(|y| (0..big.0).map(move |x| around(x, y))).collect();
        ctx.write_buffer(buffers[3], &before).unwrap();
        let mut list = CommandList::new();
        list.append_launch_2d(0, W, H).unwrap();
        list.append_stage(denoiser, W, H).unwrap();
        list.append_stage(tonemapper, big.0, big.1).unwrap();
        list.finalize(&ctx).unwrap();
        list.execute(&mut ctx).unwrap();
        (read(&ctx, &buffers[3..]), ctx.stage_submissions())
    };
    let (cpu, _) = run(On::CPU);
    let (gpu, stage_submissions) = run(On::COMPUTE);
    assert_eq!(stage_submissions, 1, "the tonemapper in a submission of its own");
    let [denoised, display] = [&cpu[0], &cpu[1]];
    for (i, (d, p)) in denoised.iter().zip(display).enumerate() {
        let (x, y) = (i as u32 % big.0, i as u32 / big.0);
        if x >= W || y >= H {
            assert_eq!(*d, around(x, y), "({x}, {y}) outside the denoiser's run");
        }
        assert_eq!(*p, postprocess::tonemap::tonemap_pixel(*d, 2.0, 2.2), "({x}, {y})");
    }
    for (a, b) in cpu.iter().flatten().zip(gpu.iter().flatten()) {
        let tolerance = 1e-4 * a.abs().max_element().max(1.0);
        assert!((*a - *b).abs().max_element() <= tolerance, "cpu {a}, wgpu {b}");
    }
}

/// On wgpu, a list whose launch is cancelled between tiles runs none of
/// its stages and leaves every buffer as it was, and the list after runs
/// whole.
#[test]
fn on_wgpu_a_cancelled_launch_runs_none_of_the_stages_riding_in_it() {
    let Frame { mut ctx, buffers, denoiser, tonemapper } = frame(On::COMPUTE);
    ctx.set_tile_budget(TileBudget::Indices(64));
    let list = frame_list(&ctx, denoiser, tonemapper);
    let mut seen = 0;
    let e = list
        .execute_with_progress(&mut ctx, |_| {
            seen += 1;
            if seen == 2 { LaunchControl::Cancel } else { LaunchControl::Continue }
        })
        .unwrap_err();
    assert!(matches!(e, RtError::Launch(LaunchError::LaunchCancelled { entry: 0, done: 128, .. })), "{e}");
    for (b, pixels) in read(&ctx, &buffers).into_iter().enumerate() {
        assert_eq!(pixels, vec![Vec4::ZERO; (W * H) as usize], "buffer {b} as it was");
    }
    list.execute(&mut ctx).unwrap();
    let mut one_by_one = frame(On::COMPUTE);
    one_by_one.ctx.launch(0, W, H).unwrap();
    one_by_one.ctx.run_stage(one_by_one.denoiser, W, H).unwrap();
    one_by_one.ctx.run_stage(one_by_one.tonemapper, W, H).unwrap();
    assert_eq!(read(&ctx, &buffers), read(&one_by_one.ctx, &one_by_one.buffers));
}

#[test]
fn a_cancelled_launch_stops_the_list_before_its_stages() {
    let Frame { mut ctx, buffers, denoiser, .. } = frame(On::CPU);
    ctx.set_tile_budget(TileBudget::Indices(64));
    let mut list = CommandList::new();
    list.append_launch_2d(0, W, H).unwrap();
    list.append_stage(denoiser, W, H).unwrap();
    list.finalize(&ctx).unwrap();
    let mut seen = Vec::new();
    let e = list
        .execute_with_progress(&mut ctx, |p| {
            seen.push((p.command, p.commands));
            LaunchControl::Cancel
        })
        .unwrap_err();
    assert!(matches!(e, RtError::Launch(LaunchError::LaunchCancelled { entry: 0, .. })), "{e}");
    assert_eq!(seen, vec![(0, 2)]);
    for pixels in read(&ctx, &buffers) {
        assert_eq!(pixels, vec![Vec4::ZERO; (W * H) as usize], "a cancelled list leaves its buffers as they were");
    }
}

#[test]
fn a_list_used_out_of_order_is_refused_and_keeps_its_commands() {
    let Frame { mut ctx, denoiser, tonemapper, .. } = frame(On::CPU);
    let mut list = CommandList::new();
    list.append_launch_2d(0, W, H).unwrap();
    let e = list.execute(&mut ctx).unwrap_err().to_string();
    assert_eq!(e, "command list: executed before it was finalized");
    list.append_stage(denoiser, W, H).unwrap();
    list.finalize(&ctx).unwrap();
    let e = list.append_stage(tonemapper, W, H).unwrap_err();
    assert_eq!(
        e.to_string(),
        "command list: post-processing stage 1 was appended after the list was finalized; a finalized list is fixed: make a new one"
    );
    assert!(matches!(e, RtError::PostProcess(PostProcessError::BadCommandList { .. })));
    assert_eq!(list.commands().len(), 2, "nothing lost, nothing added");
    assert!(list.is_finalized());
    list.execute(&mut ctx).unwrap();
}

#[test]
fn finalize_names_the_stage_and_variable_or_the_launch_at_fault() {
    let Frame { mut ctx, denoiser, .. } = frame(On::CPU);
    let mut list = CommandList::new();
    list.append_launch_2d(0, W, H).unwrap();
    list.append_stage(denoiser, W, H + 8).unwrap();
    match list.finalize(&ctx).unwrap_err() {
        RtError::PostProcess(PostProcessError::BadStage { stage, variable, problem }) => {
            assert_eq!((stage.as_str(), variable.as_str()), ("0 (`denoiser`)", "input_buffer"));
            assert_eq!(
                problem,
                format!(
                    "is buffer 0 of {W}x{H} elements, but the stage runs at {W}x{}: its buffers must be at least that large",
                    H + 8
                )
            );
        }
        other => panic!("{other:?}"),
    }
    assert!(!list.is_finalized(), "a list that fails to finalize stays open");

    let ints = ctx.create_buffer_2d::<f32>(BufferType::Output, W, H).unwrap();
    ctx.set_stage_var(denoiser, "output_buffer", ints).unwrap();
    let mut list = CommandList::new();
    list.append_stage(denoiser, W, H).unwrap();
    match list.finalize(&ctx).unwrap_err() {
        RtError::PostProcess(PostProcessError::BadStage { variable, problem, .. }) => {
            assert_eq!(variable, "output_buffer");
            assert!(problem.contains("holds `f32`"), "{problem}");
        }
        other => panic!("{other:?}"),
    }

    for (entry, size, want) in [
        (1, (W, H), "command list: command 0 (a launch): entry point 1 does not exist: the context has 1"),
        (0, (0, H), "command list: command 0 (a launch): 0x16x1 has no index; a launch needs at least one a dimension"),
    ] {
        let mut list = CommandList::new();
        list.append_launch_2d(entry, size.0, size.1).unwrap();
        assert_eq!(list.finalize(&ctx).unwrap_err().to_string(), want);
    }
    ctx.set_entry_point_count(2);
    let mut list = CommandList::new();
    list.append_launch_1d(1, 4).unwrap();
    let e = list.finalize(&ctx).unwrap_err().to_string();
    assert_eq!(e, "command list: command 0 (a launch): entry point 1 has no ray generation program");
}

/// A list on the wgpu backend: its stages take the launch's outputs from
/// the device, copied there (the denoiser's colour, albedo and normal;
/// the tonemapper reads the denoiser's output where it wrote it), whether
/// the buffers are device-local or not, and the pictures are the CPU
/// backend's within 1e-4.
#[test]
fn stages_read_a_launchs_device_local_outputs() {
    let run = |on: On, device_local: bool| {
        let Frame { mut ctx, buffers, denoiser, tonemapper } = frame_with(on, device_local);
        let list = frame_list(&ctx, denoiser, tonemapper);
        list.execute(&mut ctx).unwrap();
        (read(&ctx, &buffers), ctx.stage_inputs_read_on_device())
    };
    let (cpu, none) = run(On::CPU, false);
    assert_eq!(none, 0);
    let (on_device, copied) = run(On::COMPUTE, true);
    assert_eq!(copied, 3, "the denoiser's three inputs are taken on the device");
    let (not_local, copied) = run(On::COMPUTE, false);
    assert_eq!(copied, 3, "in a list, the launch's outputs the stages read stay on the device too");
    for gpu in [on_device, not_local] {
        assert_close(&cpu, &gpu);
    }
}

fn assert_close(want: &[Vec<Vec4>], got: &[Vec<Vec4>]) {
    for (b, (c, g)) in want.iter().zip(got).enumerate() {
        for (i, (x, y)) in c.iter().zip(g).enumerate() {
            assert!(
                (*x - *y).abs().max_element() <= 1e-4 * x.abs().max_element().max(1.0),
                "buffer {b} pixel {i}: {x} {y}"
            );
        }
    }
}

/// A device-local input the host writes after the launch: the stage reads
/// the host's words, not the device's older ones.
#[test]
fn a_host_write_after_the_launch_is_what_a_stage_reads() {
    let run = |on: On| {
        let Frame { mut ctx, buffers, denoiser, .. } = frame_with(on, true);
        ctx.launch(0, W, H).unwrap();
        let flat = vec![Vec4::new(0.25, 0.5, 0.75, 1.0); (W * H) as usize];
        ctx.write_buffer(buffers[0], &flat).unwrap();
        ctx.run_stage(denoiser, W, H).unwrap();
        (read(&ctx, &buffers), ctx.stage_inputs_read_on_device())
    };
    let (cpu, _) = run(On::CPU);
    let (gpu, copied) = run(On::COMPUTE);
    assert_eq!(copied, 2, "the albedo and normal come from the device, the colour from the host");
    // A flat colour over one albedo stays flat where the normals agree.
    assert_eq!(cpu[3][0], Vec4::new(0.25, 0.5, 0.75, 1.0));
    assert_close(&cpu, &gpu);
}

/// A stage that fails its check as the list runs (its buffers changed
/// after finalize) stops the list there, the stage before it done, on
/// the CPU and in a wgpu run of stages alike.
#[test]
fn a_stage_failing_as_the_list_runs_leaves_the_stages_before_it_done() {
    for on in [On::CPU, On::COMPUTE] {
        let Frame { mut ctx, buffers, denoiser, tonemapper } = frame(on);
        ctx.launch(0, W, H).unwrap();
        let mut list = CommandList::new();
        list.append_stage(denoiser, W, H).unwrap();
        list.append_stage(tonemapper, W, H).unwrap();
        list.finalize(&ctx).unwrap();
        let small = ctx.create_buffer_2d::<Vec4>(BufferType::Output, W, H - 1).unwrap();
        ctx.set_stage_var(tonemapper, "output_buffer", small).unwrap();
        let e = list.execute(&mut ctx).unwrap_err();
        assert!(
            matches!(&e, RtError::PostProcess(PostProcessError::BadStage { variable, .. }) if variable == "output_buffer"),
            "{e}"
        );
        let denoised = ctx.read_buffer::<Vec4>(buffers[3]).unwrap();
        assert_ne!(denoised, vec![Vec4::ZERO; (W * H) as usize], "{}: the denoiser ran", on.name());
        assert_eq!(ctx.read_buffer::<Vec4>(buffers[4]).unwrap(), vec![Vec4::ZERO; (W * H) as usize]);
    }
}

/// A temporal denoiser after a list's launch (on wgpu riding in the
/// launch's submission, its history read and written there and left on
/// the device: the list reads back the denoised picture and the log,
/// nothing of the history) keeps the history and gives the pictures that
/// running it alone after each launch does, frame after frame.
#[test]
fn a_temporal_denoiser_in_a_list_keeps_its_history_as_one_run_alone_does() {
    let run = |on: On, listed: bool| {
        let Frame { mut ctx, buffers, denoiser, .. } = frame_with(on, true);
        // A plane at z = 0 seen square-on: each pixel's centre.
        let position = ctx.create_buffer_2d::<Vec4>(BufferType::Input, W, H).unwrap();
        let px: Vec<Vec4> =
            (0..H).flat_map(|y| (0..W).map(move |x| Vec4::new(x as f32 + 0.5, y as f32 + 0.5, 0.0, 1.0))).collect();
        ctx.write_buffer(position, &px).unwrap();
        ctx.set_stage_var(denoiser, "input_position_buffer", position).unwrap();
        ctx.set_stage_var(denoiser, "temporal", 1.0f32).unwrap();
        let (w, h) = (W as f32, H as f32);
        let camera = [
            ("camera_eye", Vec3::new(w / 2.0, h / 2.0, 10.0)),
            ("camera_u", Vec3::new(w / 20.0, 0.0, 0.0)),
            ("camera_v", Vec3::new(0.0, h / 20.0, 0.0)),
            ("camera_w", Vec3::NEG_Z),
        ];
        for (name, v) in camera {
            ctx.set_stage_var(denoiser, name, v).unwrap();
        }
        let mut list = CommandList::new();
        list.append_launch_2d(0, W, H).unwrap();
        list.append_stage(denoiser, W, H).unwrap();
        list.finalize(&ctx).unwrap();
        let mut frames = Vec::new();
        for f in 0..3u32 {
            ctx.set_var(Scope::Context, "frame", f).unwrap();
            if listed {
                let (up, down) = (ctx.stage_upload_bytes(), ctx.stage_read_back_bytes());
                list.execute(&mut ctx).unwrap();
                if ctx.backend() == Backend::Wgpu {
                    let image = (W * H) as u64 * 16;
                    let read = ctx.last_read_back_bytes();
                    // The launch's one writable buffer the stage does not
                    // touch (the fifth, `display`) and the denoised picture.
                    let log = read.checked_sub(2 * image);
                    assert!(matches!(log, Some(16 | 32)), "{}: {read} bytes read back", on.name());
                    assert_eq!(ctx.stage_read_back_bytes() - down, image, "{}", on.name());
                    assert_eq!(ctx.stage_upload_bytes() - up, image, "{}: the position guide alone", on.name());
                }
            } else {
                ctx.launch(0, W, H).unwrap();
                ctx.run_stage(denoiser, W, H).unwrap();
            }
            frames.push(ctx.read_buffer::<Vec4>(buffers[3]).unwrap());
        }
        (frames, ctx.stage_history(denoiser).unwrap().expect("a history"))
    };
    for on in On::ALL {
        let (alone, history) = run(on, false);
        assert!(history.2.iter().all(|p| p.w == 3.0), "{}: every pixel holds the 3 frames", on.name());
        assert_eq!(run(on, true), (alone.clone(), history), "{}", on.name());
        assert_ne!(alone[2], alone[0], "{}", on.name());
    }
}
