//! A lane: one thread's run over launch indices, tracing rays through the
//! node graph (groups' BVH2s, transforms, selectors, geometry groups'
//! SIMD trees), calling programs in place, and serving rt-std's intrinsics as
//! its [`Tracer`].

use super::super::{ExceptionRecord, LaunchReport};
use super::bind::{AttributeType, Linked, Program};
use super::triangle::{geometric_normal, triangle_builtins};
use crate::accel::cache::NodeAccel;
use crate::accel::wide::isa::{Isa, walk_on};
use crate::accel::wide::kernels::WalkRay;
use crate::accel::wide::watertight::WatertightRay;
use crate::accel::wide::{PACKET, leaf_of};
use crate::handles::{BufferId, SamplerId};
use crate::link;
use crate::link::instances::{self, InstancePath};
use crate::scene::{NodeId, NodeKind, ProgramId, TriangleMesh};
use glam::{UVec2, Vec2, Vec3};
use rt_std::cpu::{
    AnyAttributes, CpuArgs, CpuResult, ExecutionContext, HIT_CUSTOM, HIT_TRIANGLE_BACK, HIT_TRIANGLE_FRONT, Tracer,
    Transforms, TriangleBuiltins,
};
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
fn under(outer: &Xf, own: &Xf) -> Xf {
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

/// One worker's state over a chunk of launch indices; also rt-std's
/// [`Tracer`] for the programs it runs.
pub(crate) struct Lane<'a> {
    pub(crate) l: &'a Linked<'a, Program<'a>>,
    pub(crate) index: Cell<UVec2>,
    pub(crate) depth: Cell<u32>,
    /// The launch index's first exception, and where it was raised when
    /// the raiser said (integer exceptions).
    pub(crate) exception: Cell<Option<(u32, Option<&'static std::panic::Location<'static>>)>>,
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
        report.rays += self.rays.get();
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
    fn launch_index(&self) -> (UVec2, u32) {
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

    /// The instance index and id of geometry instance `gi` in the geometry
    /// group being searched.
    fn instance_of(&self, s: &Search, gi: u32) -> (u32, u32) {
        let (path, group) = s.group.get();
        instances::resolve(self.l.scene, path, group, gi)
    }

    pub(crate) fn traverse(&self, s: &Search, mut node: NodeId, xf: Option<&Xf>, mask: u32, path: InstancePath) {
        let l = self.l;
        let rec = loop {
            let rec = &l.scene.nodes[node.index() as usize];
            if (rec.visibility_mask as u32) & mask == 0 || s.done.get() {
                return;
            }
            match &rec.kind {
                // One child (a scene's usual top group): its own tree tests
                // the ray first thing, so the group's box test would be
                // repeated; the child is searched in this call, not a
                // nested one.
                NodeKind::Group { children, .. } if children.len() == 1 => node = children[0],
                _ => break rec,
            }
        };
        let world_ray = s.world_ray;
        let (origin, direction) = match xf {
            None => (world_ray.origin, world_ray.direction),
            Some(x) => (
                x.world_to_object.transform_point3(world_ray.origin),
                x.world_to_object.transform_vector3(world_ray.direction),
            ),
        };
        match &rec.kind {
            NodeKind::Transform { motion: Some(motion), child, .. } => {
                // The transform at the ray's time; an instant where it has no
                // inverse hides the child.
                let m = motion.matrix_at(self.time.get());
                let det = m.determinant();
                if det == 0.0 || !det.is_finite() {
                    return;
                }
                let own = Xf { object_to_world: m, world_to_object: m.inverse() };
                let composed = xf.map_or(own, |x| under(x, &own));
                self.traverse(s, *child, Some(&composed), mask, path.through(rec.instance_id))
            }
            NodeKind::Transform { child, motion: None, .. } => {
                let path = path.through(rec.instance_id);
                // The launch holds every static transform's matrices.
                let Some(own) = l.transforms.get(node.index() as usize).and_then(Option::as_ref) else { return };
                match xf {
                    // Under no other transform: the node's own matrices,
                    // borrowed, not their products with the identity.
                    None => self.traverse(s, *child, Some(own), mask, path),
                    Some(x) => self.traverse(s, *child, Some(&under(x, own)), mask, path),
                }
            }
            NodeKind::Group { children, .. } => {
                let Some(Some(NodeAccel::Children { bvh, .. })) = l.accels.get(node.index() as usize) else {
                    return;
                };
                let offsets = &l.instance_offsets[node.index() as usize];
                bvh.traverse(origin, direction.recip(), world_ray.tmin, &|| s.tmax.get(), &mut |c| {
                    self.traverse(s, children[c as usize], xf, mask, path.child(offsets[c as usize]));
                    !s.done.get()
                });
            }
            NodeKind::Selector { children, .. } => {
                let Some(call) = &l.visit[node.index() as usize] else { return };
                // The ray in the selector's space, `tmax` the closest hit so far.
                let mut ctx = self.context();
                ctx.current_ray = Ray { origin, direction, tmax: s.tmax.get(), ..*world_ray };
                // SAFETY: the payload pointer comes from the `&mut` the trace
                // call holds for the whole search; nothing else uses it now.
                let payload = unsafe { &mut *s.payload };
                let r = self.invoke(call, &mut ctx, Some(payload), None);
                if let CpuResult::Child(c) = r
                    && let Some(child) = children.get(c as usize)
                {
                    let offset = l.instance_offsets[node.index() as usize][c as usize];
                    self.traverse(s, *child, xf, mask, path.child(offset));
                }
            }
            NodeKind::GeometryGroup { .. } => {
                let Some(Some(NodeAccel::Prims { bvh, simd, prims, .. })) = l.accels.get(node.index() as usize) else {
                    return;
                };
                s.group.set((path, node));
                // The world ray's `tmax` is not read here (the search's is):
                // copying the whole ray loads `tmin` and `tmax` as one 8-byte
                // word, which stalls when the tracing program stored them
                // one by one just before.
                let (ray_type, tmin) = (world_ray.ray_type, world_ray.tmin);
                let object_ray = || Ray { origin, direction, ray_type, tmin, tmax: s.tmax.get() };
                let prepared = WatertightRay::new(origin, direction, tmin);
                let visit = |p: u32| {
                    let (gi, prim) = prims[p as usize];
                    match l.meshes[gi as usize] {
                        Some(mesh) => {
                            // (Moving triangles are never in the SIMD
                            // tree's packets: they come here.)
                            let [a, b, c] = match l.vertex_motion[gi as usize] {
                                Some(m) => m.triangle_at(mesh.indices[prim as usize], self.time.get()),
                                None => mesh.triangle(prim as usize),
                            };
                            if let Some(ray) = &prepared
                                && let Some(hit) = ray.intersect(a, b, c, s.tmax.get())
                            {
                                self.triangle_hit(s, ray, mesh, gi, prim, hit, [a, b, c], xf);
                            }
                        }
                        None => self.intersect_custom(s, gi, prim, &object_ray(), xf),
                    }
                };
                let Some(tree) = simd else {
                    // `NoAccel`'s single leaf.
                    bvh.traverse(origin, direction.recip(), tmin, &|| s.tmax.get(), &mut |p| {
                        visit(p);
                        !s.done.get()
                    });
                    return;
                };
                let ray = WalkRay { origin, inv_dir: direction.recip(), tmin, triangle: prepared.as_ref() };
                let next = || (!s.done.get()).then(|| s.tmax.get());
                walk_on(self.isa, tree, &ray, s.tmax.get(), |leaf, hits| {
                    let (index, count) = leaf_of(leaf);
                    let slots = &tree.slots[index as usize * PACKET..][..count as usize];
                    match hits {
                        // Triangle packets: each lane hit, in lane order,
                        // against the closest hit so far (an earlier lane
                        // may have committed a closer one).
                        Some(hits) => {
                            // (The walk tests packets only with a setup.)
                            let ray = prepared.as_ref()?;
                            let mut mask = hits.mask;
                            while mask != 0 {
                                let lane = mask.trailing_zeros() as usize;
                                mask &= mask - 1;
                                let t = hits.t[lane];
                                // (Hits are never NaN.)
                                if t >= s.tmax.get() {
                                    continue;
                                }
                                let (gi, prim) = prims[slots[lane] as usize];
                                if let Some(mesh) = l.meshes[gi as usize] {
                                    let vertices = tree.packets[index as usize].vertices(lane);
                                    self.triangle_hit(
                                        s,
                                        ray,
                                        mesh,
                                        gi,
                                        prim,
                                        (t, hits.u[lane], hits.v[lane]),
                                        vertices,
                                        xf,
                                    );
                                }
                                if s.done.get() {
                                    return None;
                                }
                            }
                        }
                        None => {
                            for &p in slots {
                                visit(p);
                                if s.done.get() {
                                    return None;
                                }
                            }
                        }
                    }
                    next()
                });
            }
        }
    }

    /// A ray/triangle hit `(t, u, v)` with triangle `prim` (vertices
    /// `[a, b, c]`) of instance `gi`: culling, any hit, and the commit.
    ///
    /// Inlined into the traversal's triangle test: the usual hit (no
    /// culling flags, no any-hit program) commits there; the rest is
    /// [`triangle_hit_protocol`](Self::triangle_hit_protocol)'s.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn triangle_hit(
        &self,
        s: &Search,
        ray: &WatertightRay,
        mesh: &TriangleMesh,
        gi: u32,
        prim: u32,
        (t, u, v): (f32, f32, f32),
        [a, b, c]: [Vec3; 3],
        xf: Option<&Xf>,
    ) {
        if s.flags & (RAY_FLAG_CULL_FRONT_FACING | RAY_FLAG_CULL_BACK_FACING | RAY_FLAG_TERMINATE_ON_FIRST_HIT) == 0
            && !self.l.any_hit[gi as usize][s.ray_type as usize]
            && mesh.material_indices.is_none()
            && !self.l.hits[gi as usize].is_empty()
        {
            Self::commit_triangle(s, gi, 0, prim, (t, u, v), [a, b, c], xf);
        } else {
            self.triangle_hit_protocol(s, ray, mesh, gi, prim, (t, u, v), [a, b, c], xf);
        }
    }

    /// [`triangle_hit`](Self::triangle_hit) with culling, materials per
    /// triangle, any hit and termination.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    pub(crate) fn triangle_hit_protocol(
        &self,
        s: &Search,
        ray: &WatertightRay,
        mesh: &TriangleMesh,
        gi: u32,
        prim: u32,
        (t, u, v): (f32, f32, f32),
        [a, b, c]: [Vec3; 3],
        xf: Option<&Xf>,
    ) {
        let flags = s.flags;
        // The geometric normal, made once where culling or an any-hit
        // program asks for it.
        let normal = std::cell::OnceCell::new();
        let normal = || *normal.get_or_init(|| geometric_normal(&[a, b, c]));
        let front = || ray.direction.dot(normal()) < 0.0;
        if flags & (RAY_FLAG_CULL_FRONT_FACING | RAY_FLAG_CULL_BACK_FACING) != 0 {
            let front = front();
            if (front && flags & RAY_FLAG_CULL_FRONT_FACING != 0) || (!front && flags & RAY_FLAG_CULL_BACK_FACING != 0)
            {
                return;
            }
        }
        let material = mesh.material_indices.as_ref().map_or(0, |m| m[prim as usize]);
        let Some(per_ray) = self.l.hits[gi as usize].get(material as usize) else {
            // A material index the instance does not have: nothing to run.
            return;
        };
        let mut terminate = flags & RAY_FLAG_TERMINATE_ON_FIRST_HIT != 0;
        if self.l.any_hit[gi as usize][s.ray_type as usize]
            && flags & RAY_FLAG_DISABLE_ANYHIT == 0
            && let (_, Some(ah)) = &per_ray[s.ray_type as usize]
        {
            let attributes = ah.attributes.as_ref().map(|ty| {
                let hit = triangle_builtins(mesh, prim, normal(), u, v);
                self.attributes_of(ty, Some(&hit))
            });
            let kind = if front() { HIT_TRIANGLE_FRONT } else { HIT_TRIANGLE_BACK };
            match self.any_hit(s, ah, (t, kind), (gi, prim), xf, attributes) {
                None => return,
                Some(terminated) => terminate |= terminated,
            }
        }
        Self::commit_triangle(s, gi, material, prim, (t, u, v), [a, b, c], xf);
        s.done.set(s.done.get() | terminate);
    }

    /// Makes a triangle hit the closest so far.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn commit_triangle(
        s: &Search,
        gi: u32,
        material: u32,
        prim: u32,
        (t, u, v): (f32, f32, f32),
        vertices: [Vec3; 3],
        xf: Option<&Xf>,
    ) {
        s.tmax.set(t);
        s.committed.set(Some(Hit {
            instance: gi,
            material,
            primitive: prim,
            t,
            barycentrics: Vec2::new(u, v),
            vertices,
            xf: xf.copied(),
            path: s.group.get(),
        }));
    }

    /// Runs any hit `ah` for a candidate at `t` (of kind `hit_kind`, one
    /// of rt-std's `HIT_*`); None if it ignored the candidate, else whether
    /// it terminated the ray.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn any_hit(
        &self,
        s: &Search,
        ah: &Program<'_>,
        (t, hit_kind): (f32, u32),
        (gi, prim): (u32, u32),
        xf: Option<&Xf>,
        mut attributes: Option<Box<dyn AnyAttributes>>,
    ) -> Option<bool> {
        let (instance_index, instance_id) = self.instance_of(s, gi);
        let mut ctx = self.context();
        set_current_ray(&mut ctx, s.world_ray, t);
        ctx.t_hit = t;
        ctx.primitive_index = prim;
        ctx.hit_kind = hit_kind;
        ctx.ray_flags = s.flags;
        ctx.ray_mask = s.mask;
        ctx.instance_index = instance_index;
        ctx.instance_id = instance_id;
        set_transforms(&mut ctx, xf);
        // SAFETY: see `traverse`: the search's payload is only used here.
        let payload = unsafe { &mut *s.payload };
        self.invoke(ah, &mut ctx, Some(payload), attributes.as_mut());
        if let Some(a) = attributes {
            self.return_attributes(a);
        }
        (!ctx.ignored).then_some(ctx.terminated)
    }

    pub(crate) fn intersect_custom(&self, s: &Search, gi: u32, prim: u32, object_ray: &Ray, xf: Option<&Xf>) {
        let Some(call) = &self.l.intersection[gi as usize] else { return };
        s.candidate.set(Some(Candidate { instance: gi, primitive: prim, object_ray: *object_ray, xf: xf.copied() }));
        s.candidate_t.set(None);
        let (instance_index, instance_id) = self.instance_of(s, gi);
        let mut ctx = self.context();
        set_current_ray(&mut ctx, object_ray, s.tmax.get());
        ctx.primitive_index = prim;
        ctx.ray_flags = s.flags;
        ctx.ray_mask = s.mask;
        ctx.instance_index = instance_index;
        ctx.instance_id = instance_id;
        set_transforms(&mut ctx, xf);
        let mut attributes = call.attributes.as_ref().map(|ty| self.attributes_of(ty, None));
        self.invoke(call, &mut ctx, None, attributes.as_mut());
        if let Some(a) = attributes {
            self.return_attributes(a);
        }
        s.candidate.set(None);
    }
}

impl Tracer for Lane<'_> {
    fn trace(&self, object: Object, ray: &Ray, payload: &mut dyn Any, flags: u32, mask: u32, time: f32) {
        if self.exception.get().is_some() || rt_std::cpu::pending_exception().is_some() {
            return;
        }
        let depth = self.depth.get();
        let l = self.l;
        if depth >= l.settings.max_trace_depth {
            rt_std::cpu::raise(EXCEPTION_TRACE_DEPTH_EXCEEDED);
            return;
        }
        let node = NodeId(object.id);
        if object.id as usize >= l.scene.nodes.len() || ray.ray_type >= l.scene.ray_type_count() {
            rt_std::cpu::raise(EXCEPTION_INVALID_RAY);
            return;
        }
        self.depth.set(depth + 1);
        self.rays.set(self.rays.get() + 1);
        let outer_time = self.time.replace(time);
        let mut search = Search {
            ray_type: ray.ray_type,
            flags,
            mask: mask & 0xff,
            world_ray: ray,
            payload: payload as *mut dyn Any,
            tmax: Cell::new(ray.tmax),
            done: Cell::new(false),
            committed: Cell::new(None),
            attributes: RefCell::new(None),
            candidate: Cell::new(None),
            candidate_t: Cell::new(None),
            group: Cell::new((InstancePath::ROOT, node)),
        };
        // The pointer's lifetime is erased; it is restored below, before
        // `search` (and the ray it borrows) go away.
        let outer = self.search.replace((&search as *const Search<'_>).cast());
        self.traverse(&search, node, None, mask & 0xff, InstancePath::ROOT);
        self.search.set(outer);
        let mut attributes = search.attributes.take();
        // Read in place: a copy of the hit would load the fields its last
        // commit stored one by one in wider words (a stall).
        match search.committed.get_mut() {
            Some(hit) => {
                let (closest, _) = &l.hits[hit.instance as usize][hit.material as usize][ray.ray_type as usize];
                if let Some(ch) = closest
                    && flags & RAY_FLAG_DISABLE_CLOSESTHIT == 0
                {
                    let mesh = l.meshes[hit.instance as usize];
                    // The geometric normal, once: the attributes and the
                    // side of the triangle both take it.
                    let normal = mesh.map(|_| geometric_normal(&hit.vertices));
                    if let (Some(mesh), Some(normal), Some(ty)) = (mesh, normal, &ch.attributes) {
                        let (u, v) = hit.barycentrics.into();
                        let values = triangle_builtins(mesh, hit.primitive, normal, u, v);
                        attributes = Some(self.attributes_of(ty, Some(&values)));
                    }
                    let hit_kind = match normal {
                        Some(normal) => front_or_back(hit.xf.as_ref(), normal, ray.direction),
                        None => HIT_CUSTOM,
                    };
                    let (path, group) = hit.path;
                    let (instance_index, instance_id) = instances::resolve(l.scene, path, group, hit.instance);
                    let mut ctx = self.context();
                    ctx.t_hit = hit.t;
                    ctx.primitive_index = hit.primitive;
                    ctx.hit_kind = hit_kind;
                    ctx.ray_flags = flags;
                    ctx.ray_mask = mask & 0xff;
                    ctx.instance_index = instance_index;
                    ctx.instance_id = instance_id;
                    set_transforms(&mut ctx, hit.xf.as_ref());
                    set_current_ray(&mut ctx, ray, hit.t);
                    self.invoke(ch, &mut ctx, Some(payload), attributes.as_mut());
                }
            }
            None => {
                let mut ctx = self.context();
                ctx.ray_flags = flags;
                ctx.ray_mask = mask & 0xff;
                set_current_ray(&mut ctx, ray, ray.tmax);
                self.invoke(&l.miss[ray.ray_type as usize], &mut ctx, Some(payload), None);
            }
        }
        if let Some(a) = attributes {
            self.return_attributes(a);
        }
        self.time.set(outer_time);
        self.depth.set(depth);
    }

    fn potential_intersection(&self, t: f32) -> bool {
        if self.search.get().is_null() {
            return false;
        }
        let s = self.search();
        let Some(c) = s.candidate.get() else { return false };
        let ok = t > c.object_ray.tmin && t < s.tmax.get();
        s.candidate_t.set(ok.then_some(t));
        if ok {
            rt_std::cpu::context_mut(|ctx| ctx.t_hit = t);
        }
        ok
    }

    fn report_intersection(&self, material: u32, attributes: Option<&dyn AnyAttributes>) -> bool {
        if self.search.get().is_null() {
            return false;
        }
        let s = self.search();
        let (Some(c), Some(t)) = (s.candidate.get(), s.candidate_t.get()) else { return false };
        if t >= s.tmax.get() {
            return false;
        }
        let gi = c.instance;
        let Some(per_ray) = self.l.hits[gi as usize].get(material as usize) else {
            // A material index the instance does not have: nothing to run.
            return false;
        };
        let attributes = attributes.unwrap_or(&NoAttributes);
        let mut terminate = s.flags & RAY_FLAG_TERMINATE_ON_FIRST_HIT != 0;
        if let (_, Some(ah)) = &per_ray[s.ray_type as usize]
            && s.flags & RAY_FLAG_DISABLE_ANYHIT == 0
        {
            let copy = self.copy_of(attributes);
            match self.any_hit(s, ah, (t, HIT_CUSTOM), (gi, c.primitive), c.xf.as_ref(), Some(copy)) {
                None => return false,
                Some(terminated) => terminate |= terminated,
            }
        }
        {
            let mut committed = s.attributes.borrow_mut();
            let reused = committed.as_mut().is_some_and(|a| a.copy_from(attributes));
            if !reused && let Some(old) = committed.replace(self.copy_of(attributes)) {
                self.return_attributes(old);
            }
        }
        s.tmax.set(t);
        s.committed.set(Some(Hit {
            instance: gi,
            material,
            primitive: c.primitive,
            t,
            barycentrics: Vec2::ZERO,
            vertices: [Vec3::ZERO; 3],
            xf: c.xf,
            path: s.group.get(),
        }));
        s.done.set(s.done.get() | terminate);
        true
    }

    fn callable(&self, id: u32) -> Option<&'static (dyn std::any::Any + Send + Sync)> {
        let rec = self.l.scene.programs.get(ProgramId::from_callable_id(id)?.index() as usize)?;
        rec.desc.callable.map(|c| c.cpu)
    }

    fn callable_variables(&self, id: u32) -> Option<&rt_std::cpu::BoundVariables<'_>> {
        let p = ProgramId::from_callable_id(id)?;
        self.l.callables.get(p.index() as usize)?.as_ref().map(|c| &c.vars)
    }

    fn buffer(&self, id: u32, writable: bool) -> Option<&(dyn std::any::Any + Send + Sync)> {
        let handles = self.l.bindless.get(BufferId::from_bindless_id(id)?.index() as usize)?;
        match writable {
            false => Some(&*handles.read),
            true => handles.write.as_deref(),
        }
    }

    fn sampler(&self, id: u32) -> Option<&(dyn std::any::Any + Send + Sync)> {
        Some(&**self.l.samplers.get(SamplerId::from_bindless_id(id)?.index() as usize)?)
    }

    fn print(&self, text: &str) {
        let settings = self.l.settings;
        if settings.print_enabled && settings.print_launch_index.is_none_or(|i| i == self.index.get()) {
            self.prints.borrow_mut().push(text.to_string());
        }
    }
}

/// The side of a triangle with geometric normal `normal` (in object space,
/// [`geometric_normal`]) a ray along world direction `d` meets, under
/// transforms `xf`: as the wgpu kernel's `rt_hit_kind` says, in the
/// instance's object space.
fn front_or_back(xf: Option<&Xf>, normal: Vec3, d: Vec3) -> u32 {
    let d = xf.map_or(d, |x| (x.world_to_object * d.extend(0.0)).truncate());
    if d.dot(normal) < 0.0 { HIT_TRIANGLE_FRONT } else { HIT_TRIANGLE_BACK }
}

/// Attributes of an intersection program that declares none.
#[derive(Clone, Copy, Default, Debug, PartialEq)]
pub(crate) struct NoAttributes;

impl RtData for NoAttributes {
    const LAYOUT: TypeLayout = TypeLayout { rust: "()", wgsl: "", words: 0, fields: &[] };
    fn write_words(&self, _: &mut [u32]) {}
    fn read_words(_: &[u32]) -> Self {
        NoAttributes
    }
}

impl rt_std::Attributes for NoAttributes {}
