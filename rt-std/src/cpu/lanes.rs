//! Lane-wise execution's run-time half: what the lane-wise form of a ray
//! program (written by the compiler beside its scalar Rust copy) calls.
//!
//! A lane-wise program runs a block of [`LANES`] launch indices at once.
//! Each local variable holds one value per lane (`[T; LANES]`); a
//! statement runs for every lane of the active [`Mask`] in turn
//! ([`each`], [`fill`]), with the backend's per-index state switched to
//! that lane around it ([`Tracer::enter_lane`](super::Tracer::enter_lane)), so intrinsics, exceptions
//! and prints behave exactly as in the scalar copy. Control flow that holds
//! a trace runs under masks, and [`trace`] hands the active lanes' rays to
//! the backend together ([`Tracer::trace_lanes`](super::Tracer::trace_lanes)), which traces them as a
//! packet where it can.
//!
//! A lane that returns leaves the mask; a block whose mask is empty is not
//! run, so [`fill`] always has a lane to take a value from.

use super::execution::{raise, with_installed_tracer};
use crate::{EXCEPTION_INVALID_RAY, Object, Payload, RAY_FLAG_NONE, RAY_MASK_ALL, Ray};
use core::any::Any;

/// The number of launch indices a lane-wise program runs at once.
pub const LANES: usize = 8;

/// Which lanes run: `true` for a running lane.
pub type Mask = [bool; LANES];

/// A program's lane-wise entry: runs the lanes of `mask` (the backend has
/// set up each lane's launch index) with the program's variables.
pub type LanesEntry = fn(&Mask, &super::BoundVariables<'_>);

/// Whether any lane of `mask` runs.
#[inline(always)]
pub fn any(mask: &Mask) -> bool {
    mask.iter().any(|&m| m)
}

/// The lanes of `mask` where `cond` holds.
#[inline(always)]
pub fn and(mask: &Mask, cond: &[bool; LANES]) -> Mask {
    core::array::from_fn(|l| mask[l] && cond[l])
}

/// The lanes of `mask` where `cond` does not hold.
#[inline(always)]
pub fn and_not(mask: &Mask, cond: &[bool; LANES]) -> Mask {
    core::array::from_fn(|l| mask[l] && !cond[l])
}

/// The lanes running in `a` or in `b`.
#[inline(always)]
pub fn or(a: &Mask, b: &Mask) -> Mask {
    core::array::from_fn(|l| a[l] || b[l])
}

/// Runs `f(lane)` for the lanes of `mask` inside the backend's state for
/// that lane.
#[inline(always)]
fn in_lane<R>(lane: usize, f: impl FnOnce() -> R) -> R {
    with_installed_tracer(|t| t.enter_lane(lane), || ());
    let r = f();
    with_installed_tracer(|t| t.leave_lane(lane), || ());
    r
}

/// Runs a statement for each lane of `mask`; `f` returns whether the lane
/// returned from the program, and such lanes leave `mask`.
#[inline(always)]
pub fn each(mask: &mut Mask, mut f: impl FnMut(usize) -> bool) {
    for (l, running) in mask.iter_mut().enumerate() {
        if *running && in_lane(l, || f(l)) {
            *running = false;
        }
    }
}

/// A local's values: `f(lane)` for each lane of `mask`, and for the lanes
/// not running a copy of the first running lane's value (never read).
///
/// # Panics
/// If no lane of `mask` runs: the compiler never lets that happen.
#[inline(always)]
pub fn fill<T: Copy>(mask: &Mask, mut f: impl FnMut(usize) -> T) -> [T; LANES] {
    let first = mask.iter().position(|&m| m).expect("a lane-wise block runs with at least one lane");
    let v = in_lane(first, || f(first));
    let mut values = [v; LANES];
    for (l, value) in values.iter_mut().enumerate().skip(first + 1) {
        if mask[l] {
            *value = in_lane(l, || f(l));
        }
    }
    values
}

/// `rt_trace(objects[l], rays[l], &mut payloads[l])` for the lanes of
/// `mask`: an invalid ray raises [`EXCEPTION_INVALID_RAY`] in its lane and
/// is not traced, as [`rt_trace`](crate::rt_trace) does; the others go to
/// the backend together.
pub fn trace<P: Payload>(mask: &Mask, objects: &[Object; LANES], rays: &[Ray; LANES], payloads: &mut [P; LANES]) {
    let mut go = *mask;
    for (l, (going, ray)) in go.iter_mut().zip(rays).enumerate() {
        if *going && !ray.is_valid() {
            in_lane(l, || raise(EXCEPTION_INVALID_RAY));
            *going = false;
        }
    }
    if !any(&go) {
        return;
    }
    let mut refs: [Option<&mut dyn Any>; LANES] = Default::default();
    for (slot, p) in refs.iter_mut().zip(payloads.iter_mut()) {
        *slot = Some(p as &mut dyn Any);
    }
    with_installed_tracer(|t| t.trace_lanes(&go, objects, rays, &mut refs, RAY_FLAG_NONE, RAY_MASK_ALL, 0.0), || ());
}

/// A lane's own part of this thread's execution context: its launch index
/// and slice, and the exception its program raised and where.
#[derive(Clone, Copy, Debug, Default)]
pub struct LaneContext {
    /// [`launch_index`](crate::launch_index) in the lane.
    pub launch_index: glam::UVec2,
    /// The slice of a 3D launch.
    pub launch_z: u32,
    /// The exception the lane's program raised, if any.
    pub pending_exception: Option<u32>,
    /// Where, when the raiser said.
    pub pending_location: Option<&'static core::panic::Location<'static>>,
}

/// Puts `lane`'s part into this thread's execution context (a backend's
/// [`Tracer::enter_lane`](super::Tracer::enter_lane)).
#[inline]
pub fn put_lane_context(lane: &LaneContext) {
    super::execution::update(|c| {
        c.launch_index = lane.launch_index;
        c.launch_z = lane.launch_z;
        c.pending_exception = lane.pending_exception;
        c.pending_location = lane.pending_location;
    })
}

/// Takes the running lane's exception back out of this thread's execution
/// context (a backend's [`Tracer::leave_lane`](super::Tracer::leave_lane)).
#[inline]
pub fn take_lane_exception(lane: &mut LaneContext) {
    super::execution::read(|c| {
        lane.pending_exception = c.pending_exception;
        lane.pending_location = c.pending_location;
    })
}
