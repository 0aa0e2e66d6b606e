//! A lane: one thread's run over launch indices, the state a launch index's
//! programs share (the current search, attributes for reuse, the first
//! exception) and how a program is invoked. Its search through the scene
//! is `traverse.rs`; the intrinsics it serves as rt-std's `Tracer`,
//! `tracer.rs`.

use super::super::{ExceptionRecord, LaunchReport};
use super::bind::{AttributeType, Linked, Program};
use crate::accel::wide::isa::Isa;
use crate::link;
use crate::link::instances::InstancePath;
use crate::scene::NodeId;
use glam::{UVec2, Vec2, Vec3};
use rt_std::cpu::{AnyAttributes, CpuArgs, CpuResult, ExecutionContext, Transforms, TriangleBuiltins};
use rt_std::program::TypeLayout;
use rt_std::*;
use std::any::{Any, TypeId};
use std::cell::{Cell, RefCell};

/// Sets `ctx`'s current ray to `ray` with `tmax`, field by field.
///
/// Built as a whole `Ray` first, the value went through a temporary in
/// stores of 4 and 8 bytes and was copied on in 16-byte loads, which the CPU
/// cannot forward from those stores: a stall per program call.
#[inline(always)]
pub(crate) fn set_current_ray(ctx: &mut ExecutionContext<'_>, ray: &Ray, tmax: f32) {
    let r = &mut ctx.current_ray;
    r.origin = ray.origin;
    r.direction = ray.direction;
    r.ray_type = ray.ray_type;
    r.tmin = ray.tmin;
    r.tmax = tmax;
}

/// The closest hit so far of a search.
#[derive(Clone, Copy)]
pub(crate) struct Hit {
    pub(crate) instance: u32,
    pub(crate) material: u32,
    pub(crate) primitive: u32,
    pub(crate) t: f32,
    /// Weights of vertices 1 and 2 (triangles; the custom attributes are in
    /// [`Search::attributes`]).
    pub(crate) barycentrics: Vec2,
    /// The triangle's vertices (triangles).
    pub(crate) vertices: [Vec3; 3],
    /// The instance's transforms (None: identity).
    pub(crate) xf: Option<Xf>,
    /// The path the search reached the hit's geometry group by, and the
    /// group ([`instances::resolve`]).
    pub(crate) path: (InstancePath, NodeId),
}

/// The transforms of a node being traversed: the product of the transform
/// nodes above it. Traversal passes `None` where there are none, so the
/// usual scene (geometry not under a transform) neither transforms its rays
/// nor copies matrices into each hit.
pub(crate) type Xf = Transforms;

/// The transforms of a node with matrices `own` under the transforms
/// `outer` of the nodes above it.
#[inline]
pub(crate) fn under(outer: &Xf, own: &Xf) -> Xf {
    Xf {
        object_to_world: outer.object_to_world * own.object_to_world,
        world_to_object: own.world_to_object * outer.world_to_object,
    }
}

/// Points `ctx` at `xf`'s transforms; `ctx` holds the identity already (a
/// context from [`Lane::context`]): nothing to do for None. The matrices
/// are not copied: the context borrows them where the traversal (or the
/// committed hit) holds them.
#[inline(always)]
pub(crate) fn set_transforms<'x>(ctx: &mut ExecutionContext<'x>, xf: Option<&'x Xf>) {
    if let Some(x) = xf {
        ctx.transforms = x;
    }
}

/// The intersection program running now, for the protocol callbacks.
#[derive(Clone, Copy)]
pub(crate) struct Candidate {
    pub(crate) instance: u32,
    pub(crate) primitive: u32,
    pub(crate) object_ray: Ray,
    pub(crate) xf: Option<Xf>,
}

/// One ray's search. It lives in `trace`'s frame; the lane points at it
/// while the traversal runs, so the protocol callbacks find it.
pub(crate) struct Search<'r> {
    pub(crate) ray_type: u32,
    pub(crate) flags: u32,
    /// The ray's visibility mask (8 bits).
    pub(crate) mask: u32,
    /// The traced ray, where the tracing program built it (read field by
    /// field: see [`Tracer::trace`]).
    pub(crate) world_ray: &'r Ray,
    pub(crate) payload: *mut dyn Any,
    /// Closest accepted distance so far.
    pub(crate) tmax: Cell<f32>,
    pub(crate) done: Cell<bool>,
    pub(crate) committed: Cell<Option<Hit>>,
    /// The committed hit's attributes, for custom primitives.
    pub(crate) attributes: RefCell<Option<Box<dyn AnyAttributes>>>,
    pub(crate) candidate: Cell<Option<Candidate>>,
    /// The distance `rt_potential_intersection` accepted for the candidate.
    pub(crate) candidate_t: Cell<Option<f32>>,
    /// The geometry group being searched and the path to it.
    pub(crate) group: Cell<(InstancePath, NodeId)>,
}

/// A launch index's first exception: its code, and where it was raised
/// when the raiser said (integer exceptions).
pub(crate) type FirstException = (u32, Option<&'static std::panic::Location<'static>>);

/// One worker's state over a chunk of launch indices; also rt-std's
/// [`Tracer`] for the programs it runs.
pub(crate) struct Lane<'a> {
    pub(crate) l: &'a Linked<'a, Program<'a>>,
    pub(crate) index: Cell<UVec2>,
    pub(crate) depth: Cell<u32>,
    /// The launch index's first exception.
    pub(crate) exception: Cell<Option<FirstException>>,
    /// The innermost program running (left as it was when a panic unwinds
    /// past `invoke`: the program that panicked).
    pub(crate) program: Cell<Option<&'static rt_std::program::ProgramDescriptor>>,
    pub(crate) prints: RefCell<Vec<String>>,
    pub(crate) rays: Cell<u64>,
    /// The innermost search in progress (null: none).
    pub(crate) search: Cell<*const Search<'static>>,
    /// Attribute values not in use, by type, for reuse.
    pub(crate) pool: RefCell<Vec<(TypeId, Box<dyn AnyAttributes>)>>,
    /// The instruction set geometry groups' trees are walked on.
    pub(crate) isa: Isa,
    /// The time of the ray being traced (`current_time()`; 0 in the ray
    /// generation and exception programs).
    pub(crate) time: Cell<f32>,
    /// The context every program call starts from (the launch's size and
    /// the exceptions enabled; identity transforms), built once per lane: a
    /// call copies it and writes only its own fields, rather than building
    /// the whole context (and copying it again) each time.
    pub(crate) base: ExecutionContext<'static>,
    /// The launch index as programs see it, and its 3D launch's slice
    /// (`launch_index`, `launch_z`), set per index by `run_index`.
    pub(crate) launch: Cell<(UVec2, u32)>,
    /// The lanes of the block running lane-wise (`block.rs`).
    pub(crate) block: Block,
}

impl<'a> Lane<'a> {
    pub(crate) fn new(l: &'a Linked<'a, Program<'a>>) -> Self {
        Lane {
            l,
            index: Cell::new(UVec2::ZERO),
            depth: Cell::new(0),
            exception: Cell::new(None),
            program: Cell::new(None),
            prints: RefCell::new(Vec::new()),
            rays: Cell::new(0),
            search: Cell::new(std::ptr::null()),
            pool: RefCell::new(Vec::new()),
            isa: Isa::current(),
            time: Cell::new(0.0),
            base: ExecutionContext {
                launch_dim: l.launch_dim,
                launch_depth: l.launch_depth,
                exceptions_enabled: l.settings.exceptions,
                ..ExecutionContext::DEFAULT
            },
            launch: Cell::new((UVec2::ZERO, 0)),
            block: Block { loaded: Cell::new(usize::MAX), ..Default::default() },
        }
    }

    pub(crate) fn run_index(&self, index: UVec2, report: &mut LaunchReport) {
        let l = self.l;
        self.index.set(index);
        self.depth.set(0);
        self.exception.set(None);
        self.program.set(None);
        self.rays.set(0);
        self.time.set(0.0);
        self.launch.set(self.launch_index());
        let mut ctx = self.context();
        self.invoke(&l.ray_generation, &mut ctx, None, None);
        report.rays += self.rays.get();
        self.finish_index(index, report);
    }

    /// The end of a launch index's run: its exception recorded and handled
    /// (the exception program, or the default's magenta), its prints kept.
    pub(crate) fn finish_index(&self, index: UVec2, report: &mut LaunchReport) {
        let l = self.l;
        if let Some((code, location)) = self.exception.get() {
            report.exceptions.push(ExceptionRecord { launch_index: index, code, location });
            if let Some(ex) = &l.exception {
                let mut ctx = self.context();
                ctx.exception_code = code;
                self.invoke(ex, &mut ctx, None, None);
            } else if let Some(v) = link::default_exception_output(l.ray_generation.desc)
                && let Some(out) = l.ray_generation.call.vars[v].downcast_ref::<RwBuffer2d<glam::Vec4>>()
            {
                // The default exception program: magenta at the launch index.
                let size = out.size();
                if index.x < size.x && index.y < size.y {
                    out.store(index, link::EXCEPTION_COLOR);
                }
            }
        }
        if !self.prints.borrow().is_empty() {
            report.prints.extend(self.prints.take().into_iter().map(|t| (index, t)));
        }
    }

    /// The context of a program call: the lane's base context at the
    /// launch index and the current ray's time, for the caller to write
    /// its fields into.
    #[inline(always)]
    pub(crate) fn context(&self) -> ExecutionContext<'static> {
        let mut ctx = self.base;
        (ctx.launch_index, ctx.launch_z) = self.launch.get();
        ctx.time = self.time.get();
        ctx
    }

    /// The launch index and slice programs see at grid index `index` (see
    /// [`Lane::launch`]).
    pub(crate) fn launch_index(&self) -> (UVec2, u32) {
        // The index goes in as one 8-byte store. Built from two `u32`s, LLVM
        // stores it as two 4-byte halves, and the 8-byte load of the
        // program's `launch_index()` just after cannot be forwarded from two
        // pending stores: it stalls until they reach the cache (about 4% of
        // a primary + AO launch on the bunny). `black_box` keeps the packed
        // value whole.
        let mut index = self.index.get();
        let (mut launch_z, launch_depth) = (0, self.l.launch_depth);
        if launch_depth > 1 {
            // A 3D launch's grid runs over its slices' rows in turn.
            let h = self.l.launch_dim.y;
            (index.y, launch_z) = (index.y % h, index.y / h);
        }
        let bits = std::hint::black_box(index.x as u64 | (index.y as u64) << 32);
        (UVec2::new(bits as u32, (bits >> 32) as u32), launch_z)
    }

    /// The search in progress. Only called inside one (during `traverse`).
    pub(crate) fn search(&self) -> &Search<'_> {
        // SAFETY: `trace` points `search` at a `Search` in its own frame for
        // the duration of its traversal and restores the outer pointer
        // before that frame ends; the search is only used through `&`.
        unsafe { &*self.search.get() }
    }

    /// Calls a program in context `ctx`; the first exception it raises is
    /// kept for the lane. `ctx` holds the flags the program set, and the
    /// primitive index the program gets.
    ///
    /// Six arguments, all in registers: the attributes come as a thin
    /// pointer and the primitive in `ctx`. As a seventh and eighth, the
    /// attributes' fat pointer went on the stack in two 8-byte stores and
    /// came back as one 16-byte load, a store-forwarding stall per call.
    pub(crate) fn invoke(
        &self,
        p: &Program<'_>,
        ctx: &mut ExecutionContext<'_>,
        payload: Option<&mut dyn Any>,
        attributes: Option<&mut Box<dyn AnyAttributes>>,
    ) -> CpuResult {
        let attributes = attributes.map(|a| a.as_any_mut());
        let mut args = CpuArgs { payload, attributes, primitive: ctx.primitive_index, variables: &p.vars };
        let outer = self.program.replace(Some(p.desc));
        let r = rt_std::cpu::in_context(ctx, || (p.desc.cpu)(&mut args));
        self.program.set(outer);
        if let Some(code) = ctx.pending_exception
            && self.exception.get().is_none()
        {
            self.exception.set(Some((code, ctx.pending_location)));
        }
        r
    }

    /// An attribute value of type `id` from the pool, or `make`'s.
    pub(crate) fn take_attributes(
        &self,
        id: TypeId,
        make: impl FnOnce() -> Box<dyn AnyAttributes>,
    ) -> Box<dyn AnyAttributes> {
        let mut pool = self.pool.borrow_mut();
        match pool.iter().position(|(t, _)| *t == id) {
            Some(i) => pool.swap_remove(i).1,
            None => make(),
        }
    }

    pub(crate) fn return_attributes(&self, a: Box<dyn AnyAttributes>) {
        self.pool.borrow_mut().push((Any::type_id(a.as_any()), a));
    }

    /// An attribute value of type `ty`, holding `hit`'s triangle attributes
    /// (or zero).
    pub(crate) fn attributes_of(&self, ty: &AttributeType, hit: Option<&TriangleBuiltins>) -> Box<dyn AnyAttributes> {
        let mut a = self.take_attributes(ty.id, || (ty.make)(&vec![0; ty.words]));
        match hit {
            Some(h) => a.set_triangle(h),
            None => ty.with_zero_words(|w| a.set_words(w)),
        }
        a
    }

    /// An attribute value holding a copy of `value`.
    pub(crate) fn copy_of(&self, value: &dyn AnyAttributes) -> Box<dyn AnyAttributes> {
        let mut a = self.take_attributes(Any::type_id(value.as_any()), || value.clone_box());
        a.copy_from(value);
        a
    }
}

/// Attributes of an intersection program that declares none.
#[derive(Clone, Copy, Default, Debug, PartialEq)]
pub(crate) struct NoAttributes;

impl RtData for NoAttributes {
    const LAYOUT: TypeLayout =
        TypeLayout { kind: rt_std::program::LayoutKind::Unit, rust: "()", wgsl: "", words: 0, fields: &[] };
    fn write_words(&self, _: &mut [u32]) {}
    fn read_words(_: &[u32]) -> Self {
        NoAttributes
    }
}

impl rt_std::Attributes for NoAttributes {}

/// The running block's launch indices, each one's own state, and which
/// lane's state the lane holds now (`block.rs`). Kept field by field, so
/// switching lanes copies only what a lane's programs change.
#[derive(Default)]
pub(crate) struct Block {
    /// Whether a block is running.
    pub(crate) active: Cell<bool>,
    /// The block lane whose state `index`, `launch`, `exception` and
    /// `prints` hold (`usize::MAX`: none).
    pub(crate) loaded: Cell<usize>,
    /// Each lane's grid index (what reports name).
    pub(crate) indices: [Cell<UVec2>; rt_std::cpu::lanes::LANES],
    /// Each lane's launch index and slice as programs see them
    /// ([`Lane::launch`]).
    pub(crate) launches: [Cell<(UVec2, u32)>; rt_std::cpu::lanes::LANES],
    /// Each lane's first exception of a program its traces ran.
    pub(crate) exceptions: [Cell<Option<FirstException>>; rt_std::cpu::lanes::LANES],
    /// Each lane's prints.
    pub(crate) prints: RefCell<[Vec<String>; rt_std::cpu::lanes::LANES]>,
}
