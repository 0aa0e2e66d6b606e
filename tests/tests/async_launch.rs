//! `Context::launch_async`, the launch a browser page awaits: natively the
//! same launch as `Context::launch` (outputs, exceptions, prints and rays
//! equal on every target, whole and in tiles, and a refused launch the
//! same error), ready at its first poll (every wait inside it has happened
//! once the device was polled idle, so a blocking caller never parks).

use glam::{UVec2, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::meshes::bumpy_grid;
use rt_tests::targets::On;
use std::future::Future;
use std::pin::pin;
use std::task::{Context as TaskContext, Poll, Waker};

#[rt_payload]
pub struct Shade {
    pub c: Vec3,
}

#[rt_program(ray_generation)]
pub fn camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let mut prd = Shade { c: Vec3::ZERO };
    rt_trace(top, Ray::new(vec3(p.x, p.y, 3.0), vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY), &mut prd);
    out[idx] = prd.c.extend(t_of(prd.c));
    if idx.x == 3 && idx.y == 5 {
        rt_printf!("pixel {} {}", idx.x, prd.c.x);
    }
    if idx.x == 7 && idx.y == 2 {
        rt_throw(EXCEPTION_USER + 3);
    }
}

#[rt_function]
pub fn t_of(c: Vec3) -> f32 {
    c.x + c.y + c.z
}

#[rt_program(closest_hit)]
pub fn depth(prd: &mut Shade) {
    prd.c = vec3(t_hit(), 1.0, 0.5);
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade) {
    prd.c = Vec3::ZERO;
}

#[rt_program(exception)]
pub fn caught() {}

/// A context on `on` over a bumpy grid, with the output buffer.
fn scene(on: On, budget: TileBudget) -> (Context, BufferId) {
    let mut ctx = on.context();
    ctx.set_tile_budget(budget);
    ctx.set_print(true, None);
    let g = ctx.create_triangles(bumpy_grid(8)).unwrap();
    let m = ctx.create_material();
    let ch = ctx.create_program(&depth::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
    let top = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 24, 16).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&sky::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let ex = ctx.create_program(&caught::PROGRAM);
    ctx.set_exception_program(0, ex).unwrap();
    (ctx, out)
}

/// Polls `f` once, as an executor that never blocks would.
fn first_poll<F: Future>(f: F) -> Poll<F::Output> {
    let mut f = pin!(f);
    f.as_mut().poll(&mut TaskContext::from_waker(Waker::noop()))
}

/// What a launch gave: the outputs, and the report's exceptions, prints,
/// rays and tiles (not its timings).
type Outcome = (Vec<Vec4>, Vec<ExceptionRecord>, Vec<(UVec2, String)>, u64, u32);

fn outcome(ctx: &Context, out: BufferId, report: LaunchReport) -> Outcome {
    (ctx.read_buffer::<Vec4>(out).unwrap(), report.exceptions, report.prints, report.rays, report.tiles)
}

#[test]
fn an_awaited_launch_is_the_blocking_launch() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        for budget in [TileBudget::Whole, TileBudget::Indices(128)] {
            let name = format!("{} {budget:?}", on.name());
            let (mut blocking, out) = scene(on, budget);
            let report = blocking.launch(0, 24, 16).unwrap();
            let expected = outcome(&blocking, out, report);
            let (mut awaited, out) = scene(on, budget);
            let Poll::Ready(report) = first_poll(awaited.launch_async(0, 24, 16)) else {
                panic!("{name}: the launch was not ready at its first poll");
            };
            let got = outcome(&awaited, out, report.unwrap());
            assert_eq!(got, expected, "{name}");
            // Real values: the grid's depth under the camera, the print and
            // the exception at their pixels, one ray a pixel.
            let (pixels, exceptions, prints, rays, tiles) = got;
            assert!(pixels.iter().all(|p| p.y == 1.0 && (p.x - 3.0).abs() < 0.5), "{name}");
            assert_eq!(
                exceptions.iter().map(|e| (e.launch_index, e.code)).collect::<Vec<_>>(),
                [(UVec2::new(7, 2), EXCEPTION_USER + 3)]
            );
            assert_eq!(prints.len(), 1, "{name}");
            assert_eq!(prints[0].0, UVec2::new(3, 5), "{name}");
            assert_eq!(rays, 24 * 16, "{name}");
            assert_eq!(tiles > 1, budget != TileBudget::Whole, "{name}");
        }
    }
}

#[test]
fn an_awaited_launch_refuses_what_the_blocking_one_refuses() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (mut ctx, _) = scene(on, TileBudget::Whole);
        let blocking = ctx.launch(0, 0, 16).unwrap_err().to_string();
        let Poll::Ready(awaited) = first_poll(ctx.launch_async(0, 0, 16)) else { panic!("{}", on.name()) };
        assert_eq!(awaited.unwrap_err().to_string(), blocking, "{}", on.name());
        // The context still launches, awaited.
        let Poll::Ready(report) = first_poll(ctx.launch_async(0, 24, 16)) else { panic!("{}", on.name()) };
        assert_eq!(report.unwrap().rays, 24 * 16, "{}", on.name());
    }
}

/// A device-local output (`Context::set_buffer_device_local`) stays on the
/// device after the launch: `read_buffer_async` awaits its words there and
/// gives what `read_buffer` gives, ready at its first poll natively.
#[test]
fn a_device_local_buffer_is_read_awaited() {
    let on = On::COMPUTE;
    if !on.available() {
        return;
    }
    let (mut ctx, out) = scene(on, TileBudget::Whole);
    ctx.set_buffer_device_local(out, true).unwrap();
    let Poll::Ready(report) = first_poll(ctx.launch_async(0, 24, 16)) else { panic!("the launch was not ready") };
    report.unwrap();
    // The log's header, its exception and its print: not the 6144 bytes
    // of the output, which stayed on the device.
    assert!(ctx.last_read_back_bytes() < 200, "{} bytes read back", ctx.last_read_back_bytes());
    let blocking = ctx.read_buffer::<Vec4>(out).unwrap();
    let Poll::Ready(awaited) = first_poll(ctx.read_buffer_async::<Vec4>(out)) else { panic!("the read was not ready") };
    let awaited = awaited.unwrap();
    assert_eq!(awaited, blocking);
    assert!(awaited.iter().all(|p| p.y == 1.0 && (p.x - 3.0).abs() < 0.5));
}
