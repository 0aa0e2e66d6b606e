//! The CPU backend: programs run natively as Rust (each descriptor's `cpu`
//! entry), rays traverse the node graph as built (groups' obvhs BVH2s over
//! their children, transforms composed on the way down, selectors' visit
//! programs choosing one child, geometry groups' BVH2s over primitives),
//! rayon spreads chunks of launch indices over all cores.
//!
//! Semantics are OptiX's and the megakernel's: the intersection protocol
//! (`rt_potential_intersection` accepts `t` in `(tmin, closest)`,
//! `rt_report_intersection` runs any hit, which may ignore the candidate or
//! terminate the ray), ray flags and visibility masks, the trace-depth limit
//! and exceptions. Intrinsics reach this backend through rt-std's
//! thread-local execution context and the [`Tracer`] it installs.
//!
//! Per ray nothing is allocated and nothing is looked up by name: variables
//! are bound once per launch and program use, their types checked then
//! ([`rt_std::cpu::BoundVariables`]: a call reads them after one comparison,
//! not one downcast per variable),
//! each program call's context is built in place and installed by pointer
//! ([`rt_std::cpu::in_context`]), the tracer is installed once per chunk of
//! launch indices, and attribute values are reused from a per-thread pool.
//! Triangle hits of instances without any-hit programs commit just the
//! distance and barycentrics; the attributes are computed once, for the
//! closest hit.

use super::{ExceptionRecord, Launch, LaunchBackend, LaunchReport, Settings};
use crate::accel::bvh::TreeForm;
use crate::accel::cache::{NodeAccel, Trees};
use crate::buffer::BufferRec;
use crate::error::{Result, RtError};
use crate::link::{self, Call, Record};
use crate::scene::{GeometryKind, NodeId, NodeKind, Scene, TriangleMesh};
use glam::{Mat3A, Mat4, UVec2, Vec2, Vec3, Vec3A, Vec3Swizzles};

use rayon::prelude::*;
use rt_std::cpu::{AnyAttributes, BoundVariables, CpuArgs, CpuResult, ExecutionContext, Tracer, TriangleBuiltins};
use rt_std::program::{AttributesFromWords, ProgramDescriptor, TypeLayout};
use rt_std::*;
use std::any::{Any, TypeId};
use std::cell::{Cell, RefCell};

/// Closest hit and any hit of one (instance, material, ray type).
type HitPrograms<P> = (Option<P>, Option<P>);

/// Every program use of a launch, resolved: `P` is [`Call`] (variables
/// owned) after linking, [`Program`] (variables bound) while running.
struct Linked<'a, P> {
    scene: &'a Scene,
    settings: &'a Settings,
    accels: &'a [Option<NodeAccel>],
    ray_generation: P,
    exception: Option<P>,
    miss: Vec<P>,
    /// `[instance][material slot][ray type]` → (closest hit, any hit).
    hits: Vec<Vec<Vec<HitPrograms<P>>>>,
    /// `[instance][ray type]`: whether some material of the instance has an
    /// any-hit program for the ray type (if not, triangle hits commit
    /// without building attributes).
    any_hit: Vec<Vec<bool>>,
    /// The triangles of each instance (None: custom geometry).
    meshes: Vec<Option<&'a TriangleMesh>>,
    /// Intersection program per instance (custom geometry only).
    intersection: Vec<Option<P>>,
    /// Visit program per node (selectors only).
    visit: Vec<Option<P>>,
    launch_dim: UVec2,
}

fn link_all<'a>(
    scene: &'a Scene,
    settings: &'a Settings,
    accels: &'a [Option<NodeAccel>],
    entry: u32,
    dim: UVec2,
) -> Result<Linked<'a, Call>> {
    let count = scene.entry_points.len() as u32;
    let ep = scene.entry_points.get(entry as usize).ok_or(RtError::NoSuchEntryPoint { entry, count })?;
    let rg = ep.ray_generation.ok_or(RtError::NoRayGeneration { entry })?;
    link::check_types(scene)?;
    let ray_generation = link::resolve(scene, rg, Record::default())?;
    let exception = ep.exception.map(|p| link::resolve(scene, p, Record::default())).transpose()?;
    let miss = scene
        .miss
        .iter()
        .enumerate()
        .map(|(r, m)| {
            let p = m.ok_or(RtError::NoMissProgram { ray_type: r as u32 })?;
            link::resolve(scene, p, Record::default())
        })
        .collect::<Result<Vec<_>>>()?;
    let mut hits = Vec::with_capacity(scene.instances.len());
    let mut any_hit = Vec::with_capacity(scene.instances.len());
    let mut meshes = Vec::with_capacity(scene.instances.len());
    let mut intersection = Vec::with_capacity(scene.instances.len());
    for (i, gi) in scene.instances.iter().enumerate() {
        let instance = Some(crate::handles::GeometryInstanceId(i as u32));
        let mut per_material = Vec::new();
        let mut with_any_hit = vec![false; scene.ray_type_count() as usize];
        for m in &gi.materials {
            let mat = &scene.materials[m.index() as usize];
            let record = Record { instance, material: Some(*m), ..Record::default() };
            let mut per_ray = Vec::new();
            for (r, (ch, ah)) in mat.closest_hit.iter().zip(&mat.any_hit).enumerate() {
                if let Some(flag) = with_any_hit.get_mut(r) {
                    *flag |= ah.is_some();
                }
                per_ray.push((
                    ch.map(|p| link::resolve(scene, p, record)).transpose()?,
                    ah.map(|p| link::resolve(scene, p, record)).transpose()?,
                ));
            }
            per_material.push(per_ray);
        }
        hits.push(per_material);
        any_hit.push(with_any_hit);
        match &scene.geometries[gi.geometry.index() as usize].kind {
            GeometryKind::Custom { intersection: p, .. } => {
                meshes.push(None);
                intersection.push(Some(link::resolve(
                    scene,
                    *p,
                    Record { instance, geometry: Some(gi.geometry), ..Record::default() },
                )?));
            }
            GeometryKind::Triangles(mesh) => {
                meshes.push(Some(mesh));
                intersection.push(None);
            }
        }
    }
    let visit = scene
        .nodes
        .iter()
        .enumerate()
        .map(|(n, rec)| match rec.kind {
            NodeKind::Selector { visit, .. } => {
                link::resolve(scene, visit, Record { node: Some(NodeId(n as u32)), ..Record::default() }).map(Some)
            }
            _ => Ok(None),
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Linked {
        scene,
        settings,
        accels,
        ray_generation,
        exception,
        miss,
        hits,
        any_hit,
        meshes,
        intersection,
        visit,
        launch_dim: dim,
    })
}

impl<'a> Linked<'a, Call> {
    /// The same uses with their variables bound to their programs, for the
    /// run.
    fn bind(&self) -> Result<Linked<'_, Program<'_>>> {
        fn opt(c: &Option<Call>) -> Result<Option<Program<'_>>> {
            c.as_ref().map(Program::bind).transpose()
        }
        Ok(Linked {
            scene: self.scene,
            settings: self.settings,
            accels: self.accels,
            ray_generation: Program::bind(&self.ray_generation)?,
            exception: opt(&self.exception)?,
            miss: self.miss.iter().map(Program::bind).collect::<Result<_>>()?,
            hits: self
                .hits
                .iter()
                .map(|m| m.iter().map(|r| r.iter().map(|(ch, ah)| Ok((opt(ch)?, opt(ah)?))).collect()).collect())
                .collect::<Result<_>>()?,
            any_hit: self.any_hit.clone(),
            meshes: self.meshes.clone(),
            intersection: self.intersection.iter().map(opt).collect::<Result<_>>()?,
            visit: self.visit.iter().map(opt).collect::<Result<_>>()?,
            launch_dim: self.launch_dim,
        })
    }
}

/// A program use ready to call: its variables bound to its parameter types
/// (checked once here, read per call without a check), and its attribute
/// type.
struct Program<'a> {
    desc: &'static ProgramDescriptor,
    call: &'a Call,
    vars: BoundVariables<'a>,
    attributes: Option<AttributeType>,
}

impl<'a> Program<'a> {
    fn bind(call: &'a Call) -> Result<Self> {
        let attributes = match (call.desc.attributes, call.desc.cpu_attributes) {
            (Some(layout), Some(make)) => Some(AttributeType::new(&layout, make)),
            _ => None,
        };
        let refs = link::var_refs(call);
        let vars = (call.desc.cpu_bind)(&refs[..call.vars.len()]).map_err(|e| link::bind_error(call, e))?;
        Ok(Program { desc: call.desc, call, vars, attributes })
    }
}

/// Sets `ctx`'s current ray to `ray` with `tmax`, field by field.
///
/// Built as a whole `Ray` first, the value went through a temporary in
/// stores of 4 and 8 bytes and was copied on in 16-byte loads, which the CPU
/// cannot forward from those stores: a stall per program call.
#[inline(always)]
fn set_current_ray(ctx: &mut ExecutionContext, ray: &Ray, tmax: f32) {
    let r = &mut ctx.current_ray;
    r.origin = ray.origin;
    r.direction = ray.direction;
    r.ray_type = ray.ray_type;
    r.tmin = ray.tmin;
    r.tmax = tmax;
}

/// The attribute type a program takes, resolved once per launch: how to
/// make a value and how to recognise a reusable one.
struct AttributeType {
    id: TypeId,
    words: usize,
    make: AttributesFromWords,
}

/// Attribute structs up to this many words are zeroed on the stack.
const STACK_WORDS: usize = 64;

impl AttributeType {
    fn new(layout: &TypeLayout, make: AttributesFromWords) -> Self {
        let words = layout.words as usize;
        let id = Any::type_id(make(&vec![0; words]).as_any());
        AttributeType { id, words, make }
    }

    /// Runs `f` on zeroed heap words of this type.
    fn with_zero_words<R>(&self, f: impl FnOnce(&[u32]) -> R) -> R {
        // In a small buffer when that holds them (the usual attribute
        // struct: four stores rather than a `memset` call).
        let small = [0u32; 16];
        if self.words <= small.len() {
            f(&small[..self.words])
        } else if self.words <= STACK_WORDS {
            f(&[0u32; STACK_WORDS][..self.words])
        } else {
            f(&vec![0; self.words])
        }
    }
}

/// The built-in attributes of triangle `prim` of `mesh`, with vertices `[a,
/// b, c]`, hit at barycentrics `(u, v)` (weights of vertices 1 and 2).
///
/// The vertices come by reference: copied as an argument, they went through
/// the stack in stores and loads of other widths (a stall).
fn triangle_builtins(mesh: &TriangleMesh, prim: u32, &[a, b, c]: &[Vec3; 3], u: f32, v: f32) -> TriangleBuiltins {
    let [i0, i1, i2] = mesh.indices[prim as usize].map(|i| i as usize);
    let gn = (b - a).cross(c - a);
    let w = 1.0 - u - v;
    let sn = match &mesh.normals {
        Some(n) => n[i0] * w + n[i1] * u + n[i2] * v,
        None => gn,
    };
    let uv = match &mesh.texcoords {
        Some(tc) => tc[i0] * w + tc[i1] * u + tc[i2] * v,
        None => Vec2::new(u, v),
    };
    TriangleBuiltins { geometric_normal: gn, shading_normal: sn, texcoord: uv, barycentrics: Vec2::new(u, v) }
}

/// The CPU backend: it keeps nothing between launches.
#[derive(Default)]
pub(crate) struct CpuBackend;

impl LaunchBackend for CpuBackend {
    fn kind(&self) -> super::Backend {
        super::Backend::Cpu
    }

    fn prepare(&mut self) -> Result<()> {
        Ok(())
    }

    /// Groups' BVH2s as the wide form's; every geometry group's CWBVH with
    /// its triangles in slot order.
    fn trees(&self, _: &Scene) -> Trees {
        Trees { groups: TreeForm::Wide, cwbvh: true, slot_triangles: true }
    }

    fn launch(&mut self, launch: &Launch) -> Result<LaunchReport> {
        run(launch)
    }

    /// Programs wrote the host's buffers themselves.
    fn read_back_outputs(&mut self, _: &mut [BufferRec]) {}

    fn stats(&self) -> super::BackendStats<'_> {
        super::BackendStats::default()
    }
}

/// Runs a launch over its launch indices.
fn run(launch: &Launch) -> Result<LaunchReport> {
    let &Launch { scene, settings, accels, entry, width, height } = launch;
    let t1 = std::time::Instant::now();
    let calls = link_all(scene, settings, &accels.nodes, entry, UVec2::new(width, height))?;
    let linked = calls.bind()?;
    let t2 = std::time::Instant::now();
    // Chunks of launch indices in row-major order (not rows: a 1D launch
    // spreads over all cores too); reports are merged in index order.
    let total = width as u64 * height as u64;
    let chunk = (total / (rayon::current_num_threads() as u64 * 8)).clamp(64, 16384);
    let chunks: Vec<LaunchReport> = (0..total.div_ceil(chunk))
        .into_par_iter()
        .map(|c| {
            let mut report = LaunchReport::default();
            let lane = Lane::new(&linked);
            rt_std::cpu::serving(&lane, || {
                for i in c * chunk..((c + 1) * chunk).min(total) {
                    let index = UVec2::new((i % width as u64) as u32, (i / width as u64) as u32);
                    lane.run_index(index, &mut report);
                }
            });
            report
        })
        .collect();
    let mut report = LaunchReport::default();
    for r in chunks {
        report.exceptions.extend(r.exceptions);
        report.prints.extend(r.prints);
        report.rays += r.rays;
    }
    report.timings = super::Timings {
        build: Default::default(),
        encode: t2 - t1,
        link: Default::default(),
        run: t2.elapsed(),
        kernel: None,
    };
    Ok(report)
}

/// The closest hit so far of a search.
#[derive(Clone, Copy)]
struct Hit {
    instance: u32,
    material: u32,
    primitive: u32,
    t: f32,
    /// Weights of vertices 1 and 2 (triangles; the custom attributes are in
    /// [`Search::attributes`]).
    barycentrics: Vec2,
    /// The triangle's vertices (triangles).
    vertices: [Vec3; 3],
    /// The instance's transforms (None: identity).
    xf: Option<Xf>,
}

/// The transforms of a node being traversed: the product of the transform
/// nodes above it. Traversal passes `None` where there are none, so the
/// usual scene (geometry not under a transform) neither transforms its rays
/// nor copies matrices into each hit.
#[derive(Clone, Copy)]
struct Xf {
    object_to_world: Mat4,
    world_to_object: Mat4,
}

impl Xf {
    /// (object to world, world to object) of `xf`, identity for None.
    fn matrices(xf: Option<&Xf>) -> (Mat4, Mat4) {
        xf.map_or((Mat4::IDENTITY, Mat4::IDENTITY), |x| (x.object_to_world, x.world_to_object))
    }

    /// Puts `xf`'s transforms in `ctx`, which holds the identity already
    /// (a context from `base_context`): nothing to copy for None.
    fn set(ctx: &mut ExecutionContext, xf: Option<&Xf>) {
        if let Some(x) = xf {
            ctx.object_to_world = x.object_to_world;
            ctx.world_to_object = x.world_to_object;
        }
    }
}

/// The intersection program running now, for the protocol callbacks.
#[derive(Clone, Copy)]
struct Candidate {
    instance: u32,
    primitive: u32,
    object_ray: Ray,
    xf: Option<Xf>,
}

/// One ray's search. It lives in `trace`'s frame; the lane points at it
/// while the traversal runs, so the protocol callbacks find it.
struct Search<'r> {
    ray_type: u32,
    flags: u32,
    /// The traced ray, where the tracing program built it (read field by
    /// field: see [`Tracer::trace`]).
    world_ray: &'r Ray,
    payload: *mut dyn Any,
    /// Closest accepted distance so far.
    tmax: Cell<f32>,
    done: Cell<bool>,
    committed: Cell<Option<Hit>>,
    /// The committed hit's attributes, for custom primitives.
    attributes: RefCell<Option<Box<dyn AnyAttributes>>>,
    candidate: Cell<Option<Candidate>>,
    /// The distance `rt_potential_intersection` accepted for the candidate.
    candidate_t: Cell<Option<f32>>,
}

/// One worker's state over a chunk of launch indices; also rt-std's
/// [`Tracer`] for the programs it runs.
struct Lane<'a> {
    l: &'a Linked<'a, Program<'a>>,
    index: Cell<UVec2>,
    depth: Cell<u32>,
    exception: Cell<Option<u32>>,
    prints: RefCell<Vec<String>>,
    rays: Cell<u64>,
    /// The innermost search in progress (null: none).
    search: Cell<*const Search<'static>>,
    /// Attribute values not in use, by type, for reuse.
    pool: RefCell<Vec<(TypeId, Box<dyn AnyAttributes>)>>,
}

impl<'a> Lane<'a> {
    fn new(l: &'a Linked<'a, Program<'a>>) -> Self {
        Lane {
            l,
            index: Cell::new(UVec2::ZERO),
            depth: Cell::new(0),
            exception: Cell::new(None),
            prints: RefCell::new(Vec::new()),
            rays: Cell::new(0),
            search: Cell::new(std::ptr::null()),
            pool: RefCell::new(Vec::new()),
        }
    }

    fn run_index(&self, index: UVec2, report: &mut LaunchReport) {
        let l = self.l;
        self.index.set(index);
        self.depth.set(0);
        self.exception.set(None);
        self.rays.set(0);
        let mut ctx = self.base_context();
        self.invoke(&l.ray_generation, &mut ctx, None, None);
        if let Some(code) = self.exception.get() {
            report.exceptions.push(ExceptionRecord { launch_index: index, code });
            if let Some(ex) = &l.exception {
                let mut ctx = ExecutionContext { exception_code: code, ..self.base_context() };
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

    fn base_context(&self) -> ExecutionContext {
        // The index goes in as one 8-byte store. Built from two `u32`s, LLVM
        // stores it as two 4-byte halves, and the 8-byte load of the
        // program's `launch_index()` just after cannot be forwarded from two
        // pending stores: it stalls until they reach the cache (about 4% of
        // a primary + AO launch on the bunny). `black_box` keeps the packed
        // value whole.
        let index = self.index.get();
        let bits = std::hint::black_box(index.x as u64 | (index.y as u64) << 32);
        let launch_index = UVec2::new(bits as u32, (bits >> 32) as u32);
        ExecutionContext { launch_index, launch_dim: self.l.launch_dim, ..ExecutionContext::DEFAULT }
    }

    /// The search in progress. Only called inside one (during `traverse`).
    fn search(&self) -> &Search<'_> {
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
    fn invoke(
        &self,
        p: &Program<'_>,
        ctx: &mut ExecutionContext,
        payload: Option<&mut dyn Any>,
        attributes: Option<&mut Box<dyn AnyAttributes>>,
    ) -> CpuResult {
        let attributes = attributes.map(|a| a.as_any_mut());
        let mut args = CpuArgs { payload, attributes, primitive: ctx.primitive_index, variables: &p.vars };
        let r = rt_std::cpu::in_context(ctx, || (p.desc.cpu)(&mut args));
        if let Some(code) = ctx.pending_exception
            && self.exception.get().is_none()
        {
            self.exception.set(Some(code));
        }
        r
    }

    /// An attribute value of type `id` from the pool, or `make`'s.
    fn take_attributes(&self, id: TypeId, make: impl FnOnce() -> Box<dyn AnyAttributes>) -> Box<dyn AnyAttributes> {
        let mut pool = self.pool.borrow_mut();
        match pool.iter().position(|(t, _)| *t == id) {
            Some(i) => pool.swap_remove(i).1,
            None => make(),
        }
    }

    fn return_attributes(&self, a: Box<dyn AnyAttributes>) {
        self.pool.borrow_mut().push((Any::type_id(a.as_any()), a));
    }

    /// An attribute value of type `ty`, holding `hit`'s triangle attributes
    /// (or zero).
    fn attributes_of(&self, ty: &AttributeType, hit: Option<&TriangleBuiltins>) -> Box<dyn AnyAttributes> {
        let mut a = self.take_attributes(ty.id, || (ty.make)(&vec![0; ty.words]));
        match hit {
            Some(h) => a.set_triangle(h),
            None => ty.with_zero_words(|w| a.set_words(w)),
        }
        a
    }

    /// An attribute value holding a copy of `value`.
    fn copy_of(&self, value: &dyn AnyAttributes) -> Box<dyn AnyAttributes> {
        let mut a = self.take_attributes(Any::type_id(value.as_any()), || value.clone_box());
        a.copy_from(value);
        a
    }

    fn traverse(&self, s: &Search, node: NodeId, xf: Option<&Xf>, mask: u32) {
        let l = self.l;
        let rec = &l.scene.nodes[node.index() as usize];
        if (rec.visibility_mask as u32) & mask == 0 || s.done.get() {
            return;
        }
        let world_ray = s.world_ray;
        let (origin, direction) = match xf {
            None => (world_ray.origin, world_ray.direction),
            Some(x) => (
                x.world_to_object.transform_point3(world_ray.origin),
                x.world_to_object.transform_vector3(world_ray.direction),
            ),
        };
        match &rec.kind {
            NodeKind::Transform { matrix, inverse, child } => {
                let (o2w, w2o) = Xf::matrices(xf);
                let composed = Xf { object_to_world: o2w * *matrix, world_to_object: *inverse * w2o };
                self.traverse(s, *child, Some(&composed), mask)
            }
            NodeKind::Group { children, .. } => {
                let Some(Some(NodeAccel::Children { bvh, .. })) = l.accels.get(node.index() as usize) else {
                    return;
                };
                bvh.traverse(origin, direction.recip(), world_ray.tmin, &|| s.tmax.get(), &mut |c| {
                    self.traverse(s, children[c as usize], xf, mask);
                    !s.done.get()
                });
            }
            NodeKind::Selector { children, .. } => {
                let Some(call) = &l.visit[node.index() as usize] else { return };
                // The ray in the selector's space, `tmax` the closest hit so far.
                let mut ctx = ExecutionContext {
                    current_ray: Ray { origin, direction, tmax: s.tmax.get(), ..*world_ray },
                    ..self.base_context()
                };
                // SAFETY: the payload pointer comes from the `&mut` the trace
                // call holds for the whole search; nothing else uses it now.
                let payload = unsafe { &mut *s.payload };
                let r = self.invoke(call, &mut ctx, Some(payload), None);
                if let CpuResult::Child(c) = r
                    && let Some(child) = children.get(c as usize)
                {
                    self.traverse(s, *child, xf, mask);
                }
            }
            NodeKind::GeometryGroup { .. } => {
                let Some(Some(NodeAccel::Prims { bvh, wide, triangles, prims, .. })) =
                    l.accels.get(node.index() as usize)
                else {
                    return;
                };
                // The world ray's `tmax` is not read here (the search's is):
                // copying the whole ray loads `tmin` and `tmax` as one 8-byte
                // word, which stalls when the tracing program stored them
                // one by one just before.
                let (ray_type, tmin) = (world_ray.ray_type, world_ray.tmin);
                let object_ray = || Ray { origin, direction, ray_type, tmin, tmax: s.tmax.get() };
                // Prepared on the first triangle test: most rays that miss
                // never get there.
                let prepared = std::cell::OnceCell::new();
                let prepared = || prepared.get_or_init(|| WatertightRay::new(origin, direction, tmin)).as_ref();
                let visit = |p: u32| {
                    let (gi, prim) = prims[p as usize];
                    match l.meshes[gi as usize] {
                        Some(mesh) => {
                            let [a, b, c] = mesh.triangle(prim as usize);
                            if let Some(ray) = prepared()
                                && let Some(hit) = ray.intersect(a, b, c, s.tmax.get())
                            {
                                self.triangle_hit(s, ray, mesh, gi, prim, hit, [a, b, c], xf);
                            }
                        }
                        None => self.intersect_custom(s, gi, prim, &object_ray(), xf),
                    }
                };
                match (wide, triangles.as_deref()) {
                    // obvhs's 8-wide traversal over triangles in slot order:
                    // the instance and primitive are looked up on hits only.
                    (Some(cw), Some(triangles)) if !triangles.is_empty() => {
                        let mut hit = obvhs::ray::RayHit::none();
                        let ray = obvhs::ray::Ray::new(origin.into(), direction.into(), world_ray.tmin, s.tmax.get());
                        cw.ray_traverse(ray, &mut hit, |_, slot| {
                            let [a, b, c] = triangles[slot];
                            if let Some(ray) = prepared()
                                && let Some(hit) = ray.intersect(a, b, c, s.tmax.get())
                            {
                                let (gi, prim) = prims[cw.primitive_indices[slot] as usize];
                                if let Some(mesh) = l.meshes[gi as usize] {
                                    self.triangle_hit(s, ray, mesh, gi, prim, hit, [a, b, c], xf);
                                }
                            }
                            if s.done.get() { f32::NEG_INFINITY } else { s.tmax.get() }
                        });
                    }
                    // obvhs's 8-wide traversal; the callback runs the whole
                    // hit protocol and returns the closest committed distance
                    // (unchanged if nothing committed), or -inf to stop.
                    (Some(cw), _) => {
                        let mut hit = obvhs::ray::RayHit::none();
                        let ray = obvhs::ray::Ray::new(origin.into(), direction.into(), world_ray.tmin, s.tmax.get());
                        cw.ray_traverse(ray, &mut hit, |_, slot| {
                            visit(cw.primitive_indices[slot]);
                            if s.done.get() { f32::NEG_INFINITY } else { s.tmax.get() }
                        });
                    }
                    (None, _) => bvh.traverse(origin, direction.recip(), world_ray.tmin, &|| s.tmax.get(), &mut |p| {
                        visit(p);
                        !s.done.get()
                    }),
                }
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
    fn triangle_hit(
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
    fn triangle_hit_protocol(
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
        if flags & (RAY_FLAG_CULL_FRONT_FACING | RAY_FLAG_CULL_BACK_FACING) != 0 {
            let front = ray.direction.dot((b - a).cross(c - a)) < 0.0;
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
                let hit = triangle_builtins(mesh, prim, &[a, b, c], u, v);
                self.attributes_of(ty, Some(&hit))
            });
            match self.any_hit(s, ah, t, prim, xf, attributes) {
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
    fn commit_triangle(
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
        }));
    }

    /// Runs any hit `ah` for a candidate at `t`; None if it ignored the
    /// candidate, else whether it terminated the ray.
    #[allow(clippy::too_many_arguments)]
    fn any_hit(
        &self,
        s: &Search,
        ah: &Program<'_>,
        t: f32,
        prim: u32,
        xf: Option<&Xf>,
        mut attributes: Option<Box<dyn AnyAttributes>>,
    ) -> Option<bool> {
        let mut ctx = ExecutionContext {
            current_ray: Ray { tmax: t, ..*s.world_ray },
            t_hit: t,
            primitive_index: prim,
            ..self.base_context()
        };
        Xf::set(&mut ctx, xf);
        // SAFETY: see `traverse`: the search's payload is only used here.
        let payload = unsafe { &mut *s.payload };
        self.invoke(ah, &mut ctx, Some(payload), attributes.as_mut());
        if let Some(a) = attributes {
            self.return_attributes(a);
        }
        (!ctx.ignored).then_some(ctx.terminated)
    }

    fn intersect_custom(&self, s: &Search, gi: u32, prim: u32, object_ray: &Ray, xf: Option<&Xf>) {
        let Some(call) = &self.l.intersection[gi as usize] else { return };
        s.candidate.set(Some(Candidate { instance: gi, primitive: prim, object_ray: *object_ray, xf: xf.copied() }));
        s.candidate_t.set(None);
        let mut ctx = ExecutionContext {
            current_ray: Ray { tmax: s.tmax.get(), ..*object_ray },
            primitive_index: prim,
            ..self.base_context()
        };
        Xf::set(&mut ctx, xf);
        let mut attributes = call.attributes.as_ref().map(|ty| self.attributes_of(ty, None));
        self.invoke(call, &mut ctx, None, attributes.as_mut());
        if let Some(a) = attributes {
            self.return_attributes(a);
        }
        s.candidate.set(None);
    }
}

impl Tracer for Lane<'_> {
    fn trace(&self, object: Object, ray: &Ray, payload: &mut dyn Any, flags: u32, mask: u32) {
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
        let mut search = Search {
            ray_type: ray.ray_type,
            flags,
            world_ray: ray,
            payload: payload as *mut dyn Any,
            tmax: Cell::new(ray.tmax),
            done: Cell::new(false),
            committed: Cell::new(None),
            attributes: RefCell::new(None),
            candidate: Cell::new(None),
            candidate_t: Cell::new(None),
        };
        // The pointer's lifetime is erased; it is restored below, before
        // `search` (and the ray it borrows) go away.
        let outer = self.search.replace((&search as *const Search<'_>).cast());
        self.traverse(&search, node, None, mask & 0xff);
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
                    if let (Some(mesh), Some(ty)) = (l.meshes[hit.instance as usize], &ch.attributes) {
                        let (u, v) = hit.barycentrics.into();
                        let values = triangle_builtins(mesh, hit.primitive, &hit.vertices, u, v);
                        attributes = Some(self.attributes_of(ty, Some(&values)));
                    }
                    let mut ctx =
                        ExecutionContext { t_hit: hit.t, primitive_index: hit.primitive, ..self.base_context() };
                    Xf::set(&mut ctx, hit.xf.as_ref());
                    set_current_ray(&mut ctx, ray, hit.t);
                    self.invoke(ch, &mut ctx, Some(payload), attributes.as_mut());
                }
            }
            None => {
                let mut ctx = self.base_context();
                set_current_ray(&mut ctx, ray, ray.tmax);
                self.invoke(&l.miss[ray.ray_type as usize], &mut ctx, Some(payload), None);
            }
        }
        if let Some(a) = attributes {
            self.return_attributes(a);
        }
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
            match self.any_hit(s, ah, t, c.primitive, c.xf.as_ref(), Some(copy)) {
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
        }));
        s.done.set(s.done.get() | terminate);
        true
    }

    fn print(&self, text: &str) {
        let settings = self.l.settings;
        if settings.print_enabled && settings.print_launch_index.is_none_or(|i| i == self.index.get()) {
            self.prints.borrow_mut().push(text.to_string());
        }
    }
}

/// Attributes of an intersection program that declares none.
#[derive(Clone, Copy, Default, Debug, PartialEq)]
struct NoAttributes;

impl RtData for NoAttributes {
    const LAYOUT: TypeLayout = TypeLayout { rust: "()", wgsl: "", words: 0, fields: &[] };
    fn write_words(&self, _: &mut [u32]) {}
    fn read_words(_: &[u32]) -> Self {
        NoAttributes
    }
}

impl rt_std::Attributes for NoAttributes {}

/// A ray prepared for watertight ray/triangle intersection (Woop, Benthin
/// and Wald, JCGT 2013: no cracks between triangles sharing an edge): the
/// axis permutation and shear depend on the direction only, so they are
/// computed once per ray and geometry group.
///
/// The permutation and shear are kept as a matrix of three rows, so a
/// vertex's sheared coordinates are the rows' dot products with it (`p ·
/// (e[kx] - sx * e[kz])` is `p[kx] - sx * p[kz]`) instead of components
/// picked by run-time index per triangle. The values are the same (up to the
/// sign of a zero): the extra terms are exact zeros, and the sum of the other
/// two rounds as before.
struct WatertightRay {
    origin: Vec3A,
    direction: Vec3,
    tmin: f32,
    /// The rows `e[kx] - sx * e[kz]` (a point's sheared x), `e[ky] - sy *
    /// e[kz]` (its sheared y) and `sz * e[kz]` (its scaled z). A vertex is
    /// sheared in one four-lane product, `(x * c0 + y * c1) + z * c2` over
    /// the columns, which sums each lane in the order of `Vec3::dot` over a
    /// row: the same values as three dot products, in a third of the
    /// instructions.
    shear: Mat3A,
}

impl WatertightRay {
    /// None for a direction without a non-zero component.
    ///
    /// The paper swaps `kx` and `ky` when `d[kz]` is negative, to keep the
    /// sign of the determinant for back-face culling. Here the swap would
    /// only negate `u`, `v`, `w`, the determinant and the scaled distance,
    /// exactly, leaving `t` and the barycentrics as they are (culling takes
    /// the facing from the geometric normal), so there is none.
    fn new(origin: Vec3, d: Vec3, tmin: f32) -> Option<Self> {
        let abs = d.abs();
        // `kz` is the axis of the largest component; `kx`, `ky` the next two
        // in cyclic order. Components picked as constants per case: indexed
        // at run time, a `Vec3` branches on the index.
        let (kz, dx, dy, dz) = if abs.x > abs.y {
            if abs.x > abs.z { (0, d.y, d.z, d.x) } else { (2, d.x, d.y, d.z) }
        } else if abs.y > abs.z {
            (1, d.z, d.x, d.y)
        } else {
            (2, d.x, d.y, d.z)
        };
        if dz == 0.0 {
            return None;
        }
        // Rows `e[kx] - (dx / dz) e[kz]`, `e[ky] - (dy / dz) e[kz]` and
        // `e[kz] / dz`, as columns: column `kx` is (1, 0, 0), column `ky`
        // (0, 1, 0) and column `kz` holds the shear and scale.
        let k = Vec3A::new(-(dx / dz), -(dy / dz), 1.0 / dz);
        let shear = match kz {
            0 => Mat3A::from_cols(k, Vec3A::X, Vec3A::Y),
            1 => Mat3A::from_cols(Vec3A::Y, k, Vec3A::X),
            _ => Mat3A::from_cols(Vec3A::X, Vec3A::Y, k),
        };
        Some(WatertightRay { origin: origin.into(), direction: d, tmin, shear })
    }

    /// The hit with triangle `(a, b, c)` as `(t, u, v)` for `t` in `(tmin,
    /// tmax)`; `u`, `v` weight vertices `b` and `c`.
    #[inline(always)]
    fn intersect(&self, a: Vec3, b: Vec3, c: Vec3, tmax: f32) -> Option<(f32, f32, f32)> {
        let shear = |p: Vec3| self.shear.mul_vec3a(Vec3A::from(p) - self.origin);
        let (pa, pb, pc) = (shear(a), shear(b), shear(c));
        // The sheared coordinates by axis, one vertex per lane.
        let (x, y) = (Vec3A::new(pa.x, pb.x, pc.x), Vec3A::new(pa.y, pb.y, pc.y));
        // u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax,
        // each lane as the scalar expression computes it.
        let mut uvw = x.zxy() * y.yzx() - y.zxy() * x.yzx();
        // Whether a ray passes a triangle's edges is a coin toss the branch
        // predictor loses, so the sign tests are lane masks combined without
        // branches (short-circuit tests branched up to six times per
        // triangle).
        if uvw.cmpeq(Vec3A::ZERO).any() {
            // Fall back to double precision on edges.
            let ([ax, bx, cx], [ay, by, cy]) = (x.to_array().map(f64::from), y.to_array().map(f64::from));
            uvw = Vec3A::new((cx * by - cy * bx) as f32, (ax * cy - ay * cx) as f32, (bx * ay - by * ax) as f32);
        }
        if uvw.cmplt(Vec3A::ZERO).any() & uvw.cmpgt(Vec3A::ZERO).any() {
            return None;
        }
        let [u, v, w] = uvw.to_array();
        let (az, bz, cz) = (pa.z, pb.z, pc.z);
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let t_scaled = u * az + v * bz + w * cz;
        let t = t_scaled / det;
        if !(t > self.tmin && t < tmax && t.is_finite()) {
            return None;
        }
        // u weights vertex a here; report the weights of b and c.
        Some((t, v / det, w / det))
    }
}

#[cfg(test)]
mod tests {
    use super::WatertightRay;
    use glam::Vec3;

    /// Woop, Benthin and Wald's test as the paper writes it: components by
    /// run-time index, `kx` and `ky` swapped for a negative `d[kz]`, the
    /// shear applied per coordinate.
    fn paper(o: Vec3, d: Vec3, tmin: f32, [a, b, c]: [Vec3; 3], tmax: f32) -> Option<(f32, f32, f32)> {
        let abs = d.abs();
        let kz = if abs.x > abs.y {
            if abs.x > abs.z { 0 } else { 2 }
        } else if abs.y > abs.z {
            1
        } else {
            2
        };
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        if d[kz] == 0.0 {
            return None;
        }
        let (sx, sy, sz) = (d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
        let (pa, pb, pc) = (a - o, b - o, c - o);
        let (ax, ay) = (pa[kx] - sx * pa[kz], pa[ky] - sy * pa[kz]);
        let (bx, by) = (pb[kx] - sx * pb[kz], pb[ky] - sy * pb[kz]);
        let (cx, cy) = (pc[kx] - sx * pc[kz], pc[ky] - sy * pc[kz]);
        let (mut u, mut v, mut w) = (cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax);
        if u == 0.0 || v == 0.0 || w == 0.0 {
            let (cxd, cyd, bxd, byd, axd, ayd) = (cx as f64, cy as f64, bx as f64, by as f64, ax as f64, ay as f64);
            u = (cxd * byd - cyd * bxd) as f32;
            v = (axd * cyd - ayd * cxd) as f32;
            w = (bxd * ayd - byd * axd) as f32;
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let t = (u * (sz * pa[kz]) + v * (sz * pb[kz]) + w * (sz * pc[kz])) / det;
        (t > tmin && t < tmax && t.is_finite()).then_some((t, v / det, w / det))
    }

    /// A small deterministic generator (xorshift), uniform in `[-r, r]`.
    struct Rng(u64);
    impl Rng {
        fn f(&mut self, r: f32) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            ((self.0 >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0) * r
        }
        fn v(&mut self, r: f32) -> Vec3 {
            Vec3::new(self.f(r), self.f(r), self.f(r))
        }
    }

    /// The shear as one matrix product, without the paper's swap, gives the
    /// paper's hits: the same distances and barycentrics, bit for bit.
    #[test]
    fn the_watertight_test_gives_the_papers_hits() {
        let mut rng = Rng(0x9e3779b97f4a7c15);
        let (mut hits, mut misses) = (0, 0);
        for i in 0..20000 {
            let tri = [rng.v(1.0), rng.v(1.0), rng.v(1.0)];
            let o = rng.v(3.0);
            // Aimed near the triangle (half of them hit), some along an axis.
            let mut d = tri[0] + (tri[1] - tri[0]) * rng.f(1.0).abs() + (tri[2] - tri[0]) * rng.f(0.6).abs() - o;
            if i % 10 == 0 {
                d[i % 3] = 0.0;
            }
            let tmin = if i % 7 == 0 { -1.0 } else { 0.0 };
            let ours = WatertightRay::new(o, d, tmin).and_then(|r| r.intersect(tri[0], tri[1], tri[2], f32::INFINITY));
            let theirs = paper(o, d, tmin, tri, f32::INFINITY);
            assert_eq!(ours, theirs, "ray {o} + t {d} against {tri:?}");
            match ours {
                Some(_) => hits += 1,
                None => misses += 1,
            }
        }
        assert!(hits > 5000 && misses > 5000, "{hits} hits, {misses} misses");
    }

    /// Rays through a point of the edge two triangles share hit at least one
    /// of them: no ray slips through the crack.
    #[test]
    fn no_ray_slips_between_triangles_sharing_an_edge() {
        let mut rng = Rng(0x2545f4914f6cdd1d);
        for _ in 0..20000 {
            let (a, b) = (rng.v(1.0), rng.v(1.0));
            let (c, e) = (rng.v(1.0), rng.v(1.0));
            // On the edge, and on a line through the two far corners' sides.
            let p = a + (b - a) * rng.f(1.0).abs();
            let o = p + rng.v(3.0);
            let d = p - o;
            let ray = WatertightRay::new(o, d, 0.0).expect("a direction");
            let (n1, n2) = ((b - a).cross(c - a), (a - b).cross(e - b));
            // Only when the two triangles lie on opposite sides of the edge
            // as seen along the ray does the ray have to hit one of them.
            let (s1, s2) = ((c - p).dot(d.cross(b - a)), (e - p).dot(d.cross(b - a)));
            if s1 * s2 >= 0.0 || n1.length() < 1e-3 || n2.length() < 1e-3 {
                continue;
            }
            let hit =
                ray.intersect(a, b, c, f32::INFINITY).is_some() || ray.intersect(b, a, e, f32::INFINITY).is_some();
            assert!(hit, "ray {o} + t {d} through the shared edge {a} {b} hits neither triangle");
        }
    }
}
