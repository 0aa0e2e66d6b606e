//! Lane-wise execution's run-time half: what the lane-wise form of a ray
//! program (written by the compiler beside its scalar Rust copy) calls.
//!
//! A lane-wise program runs a block of [`LANES`] launch indices at once.
//! Each local variable holds one value per lane (`[T; LANES]`); a
//! statement runs for every lane of the active [`Mask`] in turn
//! ([`each`], [`fill`]). Each lane has its own execution context, which the
//! backend lends for the block ([`in_block`]); running a lane's statement
//! makes its context current ([`enter_lane`]: one pointer), so intrinsics
//! and exceptions behave exactly as in the scalar copy. A backend finds the
//! lane a call into it comes from with [`current_lane`]. Control flow that holds
//! a trace runs under masks, and [`trace`] hands the active lanes' rays to
//! the backend together ([`Tracer::trace_lanes`](super::Tracer::trace_lanes)), which traces them as a
//! packet where it can.
//!
//! A lane that returns leaves the mask; a block whose mask is empty is not
//! run, so [`fill`] always has a lane to take a value from.

pub use super::execution::{current_lane, enter_lane, in_block};
use super::execution::{raise, with_installed_tracer};
pub use super::mask::{LANES, LaneArgs, LanesEntry, Mask};
use crate::{EXCEPTION_INVALID_RAY, Object, Payload, RAY_FLAG_NONE, RAY_MASK_ALL, Ray, RtData};
use core::any::Any;

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

/// Runs a statement (or a run of them) for each lane of `mask` in turn;
/// `f` returns whether the lane returned from the program, and such lanes
/// leave `mask`.
#[inline(always)]
pub fn each(mask: &mut Mask, mut f: impl FnMut(usize) -> bool) {
    for (l, running) in mask.iter_mut().enumerate() {
        if *running {
            enter_lane(l);
            if f(l) {
                *running = false;
            }
        }
    }
}

/// A value's lanes: `f(lane)` for each lane of `mask`, in that lane's
/// context, and for the lanes not running a copy of the first running lane's
/// value (never read).
///
/// # Panics
/// If no lane of `mask` runs: the compiler never lets that happen.
#[inline(always)]
pub fn fill<T: Copy>(mask: &Mask, mut f: impl FnMut(usize) -> T) -> [T; LANES] {
    let first = mask.iter().position(|&m| m).expect("a lane-wise block runs with at least one lane");
    enter_lane(first);
    let mut values = [f(first); LANES];
    for (l, value) in values.iter_mut().enumerate().skip(first + 1) {
        if mask[l] {
            enter_lane(l);
            *value = f(l);
        }
    }
    values
}

/// The values a run of statements leaves in a local, lane by lane: a lane
/// sets its value at the run's end; [`Slots::finish`] makes the lane-wise
/// local the statements after the run read.
pub struct Slots<T>([Option<T>; LANES]);

impl<T: Copy> Slots<T> {
    /// No lane's value yet.
    #[allow(clippy::new_without_default)]
    #[inline(always)]
    pub fn new() -> Self {
        Slots([None; LANES])
    }

    /// Lane `lane`'s value.
    #[inline(always)]
    pub fn set(&mut self, lane: usize, value: T) {
        self.0[lane] = Some(value);
    }

    /// The values, a lane that set none holding a copy of one that did
    /// (it is not running, so never read).
    ///
    /// # Panics
    /// If no lane set a value: the compiler reads slots only while a lane
    /// runs, and every running lane ran the whole run.
    #[inline(always)]
    pub fn finish(self) -> [T; LANES] {
        let any = self.0.iter().flatten().next().copied().expect("a running lane set its value");
        core::array::from_fn(|l| self.0[l].unwrap_or(any))
    }
}

/// `rt_trace(objects[l], rays[l], &mut payloads[l])` for the lanes of
/// `mask`: an invalid ray raises [`EXCEPTION_INVALID_RAY`] in its lane and
/// is not traced, as [`rt_trace`](crate::rt_trace) does; the others go to
/// the backend together.
pub fn trace<P: Payload>(mask: &Mask, objects: &[Object; LANES], rays: &[Ray; LANES], payloads: &mut [P; LANES]) {
    let mut go = *mask;
    for (l, (going, ray)) in go.iter_mut().zip(rays).enumerate() {
        if *going && !ray.is_valid() {
            enter_lane(l);
            raise(EXCEPTION_INVALID_RAY);
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

/// Values of `T` for the lanes that do not run, so a lane-wise parameter
/// has a reference in every lane ([`refs`]): `T` read from zero words.
pub fn spares<T: RtData>() -> [T; LANES] {
    let words = T::LAYOUT.words as usize;
    let zeros = [0u32; 64];
    let big;
    let zeros = match zeros.get(..words) {
        Some(z) => z,
        None => {
            big = std::vec![0u32; words];
            &big[..]
        }
    };
    core::array::from_fn(|_| T::read_words(zeros))
}

/// A payload or attributes parameter, lane-wise: each running lane's
/// `&mut T` from `slots` (a [`LaneArgs`] field), each other lane's into
/// `spares`. A running lane whose slot holds no `T` (a ray traced with a
/// payload type its programs do not take) raises
/// [`EXCEPTION_INVALID_RAY`] and leaves `mask`, as the scalar thunk raises
/// it instead of running the program.
pub fn refs<'a, T: 'static>(
    mask: &mut Mask,
    slots: &'a mut [Option<&mut dyn Any>; LANES],
    spares: &'a mut [T; LANES],
) -> [&'a mut T; LANES] {
    let mut refs = spares.each_mut();
    for (l, (r, slot)) in refs.iter_mut().zip(slots.iter_mut()).enumerate() {
        if !mask[l] {
            continue;
        }
        match slot.as_deref_mut().and_then(|a| a.downcast_mut::<T>()) {
            Some(value) => *r = value,
            None => {
                enter_lane(l);
                raise(EXCEPTION_INVALID_RAY);
                mask[l] = false;
            }
        }
    }
    refs
}
