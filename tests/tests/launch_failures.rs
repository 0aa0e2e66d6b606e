//! A panic inside a launch on the CPU backend (in a program, or in a
//! bounding-box program during the build) comes back as a typed error
//! naming the program, its file and line, the launch index and the message;
//! the output buffers are as they were before the launch, nothing is
//! printed, and the context stays usable.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_std::program::ProgramDescriptor;

#[rt_program(ray_generation)]
pub fn fill(#[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    out[i] = i + 100;
}

#[rt_program(bounding_box)]
pub fn unit_bounds(prim: u32) -> Aabb {
    let _ = prim;
    Aabb::new(Vec3::ZERO, Vec3::ONE)
}

#[rt_program(intersection)]
pub fn never(prim: u32) {
    let _ = prim;
}

#[rt_program(ray_generation)]
pub fn trace_once(#[var] top: Object) {
    let mut prd = Empty { hit: 0 };
    rt_trace(top, Ray::new(Vec3::splat(-1.0), Vec3::ONE, 0, 0.0, 10.0), &mut prd);
}

#[rt_payload]
pub struct Empty {
    pub hit: u32,
}

#[rt_program(miss)]
pub fn nothing(prd: &mut Empty) {
    prd.hit = 0;
}

/// `desc` with a CPU body that panics where `panics_at` says, else runs the
/// program's own: a program with a bug only the CPU run shows (what a
/// user's `unwrap` or assertion in CPU-only code would do).
fn with_cpu(
    desc: &'static ProgramDescriptor,
    cpu: fn(&mut rt_std::cpu::CpuArgs<'_>) -> rt_std::cpu::CpuResult,
) -> &'static ProgramDescriptor {
    // (The scalar entry replaced, and so the one that runs.)
    let cpu_lanes = rt_std::program::CpuLanes::Scalar("the test replaces the scalar entry");
    Box::leak(Box::new(ProgramDescriptor { cpu, cpu_lanes, ..*desc }))
}

fn fill_panicking_at_five(args: &mut rt_std::cpu::CpuArgs<'_>) -> rt_std::cpu::CpuResult {
    if launch_index().x == 5 {
        panic!("boom at five");
    }
    (fill::PROGRAM.cpu)(args)
}

fn bounds_panicking(_: &mut rt_std::cpu::CpuArgs<'_>) -> rt_std::cpu::CpuResult {
    let v: Vec<u32> = std::hint::black_box(Vec::new());
    rt_std::cpu::CpuResult::Child(v[2])
}

#[test]
fn a_panicking_program_is_an_error_naming_it_and_the_outputs_stay_as_they_were() {
    let mut ctx = Context::new();
    ctx.set_ray_type_count(0);
    let before: Vec<u32> = (0..64).map(|i| 7 * i).collect();
    let out = ctx.create_buffer::<u32>(BufferType::InputOutput, before.clone());
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let bad = ctx.create_program(with_cpu(&fill::PROGRAM, fill_panicking_at_five));
    ctx.set_ray_generation_program(0, bad).unwrap();
    let err = ctx.launch_1d(0, 64).unwrap_err();
    match &err {
        RtError::Launch(LaunchError::ProgramPanicked { program, location, launch_index, message, at }) => {
            assert_eq!(*program, "fill");
            assert!(location.ends_with("launch_failures.rs:12"), "{location}");
            assert_eq!(*launch_index, glam::UVec2::new(5, 0));
            assert_eq!(message, "boom at five");
            assert!(at.contains("launch_failures.rs:"), "{at}");
        }
        other => panic!("expected ProgramPanicked, got {other:?}"),
    }
    let text = err.to_string();
    assert!(text.starts_with("program `fill` (") && text.contains("panicked at launch index [5, 0]"), "{text}");
    assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), before, "the launch wrote none of its outputs");
    // The context is usable: the program itself runs.
    let good = ctx.create_program(&fill::PROGRAM);
    ctx.set_ray_generation_program(0, good).unwrap();
    ctx.launch_1d(0, 64).unwrap();
    assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), (0..64).map(|i| i + 100).collect::<Vec<u32>>());
}

/// `fill`'s lane-wise form, panicking in the lane of launch index 13 (lane
/// 5 of the second block) after the lanes before it ran the statement.
fn fill_lanes_panicking_at_thirteen(
    mask: &rt_std::cpu::lanes::Mask,
    args: &mut rt_std::cpu::lanes::LaneArgs<'_>,
    vars: &rt_std::cpu::BoundVariables<'_>,
) {
    let mut running = *mask;
    rt_std::cpu::lanes::each(&mut running, |_| {
        if launch_index().x == 13 {
            panic!("boom at thirteen");
        }
        false
    });
    match fill::PROGRAM.cpu_lanes {
        rt_std::program::CpuLanes::Lanes(entry) => entry(mask, args, vars),
        rt_std::program::CpuLanes::Scalar(why) => panic!("`fill` runs lane-wise, not scalar: {why}"),
    }
}

#[test]
fn a_panic_in_a_lane_names_that_lanes_launch_index() {
    let mut ctx = Context::new();
    ctx.set_ray_type_count(0);
    ctx.set_cpu_execution(CpuExecution::Lanes);
    let before: Vec<u32> = (0..64).map(|i| 7 * i).collect();
    let out = ctx.create_buffer::<u32>(BufferType::InputOutput, before.clone());
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let lanes = rt_std::program::CpuLanes::Lanes(fill_lanes_panicking_at_thirteen);
    let bad = ctx.create_program(Box::leak(Box::new(ProgramDescriptor { cpu_lanes: lanes, ..fill::PROGRAM })));
    ctx.set_ray_generation_program(0, bad).unwrap();
    let text = ctx.launch_1d(0, 64).unwrap_err().to_string();
    assert!(text.starts_with("program `fill` (") && text.contains("panicked at launch index [13, 0]"), "{text}");
    assert!(text.contains("boom at thirteen"), "{text}");
    assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), before, "the launch wrote none of its outputs");
    // The context is usable: the program's own lane-wise form runs.
    let good = ctx.create_program(&fill::PROGRAM);
    ctx.set_ray_generation_program(0, good).unwrap();
    ctx.launch_1d(0, 64).unwrap();
    assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), (0..64).map(|i| i + 100).collect::<Vec<u32>>());
}

#[test]
fn a_panicking_bounding_box_program_is_an_error_naming_it_and_the_primitive() {
    let mut ctx = Context::new();
    let isect = ctx.create_program(&never::PROGRAM);
    let bounds = ctx.create_program(with_cpu(&unit_bounds::PROGRAM, bounds_panicking));
    let geom = ctx.create_custom_geometry(3, isect, bounds).unwrap();
    let mat = ctx.create_material();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let rg = ctx.create_program(&trace_once::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&nothing::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let err = ctx.launch(0, 1, 1).unwrap_err();
    match &err {
        RtError::Launch(LaunchError::BoundsPanicked { program, primitive, message, .. }) => {
            assert_eq!(*program, "unit_bounds");
            assert_eq!(*primitive, 0);
            assert!(message.contains("index out of bounds"), "{message}");
        }
        other => panic!("expected BoundsPanicked, got {other:?}"),
    }
    // Nothing was left half built: the next launch fails the same way.
    assert_eq!(ctx.launch(0, 1, 1).unwrap_err().to_string(), err.to_string());
    assert!(err.to_string().starts_with("bounding-box program `unit_bounds` ("), "{err}");
}
