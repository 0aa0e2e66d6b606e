//! 3D launches (OptiX's `rtContextLaunch3D`): `Context::launch_3d`,
//! `launch_index_3d()` and `launch_dim_3d()` (with `launch_index()` and
//! `launch_dim()` the first two axes), written into a 3D buffer per launch
//! index and exact on every target, whole and in several tiles; a 2D
//! launch seen in 3D; exceptions named by grid index; and 1D and 3D
//! launches past the device's dispatch limit (65,535 workgroups of 8 x 8
//! per dimension).

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// Each launch index writes its own cell: its coordinates, whether
/// `launch_index()` agrees with the first two, and the sizes; (1, 2, 3)
/// throws.
#[rt_program(ray_generation)]
pub fn cells(#[var] mut out: RwBuffer3d<u32>, #[var] mut dims: RwBuffer<u32>) {
    let i = launch_index_3d();
    let d = launch_dim_3d();
    let mut agrees = 0u32;
    if launch_index() == i.xy() && launch_dim() == d.xy() {
        agrees = 1;
    }
    out[i] = i.x + 16 * i.y + 256 * i.z + 4096 * agrees;
    if i == UVec3::ZERO {
        dims[0] = d.x;
        dims[1] = d.y;
        dims[2] = d.z;
    }
    if i == uvec3(1, 2, 3) {
        rt_throw(EXCEPTION_USER + 3);
    }
}

/// A 1D or 3D launch of one word per index: `i * 3 + 1` by its grid
/// index.
#[rt_program(ray_generation)]
pub fn count(#[var] mut out: RwBuffer<u32>) {
    let i = launch_index_3d();
    let d = launch_dim_3d();
    let at = i.x + d.x * (i.y + d.y * i.z);
    out[at] = at * 3 + 1;
}

const W: u32 = 5;
const H: u32 = 3;
const D: u32 = 7;

fn cells_on(
    on: On,
    budget: TileBudget,
    (w, h, d): (u32, u32, u32),
    launch3: bool,
) -> (Vec<u32>, Vec<u32>, LaunchReport) {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    ctx.set_tile_budget(budget);
    let out = ctx.create_buffer_3d::<u32>(BufferType::Output, w, h, d).unwrap();
    let dims = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 3]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "dims", dims).unwrap();
    let rg = ctx.create_program(&cells::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = if launch3 { ctx.launch_3d(0, w, h, d) } else { ctx.launch(0, w, h) }.unwrap();
    (ctx.read_buffer(out).unwrap(), ctx.read_buffer(dims).unwrap(), report)
}

#[test]
fn a_3d_launch_runs_every_index_once_whole_and_tiled_on_every_target() {
    let mut expected = Vec::new();
    for z in 0..D {
        for y in 0..H {
            for x in 0..W {
                expected.push(x + 16 * y + 256 * z + 4096);
            }
        }
    }
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        for budget in [TileBudget::Whole, TileBudget::Indices(64)] {
            let (out, dims, report) = cells_on(on, budget, (W, H, D), true);
            let what = format!("{} {budget:?}", on.name());
            assert_eq!(out, expected, "{what}");
            assert_eq!(dims, [W, H, D], "{what}");
            let thrown: Vec<(UVec2, u32)> = report.exceptions.iter().map(|e| (e.launch_index, e.code)).collect();
            assert_eq!(thrown, [(UVec2::new(1, 2 + 3 * H), EXCEPTION_USER + 3)], "{what}");
            if budget == TileBudget::Whole {
                assert_eq!(report.tiles, 1, "{what}");
            } else {
                // 5 x 21 indices: two 8 x 8 blocks a column, one a tile.
                assert_eq!(report.tiles, 3, "{what}");
            }
        }
    }
}

#[test]
fn a_2d_launch_is_one_slice_deep() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (out, dims, report) = cells_on(on, TileBudget::Whole, (W, H, 1), false);
        let expected: Vec<u32> = (0..H).flat_map(|y| (0..W).map(move |x| x + 16 * y + 4096)).collect();
        assert_eq!(out, expected, "{}", on.name());
        assert_eq!(dims, [W, H, 1], "{}", on.name());
        assert!(report.exceptions.is_empty(), "{}", on.name());
    }
}

/// A launch of `(w, h, d)` (`d == 0`: a 1D launch of `w`) writing `count`,
/// in one tile: the wgpu backend splits it into dispatches.
fn counted(on: On, (w, h, d): (u32, u32, u32)) -> LaunchReport {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    ctx.set_tile_budget(TileBudget::Whole);
    let n = w * h * d.max(1);
    let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; n as usize]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&count::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = if d == 0 { ctx.launch_1d(0, w) } else { ctx.launch_3d(0, w, h, d) }.unwrap();
    let words = ctx.read_buffer::<u32>(out).unwrap();
    let wrong = words.iter().enumerate().find(|(i, v)| **v != *i as u32 * 3 + 1);
    assert_eq!(wrong, None, "{} {w}x{h}x{d}: the first index not written once", on.name());
    report
}

#[test]
fn launches_past_the_dispatch_limit_run_every_index_on_every_target() {
    // 65,535 groups of 8 in x, and of 8 rows in y, is the most one
    // dispatch reaches.
    let beyond = 65_535 * 8 + 24;
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        assert_eq!(counted(on, (beyond, 1, 0)).tiles, 1);
        assert_eq!(counted(on, (2, 1024, beyond.div_ceil(1024))).tiles, 1);
    }
}
