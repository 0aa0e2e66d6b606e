//! Intrinsics: the semantic values a program reads, the calls that leave the
//! program (tracing, the intersection protocol, exceptions, debug output)
//! and the instance transforms.
//!
//! On the GPU each is a call into the linked megakernel. On the CPU each
//! reads or writes this thread's [`ExecutionContext`](crate::cpu::ExecutionContext)
//! and, for the calls that need the rest of the scene, the
//! [`Tracer`](crate::cpu::Tracer) the backend installed. Without a tracer (a
//! program called directly, say from a unit test) each documents what it
//! does instead.
//!
//! Unlike their OptiX namesakes, [`rt_ignore_intersection`],
//! [`rt_terminate_ray`] and [`rt_throw`] return: they set a flag that takes
//! effect when the program returns, and the code after them still runs, on
//! the GPU too. Write `return` after them to stop there.

use glam::{Mat4, UVec2, UVec3, Vec3};

use crate::cpu::{self, update, with_installed_tracer};
use crate::data::Payload;
use crate::ray::{RAY_FLAG_NONE, RAY_MASK_ALL, Ray};
use crate::scene::{Object, TransformKind};

/// Exception code: `rt_trace` was called at the context's maximum trace
/// depth; the ray was not traced.
#[doc(alias = "RT_EXCEPTION_STACK_OVERFLOW")]
#[doc(alias = "RT_EXCEPTION_TRACE_DEPTH_EXCEEDED")]
pub const EXCEPTION_TRACE_DEPTH_EXCEEDED: u32 = rt_abi::EXCEPTION_TRACE_DEPTH_EXCEEDED;
/// Exception code: a buffer was accessed outside its bounds; loads read
/// zero, stores were dropped.
#[doc(alias = "RT_EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS")]
pub const EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS: u32 = rt_abi::EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS;
/// Exception code: `rt_trace` was given a ray with NaN or infinite origin or
/// direction, or NaN `tmin`/`tmax` (see [`Ray::is_valid`]); it was not
/// traced.
#[doc(alias = "RT_EXCEPTION_INVALID_RAY")]
pub const EXCEPTION_INVALID_RAY: u32 = rt_abi::EXCEPTION_INVALID_RAY;
/// Exception code: integer overflow (`+ - *`, negation, `abs`, a shift by
/// 32 or more, `i32::MIN / -1`). Raised only on the CPU backend with
/// integer exceptions on (`Context::set_integer_exceptions`), a debugging
/// aid OptiX does not have; otherwise the value wraps as on the GPU
/// ([`crate::arith`]). The exception record carries the operator's file
/// and line.
pub const EXCEPTION_INTEGER_OVERFLOW: u32 = rt_abi::EXCEPTION_INTEGER_OVERFLOW;
/// Exception code: integer division or remainder by zero, raised as
/// [`EXCEPTION_INTEGER_OVERFLOW`] is (`x / 0` is `x` and `x % 0` is 0
/// either way).
pub const EXCEPTION_INTEGER_DIVIDE_BY_ZERO: u32 = rt_abi::EXCEPTION_INTEGER_DIVIDE_BY_ZERO;
/// Exception code: a callable program was called through an id that names
/// no callable program of the call's signature (zero, an id the context did
/// not give, or a callable of another signature); the call returned the
/// zero value of its result type.
#[doc(alias = "RT_EXCEPTION_PROGRAM_ID_INVALID")]
pub const EXCEPTION_PROGRAM_ID_INVALID: u32 = rt_abi::EXCEPTION_PROGRAM_ID_INVALID;
/// Exception code: a buffer was read or written through a bindless id
/// ([`BindlessBuffer`](crate::BindlessBuffer)) that names no buffer of the
/// launch (zero, an id the context did not give), a buffer of another
/// element type, or, for an [`RwBindlessBuffer`](crate::RwBindlessBuffer),
/// a buffer programs may not write; the load returned zero, the store was
/// dropped.
#[doc(alias = "RT_EXCEPTION_BUFFER_ID_INVALID")]
pub const EXCEPTION_BUFFER_ID_INVALID: u32 = rt_abi::EXCEPTION_BUFFER_ID_INVALID;
/// Exception code: a texture was sampled through a bindless sampler id
/// ([`BindlessSampler`](crate::BindlessSampler)) that names no sampler of
/// the launch (zero, an id the context did not give) or a sampler of
/// another shape; the read returned zero (size 0).
#[doc(alias = "RT_EXCEPTION_TEXTURE_ID_INVALID")]
pub const EXCEPTION_TEXTURE_ID_INVALID: u32 = rt_abi::EXCEPTION_TEXTURE_ID_INVALID;
/// Exception code: the program panicked, as Rust would: `unwrap`/`expect`
/// met a `None`. The program went on with the zero value; on the CPU backend the
/// record has the file and line. Enabled and disabled with the programs'
/// own codes.
pub const EXCEPTION_PANIC: u32 = rt_abi::EXCEPTION_PANIC;
/// The first exception code free for programs' own [`rt_throw`] codes; the
/// codes below are reserved for the runtime's exceptions.
#[doc(alias = "RT_EXCEPTION_USER")]
pub const EXCEPTION_USER: u32 = rt_abi::EXCEPTION_USER;

/// The launch index being computed: in `[0, launch_dim())`.
#[rt_macros::rt_intrinsic]
#[inline]
pub fn launch_index() -> UVec2 {
    crate::cpu::read(|c| c.launch_index)
}

/// The size of the launch.
#[rt_macros::rt_intrinsic]
#[inline]
pub fn launch_dim() -> UVec2 {
    crate::cpu::read(|c| c.launch_dim)
}

/// The launch index of a 3D launch (`Context::launch_3d`): `x` and `y` as
/// [`launch_index`] gives them, `z` the slice, in `[0, launch_dim_3d())`;
/// `z` is 0 in 1D and 2D launches. (OptiX declares `rtLaunchIndex` as a
/// `uint3` for this; here `launch_index()` keeps its `UVec2`, the first two
/// axes of every launch, and this function adds the third.)
#[rt_macros::rt_intrinsic]
#[inline]
pub fn launch_index_3d() -> UVec3 {
    crate::cpu::read(|c| c.launch_index.extend(c.launch_z))
}

/// The size of a 3D launch: width, height and depth ([`launch_dim`] and
/// the depth; 1 in 1D and 2D launches).
#[rt_macros::rt_intrinsic]
#[inline]
pub fn launch_dim_3d() -> UVec3 {
    crate::cpu::read(|c| c.launch_dim.extend(c.launch_depth))
}

/// The ray being traced, as passed to `rt_trace` but with `tmax` the
/// distance of the closest hit committed so far. In intersection programs
/// (and their any-hit and closest-hit programs) it is in the object space of
/// the current instance; in miss and visit programs, in the space of the
/// node being traversed.
#[rt_macros::rt_intrinsic]
#[inline]
pub fn current_ray() -> Ray {
    crate::cpu::read(|c| c.current_ray)
}

/// The distance along the current ray of the intersection being considered
/// (any hit) or committed (closest hit).
#[rt_macros::rt_intrinsic]
#[inline]
pub fn t_hit() -> f32 {
    crate::cpu::read(|c| c.t_hit)
}

/// The index, within its geometry, of the primitive being intersected or
/// hit.
#[rt_macros::rt_intrinsic]
#[inline]
pub fn primitive_index() -> u32 {
    crate::cpu::read(|c| c.primitive_index)
}

/// The code of the exception being handled: one of the `EXCEPTION_*`
/// constants, or a program's own code from [`rt_throw`].
#[rt_macros::rt_intrinsic]
#[inline]
pub fn exception_code() -> u32 {
    crate::cpu::read(|c| c.exception_code)
}

/// Whether the hit being considered (any hit) or committed (closest hit)
/// is a triangle's, not a custom primitive's.
#[rt_macros::rt_intrinsic]
#[inline]
pub fn is_triangle_hit() -> bool {
    crate::cpu::read(|c| matches!(c.hit_kind, cpu::HIT_TRIANGLE_FRONT | cpu::HIT_TRIANGLE_BACK))
}

/// Whether the hit is a triangle's met on its front: the side from which
/// its vertices run counter-clockwise, in object space (the side that
/// [`RAY_FLAG_CULL_FRONT_FACING`](crate::RAY_FLAG_CULL_FRONT_FACING)
/// culls). False for custom primitives.
#[rt_macros::rt_intrinsic]
#[inline]
pub fn is_triangle_hit_front_face() -> bool {
    crate::cpu::read(|c| c.hit_kind == cpu::HIT_TRIANGLE_FRONT)
}

/// Whether the hit is a triangle's met on its back (see
/// [`is_triangle_hit_front_face`]). False for custom primitives.
#[rt_macros::rt_intrinsic]
#[inline]
pub fn is_triangle_hit_back_face() -> bool {
    crate::cpu::read(|c| c.hit_kind == cpu::HIT_TRIANGLE_BACK)
}

/// The instance the hit being considered (any hit, intersection) or
/// committed (closest hit) is on: its place among the geometry instances
/// the traced node reaches, counted depth first in child order, a geometry
/// instance once for every path down to it. Tracing a group over the same
/// geometry under two transforms therefore gives two indices. Through a
/// geometry group's children in order, a group's or selector's children in
/// order (a selector's every child counts, chosen or not), a transform's
/// child: so the index depends only on the graph below the traced node, the
/// same on every backend and across launches. (OptiX 7's instance index
/// counts the instances of the innermost instance acceleration structure;
/// here every geometry instance reached counts, and nested groups are
/// numbered as one list.) A graph reaching more than `u32::MAX` instances
/// wraps.
#[rt_macros::rt_intrinsic]
#[inline]
pub fn instance_index() -> u32 {
    crate::cpu::read(|c| c.instance_index)
}

/// The id the host gave the instance of the hit
/// ([`instance_index`]) with `Context::set_instance_id`: the geometry
/// instance's own id if it has one, else that of the innermost transform
/// above it on the traced path that has one, else [`INSTANCE_ID_NONE`].
#[rt_macros::rt_intrinsic]
#[inline]
pub fn instance_id() -> u32 {
    crate::cpu::read(|c| c.instance_id)
}

/// What [`instance_id`] returns when no id was set on the instance's
/// geometry instance or on a transform above it (`u32::MAX`); setting it
/// clears an id.
pub const INSTANCE_ID_NONE: u32 = rt_abi::INSTANCE_ID_NONE;

/// The `RAY_FLAG_*` bits the current ray was traced with
/// ([`rt_trace_with`]; [`RAY_FLAG_NONE`] for [`rt_trace`]).
#[rt_macros::rt_intrinsic]
#[inline]
pub fn ray_flags() -> u32 {
    crate::cpu::read(|c| c.ray_flags)
}

/// The current ray's visibility mask: the low 8 bits of the mask it was
/// traced with ([`RAY_MASK_ALL`] for [`rt_trace`]).
#[rt_macros::rt_intrinsic]
#[inline]
pub fn ray_mask() -> u32 {
    crate::cpu::read(|c| c.ray_mask)
}

/// Traces `ray` against `object` with payload `prd`: runs the intersection,
/// any-hit and closest-hit programs of what it hits, or the miss program of
/// its ray type, which update `prd`. Same as [`rt_trace_with`] with
/// [`RAY_FLAG_NONE`] and [`RAY_MASK_ALL`].
#[rt_macros::rt_intrinsic]
pub fn rt_trace<P: Payload>(object: Object, ray: Ray, prd: &mut P) {
    rt_trace_with(object, ray, prd, RAY_FLAG_NONE, RAY_MASK_ALL)
}

/// [`rt_trace`] with `RAY_FLAG_*` bits `flags` and visibility mask `mask`
/// (an instance is traversed when its mask shares a bit with it).
///
/// An invalid ray ([`Ray::is_valid`]) raises [`EXCEPTION_INVALID_RAY`] and is
/// not traced; `prd` is left as it is. Without a tracer, `prd` is also left
/// as it is.
#[rt_macros::rt_intrinsic]
pub fn rt_trace_with<P: Payload>(object: Object, ray: Ray, prd: &mut P, flags: u32, mask: u32) {
    if !ray.is_valid() {
        cpu::raise(EXCEPTION_INVALID_RAY);
        return;
    }
    trace_valid(object, &ray, prd, flags, mask, 0.0)
}

/// [`rt_trace_with`] at ray time `time` (OptiX 6's `rtTrace(.., time)`, OptiX
/// 7's `rayTime`): motion transforms are intersected as they are at `time`
/// (clamped to their time range), and the programs the trace runs read it
/// with [`current_time`]. A trace without a
/// time ([`rt_trace`], [`rt_trace_with`]) is at time 0; a trace from a
/// closest-hit or miss program does not inherit its ray's time: pass
/// [`current_time`] to keep it.
///
/// An invalid ray ([`Ray::is_valid`]) raises [`EXCEPTION_INVALID_RAY`] and is
/// not traced; a time that is not finite is traced at time 0.
#[rt_macros::rt_intrinsic]
pub fn rt_trace_at<P: Payload>(object: Object, ray: Ray, prd: &mut P, flags: u32, mask: u32, time: f32) {
    if !ray.is_valid() {
        cpu::raise(EXCEPTION_INVALID_RAY);
        return;
    }
    let time = if time.is_finite() { time } else { 0.0 };
    trace_valid(object, &ray, prd, flags, mask, time)
}

/// [`rt_trace_at`] for a ray that has passed [`Ray::is_valid`], at a finite
/// time: [`rt_trace_with`] checked the ray already.
#[inline(always)]
fn trace_valid<P: Payload>(object: Object, ray: &Ray, prd: &mut P, flags: u32, mask: u32, time: f32) {
    with_installed_tracer(|tracer| tracer.trace(object, ray, prd, flags, mask, time), || ())
}

/// The current ray's time: what [`rt_trace_at`] traced it with (0 for
/// [`rt_trace`] and [`rt_trace_with`]).
#[rt_macros::rt_intrinsic]
#[inline]
pub fn current_time() -> f32 {
    crate::cpu::read(|c| c.time)
}

/// Whether distance `t` lies inside the current ray's open interval
/// `(tmin, tmax)`, with `tmax` the closest hit so far: call it before
/// writing attributes, and report the intersection only if it returns true.
/// An accepted `t` becomes the candidate's [`t_hit`].
///
/// Without a tracer: `t > tmin && t < tmax` of the context's current ray,
/// also setting the context's `t_hit` when true.
#[rt_macros::rt_intrinsic]
pub fn rt_potential_intersection(t: f32) -> bool {
    with_installed_tracer(
        |tracer| tracer.potential_intersection(t),
        || {
            update(|ctx| {
                let accepted = t > ctx.current_ray.tmin && t < ctx.current_ray.tmax;
                if accepted {
                    ctx.t_hit = t;
                }
                accepted
            })
        },
    )
}

/// Reports the intersection accepted by the last
/// [`rt_potential_intersection`], with material index `material` (of the
/// geometry instance), and the attributes written since: runs the
/// material's any-hit program. Returns whether the intersection was
/// accepted (not ignored); if so it becomes the closest hit so far.
///
/// Without a tracer: returns true and records nothing.
#[rt_macros::rt_intrinsic]
pub fn rt_report_intersection(material: u32) -> bool {
    with_installed_tracer(|tracer| tracer.report_intersection(material, None), || true)
}

/// Rejects the current candidate intersection: when the any-hit program
/// returns, the search goes on as if it had not been reported. Returns (see
/// the [module docs](self)).
#[rt_macros::rt_intrinsic]
pub fn rt_ignore_intersection() {
    update(|ctx| ctx.ignored = true);
}

/// Accepts the current candidate intersection and ends the search: when the
/// any-hit program returns, it becomes the committed hit and closest hit
/// runs. Returns (see the [module docs](self)).
#[rt_macros::rt_intrinsic]
pub fn rt_terminate_ray() {
    update(|ctx| ctx.terminated = true);
}

/// Raises exception `code`: when the program returns, the launch index's
/// work stops and the exception program runs with
/// [`exception_code`]` == code`. Only the first exception of a program
/// invocation counts. Use codes from [`EXCEPTION_USER`] up: smaller codes
/// are reserved for the runtime's exceptions (a smaller code is still
/// recorded as given, and the exception program cannot tell it from the
/// runtime's). Returns (see the [module docs](self)).
#[rt_macros::rt_intrinsic]
pub fn rt_throw(code: u32) {
    cpu::raise(code);
}

#[inline]
fn transform(kind: TransformKind) -> Mat4 {
    cpu::read(|ctx| match kind {
        TransformKind::ObjectToWorld => ctx.transforms.object_to_world,
        TransformKind::WorldToObject => ctx.transforms.world_to_object,
    })
}

/// Transforms point `p` between the current instance's object space and
/// world space: `(M * vec4(p, 1)).xyz` with `M` the transform `kind` names
/// (affine: no division by `w`).
#[rt_macros::rt_intrinsic]
pub fn rt_transform_point(kind: TransformKind, p: Vec3) -> Vec3 {
    (transform(kind) * p.extend(1.0)).truncate()
}

/// Transforms direction `v` between the current instance's object space
/// and world space: `(M * vec4(v, 0)).xyz` with `M` the transform `kind`
/// names. The result is not normalised.
#[rt_macros::rt_intrinsic]
pub fn rt_transform_vector(kind: TransformKind, v: Vec3) -> Vec3 {
    (transform(kind) * v.extend(0.0)).truncate()
}

/// Transforms normal `n` between the current instance's object space and
/// world space, by the inverse transpose so that it stays perpendicular to
/// the surface: `(transpose(W) * vec4(n, 0)).xyz` where `W` is the *other*
/// transform (world-to-object for [`ObjectToWorld`](TransformKind::ObjectToWorld)).
/// The result is not normalised.
#[rt_macros::rt_intrinsic]
pub fn rt_transform_normal(kind: TransformKind, n: Vec3) -> Vec3 {
    let inverse = match kind {
        TransformKind::ObjectToWorld => TransformKind::WorldToObject,
        TransformKind::WorldToObject => TransformKind::ObjectToWorld,
    };
    (transform(inverse).transpose() * n.extend(0.0)).truncate()
}

/// The current instance's transform that `kind` names, as a matrix: the
/// product of the transforms above the geometry instance being hit (or
/// intersected) for [`ObjectToWorld`](TransformKind::ObjectToWorld), its
/// inverse for [`WorldToObject`](TransformKind::WorldToObject). The
/// identity where no transform is above it, or without a tracer.
#[rt_macros::rt_intrinsic]
pub fn rt_get_transform(kind: TransformKind) -> Mat4 {
    transform(kind)
}

/// Prints formatted text for debugging, like `print!`: `{}` placeholders
/// formatted with `Display` (glam vectors print as `[x, y, z]`). No newline
/// is added. The text goes to the backend's tracer, or to stdout when there
/// is none.
///
/// ```
/// use rt_std::prelude::*;
///
/// rt_printf!("launch index {} sees {}\n", launch_index(), vec3(0.0, 1.0, 0.5));
/// ```
///
/// Program kinds: all.
#[doc(alias = "rtPrintf")]
#[macro_export]
macro_rules! rt_printf {
    ($($arg:tt)*) => {
        $crate::cpu::__print(&::std::format!($($arg)*))
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::{ExecutionContext, Tracer, Transforms, context, with_context, with_tracer};
    use core::any::Any;
    use core::cell::RefCell;
    use glam::Vec4;

    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    struct Prd {
        value: f32,
    }
    impl crate::RtData for Prd {
        const LAYOUT: crate::program::TypeLayout = f32::LAYOUT;
        fn write_words(&self, out: &mut [u32]) {
            self.value.write_words(out)
        }
        fn read_words(words: &[u32]) -> Self {
            Prd { value: f32::read_words(words) }
        }
    }
    impl Payload for Prd {}

    #[test]
    fn semantic_values_read_the_context() {
        let ctx = ExecutionContext {
            launch_index: UVec2::new(3, 4),
            launch_dim: UVec2::new(640, 480),
            t_hit: 2.5,
            primitive_index: 17,
            exception_code: EXCEPTION_USER + 1,
            ..ExecutionContext::default()
        };
        let (seen, _) = with_context(ctx, || {
            (launch_index(), launch_dim(), current_ray(), t_hit(), primitive_index(), exception_code())
        });
        assert_eq!(seen, (ctx.launch_index, ctx.launch_dim, ctx.current_ray, 2.5, 17, EXCEPTION_USER + 1));
        // Restored afterwards.
        assert_eq!(launch_index(), UVec2::ZERO);
    }

    #[test]
    fn potential_intersection_without_tracer_uses_the_current_ray() {
        // Outside any context: the default ray accepts (0, inf).
        assert!(rt_potential_intersection(1e20));
        assert!(!rt_potential_intersection(0.0));
        assert!(!rt_potential_intersection(-1.0));
        assert!(!rt_potential_intersection(f32::NAN));

        let ray = Ray::new(Vec3::ZERO, Vec3::X, 0, 0.5, 2.0);
        let ctx = ExecutionContext { current_ray: ray, ..ExecutionContext::default() };
        let (results, after) =
            with_context(ctx, || [0.5, 0.50001, 1.0, 1.99999, 2.0, 3.0].map(rt_potential_intersection));
        assert_eq!(results, [false, true, true, true, false, false]);
        assert_eq!(after.t_hit, 1.99999, "the last accepted t");
        assert!(with_context(ctx, || rt_report_intersection(3)).0);
    }

    #[test]
    fn hit_flags_and_exceptions() {
        let ((), ctx) = with_context(ExecutionContext::default(), || {
            rt_ignore_intersection();
            rt_terminate_ray();
            rt_throw(EXCEPTION_USER + 5);
            rt_throw(EXCEPTION_USER + 6);
        });
        assert!(ctx.ignored && ctx.terminated);
        assert_eq!(ctx.pending_exception, Some(EXCEPTION_USER + 5));
        // A reserved code is recorded as given.
        let ((), ctx) = with_context(ExecutionContext::default(), || rt_throw(1));
        assert_eq!(ctx.pending_exception, Some(1));
    }

    #[test]
    fn transform_normal_uses_the_inverse_transpose() {
        // Non-uniform scale: x stretched by 4. The plane x + y = 1 has object
        // normal (1, 1, 0); after scaling, its points satisfy x/4 + y = 1,
        // whose normal is (1/4, 1, 0).
        let o2w = Mat4::from_scale(Vec3::new(4.0, 1.0, 1.0)) * Mat4::from_translation(Vec3::new(0.0, 0.0, 2.0));
        let transforms = Transforms { object_to_world: o2w, world_to_object: o2w.inverse() };
        let ctx = ExecutionContext { transforms: &transforms, ..Default::default() };
        let (r, _) = with_context(ctx, || {
            (
                rt_transform_normal(TransformKind::ObjectToWorld, Vec3::new(1.0, 1.0, 0.0)),
                rt_transform_normal(TransformKind::WorldToObject, Vec3::new(0.25, 1.0, 0.0)),
                rt_transform_vector(TransformKind::ObjectToWorld, Vec3::new(1.0, 1.0, 0.0)),
                rt_transform_point(TransformKind::ObjectToWorld, Vec3::new(1.0, 0.0, 0.0)),
                rt_transform_point(TransformKind::WorldToObject, Vec3::new(4.0, 0.0, 2.0)),
            )
        });
        assert_eq!(r.0, Vec3::new(0.25, 1.0, 0.0));
        assert_eq!(r.1, Vec3::new(1.0, 1.0, 0.0));
        // The transformed normal stays perpendicular to transformed tangents.
        let tangent = rt_transform_vector_with(o2w, Vec3::new(1.0, -1.0, 0.0));
        assert_eq!(r.0.dot(tangent), 0.0);
        assert_eq!(r.2, Vec3::new(4.0, 1.0, 0.0), "vectors ignore translation");
        assert_eq!(r.3, Vec3::new(4.0, 0.0, 2.0));
        assert_eq!(r.4, Vec3::new(1.0, 0.0, 0.0));
    }

    fn rt_transform_vector_with(m: Mat4, v: Vec3) -> Vec3 {
        let transforms = Transforms { object_to_world: m, ..Transforms::IDENTITY };
        let ctx = ExecutionContext { transforms: &transforms, ..Default::default() };
        with_context(ctx, || rt_transform_vector(TransformKind::ObjectToWorld, v)).0
    }

    #[test]
    fn trace_without_tracer_leaves_the_payload() {
        let mut prd = Prd { value: 3.0 };
        let ((), ctx) = with_context(ExecutionContext::default(), || {
            rt_trace(Object::new(0), Ray::new(Vec3::ZERO, Vec3::Z, 0, 0.0, f32::INFINITY), &mut prd)
        });
        assert_eq!(prd.value, 3.0);
        assert_eq!(ctx.pending_exception, None);
    }

    /// Records what reaches it and answers like a scene with one hit at 1.
    #[derive(Default)]
    struct Recorder {
        log: RefCell<Vec<String>>,
    }

    impl Tracer for Recorder {
        fn trace(&self, object: Object, ray: &Ray, payload: &mut dyn Any, flags: u32, mask: u32, time: f32) {
            let at = if time == 0.0 { String::new() } else { format!(" at {time}") };
            self.log.borrow_mut().push(format!("trace {} {} {flags} {mask:#x}{at}", object.id, ray.ray_type));
            // Run a "closest hit" in a nested context, as a backend would.
            let inner = context(|c| ExecutionContext { t_hit: 1.0, ..c.with_transforms(&Transforms::IDENTITY) });
            let (t, _) = with_tracer(inner, self, t_hit);
            payload.downcast_mut::<Prd>().unwrap().value = t;
        }
        fn potential_intersection(&self, t: f32) -> bool {
            t < 1.0
        }
        fn report_intersection(&self, material: u32, _attributes: Option<&dyn crate::cpu::AnyAttributes>) -> bool {
            self.log.borrow_mut().push(format!("report {material}"));
            false
        }
        fn print(&self, text: &str) {
            self.log.borrow_mut().push(text.to_owned());
        }
    }

    #[test]
    fn installed_tracer_serves_the_intrinsics() {
        let tracer = Recorder::default();
        let ctx = ExecutionContext { t_hit: 9.0, ..Default::default() };
        let mut prd = Prd::default();
        let (r, after) = with_tracer(ctx, &tracer, || {
            let ray = Ray::new(Vec3::ZERO, Vec3::Z, 1, 0.0, 10.0);
            rt_trace_with(Object::new(7), ray, &mut prd, RAY_FLAG_NONE | crate::RAY_FLAG_DISABLE_ANYHIT, 0x3);
            rt_trace(Object::new(7), Ray { origin: Vec3::splat(f32::NAN), ..ray }, &mut prd);
            rt_printf!("v = {} {}\n", prd.value, Vec4::ONE);
            (rt_potential_intersection(0.5), rt_potential_intersection(2.0), rt_report_intersection(4), t_hit())
        });
        assert_eq!(r, (true, false, false, 9.0), "the nested context is gone");
        assert_eq!(prd.value, 1.0);
        assert_eq!(after.pending_exception, Some(EXCEPTION_INVALID_RAY));
        assert_eq!(*tracer.log.borrow(), ["trace 7 1 2 0x3", "v = 1 [1, 1, 1, 1]\n", "report 4"]);
        // Uninstalled afterwards.
        assert!(rt_report_intersection(0));
    }

    #[test]
    fn a_trace_passes_its_time_and_a_non_finite_time_as_zero() {
        let tracer = Recorder::default();
        let mut prd = Prd::default();
        let ((), _) = with_tracer(ExecutionContext::default(), &tracer, || {
            let ray = Ray::new(Vec3::ZERO, Vec3::Z, 0, 0.0, 10.0);
            rt_trace_at(Object::new(1), ray, &mut prd, RAY_FLAG_NONE, RAY_MASK_ALL, 0.25);
            rt_trace_at(Object::new(2), ray, &mut prd, RAY_FLAG_NONE, RAY_MASK_ALL, f32::NAN);
            rt_trace(Object::new(3), ray, &mut prd);
        });
        assert_eq!(*tracer.log.borrow(), ["trace 1 0 0 0xff at 0.25", "trace 2 0 0 0xff", "trace 3 0 0 0xff"]);
        let ctx = ExecutionContext { time: 0.75, ..Default::default() };
        assert_eq!(with_context(ctx, current_time).0, 0.75);
    }

    #[test]
    fn context_is_restored_after_a_panic() {
        let ctx = ExecutionContext { launch_index: UVec2::new(5, 5), ..Default::default() };
        let caught = std::panic::catch_unwind(|| with_context(ctx, || panic!("program failed")));
        assert!(caught.is_err());
        assert_eq!(launch_index(), UVec2::ZERO);
    }
}
