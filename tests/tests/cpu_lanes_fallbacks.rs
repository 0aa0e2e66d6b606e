//! Each reason the lane-wise lowering gives for running a program one
//! launch index at a time (`CpuLanes::Scalar`), one program per reason:
//! `Context::cpu_execution` names the reason (with the construct's line in
//! this file), and a launch in `CpuExecution::Lanes` gives exactly the
//! scalar run's outputs, which are checked against the values the program
//! computes. (`cpu_lanes.rs` covers `let` without a value, a closure bound
//! to a local and a path through `self::`.)
//!
//! The lowering's other refusals guard forms no compiling program reaches:
//! a `self` parameter, a parameter pattern, a parameter that is no
//! variable, payload or attributes (the signature check rejects the first
//! two; the third only callables, intersection and bounding-box programs
//! have, which are refused by kind first), a structural statement that is
//! not an expression, a macro other than `rt_printf!`/`matches!` (the WGSL
//! lowering refuses it) and "the program has errors".

use glam::{Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;

#[rt_payload]
pub struct Shade {
    pub t: f32,
    pub seen: u32,
}

/// Refused: a `return` with a value (in a branch some lanes take).
#[allow(clippy::unused_unit, clippy::needless_return)]
#[rt_program(ray_generation)]
pub fn return_value(#[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    if idx.x % 3 == 1 {
        out[idx] = vec4(7.0, idx.y as f32, 0.0, 0.0);
        return ();
    }
    out[idx] = vec4(idx.x as f32, idx.y as f32, 1.0, 0.0);
}

/// Refused: `let ... else`.
#[rt_program(ray_generation)]
pub fn let_else(#[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let 0..=5 = idx.x else {
        out[idx] = vec4(-1.0, idx.y as f32, 0.0, 0.0);
        return;
    };
    out[idx] = vec4(idx.x as f32, idx.y as f32, 2.0, 0.0);
}

/// Refused: a `matches!` whose guard names a local that is lane-wise (a
/// trace before it ends the run of statements that declared it).
#[rt_program(ray_generation)]
pub fn matches_local(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let limit = idx.y + 3;
    let mut prd = Shade { t: -1.0, seen: 0 };
    rt_trace(top, Ray::new(vec3(0.0, 0.0, 3.0), vec3(0.0, 0.0, -1.0), 0, 1e-3, 1e9), &mut prd);
    let small = matches!(idx.x, 0..=7 if idx.x < limit);
    out[idx] = vec4(small as u32 as f32, idx.x as f32, idx.y as f32, prd.t);
}

/// Refused: a `return` inside a value the lane-wise form needs for all
/// lanes at once (a traced ray's argument).
#[rt_program(ray_generation)]
pub fn return_in_value(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let dim = launch_dim();
    let p = (idx.as_vec2() + 0.5) / dim.as_vec2() * 2.0 - 1.0;
    let mut prd = Shade { t: -1.0, seen: 0 };
    let ray = Ray::new(vec3(0.0, 0.0, 3.0), vec3(p.x * 0.8, p.y * 0.8, -1.0).normalize(), 0, 1e-3, f32::INFINITY);
    rt_trace(
        top,
        if idx.x % 4 == 3 {
            return;
        } else {
            ray
        },
        &mut prd,
    );
    out[idx] = vec4(prd.t, prd.seen as f32, 4.0, 0.0);
}

/// Lane-wise itself, over a material whose any-hit program runs one launch
/// index at a time.
#[rt_program(ray_generation)]
pub fn traced(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let dim = launch_dim();
    let p = (idx.as_vec2() + 0.5) / dim.as_vec2() * 2.0 - 1.0;
    let mut prd = Shade { t: -1.0, seen: 0 };
    if idx.x % 2 == 0 {
        rt_trace(top, Ray::new(vec3(0.0, 0.0, 3.0), vec3(p.x, p.y, -1.0).normalize(), 0, 1e-3, 1e9), &mut prd);
    }
    out[idx] = vec4(prd.t, prd.seen as f32, 5.0, 0.0);
}

#[rt_program(closest_hit)]
pub fn shade_hit(prd: &mut Shade) {
    prd.t = t_hit();
}

#[rt_program(miss)]
pub fn shade_miss(prd: &mut Shade) {
    prd.t = -2.0;
}

/// Refused by kind.
#[rt_program(any_hit)]
pub fn count_hits(prd: &mut Shade) {
    prd.seen += 1;
}

/// Refused by kind.
#[rt_program(exception)]
pub fn caught() {}

/// Refused by kind.
#[rt_program(intersection)]
pub fn never_hits(prim: u32) {
    let _ = prim;
}

/// Refused by kind.
#[rt_program(bounding_box)]
pub fn unit_box(prim: u32) -> Aabb {
    let _ = prim;
    Aabb::new(Vec3::ZERO, Vec3::ONE)
}

/// Refused by kind.
#[rt_program(visit)]
pub fn first(prd: &Shade) -> u32 {
    let _ = prd.seen;
    0
}

/// Refused by kind.
#[rt_program(callable)]
pub fn doubled(x: f32) -> f32 {
    x * 2.0
}

/// The 1-based line of the first line of this file that is `text` trimmed.
fn line_of(text: &str) -> usize {
    include_str!("cpu_lanes_fallbacks.rs").lines().position(|l| l.trim() == text).expect(text) + 1
}

/// `program`'s reason to run one launch index at a time in a context that
/// runs lane-wise (`None`: it runs lane-wise).
fn reason(program: &'static rt_std::program::ProgramDescriptor) -> Option<String> {
    let mut ctx = Context::new();
    ctx.set_cpu_execution(CpuExecution::Lanes);
    ctx.create_program(program);
    let ways = ctx.cpu_execution();
    assert_eq!(ways.len(), 1);
    assert_eq!(ways[0].program, program.name);
    ways[0].scalar_because.clone()
}

const W: u32 = 13;
const H: u32 = 3;

/// `rg`'s output launched `W` by `H` on the CPU in `mode`, over a grid whose
/// material has a closest-hit and an any-hit program.
fn launch(rg: &'static rt_std::program::ProgramDescriptor, mode: CpuExecution) -> Vec<Vec4> {
    let mut ctx = Context::new();
    ctx.set_backend(Backend::Cpu);
    ctx.set_cpu_execution(mode);
    let name = rg.name;
    let rg = ctx.create_program(rg);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&shade_miss::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let mesh = ctx.create_triangles(rt_tests::meshes::bumpy_grid(6)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&shade_hit::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let ah = ctx.create_program(&count_hits::PROGRAM);
    ctx.set_any_hit_program(mat, 0, ah).unwrap();
    let gi = ctx.create_geometry_instance(mesh, &[mat]).unwrap();
    let top = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh)).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, W, H).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let report = ctx.launch(0, W, H).unwrap();
    assert!(report.exceptions.is_empty(), "{name}: {:?}", report.exceptions);
    ctx.read_buffer::<Vec4>(out).unwrap()
}

/// The outputs lane-wise, asserted bit-equal to the scalar run's.
fn agreeing(rg: &'static rt_std::program::ProgramDescriptor) -> Vec<Vec4> {
    let lanes = launch(rg, CpuExecution::Lanes);
    let scalar = launch(rg, CpuExecution::Scalar);
    let bits = |v: &[Vec4]| v.iter().flat_map(|p| p.to_array().map(f32::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(&lanes), bits(&scalar), "{}: lane-wise and scalar outputs differ", rg.name);
    lanes
}

fn at(out: &[Vec4], x: u32, y: u32) -> Vec4 {
    out[(x + W * y) as usize]
}

#[test]
fn a_return_with_a_value() {
    let line = line_of("return ();");
    assert_eq!(reason(&return_value::PROGRAM), Some(format!("a `return` with a value (line {line})")));
    let out = agreeing(&return_value::PROGRAM);
    assert_eq!(at(&out, 4, 2), vec4(7.0, 2.0, 0.0, 0.0));
    assert_eq!(at(&out, 5, 1), vec4(5.0, 1.0, 1.0, 0.0));
}

#[test]
fn a_let_else() {
    let line = line_of("let 0..=5 = idx.x else {");
    assert_eq!(reason(&let_else::PROGRAM), Some(format!("`let ... else` (line {line})")));
    let out = agreeing(&let_else::PROGRAM);
    assert_eq!(at(&out, 5, 2), vec4(5.0, 2.0, 2.0, 0.0));
    assert_eq!(at(&out, 6, 1), vec4(-1.0, 1.0, 0.0, 0.0));
}

#[test]
fn a_matches_pattern_that_names_a_local() {
    let line = line_of("let small = matches!(idx.x, 0..=7 if idx.x < limit);");
    assert_eq!(reason(&matches_local::PROGRAM), Some(format!("a `matches!` pattern that names a local (line {line})")));
    let out = agreeing(&matches_local::PROGRAM);
    let t = at(&out, 0, 0).w;
    assert!(t > 0.0, "the ray down the middle hits: {t}");
    assert_eq!(at(&out, 2, 0), vec4(1.0, 2.0, 0.0, t));
    assert_eq!(at(&out, 3, 0), vec4(0.0, 3.0, 0.0, t), "3 < 0 + 3 fails the guard");
    assert_eq!(at(&out, 4, 2), vec4(1.0, 4.0, 2.0, t));
    assert_eq!(at(&out, 8, 2), vec4(0.0, 8.0, 2.0, t), "8 is outside the range");
}

#[test]
fn a_return_inside_a_value() {
    // (The ray argument, an `if`, starts the line.)
    let line = line_of("if idx.x % 4 == 3 {");
    assert_eq!(reason(&return_in_value::PROGRAM), Some(format!("a `return` inside a value (line {line})")));
    let out = agreeing(&return_in_value::PROGRAM);
    for y in 0..H {
        for x in 0..W {
            let p = at(&out, x, y);
            if x % 4 == 3 {
                assert_eq!(p, Vec4::ZERO, "({x}, {y}) returned before writing");
            } else {
                assert_eq!(p.z, 4.0, "({x}, {y})");
                assert!(p.x > 0.0 || p.x == -2.0, "({x}, {y}) hit or missed: {p}");
            }
        }
    }
    assert!(out.iter().any(|p| p.x > 0.0 && p.y >= 1.0), "a hit the any-hit program saw");
}

#[test]
fn programs_of_the_kinds_without_a_lane_wise_form() {
    let by_kind = |kind: &str| Some(format!("{kind} programs run one launch index at a time"));
    assert_eq!(reason(&count_hits::PROGRAM), by_kind("any_hit"));
    assert_eq!(reason(&caught::PROGRAM), by_kind("exception"));
    assert_eq!(reason(&never_hits::PROGRAM), by_kind("intersection"));
    assert_eq!(reason(&unit_box::PROGRAM), by_kind("bounding_box"));
    assert_eq!(reason(&first::PROGRAM), by_kind("visit"));
    assert_eq!(reason(&doubled::PROGRAM), by_kind("callable"));
    for lane_wise in [&traced::PROGRAM, &shade_hit::PROGRAM, &shade_miss::PROGRAM] {
        assert_eq!(reason(lane_wise), None, "{}", lane_wise.name);
    }
    // A lane-wise packet whose hits run an any-hit program one launch
    // index at a time: the scalar run's answer.
    let out = agreeing(&traced::PROGRAM);
    for (i, p) in out.iter().enumerate() {
        let x = i as u32 % W;
        assert_eq!(p.z, 5.0);
        if x % 2 == 1 {
            assert_eq!((p.x, p.y), (-1.0, 0.0), "lane {i} did not trace");
        }
    }
    assert!(out.iter().any(|p| p.x > 0.0 && p.y >= 1.0), "a hit the any-hit program saw");
}
