//! Watchdog-safe launches: a launch cut into tiles (by a time budget or a
//! count of indices) gives what one launch over the whole size gives, bit
//! for bit, on every target: every index runs once, and the outputs,
//! exceptions, prints and ray counts agree. A progress callback sees each
//! tile, and cancelling between tiles leaves every buffer as it was; a
//! panic in a later tile does too.

use glam::{UVec2, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::meshes::bumpy_grid;
use rt_tests::targets::On;

#[rt_payload]
pub struct Probe {
    pub t: f32,
    pub prim: u32,
}

#[rt_attributes]
pub struct Bary {
    pub barycentrics: Vec2,
}

/// A ray per index into a bumpy grid: the hit's distance and triangle,
/// and a count of the runs of each index; a user exception at some
/// indices, a print at a few.
#[rt_program(ray_generation)]
pub fn camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] mut runs: RwBuffer2d<u32>) {
    let idx = launch_index();
    runs[idx] += 1;
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x * 1.2, p.y * 1.2, 3.0), vec3(0.1, -0.05, -1.0).normalize(), 0, 0.0, f32::INFINITY);
    let mut prd = Probe { t: -1.0, prim: 0 };
    rt_trace(top, ray, &mut prd);
    out[idx] = vec4(prd.t, prd.prim as f32, p.x, p.y);
    if (idx.x * 7 + idx.y * 3) % 211 == 0 {
        rt_throw(EXCEPTION_USER + 1);
    }
    if idx.x % 150 == 3 && idx.y % 100 == 5 {
        rt_printf!("at {} t {}", idx, prd.t);
    }
}

#[rt_program(closest_hit)]
pub fn record_hit(prd: &mut Probe, attr: &Bary) {
    prd.t = t_hit() + attr.barycentrics.x * 0.0;
    prd.prim = primitive_index();
}

#[rt_program(miss)]
pub fn missed(prd: &mut Probe) {
    prd.t = -2.0;
}

#[rt_program(exception)]
pub fn mark(#[var] mut out: RwBuffer2d<Vec4>) {
    out[launch_index()] = vec4(-7.0, exception_code() as f32, 0.0, 0.0);
}

struct Scene {
    ctx: Context,
    out: BufferId,
    runs: BufferId,
}

/// The grid scene on `on`, its buffers `w` x `h`, the output filled with
/// a pattern (so that "as it was" is more than zeros).
fn scene(on: On, w: u32, h: u32) -> Scene {
    let mut ctx = on.context();
    let g = ctx.create_triangles(bumpy_grid(24)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&record_hit::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let top = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, w, h).unwrap();
    let pattern: Vec<Vec4> = (0..w * h).map(|i| Vec4::splat(i as f32 * 0.5)).collect();
    ctx.write_buffer(out, &pattern).unwrap();
    let runs = ctx.create_buffer_2d::<u32>(BufferType::InputOutput, w, h).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "runs", runs).unwrap();
    let rg = ctx.create_program(&camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let ex = ctx.create_program(&mark::PROGRAM);
    ctx.set_exception_program(0, ex).unwrap();
    let miss = ctx.create_program(&missed::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    Scene { ctx, out, runs }
}

fn bits(v: &[Vec4]) -> Vec<[u32; 4]> {
    v.iter().map(|c| c.to_array().map(f32::to_bits)).collect()
}

const W: u32 = 300;
const H: u32 = 201;

#[test]
fn a_tiled_launch_equals_one_launch_over_the_whole_size() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut whole = scene(on, W, H);
        whole.ctx.set_tile_budget(TileBudget::Whole);
        let one = whole.ctx.launch(0, W, H).unwrap();
        assert_eq!(one.tiles, 1);
        let mut tiled = scene(on, W, H);
        // 1,000 indices: 15 blocks of a band (of 38) a tile, 3 tiles a band
        // of 8 rows; the last band, of one row, is one tile.
        tiled.ctx.set_tile_budget(TileBudget::Indices(1000));
        let mut seen = Vec::new();
        let many = tiled
            .ctx
            .launch_with_progress(0, W, H, |p| {
                seen.push(p);
                LaunchControl::Continue
            })
            .unwrap();
        assert_eq!(many.tiles, 25 * 3 + 1, "{}", on.name());
        assert_eq!(seen.len(), many.tiles as usize);
        assert_eq!(seen[0].done, 15 * 64);
        assert!(seen.windows(2).all(|w| w[0].done < w[1].done && w[1].tiles == w[0].tiles + 1));
        assert_eq!(seen.last().unwrap().done, (W * H) as u64);
        assert_eq!(seen.last().unwrap().fraction(), 1.0);
        let runs = tiled.ctx.read_buffer::<u32>(tiled.runs).unwrap();
        assert!(runs.iter().all(|&r| r == 1), "{}: an index ran other than once", on.name());
        let a = whole.ctx.read_buffer::<Vec4>(whole.out).unwrap();
        let b = tiled.ctx.read_buffer::<Vec4>(tiled.out).unwrap();
        assert_eq!(bits(&a), bits(&b), "{}", on.name());
        assert!(a.iter().filter(|c| c.x > 0.0).count() > 10_000, "{}: the grid is hit", on.name());
        assert!(a.iter().any(|c| c.x == -2.0), "{}: some rays miss", on.name());
        assert!(one.exceptions.len() > 200, "{}: {}", on.name(), one.exceptions.len());
        assert_eq!(one.exceptions, many.exceptions, "{}", on.name());
        assert_eq!(one.prints.len(), 2 * 2, "{}", on.name());
        assert_eq!(one.prints, many.prints, "{}", on.name());
        assert_eq!(one.rays, many.rays, "{}", on.name());
        assert_eq!(one.rays, (W * H) as u64);
    }
}

#[test]
fn the_time_budget_probes_first_then_sizes_tiles_from_the_pace() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (w, h) = (512, 384);
        let mut s = scene(on, w, h);
        assert_eq!(s.ctx.tile_budget(), TileBudget::Time(DEFAULT_TILE_BUDGET));
        let mut done = Vec::new();
        let report = s
            .ctx
            .launch_with_progress(0, w, h, |p| {
                done.push(p.done);
                LaunchControl::Continue
            })
            .unwrap();
        // The probe: 65,536 indices, whole bands of 512.
        assert_eq!(done[0], 1 << 16, "{}", on.name());
        assert!(report.tiles >= 2 && done.len() == report.tiles as usize, "{}", on.name());
        assert_eq!(*done.last().unwrap(), (w * h) as u64);
        let mut whole = scene(on, w, h);
        whole.ctx.set_tile_budget(TileBudget::Whole);
        whole.ctx.launch(0, w, h).unwrap();
        let a = whole.ctx.read_buffer::<Vec4>(whole.out).unwrap();
        let b = s.ctx.read_buffer::<Vec4>(s.out).unwrap();
        assert_eq!(bits(&a), bits(&b), "{}", on.name());
        // A small launch is one tile.
        assert_eq!(s.ctx.launch(0, 64, 64).unwrap().tiles, 1);
    }
}

#[test]
fn cancelling_between_tiles_leaves_the_buffers_as_they_were() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut s = scene(on, W, H);
        s.ctx.set_tile_budget(TileBudget::Indices(5000));
        let before = s.ctx.read_buffer::<Vec4>(s.out).unwrap();
        let mut calls = 0;
        let err = s
            .ctx
            .launch_with_progress(0, W, H, |p| {
                calls += 1;
                if p.tiles == 3 { LaunchControl::Cancel } else { LaunchControl::Continue }
            })
            .unwrap_err();
        assert_eq!(calls, 3);
        // 5,000 indices: two bands of 300 x 8.
        let done = 3 * 2 * 8 * W as u64;
        assert!(
            matches!(err, RtError::Launch(LaunchError::LaunchCancelled { entry: 0, done: d, total }) if d == done && total == (W * H) as u64),
            "{}: {err}",
            on.name()
        );
        assert!(err.to_string().contains(&format!("after {done} of {} launch indices", W * H)), "{err}");
        assert_eq!(bits(&s.ctx.read_buffer::<Vec4>(s.out).unwrap()), bits(&before), "{}", on.name());
        assert!(s.ctx.read_buffer::<u32>(s.runs).unwrap().iter().all(|&r| r == 0), "{}", on.name());
        // The context goes on: the next launch is a fresh context's.
        let report = s.ctx.launch(0, W, H).unwrap();
        let mut fresh = scene(on, W, H);
        let expected = fresh.ctx.launch(0, W, H).unwrap();
        assert_eq!(report.exceptions, expected.exceptions);
        let a = fresh.ctx.read_buffer::<Vec4>(fresh.out).unwrap();
        assert_eq!(bits(&s.ctx.read_buffer::<Vec4>(s.out).unwrap()), bits(&a), "{}", on.name());
        // A cancel after the last tile changes nothing: the launch is done.
        let mut last = scene(on, 64, 64);
        assert!(last.ctx.launch_with_progress(0, 64, 64, |_| LaunchControl::Cancel).is_ok());
        assert!(last.ctx.read_buffer::<u32>(last.runs).unwrap().iter().all(|&r| r == 1));
    }
}

fn camera_panicking_late(args: &mut rt_std::cpu::CpuArgs<'_>) -> rt_std::cpu::CpuResult {
    if launch_index() == UVec2::new(7, 140) {
        panic!("late trouble");
    }
    (camera::PROGRAM.cpu)(args)
}

#[test]
fn a_panic_in_a_later_tile_leaves_the_buffers_as_they_were() {
    let mut s = scene(On::CPU, W, H);
    s.ctx.set_tile_budget(TileBudget::Indices(5000));
    // (The scalar entry replaced, and so the one that runs.)
    let desc = Box::leak(Box::new(rt_std::program::ProgramDescriptor {
        cpu: camera_panicking_late,
        cpu_lanes: rt_std::program::CpuLanes::Scalar("the test replaces the scalar entry"),
        ..camera::PROGRAM
    }));
    let bad = s.ctx.create_program(desc);
    s.ctx.set_ray_generation_program(0, bad).unwrap();
    let before = s.ctx.read_buffer::<Vec4>(s.out).unwrap();
    let mut tiles = 0;
    let err = s
        .ctx
        .launch_with_progress(0, W, H, |p| {
            tiles = p.tiles;
            LaunchControl::Continue
        })
        .unwrap_err();
    // Rows 0 to 127 ran (8 tiles of 16 rows) before the tile with row 140.
    assert_eq!(tiles, 8);
    assert!(
        matches!(&err, RtError::Launch(LaunchError::ProgramPanicked { launch_index, message, .. }) if *launch_index == UVec2::new(7, 140) && message == "late trouble"),
        "{err}"
    );
    assert_eq!(bits(&s.ctx.read_buffer::<Vec4>(s.out).unwrap()), bits(&before));
    assert!(s.ctx.read_buffer::<u32>(s.runs).unwrap().iter().all(|&r| r == 0));
}

#[test]
fn a_part_of_a_launch_runs_only_its_indices_and_sees_the_whole_size() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut whole = scene(on, W, H);
        whole.ctx.launch(0, W, H).unwrap();
        let all = whole.ctx.read_buffer::<Vec4>(whole.out).unwrap();
        let mut s = scene(on, W, H);
        let before = s.ctx.read_buffer::<Vec4>(s.out).unwrap();
        // Rows 64..201 from column 40 to the right edge, tiles of 1,000.
        s.ctx.set_tile_budget(TileBudget::Indices(1000));
        let part = Tile { origin: UVec2::new(40, 64), size: UVec2::new(W - 40, H - 64) };
        let mut last = None;
        let report = s
            .ctx
            .launch_part(0, W, H, part, |p| {
                last = Some(p);
                LaunchControl::Continue
            })
            .unwrap();
        assert!(report.tiles > 1);
        assert_eq!(last.unwrap().total, part.count());
        let got = s.ctx.read_buffer::<Vec4>(s.out).unwrap();
        let runs = s.ctx.read_buffer::<u32>(s.runs).unwrap();
        for y in 0..H {
            for x in 0..W {
                let i = (y * W + x) as usize;
                let inside = x >= 40 && y >= 64;
                let want = if inside { all[i] } else { before[i] };
                assert_eq!(
                    got[i].to_array().map(f32::to_bits),
                    want.to_array().map(f32::to_bits),
                    "{} ({x}, {y})",
                    on.name()
                );
                assert_eq!(runs[i], inside as u32, "{} ({x}, {y})", on.name());
            }
        }
        let inside = |e: &ExceptionRecord| e.launch_index.x >= 40 && e.launch_index.y >= 64;
        let mut whole_exceptions = whole.ctx.launch(0, W, H).unwrap().exceptions;
        whole_exceptions.retain(inside);
        assert_eq!(report.exceptions, whole_exceptions, "{}", on.name());
        // Off the 8 x 8 grid, or past the edge: refused by name.
        for (bad, problem) in [
            (Tile { origin: UVec2::new(4, 0), size: UVec2::new(8, 8) }, "is not on the 8 x 8 grid"),
            (Tile { origin: UVec2::new(0, 0), size: UVec2::new(12, 8) }, "is not on the 8 x 8 grid"),
            (Tile { origin: UVec2::new(296, 0), size: UVec2::new(8, 8) }, "reaches past the launch's edge"),
            (Tile { origin: UVec2::new(0, 0), size: UVec2::new(0, 8) }, "is empty"),
        ] {
            let err = s.ctx.launch_part(0, W, H, bad, |_| LaunchControl::Continue).unwrap_err();
            assert!(
                matches!(err, RtError::Launch(LaunchError::BadLaunch { .. })) && err.to_string().contains(problem),
                "{err}"
            );
        }
    }
}
