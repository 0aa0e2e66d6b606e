//! Lane-wise execution on the CPU backend (`rt_std::cpu::lanes`): ray
//! generation programs run a block of launch indices per call, a trace
//! under a mask goes to the backend as a packet, and the packet's
//! closest-hit and miss programs run lane-wise, one call per program (the
//! closest hit here traces again, so a nested packet too). Every launch here runs
//! lane-wise and one index at a time, and the two agree exactly: outputs,
//! exceptions (code, launch index, order), prints and ray counts; with
//! divergent control flow (early returns in some lanes, a trace inside a
//! branch, loops with lane-dependent trip counts, exceptions in some
//! lanes), launch sizes that are not a multiple of the block, a 3D launch, and both
//! scenes a packet takes (one geometry group) and ones it does not (a
//! transform). `Context::cpu_execution` names each program's way and the
//! reason a program runs one index at a time.

use glam::{Mat4, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;

#[rt_payload]
pub struct Probe {
    pub t: f32,
    pub prim: u32,
    pub depth: u32,
}

/// Divergent lanes: some return at once, some trace, some throw, each
/// runs a loop of its own length, and one prints.
#[rt_program(ray_generation)]
pub fn divergent(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>) {
    // (A function declared in the body, called after the trace.)
    fn twice(x: f32) -> f32 {
        x * 2.0
    }
    let idx = launch_index();
    let dim = launch_dim();
    if idx.x % 5 == 3 {
        out[idx] = vec4(-1.0, idx.x as f32, idx.y as f32, 0.0);
        return;
    }
    let p = (idx.as_vec2() + 0.5) / dim.as_vec2() * 2.0 - 1.0;
    let mut prd = Probe { t: -1.0, prim: 0, depth: 0 };
    if idx.y % 3 != 1 {
        let d = vec3(p.x * 0.8, p.y * 0.8, -1.0).normalize();
        rt_trace(top, Ray::new(vec3(0.0, 0.0, 3.0), d, 0, 1e-3, f32::INFINITY), &mut prd);
    } else {
        prd.t = 0.25;
        if idx.x % 7 == 2 {
            rt_throw(EXCEPTION_USER + idx.x);
        }
        if idx.x % 11 == 6 {
            out[idx] = vec4(-3.0, 0.0, 0.0, 0.0);
            return;
        }
    }
    let mut k = idx.x * 3 + idx.y + 1;
    let mut steps = 0u32;
    while k > 1 {
        k = if k % 2 == 0 { k / 2 } else { 3 * k + 1 };
        steps += 1;
    }
    if idx.x == 4 && idx.y % 2 == 0 {
        rt_printf!("lane {} {} steps {}", idx.x, idx.y, steps);
    }
    out[idx] = vec4(prd.t, prd.prim as f32, prd.depth as f32, twice(steps as f32));
}

/// A closest hit that traces again (a nested trace from a lane-wise one).
#[rt_program(closest_hit)]
pub fn nearest(prd: &mut Probe, #[var] top: Object) {
    prd.t = t_hit();
    prd.prim = primitive_index();
    prd.depth += 1;
    if prd.depth < 2 {
        let ray = current_ray();
        let p = ray.origin + ray.direction * t_hit();
        let mut again = Probe { t: -1.0, prim: 0, depth: prd.depth };
        rt_trace(top, Ray::new(p + vec3(0.0, 0.0, 0.5), vec3(0.1, 0.0, -1.0), 0, 1e-3, 10.0), &mut again);
        prd.depth = again.depth + 10;
    }
}

#[rt_program(miss)]
pub fn nothing(prd: &mut Probe) {
    prd.t = -2.0;
}

/// A program of a kind that runs one launch index at a time.
#[rt_program(any_hit)]
pub fn any_seen(prd: &mut Probe) {
    prd.depth += 100;
}

/// A 3D launch's indices, lane-wise: a block runs across rows and slices.
#[rt_program(ray_generation)]
pub fn cells_3d(#[var] mut out: RwBuffer3d<u32>) {
    let i = launch_index_3d();
    let d = launch_dim_3d();
    out[i] = i.x + 16 * i.y + 256 * i.z + 4096 * (launch_index() == i.xy()) as u32 + 65536 * d.z;
    if i.x == 2 && i.z % 2 == 1 {
        rt_throw(EXCEPTION_USER + i.y + 10 * i.z);
    }
}

/// A program the lane-wise lowering refuses: a `let` without a value.
#[allow(clippy::needless_late_init)]
#[rt_program(ray_generation)]
pub fn late_init(#[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let v: f32;
    if idx.x > 2 {
        v = 1.0;
    } else {
        v = 2.0;
    }
    out[idx] = Vec4::splat(v);
}

/// A program the lane-wise lowering refuses: a closure bound to a local.
#[rt_program(ray_generation)]
pub fn bound_closure(#[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let twice = |a: f32| a * 2.0;
    out[idx] = Vec4::splat(twice(idx.x as f32));
}

#[rt_function]
pub fn half(x: f32) -> f32 {
    x * 0.5
}

/// A program the lane-wise lowering refuses: a path through `self::`.
#[rt_program(ray_generation)]
pub fn module_path(#[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    out[idx] = Vec4::splat(self::half(idx.x as f32));
}

/// What one launch left: the output and the report's exceptions, prints and
/// ray count.
type Outcome = (Vec<Vec4>, Vec<(UVec2, u32)>, Vec<(UVec2, String)>, u64);

fn run(mode: CpuExecution, transformed: bool, (w, h): (u32, u32)) -> Outcome {
    let mut ctx = Context::new();
    ctx.set_backend(Backend::Cpu);
    ctx.set_cpu_execution(mode);
    let rg = ctx.create_program(&divergent::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&nothing::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let mesh = ctx.create_triangles(rt_tests::meshes::bumpy_grid(12)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&nearest::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(mesh, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh)).unwrap();
    let top = if transformed {
        let t = ctx.create_transform(Mat4::from_translation(Vec3::new(0.05, -0.03, 0.0)), gg).unwrap();
        ctx.create_group(&[t], Acceleration::new(Builder::Bvh)).unwrap()
    } else {
        gg
    };
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, w, h).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let report = ctx.launch(0, w, h).unwrap();
    let exceptions = report.exceptions.iter().map(|e| (e.launch_index, e.code)).collect();
    (ctx.read_buffer::<Vec4>(out).unwrap(), exceptions, report.prints, report.rays)
}

#[test]
fn lanes_and_scalar_agree_exactly() {
    for transformed in [false, true] {
        for size in [(13, 7), (8, 8), (1, 5), (30, 2)] {
            let scalar = run(CpuExecution::Scalar, transformed, size);
            let lanes = run(CpuExecution::Lanes, transformed, size);
            let what = format!("transformed: {transformed}, size {size:?}");
            let bits = |v: &[Vec4]| v.iter().flat_map(|p| p.to_array().map(f32::to_bits)).collect::<Vec<_>>();
            assert_eq!(bits(&scalar.0), bits(&lanes.0), "outputs differ ({what})");
            assert_eq!(scalar.1, lanes.1, "exceptions differ ({what})");
            assert_eq!(scalar.2, lanes.2, "prints differ ({what})");
            assert_eq!(scalar.3, lanes.3, "ray counts differ ({what})");
        }
    }
    // The scene is really exercised: hits, misses, nested traces,
    // returns, exceptions and prints all happen.
    let (out, exceptions, prints, rays) = run(CpuExecution::Lanes, false, (13, 7));
    assert!(out.iter().any(|p| p.x > 0.0 && p.z >= 11.0), "a hit whose closest hit traced again");
    assert!(out.iter().any(|p| p.x == -2.0), "a miss");
    assert!(out.iter().any(|p| p.x == -1.0), "an early return");
    assert!(out.iter().any(|p| p.x == -3.0), "a return inside a branch that runs under a mask");
    assert!(!exceptions.is_empty() && exceptions.iter().all(|e| e.1 >= EXCEPTION_USER));
    assert!(!prints.is_empty());
    assert!(rays > 13 * 7 / 2);
}

/// Launches wide enough that a band of rows is cut along its columns into
/// several chunks (a launch of few rows spreads over the cores that way),
/// whose reports come back out of launch-index order until the launch
/// sorts them; the second's bands are of two rows, in 8x2 blocks.
#[test]
fn wide_launches_cut_into_chunks_agree_in_index_order() {
    for size in [(700, 9), (20_000, 2)] {
        let scalar = run(CpuExecution::Scalar, false, size);
        let lanes = run(CpuExecution::Lanes, false, size);
        assert!(lanes.1.len() > 20 && !lanes.2.is_empty(), "exceptions all along, and prints ({size:?})");
        assert!(lanes.1.windows(2).all(|w| (w[0].0.y, w[0].0.x) <= (w[1].0.y, w[1].0.x)), "{size:?}");
        assert_eq!(scalar.1, lanes.1, "exceptions differ ({size:?})");
        assert_eq!(scalar.2, lanes.2, "prints differ ({size:?})");
        assert_eq!(scalar.3, lanes.3, "ray counts differ ({size:?})");
        assert!(scalar.0 == lanes.0, "outputs differ ({size:?})");
    }
}

#[test]
fn cpu_execution_names_each_program_and_why() {
    let mut ctx = Context::new();
    ctx.set_cpu_execution(CpuExecution::Lanes);
    ctx.create_program(&divergent::PROGRAM);
    ctx.create_program(&nearest::PROGRAM);
    ctx.create_program(&nothing::PROGRAM);
    ctx.create_program(&any_seen::PROGRAM);
    ctx.create_program(&late_init::PROGRAM);
    let ways = ctx.cpu_execution();
    let find = |name: &str| ways.iter().find(|w| w.program == name).unwrap().scalar_because.clone();
    assert_eq!(find("divergent"), None);
    assert_eq!(find("nearest"), None);
    assert_eq!(find("nothing"), None);
    assert_eq!(find("any_seen").as_deref(), Some("any_hit programs run one launch index at a time"));
    let line = include_str!("cpu_lanes.rs").lines().position(|l| l.trim() == "let v: f32;").unwrap() + 1;
    assert_eq!(find("late_init"), Some(format!("a `let` without a value (line {line})")));
    let line_of = |text: &str| include_str!("cpu_lanes.rs").lines().position(|l| l.trim() == text).unwrap() + 1;
    ctx.create_program(&bound_closure::PROGRAM);
    ctx.create_program(&module_path::PROGRAM);
    let ways = ctx.cpu_execution();
    let find = |name: &str| ways.iter().find(|w| w.program == name).unwrap().scalar_because.clone();
    let line = line_of("let twice = |a: f32| a * 2.0;");
    assert_eq!(find("bound_closure"), Some(format!("a closure bound to a local (line {line})")));
    let line = line_of("out[idx] = Vec4::splat(self::half(idx.x as f32));");
    assert_eq!(find("module_path"), Some(format!("a path through `self::` or `super::` (line {line})")));
    ctx.set_cpu_execution(CpuExecution::Scalar);
    assert!(ctx.cpu_execution().iter().all(|w| w.scalar_because.is_some()));
}

#[test]
fn refused_programs_still_run_and_agree() {
    let outcome = |program: &'static rt_std::program::ProgramDescriptor, mode| {
        let mut ctx = Context::new();
        ctx.set_backend(Backend::Cpu);
        ctx.set_cpu_execution(mode);
        let rg = ctx.create_program(program);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 9, 2).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        ctx.launch(0, 9, 2).unwrap();
        ctx.read_buffer::<Vec4>(out).unwrap()
    };
    let lanes = outcome(&late_init::PROGRAM, CpuExecution::Lanes);
    assert_eq!(lanes, outcome(&late_init::PROGRAM, CpuExecution::Scalar));
    assert_eq!(lanes[0], Vec4::splat(2.0));
    assert_eq!(lanes[5], Vec4::splat(1.0));
    for p in [&bound_closure::PROGRAM, &module_path::PROGRAM] {
        let lanes = outcome(p, CpuExecution::Lanes);
        assert_eq!(lanes, outcome(p, CpuExecution::Scalar), "{}", p.name);
        assert_ne!(lanes[5], Vec4::ZERO, "{}", p.name);
    }
}

#[test]
fn a_3d_launch_agrees_lane_wise() {
    let run = |mode| {
        let mut ctx = Context::new();
        ctx.set_backend(Backend::Cpu);
        ctx.set_cpu_execution(mode);
        ctx.set_ray_type_count(0);
        let out = ctx.create_buffer_3d::<u32>(BufferType::Output, 5, 3, 7).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&cells_3d::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let report = ctx.launch_3d(0, 5, 3, 7).unwrap();
        let exceptions: Vec<(UVec2, u32)> = report.exceptions.iter().map(|e| (e.launch_index, e.code)).collect();
        let way = ctx.cpu_execution()[0].scalar_because.clone();
        (ctx.read_buffer::<u32>(out).unwrap(), exceptions, way)
    };
    let (lanes, scalar) = (run(CpuExecution::Lanes), run(CpuExecution::Scalar));
    assert_eq!(lanes.2, None, "cells_3d runs lane-wise");
    assert_eq!(lanes.0, scalar.0, "outputs differ");
    assert_eq!(lanes.1, scalar.1, "exceptions differ");
    // Index (1, 2, 3): its own value, `launch_index` its first two.
    assert_eq!(lanes.0[1 + 5 * (2 + 3 * 3)], 1 + 16 * 2 + 256 * 3 + 4096 + 65536 * 7);
    assert_eq!(lanes.1.len(), 3 * 3, "x = 2 in each of the odd slices' rows");
}
