//! The per-thread state intrinsics read and write while programs run as
//! Rust: the launch index, the current ray and hit, the transforms, the
//! pending exception, and the tracer that serves `rt_trace` and callables.

use core::cell::Cell;

use glam::{Mat4, UVec2};

use crate::ray::Ray;
use crate::scene::Object;

use super::mask::LANES;
use super::thunk::{BoundVariables, VariableList};
use crate::layout::TriangleBuiltins;

/// [`ExecutionContext::hit_kind`]: no hit (a miss, or outside hit programs).
pub const HIT_NONE: u32 = 0;
/// A triangle, met on its counter-clockwise side.
pub const HIT_TRIANGLE_FRONT: u32 = 1;
/// A triangle, met on its clockwise side.
pub const HIT_TRIANGLE_BACK: u32 = 2;
/// A custom primitive (reported by an intersection program).
pub const HIT_CUSTOM: u32 = 3;

/// The transforms of a geometry instance: the product of the transform
/// nodes above it, and its inverse (the backend supplies both so that no
/// intrinsic inverts a matrix).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transforms {
    /// Object-to-world transform.
    pub object_to_world: Mat4,
    /// World-to-object transform (the inverse of `object_to_world`).
    pub world_to_object: Mat4,
}

impl Transforms {
    /// No transform: both matrices the identity.
    pub const IDENTITY: Transforms = Transforms { object_to_world: Mat4::IDENTITY, world_to_object: Mat4::IDENTITY };

    /// `object_to_world` and its inverse.
    pub fn new(object_to_world: Mat4) -> Self {
        Transforms { object_to_world, world_to_object: object_to_world.inverse() }
    }
}

impl Default for Transforms {
    fn default() -> Self {
        Self::IDENTITY
    }
}

/// The state of the program invocation running on this thread: what the
/// semantic values return and where the hit protocol's flags land.
///
/// The CPU backend builds one per program call and runs the program inside
/// [`in_context`]; [`launch_index`](crate::launch_index),
/// [`current_ray`](crate::current_ray) and the other intrinsics read it. Code
/// that calls a program directly (a unit test) gets [`Default`] values, or
/// installs its own.
///
/// The instance's transforms are held by reference (`'t`): the backend
/// points at the matrices where its traversal composed them, rather than
/// copying two `Mat4`s into each program call's context.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExecutionContext<'t> {
    /// The launch index being computed ([`launch_index`](crate::launch_index)).
    pub launch_index: UVec2,
    /// The launch size ([`launch_dim`](crate::launch_dim)).
    pub launch_dim: UVec2,
    /// The slice of a 3D launch being computed
    /// ([`launch_index_3d`](crate::launch_index_3d); 0 in 1D and 2D
    /// launches).
    pub launch_z: u32,
    /// The launch's depth ([`launch_dim_3d`](crate::launch_dim_3d); 1 in
    /// 1D and 2D launches).
    pub launch_depth: u32,
    /// The ray being traced, in the space of the current object: world space
    /// in miss programs, object space in intersection programs
    /// ([`current_ray`](crate::current_ray)).
    pub current_ray: Ray,
    /// Distance of the candidate (any hit) or committed (closest hit)
    /// intersection ([`t_hit`](crate::t_hit)).
    pub t_hit: f32,
    /// The current ray's time ([`current_time`](crate::current_time)).
    pub time: f32,
    /// Primitive being intersected or hit
    /// ([`primitive_index`](crate::primitive_index)).
    pub primitive_index: u32,
    /// The exception being handled, in exception programs
    /// ([`exception_code`](crate::exception_code)).
    pub exception_code: u32,
    /// What the candidate (any hit) or committed (closest hit) hit is: one
    /// of the `HIT_*` values ([`is_triangle_hit`](crate::is_triangle_hit)).
    pub hit_kind: u32,
    /// The `RAY_FLAG_*` bits the current ray was traced with
    /// ([`ray_flags`](crate::ray_flags)).
    pub ray_flags: u32,
    /// The current ray's visibility mask, 8 bits
    /// ([`ray_mask`](crate::ray_mask)).
    pub ray_mask: u32,
    /// The instance of the candidate (any hit, intersection) or committed
    /// (closest hit) hit ([`instance_index`](crate::instance_index)).
    pub instance_index: u32,
    /// Its id ([`instance_id`](crate::instance_id)).
    pub instance_id: u32,
    /// The exception kinds [`raise`](Self::raise) records, as
    /// `rt_abi::constants::exception_kind_bit`s; the others it drops.
    pub exceptions_enabled: u32,
    /// The transforms of the current geometry instance
    /// ([`rt_transform_point`](crate::rt_transform_point) and the other
    /// transform intrinsics).
    pub transforms: &'t Transforms,
    /// Set by [`rt_ignore_intersection`](crate::rt_ignore_intersection): the
    /// any-hit program rejected its candidate.
    pub ignored: bool,
    /// Set by [`rt_terminate_ray`](crate::rt_terminate_ray): the any-hit
    /// program accepted its candidate and ended the search.
    pub terminated: bool,
    /// The first exception raised during this invocation ([`raise`]): by
    /// [`rt_throw`](crate::rt_throw), a buffer access out of bounds, or an
    /// invalid ray passed to [`rt_trace`](crate::rt_trace). Later ones are
    /// dropped.
    pub pending_exception: Option<u32>,
    /// Where the pending exception was raised, when the raiser knows
    /// (integer exceptions: the operator's file, line and column).
    pub pending_location: Option<&'static core::panic::Location<'static>>,
}

impl ExecutionContext<'static> {
    /// The context outside any program invocation: launch index 0 of a 1x1
    /// launch, identity transforms, and a current ray from the origin along
    /// +z over `(0, inf)`, so that
    /// [`rt_potential_intersection`](crate::rt_potential_intersection)
    /// accepts every positive distance.
    pub const DEFAULT: ExecutionContext<'static> = ExecutionContext {
        launch_index: UVec2::ZERO,
        launch_dim: UVec2::ONE,
        launch_z: 0,
        launch_depth: 1,
        current_ray: Ray {
            origin: glam::Vec3::ZERO,
            direction: glam::Vec3::Z,
            ray_type: 0,
            tmin: 0.0,
            tmax: f32::INFINITY,
        },
        t_hit: 0.0,
        time: 0.0,
        primitive_index: 0,
        exception_code: 0,
        hit_kind: HIT_NONE,
        ray_flags: 0,
        ray_mask: 0xff,
        instance_index: 0,
        instance_id: rt_abi::constants::INSTANCE_ID_NONE,
        exceptions_enabled: rt_abi::constants::ALL_EXCEPTION_KINDS,
        transforms: &Transforms::IDENTITY,
        ignored: false,
        terminated: false,
        pending_exception: None,
        pending_location: None,
    };
}

impl<'t> ExecutionContext<'t> {
    /// This context with `transforms` as its instance's transforms.
    pub fn with_transforms<'u>(self, transforms: &'u Transforms) -> ExecutionContext<'u> {
        let ExecutionContext {
            launch_index,
            launch_dim,
            launch_z,
            launch_depth,
            current_ray,
            t_hit,
            time,
            primitive_index,
            exception_code,
            hit_kind,
            ray_flags,
            ray_mask,
            instance_index,
            instance_id,
            exceptions_enabled,
            transforms: _,
            ignored,
            terminated,
            pending_exception,
            pending_location,
        } = self;
        ExecutionContext {
            launch_index,
            launch_dim,
            launch_z,
            launch_depth,
            current_ray,
            t_hit,
            time,
            primitive_index,
            exception_code,
            hit_kind,
            ray_flags,
            ray_mask,
            instance_index,
            instance_id,
            exceptions_enabled,
            transforms,
            ignored,
            terminated,
            pending_exception,
            pending_location,
        }
    }

    /// Records `code` as the pending exception unless one is pending already:
    /// the first exception of an invocation is the one the exception program
    /// sees, as on the GPU.
    pub fn raise(&mut self, code: u32) {
        if self.pending_exception.is_none()
            && self.exceptions_enabled & rt_abi::constants::exception_kind_bit(code) != 0
        {
            self.pending_exception = Some(code);
        }
    }

    /// [`raise`](Self::raise), remembering where.
    pub fn raise_at(&mut self, code: u32, at: &'static core::panic::Location<'static>) {
        if self.pending_exception.is_none()
            && self.exceptions_enabled & rt_abi::constants::exception_kind_bit(code) != 0
        {
            self.pending_exception = Some(code);
            self.pending_location = Some(at);
        }
    }
}

impl Default for ExecutionContext<'_> {
    fn default() -> Self {
        ExecutionContext::DEFAULT
    }
}

/// What the intrinsics that leave the current program need from the backend:
/// tracing a ray, the intersection protocol and debug output.
///
/// The CPU backend implements it and installs it with [`serving`] around
/// its work (or [`with_tracer`] around one program call). Without one (a program called directly) the intrinsics
/// fall back to the behaviour documented on each.
pub trait Tracer {
    /// Traces `ray` against `object`, running intersection, any-hit,
    /// closest-hit and miss programs, which update `payload` (a `&mut P` for
    /// the [`Payload`](crate::Payload) type `P` passed to
    /// [`rt_trace`](crate::rt_trace)). `flags` are `RAY_FLAG_*` bits, `mask`
    /// the visibility mask, `time` the ray's time
    /// ([`current_time`](crate::current_time), finite). The ray has passed
    /// [`Ray::is_valid`].
    ///
    /// The ray comes by reference: the program that traces it has usually
    /// just written its fields, and a by-value copy reads them back in wider
    /// loads than they were stored with, which the CPU cannot forward from
    /// the pending stores (a stall on every trace).
    fn trace(&self, object: Object, ray: &Ray, payload: &mut dyn core::any::Any, flags: u32, mask: u32, time: f32);
    /// [`rt_potential_intersection`](crate::rt_potential_intersection): whether
    /// `t` lies inside the current ray's interval; if so it becomes the
    /// candidate's [`t_hit`](crate::t_hit).
    fn potential_intersection(&self, t: f32) -> bool;
    /// [`rt_report_intersection`](crate::rt_report_intersection): runs any-hit
    /// for the candidate with `material`; returns whether it was accepted.
    /// `attributes` are the intersection program's attributes as they were
    /// at the report (`None` for an intersection program without any).
    fn report_intersection(&self, material: u32, attributes: Option<&dyn AnyAttributes>) -> bool;
    /// [`rt_printf!`](crate::rt_printf) output.
    fn print(&self, text: &str);
    /// Lane-wise execution: [`trace`](Self::trace) for each lane of `mask`
    /// (each with a payload), in that lane's context ([`enter_lane`]); a
    /// backend traces them together where it can. The rays are valid.
    #[allow(clippy::too_many_arguments)]
    fn trace_lanes(
        &self,
        mask: &super::mask::Mask,
        objects: &[Object; super::mask::LANES],
        rays: &[Ray; super::mask::LANES],
        payloads: &mut [Option<&mut dyn core::any::Any>; super::mask::LANES],
        flags: u32,
        ray_mask: u32,
        time: f32,
    ) {
        for l in 0..super::mask::LANES {
            if mask[l]
                && let Some(p) = payloads[l].as_deref_mut()
            {
                enter_lane(l);
                self.trace(objects[l], &rays[l], p, flags, ray_mask, time);
            }
        }
    }
    /// The Rust function of the callable program of id `id` (a
    /// `fn(A, ..) -> R` behind `Any`), for
    /// [`Callable::call`](crate::Callable::call) made by the callable of id
    /// `caller` (0 when a program of another kind calls); `None` when the
    /// id names no callable program of this launch, or the caller's own
    /// program (a callable does not call itself on any backend: WGSL has
    /// no recursion).
    fn callable(&self, id: u32, caller: u32) -> Option<&'static (dyn core::any::Any + Send + Sync)> {
        let _ = (id, caller);
        None
    }
    /// The `#[var]` variables of the callable program of id `id`, bound
    /// to its parameter types once per launch (resolved in the program's
    /// scope, then the context's); `None` when the id names no callable of
    /// this launch with variables.
    fn callable_variables(&self, id: u32) -> Option<&BoundVariables<'_>> {
        let _ = id;
        None
    }
    /// The buffer of bindless id `id`, for
    /// [`BindlessBuffer`](crate::BindlessBuffer): a one-dimensional
    /// [`Buffer<T>`](crate::Buffer) of its elements behind `Any` (an
    /// [`RwBuffer<T>`](crate::RwBuffer) when `writable`); `None` when the id
    /// names no buffer of this launch (or, `writable`, none programs may
    /// write).
    fn buffer(&self, id: u32, writable: bool) -> Option<&(dyn core::any::Any + Send + Sync)> {
        let _ = (id, writable);
        None
    }
    /// The sampler of bindless sampler id `id`, for
    /// [`BindlessSampler`](crate::BindlessSampler): a
    /// [`Sampler2d`](crate::Sampler2d), [`Sampler3d`](crate::Sampler3d) or
    /// [`SamplerCube`](crate::SamplerCube) by the sampler's shape, behind
    /// `Any`; `None` when the id names no sampler of this launch.
    fn sampler(&self, id: u32) -> Option<&(dyn core::any::Any + Send + Sync)> {
        let _ = id;
        None
    }
}

thread_local! {
    // The context outside any installed one: what `context_mut` changes when
    // no program is running (a unit test calling a program directly).
    static ROOT: Cell<ExecutionContext<'static>> = const { Cell::new(ExecutionContext::DEFAULT) };
    // The context of the invocation running now, installed by `in_context`
    // (null: `ROOT`). It points at the caller's `ExecutionContext`, which
    // `in_context` borrows mutably for as long as the pointer is installed,
    // so intrinsics read and write it in place: no copy per program call.
    // Its transforms' lifetime is erased (`'static` here): the context is
    // only lent out under a lifetime its borrower cannot name (`read`,
    // `update`, `context_mut`), so no reference read from it, and none
    // stored in it but `'static` ones, outlives the `in_context` call.
    static CURRENT: Cell<*mut ExecutionContext<'static>> = const { Cell::new(core::ptr::null_mut()) };
    // The contexts of the lane-wise block running now, one per lane, lent
    // by `in_block` as `CURRENT`'s are by `in_context` (null: no block).
    static BLOCK: Cell<*mut ExecutionContext<'static>> = const { Cell::new(core::ptr::null_mut()) };
    // The lane of the block entered last (`enter_lane`). It is left as it
    // is when a block ends, so a backend finds the lane at fault after a
    // panic unwound out of the block.
    static LANE: Cell<usize> = const { Cell::new(0) };
    // The tracer installed by `with_tracer` or `serving`, lifetime erased.
    // Only those store a pointer here, and their guards remove it before the
    // borrow it came from ends, so every pointer read from this cell is live.
    static TRACER: Cell<Option<*const (dyn Tracer + 'static)>> = const { Cell::new(None) };
    // The id of the callable program `Callable::call` is running (0: none),
    // whose variables `__callable_variables` reads.
    static CALLEE: Cell<u32> = const { Cell::new(0) };
}

/// This thread's current execution context, for in-place access.
#[inline]
fn current() -> *mut ExecutionContext<'static> {
    let p = CURRENT.with(Cell::get);
    if p.is_null() { ROOT.with(Cell::as_ptr) } else { p }
}

/// Calls `f` with a copy of this thread's current execution context. The
/// copy's transforms are borrowed for the call only: `f` returns fields,
/// or a context for another invocation with
/// [`ExecutionContext::with_transforms`].
#[inline]
pub fn context<R>(f: impl FnOnce(&ExecutionContext<'_>) -> R) -> R {
    // SAFETY: `current` is live (see `CURRENT`) and only read here; `f`
    // works for every lifetime of the copy's transforms, so it keeps no
    // reference to them.
    let ctx = unsafe { *current() };
    f(&ctx)
}

/// Changes this thread's current execution context through `f`.
///
/// `f` works on a copy that is stored back when it returns, so changes made
/// meanwhile by intrinsics that `f` calls are overwritten: keep `f` to field
/// updates.
pub fn context_mut<R>(f: impl FnOnce(&mut ExecutionContext<'_>) -> R) -> R {
    // SAFETY: as in `read`. `f` works for every lifetime of the copy's
    // transforms, so it can store only `'static` ones or the copy's own.
    let mut ctx = unsafe { *current() };
    let result = f(&mut ctx);
    // SAFETY: as in `context`; no reference into the context is held here.
    unsafe { *current() = ctx };
    result
}

/// Reads this thread's execution context without copying it (the
/// intrinsics' fast path).
pub(crate) fn read<R>(f: impl FnOnce(&ExecutionContext<'_>) -> R) -> R {
    // SAFETY: the context is live (see `CURRENT`); `f` only reads fields and
    // calls nothing that writes the context.
    f(unsafe { &*current() })
}

/// Updates fields of this thread's execution context in place (the
/// intrinsics' fast path for flags).
pub(crate) fn update<R>(f: impl FnOnce(&mut ExecutionContext<'_>) -> R) -> R {
    // SAFETY: as in `read`; `f` only writes fields, so this is the only
    // reference to the context while it runs.
    f(unsafe { &mut *current() })
}

/// The exception raised in the current program call, if any.
#[inline]
pub fn pending_exception() -> Option<u32> {
    read(|c| c.pending_exception)
}

/// Records `code` as the current invocation's pending exception unless one is
/// pending ([`ExecutionContext::raise`]).
#[inline]
pub fn raise(code: u32) {
    update(|ctx| ctx.raise(code));
}

/// [`raise`], remembering where (the caller's caller, through
/// `#[track_caller]`).
#[track_caller]
pub fn raise_here(code: u32) {
    let at = core::panic::Location::caller();
    update(|ctx| ctx.raise_at(code, at));
}

/// Runs `f` with `ctx` as this thread's execution context and no tracer, and
/// returns its result with the context as `f` left it (pending exception,
/// hit flags, ...). The previous context and tracer are restored afterwards,
/// also when `f` panics, so calls nest: a tracer runs the programs of an
/// inner ray inside the outer program's call.
pub fn with_context<'t, R>(ctx: ExecutionContext<'t>, f: impl FnOnce() -> R) -> (R, ExecutionContext<'t>) {
    let mut ctx = ctx;
    let restore = TracerGuard(TRACER.with(|t| t.replace(None)));
    let result = in_context(&mut ctx, f);
    drop(restore);
    (result, ctx)
}

/// Like [`with_context`], with `tracer` serving [`rt_trace`](crate::rt_trace),
/// the intersection protocol and [`rt_printf!`](crate::rt_printf) for the
/// duration of `f`.
pub fn with_tracer<'t, R>(
    ctx: ExecutionContext<'t>,
    tracer: &dyn Tracer,
    f: impl FnOnce() -> R,
) -> (R, ExecutionContext<'t>) {
    let mut ctx = ctx;
    let result = serving(tracer, || in_context(&mut ctx, f));
    (result, ctx)
}

/// Runs `f` with `*ctx` as this thread's execution context, in place:
/// intrinsics that `f` calls read and write `*ctx` itself, so the caller
/// sees the flags and pending exception there when this returns. The tracer
/// stays as it is. The previous context is restored afterwards, also when
/// `f` panics.
///
/// The backend's way to call a program: one context per call, built where
/// it lives, never copied.
pub fn in_context<R>(ctx: &mut ExecutionContext<'_>, f: impl FnOnce() -> R) -> R {
    struct Restore(*mut ExecutionContext<'static>);
    impl Drop for Restore {
        fn drop(&mut self) {
            CURRENT.with(|c| c.set(self.0));
        }
    }
    // The pointer is installed only while `ctx` is mutably borrowed by this
    // call, and removed by the guard before the borrow ends.
    // The transforms' lifetime is erased (see `CURRENT`).
    let ctx: *mut ExecutionContext<'_> = ctx;
    let _restore = Restore(CURRENT.with(|c| c.replace(ctx.cast())));
    f()
}

/// Runs `f` with `contexts` as the execution contexts of a lane-wise
/// block ([`lanes`](super::lanes)), one per lane, lane 0's current;
/// [`enter_lane`] makes another lane's current. Intrinsics read and write
/// the contexts in place, as [`in_context`]'s. The previous context and
/// block are restored afterwards, also when `f` panics.
pub fn in_block<R>(contexts: &mut [ExecutionContext<'_>; LANES], f: impl FnOnce() -> R) -> R {
    struct Restore(*mut ExecutionContext<'static>, *mut ExecutionContext<'static>);
    impl Drop for Restore {
        fn drop(&mut self) {
            CURRENT.with(|c| c.set(self.0));
            BLOCK.with(|b| b.set(self.1));
        }
    }
    // As in `in_context`: installed only while `contexts` is mutably
    // borrowed by this call, removed by the guard before the borrow ends.
    let first: *mut ExecutionContext<'_> = contexts.as_mut_ptr();
    let first = first.cast::<ExecutionContext<'static>>();
    let _restore = Restore(CURRENT.with(|c| c.replace(first)), BLOCK.with(|b| b.replace(first)));
    LANE.with(|l| l.set(0));
    f()
}

/// Makes lane `lane`'s context the current one, inside [`in_block`]
/// (nothing outside a block: a program's lane-wise form called directly
/// runs every lane in the one current context).
#[inline(always)]
pub fn enter_lane(lane: usize) {
    let block = BLOCK.with(Cell::get);
    if !block.is_null() && lane < LANES {
        // SAFETY: `block` points at `in_block`'s `LANES` contexts, live
        // while it is installed; `lane` is in range.
        CURRENT.with(|c| c.set(unsafe { block.add(lane) }));
        LANE.with(|l| l.set(lane));
    }
}

/// The lane [`enter_lane`] entered last (0 before any): the lane running
/// now inside a block, and the one that was running when a panic unwound
/// out of one.
#[inline]
pub fn current_lane() -> usize {
    LANE.with(Cell::get)
}

/// Runs `f` with `tracer` serving [`rt_trace`](crate::rt_trace), the
/// intersection protocol and [`rt_printf!`](crate::rt_printf); the context
/// stays as it is. The previous tracer is restored afterwards, also when `f`
/// panics.
///
/// The backend installs its tracer once per batch of launch indices with
/// this, and each program call's context with [`in_context`].
pub fn serving<R>(tracer: &dyn Tracer, f: impl FnOnce() -> R) -> R {
    let tracer: *const (dyn Tracer + '_) = tracer;
    // SAFETY: only the trait object's lifetime bound changes (same fat-pointer
    // layout). The pointer is dereferenced only while it is installed, which
    // the guard limits to this call, inside the borrow of `tracer`.
    let tracer = unsafe { core::mem::transmute::<*const (dyn Tracer + '_), *const (dyn Tracer + 'static)>(tracer) };
    let _restore = TracerGuard(TRACER.with(|t| t.replace(Some(tracer))));
    f()
}

/// Puts the tracer that was installed back when dropped.
struct TracerGuard(Option<*const (dyn Tracer + 'static)>);

impl Drop for TracerGuard {
    fn drop(&mut self) {
        TRACER.with(|t| t.set(self.0));
    }
}

/// Calls `f` with the installed tracer, or `fallback` when there is none.
pub(crate) fn with_installed_tracer<R>(f: impl FnOnce(&dyn Tracer) -> R, fallback: impl FnOnce() -> R) -> R {
    match TRACER.with(Cell::get) {
        // SAFETY: see `TRACER`: an installed pointer is live until the
        // `with_tracer` call that installed it returns, and that call is
        // still on this thread's stack. The tracer is only borrowed shared.
        Some(tracer) => f(unsafe { &*tracer }),
        None => fallback(),
    }
}

/// Attributes of any `#[rt_attributes]` type, as the CPU backend moves them
/// from intersection programs to hit programs.
pub trait AnyAttributes: core::any::Any + Send {
    /// The value, for downcasting.
    fn as_any(&self) -> &dyn core::any::Any;
    /// The value, for downcasting.
    fn as_any_mut(&mut self) -> &mut dyn core::any::Any;
    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn AnyAttributes>;
    /// Copies `other` into `self` if both are the same type; false otherwise.
    fn copy_from(&mut self, other: &dyn AnyAttributes) -> bool;
    /// Overwrites `self` with the value stored in heap words `words`
    /// ([`RtData::read_words`](crate::RtData::read_words)).
    fn set_words(&mut self, words: &[u32]);
    /// Overwrites `self` with a triangle hit's built-in attributes
    /// ([`Attributes::set_triangle`](crate::Attributes::set_triangle)): the
    /// CPU backend refills a reused value with each triangle hit.
    fn set_triangle(&mut self, t: &TriangleBuiltins);
}

impl<T: crate::Attributes + Send> AnyAttributes for T {
    fn as_any(&self) -> &dyn core::any::Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn core::any::Any {
        self
    }
    fn clone_box(&self) -> Box<dyn AnyAttributes> {
        Box::new(*self)
    }
    fn copy_from(&mut self, other: &dyn AnyAttributes) -> bool {
        match other.as_any().downcast_ref::<T>() {
            Some(o) => {
                *self = *o;
                true
            }
            None => false,
        }
    }
    fn set_words(&mut self, words: &[u32]) {
        self.read_words_into(words);
    }
    fn set_triangle(&mut self, t: &TriangleBuiltins) {
        crate::Attributes::set_triangle(self, t);
    }
}

/// What `rt_report_intersection(m)` becomes in the CPU copy of an
/// intersection program: the macro passes the program's attributes along.
#[doc(hidden)]
pub fn __report_intersection<A: crate::Attributes + Send>(material: u32, attributes: &A) -> bool {
    match TRACER.with(Cell::get) {
        // SAFETY: see `with_tracer`: an installed pointer is live.
        Some(t) => unsafe { (*t).report_intersection(material, Some(attributes)) },
        None => true,
    }
}

/// The Rust function of callable `id` as the installed tracer has it for
/// the running callable, if any, to call (none without a tracer).
pub(crate) fn callable(id: u32) -> Option<&'static (dyn core::any::Any + Send + Sync)> {
    let caller = CALLEE.with(Cell::get);
    with_installed_tracer(|tracer| tracer.callable(id, caller), || None)
}

/// Runs `f`, the Rust function of callable `id`, with `id` as the callee
/// whose variables it reads (the caller's restored afterwards, also when
/// `f` unwinds: a callable may call another).
pub(crate) fn calling<R>(id: u32, f: impl FnOnce() -> R) -> R {
    struct Restore(u32);
    impl Drop for Restore {
        fn drop(&mut self) {
            CALLEE.with(|c| c.set(self.0));
        }
    }
    let _restore = Restore(CALLEE.with(|c| c.replace(id)));
    f()
}

/// Calls `f` with the running callable's `#[var]` variables as the list
/// `L` (the generated shim of a callable with variables). Without them (no
/// launch, or a callable called as a plain Rust function through its
/// `CALLABLE` pointer) it raises
/// [`EXCEPTION_PROGRAM_ID_INVALID`](crate::EXCEPTION_PROGRAM_ID_INVALID) and
/// returns zero.
#[doc(hidden)]
pub fn __callable_variables<L: VariableList, R: Default>(f: impl FnOnce(L) -> R) -> R {
    let id = CALLEE.with(Cell::get);
    let variables = with_installed_tracer(|t| t.callable_variables(id).map(BoundVariables::get::<L>), || None);
    match variables {
        Some(v) => f(v),
        None => {
            raise(crate::EXCEPTION_PROGRAM_ID_INVALID);
            R::default()
        }
    }
}

/// The handle `H` (`Buffer<T>` or `RwBuffer<T>`) of bindless id `id` as
/// the installed tracer has it: `None` without a tracer, for an id of no
/// buffer, or of a buffer of another element type.
pub(crate) fn bindless_buffer<H: Copy + 'static>(id: u32, writable: bool) -> Option<H> {
    with_installed_tracer(|tracer| tracer.buffer(id, writable).and_then(|h| h.downcast_ref::<H>().copied()), || None)
}

/// The sampler `S` of bindless sampler id `id` as the installed tracer
/// has it: `None` without a tracer, for an id of no sampler, or of a
/// sampler of another shape.
pub(crate) fn bindless_sampler<S: Copy + 'static>(id: u32) -> Option<S> {
    with_installed_tracer(|tracer| tracer.sampler(id).and_then(|s| s.downcast_ref::<S>().copied()), || None)
}

/// Sends `rt_printf!` text to the tracer or stdout.
#[doc(hidden)]
pub fn __print(text: &str) {
    with_installed_tracer(|tracer| tracer.print(text), || print!("{text}"))
}
