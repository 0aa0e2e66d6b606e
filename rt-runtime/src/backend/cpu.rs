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

use super::link::{self, Call, Record, var_refs};
use super::{ExceptionRecord, LaunchReport};
use crate::accel::{NodeAccel, build_accels};

use crate::context::Context;
use crate::error::{Result, RtError};
use crate::scene::{GeometryKind, NodeId, NodeKind, TriangleMesh};
use glam::{Mat4, UVec2, Vec2, Vec3};

use rayon::prelude::*;
use rt_std::cpu::{AnyAttributes, CpuArgs, CpuResult, ExecutionContext, Tracer};
use rt_std::program::TypeLayout;
use rt_std::*;
use std::any::Any;
use std::cell::{Cell, RefCell};

/// Closest hit and any hit of one (instance, material, ray type).
type HitPrograms = (Option<Call>, Option<Call>);

/// Every program use of a launch, resolved.
struct Linked<'a> {
    ctx: &'a Context,
    accels: &'a [Option<NodeAccel>],
    ray_generation: Call,
    exception: Option<Call>,
    miss: Vec<Call>,
    /// `[instance][material slot][ray type]` → (closest hit, any hit).
    hits: Vec<Vec<Vec<HitPrograms>>>,
    /// Intersection program per instance (custom geometry only).
    intersection: Vec<Option<Call>>,
    /// Visit program per node (selectors only).
    visit: Vec<Option<Call>>,
    launch_dim: UVec2,
}

fn link_all<'a>(ctx: &'a Context, accels: &'a [Option<NodeAccel>], entry: u32, dim: UVec2) -> Result<Linked<'a>> {
    let count = ctx.entry_points.len() as u32;
    let ep = ctx.entry_points.get(entry as usize).ok_or(RtError::NoSuchEntryPoint { entry, count })?;
    let rg = ep.ray_generation.ok_or(RtError::NoRayGeneration { entry })?;
    link::check_types(ctx)?;
    let ray_generation = link::resolve(ctx, rg, Record::default())?;
    let exception = ep.exception.map(|p| link::resolve(ctx, p, Record::default())).transpose()?;
    let miss = ctx
        .miss
        .iter()
        .enumerate()
        .map(|(r, m)| {
            let p = m.ok_or(RtError::NoMissProgram { ray_type: r as u32 })?;
            link::resolve(ctx, p, Record::default())
        })
        .collect::<Result<Vec<_>>>()?;
    let mut hits = Vec::with_capacity(ctx.instances.len());
    let mut intersection = Vec::with_capacity(ctx.instances.len());
    for (i, gi) in ctx.instances.iter().enumerate() {
        let instance = Some(crate::GeometryInstanceId(i as u32));
        let mut per_material = Vec::new();
        for m in &gi.materials {
            let mat = &ctx.materials[m.index() as usize];
            let record = Record { instance, material: Some(*m), ..Record::default() };
            let mut per_ray = Vec::new();
            for (ch, ah) in mat.closest_hit.iter().zip(&mat.any_hit) {
                per_ray.push((
                    ch.map(|p| link::resolve(ctx, p, record)).transpose()?,
                    ah.map(|p| link::resolve(ctx, p, record)).transpose()?,
                ));
            }
            per_material.push(per_ray);
        }
        hits.push(per_material);
        intersection.push(match ctx.geometries[gi.geometry.index() as usize].kind {
            GeometryKind::Custom { intersection, .. } => Some(link::resolve(
                ctx,
                intersection,
                Record { instance, geometry: Some(gi.geometry), ..Record::default() },
            )?),
            GeometryKind::Triangles(_) => None,
        });
    }
    let visit = ctx
        .nodes
        .iter()
        .enumerate()
        .map(|(n, rec)| match rec.kind {
            NodeKind::Selector { visit, .. } => {
                link::resolve(ctx, visit, Record { node: Some(NodeId(n as u32)), ..Record::default() }).map(Some)
            }
            _ => Ok(None),
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Linked { ctx, accels, ray_generation, exception, miss, hits, intersection, visit, launch_dim: dim })
}

/// Runs entry point `entry` over `width` x `height` launch indices.
pub(crate) fn launch(ctx: &mut Context, entry: u32, width: u32, height: u32) -> Result<LaunchReport> {
    if width == 0 || height == 0 {
        return Err(RtError::BadLaunch {
            width,
            height,
            problem: "a launch needs at least one index in each dimension".into(),
        });
    }
    let t0 = std::time::Instant::now();
    let mut cache = std::mem::take(&mut ctx.accels);
    let built = build_accels(ctx, &mut cache);
    ctx.accels = cache;
    built?;
    let t1 = std::time::Instant::now();
    let ctx: &Context = ctx;
    let linked = link_all(ctx, &ctx.accels.nodes, entry, UVec2::new(width, height))?;
    let t2 = std::time::Instant::now();
    // Chunks of launch indices in row-major order (not rows: a 1D launch
    // spreads over all cores too); reports are merged in index order.
    let total = width as u64 * height as u64;
    let chunk = (total / (rayon::current_num_threads() as u64 * 8)).clamp(64, 16384);
    let chunks: Vec<LaunchReport> = (0..total.div_ceil(chunk))
        .into_par_iter()
        .map(|c| {
            let mut report = LaunchReport::default();
            for i in c * chunk..((c + 1) * chunk).min(total) {
                let index = UVec2::new((i % width as u64) as u32, (i / width as u64) as u32);
                run_index(&linked, index, &mut report);
            }
            report
        })
        .collect();
    let mut report = LaunchReport::default();
    for r in chunks {
        report.exceptions.extend(r.exceptions);
        report.prints.extend(r.prints);
        report.rays += r.rays;
    }
    report.timings = super::Timings { build: t1 - t0, encode: t2 - t1, link: Default::default(), run: t2.elapsed() };
    Ok(report)
}

fn run_index(l: &Linked<'_>, index: UVec2, report: &mut LaunchReport) {
    let lane = Lane::new(l, index);
    let base = ExecutionContext { launch_index: index, launch_dim: l.launch_dim, ..ExecutionContext::DEFAULT };
    lane.invoke(&l.ray_generation, base, None, None, 0);
    if let Some(code) = lane.exception.get() {
        report.exceptions.push(ExceptionRecord { launch_index: index, code });
        if let Some(ex) = &l.exception {
            let ctx = ExecutionContext { exception_code: code, ..base };
            lane.invoke(ex, ctx, None, None, 0);
        } else if let Some(v) = link::default_exception_output(l.ray_generation.desc)
            && let Some(out) = l.ray_generation.vars[v].downcast_ref::<RwBuffer2d<glam::Vec4>>()
        {
            // The default exception program: magenta at the launch index.
            let size = out.size();
            if index.x < size.x && index.y < size.y {
                out.store(index, link::EXCEPTION_COLOR);
            }
        }
    }
    report.rays += lane.rays.get();
    report.prints.extend(lane.prints.take().into_iter().map(|t| (index, t)));
}

/// The attributes of a hit: built-in triangle values (materialised in the
/// receiving program's attribute type) or a custom intersection's value.
enum HitAttributes {
    Triangle { geometric_normal: Vec3, shading_normal: Vec3, texcoord: Vec2, barycentrics: Vec2 },
    Custom(Box<dyn AnyAttributes>),
}

impl HitAttributes {
    /// The value a program with attribute type `layout` receives.
    fn materialise(&self, desc: &rt_std::program::ProgramDescriptor) -> Option<Box<dyn AnyAttributes>> {
        match self {
            HitAttributes::Custom(a) => Some(a.clone_box()),
            HitAttributes::Triangle { geometric_normal, shading_normal, texcoord, barycentrics } => {
                let (layout, make) = (desc.attributes?, desc.cpu_attributes?);
                Some(make(&triangle_words(&layout, *geometric_normal, *shading_normal, *texcoord, *barycentrics)))
            }
        }
    }
}

/// Heap words of an attribute struct with the built-in triangle attributes
/// filled by field name (other fields zero).
fn triangle_words(layout: &TypeLayout, gn: Vec3, sn: Vec3, uv: Vec2, bary: Vec2) -> Vec<u32> {
    let mut words = vec![0u32; layout.words as usize];
    for f in layout.fields {
        let o = f.offset_words as usize;
        match (f.name, f.ty) {
            ("geometric_normal", "Vec3") => gn.write_words(&mut words[o..]),
            ("shading_normal", "Vec3") => sn.write_words(&mut words[o..]),
            ("texcoord", "Vec2") => uv.write_words(&mut words[o..]),
            ("barycentrics", "Vec2") => bary.write_words(&mut words[o..]),
            _ => {}
        }
    }
    words
}

struct Committed {
    instance: u32,
    material: u32,
    primitive: u32,
    t: f32,
    attributes: HitAttributes,
    object_to_world: Mat4,
    world_to_object: Mat4,
}

/// The intersection program running now, for the protocol callbacks.
struct Candidate {
    instance: u32,
    primitive: u32,
    object_ray: Ray,
    object_to_world: Mat4,
    world_to_object: Mat4,
    t: Option<f32>,
}

/// One ray's search.
struct Search {
    ray_type: u32,
    flags: u32,
    world_ray: Ray,
    /// Closest accepted distance so far.
    tmax: f32,
    payload: *mut dyn Any,
    committed: Option<Committed>,
    candidate: Option<Candidate>,
    done: bool,
}

/// Per-launch-index state; also rt-std's [`Tracer`] for its programs.
struct Lane<'a> {
    l: &'a Linked<'a>,
    index: UVec2,
    depth: Cell<u32>,
    exception: Cell<Option<u32>>,
    prints: RefCell<Vec<String>>,
    rays: Cell<u64>,
    search: RefCell<Option<Search>>,
}

impl<'a> Lane<'a> {
    fn new(l: &'a Linked<'a>, index: UVec2) -> Self {
        Lane {
            l,
            index,
            depth: Cell::new(0),
            exception: Cell::new(None),
            prints: RefCell::new(Vec::new()),
            rays: Cell::new(0),
            search: RefCell::new(None),
        }
    }

    fn base_context(&self) -> ExecutionContext {
        ExecutionContext { launch_index: self.index, launch_dim: self.l.launch_dim, ..ExecutionContext::DEFAULT }
    }

    /// Calls a program; the first exception it raises is kept for the lane.
    fn invoke(
        &self,
        call: &Call,
        ctx: ExecutionContext,
        payload: Option<&mut dyn Any>,
        attributes: Option<&mut dyn Any>,
        primitive: u32,
    ) -> (CpuResult, ExecutionContext) {
        let refs = var_refs(call);
        let mut args = CpuArgs { payload, attributes, primitive, variables: &refs[..call.vars.len()] };
        let (r, out) = rt_std::cpu::with_tracer(ctx, self, || (call.desc.cpu)(&mut args));
        if let Some(code) = out.pending_exception
            && self.exception.get().is_none()
        {
            self.exception.set(Some(code));
        }
        (r, out)
    }

    fn done(&self) -> bool {
        self.search.borrow().as_ref().is_none_or(|s| s.done)
    }

    fn tmax(&self) -> f32 {
        self.search.borrow().as_ref().map_or(f32::NEG_INFINITY, |s| s.tmax)
    }

    fn traverse(&self, node: NodeId, o2w: Mat4, w2o: Mat4, mask: u32) {
        let ctx = self.l.ctx;
        let rec = &ctx.nodes[node.index() as usize];
        if (rec.visibility_mask as u32) & mask == 0 || self.done() {
            return;
        }
        let (world_ray, flags) = {
            let s = self.search.borrow();
            let s = s.as_ref().expect("inside a search");
            (s.world_ray, s.flags)
        };
        let origin = w2o.transform_point3(world_ray.origin);
        let direction = w2o.transform_vector3(world_ray.direction);
        let inv_dir = direction.recip();
        match &rec.kind {
            NodeKind::Transform { matrix, inverse, child } => {
                self.traverse(*child, o2w * *matrix, *inverse * w2o, mask)
            }
            NodeKind::Group { children, .. } => {
                let Some(Some(NodeAccel::Children { bvh, .. })) = self.l.accels.get(node.index() as usize) else {
                    return;
                };
                bvh.traverse(origin, inv_dir, world_ray.tmin, &|| self.tmax(), &mut |c| {
                    self.traverse(children[c as usize], o2w, w2o, mask);
                    !self.done()
                });
            }
            NodeKind::Selector { children, .. } => {
                let Some(call) = &self.l.visit[node.index() as usize] else { return };
                let payload = self.search.borrow().as_ref().map(|s| s.payload);
                // The ray in the selector's space, `tmax` the closest hit so far.
                let ctx = ExecutionContext {
                    current_ray: Ray { origin, direction, tmax: self.tmax(), ..world_ray },
                    ..self.base_context()
                };
                // SAFETY: the payload pointer comes from the `&mut` the trace
                // call holds for the whole search; nothing else uses it now.
                let payload = payload.map(|p| unsafe { &mut *p });
                let (r, _) = self.invoke(call, ctx, payload, None, 0);
                if let CpuResult::Child(c) = r
                    && let Some(child) = children.get(c as usize)
                {
                    self.traverse(*child, o2w, w2o, mask);
                }
            }
            NodeKind::GeometryGroup { .. } => {
                let Some(Some(NodeAccel::Prims { bvh, wide, prims, .. })) = self.l.accels.get(node.index() as usize)
                else {
                    return;
                };
                let object_ray = Ray { origin, direction, ..world_ray };
                match wide {
                    // obvhs's 8-wide traversal; the callback runs the whole
                    // hit protocol and returns the closest committed distance
                    // (unchanged if nothing committed), or -inf to stop.
                    Some(cw) => {
                        let mut hit = obvhs::ray::RayHit::none();
                        let ray = obvhs::ray::Ray::new(origin.into(), direction.into(), world_ray.tmin, self.tmax());
                        cw.ray_traverse(ray, &mut hit, |_, slot| {
                            let (gi, prim) = prims[cw.primitive_indices[slot] as usize];
                            self.intersect(gi, prim, object_ray, o2w, w2o, flags);
                            if self.done() { f32::NEG_INFINITY } else { self.tmax() }
                        });
                    }
                    None => bvh.traverse(origin, inv_dir, world_ray.tmin, &|| self.tmax(), &mut |p| {
                        let (gi, prim) = prims[p as usize];
                        self.intersect(gi, prim, object_ray, o2w, w2o, flags);
                        !self.done()
                    }),
                }
            }
        }
    }

    fn intersect(&self, gi: u32, prim: u32, object_ray: Ray, o2w: Mat4, w2o: Mat4, flags: u32) {
        let ctx = self.l.ctx;
        let rec = &ctx.instances[gi as usize];
        match &ctx.geometries[rec.geometry.index() as usize].kind {
            GeometryKind::Triangles(mesh) => {
                let tmax = self.tmax();
                let Some((t, u, v, front)) = intersect_triangle(mesh, prim as usize, &object_ray, tmax) else { return };
                if (front && flags & RAY_FLAG_CULL_FRONT_FACING != 0)
                    || (!front && flags & RAY_FLAG_CULL_BACK_FACING != 0)
                {
                    return;
                }
                let [i0, i1, i2] = mesh.indices[prim as usize].map(|i| i as usize);
                let [a, b, c] = [i0, i1, i2].map(|i| mesh.positions[i]);
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
                let material = mesh.material_indices.as_ref().map_or(0, |m| m[prim as usize]);
                let attributes = HitAttributes::Triangle {
                    geometric_normal: gn,
                    shading_normal: sn,
                    texcoord: uv,
                    barycentrics: Vec2::new(u, v),
                };
                self.candidate_hit(gi, prim, material, t, attributes, object_ray, o2w, w2o);
            }
            GeometryKind::Custom { .. } => {
                let Some(call) = &self.l.intersection[gi as usize] else { return };
                let tmax = self.tmax();
                if let Some(s) = self.search.borrow_mut().as_mut() {
                    s.candidate = Some(Candidate {
                        instance: gi,
                        primitive: prim,
                        object_ray,
                        object_to_world: o2w,
                        world_to_object: w2o,
                        t: None,
                    });
                }
                let ctx = ExecutionContext {
                    current_ray: Ray { tmax, ..object_ray },
                    primitive_index: prim,
                    object_to_world: o2w,
                    world_to_object: w2o,
                    ..self.base_context()
                };
                let mut attrs = call
                    .desc
                    .cpu_attributes
                    .map(|make| make(&vec![0u32; call.desc.attributes.map_or(0, |a| a.words) as usize]));
                let attr_ref = attrs.as_mut().map(|a| a.as_any_mut());
                self.invoke(call, ctx, None, attr_ref, prim);
                if let Some(s) = self.search.borrow_mut().as_mut() {
                    s.candidate = None;
                }
            }
        }
    }

    /// A candidate intersection at `t` (already inside `(tmin, closest)`):
    /// runs any hit and commits it unless ignored.
    #[allow(clippy::too_many_arguments)]
    fn candidate_hit(
        &self,
        gi: u32,
        prim: u32,
        material: u32,
        t: f32,
        attributes: HitAttributes,
        object_ray: Ray,
        o2w: Mat4,
        w2o: Mat4,
    ) -> bool {
        let (ray_type, flags, payload, world_ray) = {
            let s = self.search.borrow();
            let s = s.as_ref().expect("inside a search");
            (s.ray_type, s.flags, s.payload, s.world_ray)
        };
        let Some(per_ray) = self.l.hits[gi as usize].get(material as usize) else {
            // A material index the instance does not have: nothing to run.
            return false;
        };
        let (_, any_hit) = &per_ray[ray_type as usize];
        let mut terminate = flags & RAY_FLAG_TERMINATE_ON_FIRST_HIT != 0;
        if let Some(ah) = any_hit
            && flags & RAY_FLAG_DISABLE_ANYHIT == 0
        {
            let mut attrs = attributes.materialise(ah.desc);
            let ctx = ExecutionContext {
                current_ray: Ray { tmax: t, ..world_ray },
                t_hit: t,
                primitive_index: prim,
                object_to_world: o2w,
                world_to_object: w2o,
                ..self.base_context()
            };
            // SAFETY: see `traverse`: the search's payload is only used here.
            let payload = unsafe { &mut *payload };
            let (_, out) = self.invoke(ah, ctx, Some(payload), attrs.as_mut().map(|a| a.as_any_mut()), prim);
            if out.ignored {
                return false;
            }
            terminate |= out.terminated;
        }
        let _ = object_ray;
        if let Some(s) = self.search.borrow_mut().as_mut() {
            s.tmax = t;
            s.committed = Some(Committed {
                instance: gi,
                material,
                primitive: prim,
                t,
                attributes,
                object_to_world: o2w,
                world_to_object: w2o,
            });
            s.done |= terminate;
        }
        true
    }
}

impl Tracer for Lane<'_> {
    fn trace(&self, object: Object, ray: Ray, payload: &mut dyn Any, flags: u32, mask: u32) {
        if self.exception.get().is_some() || rt_std::cpu::pending_exception().is_some() {
            return;
        }
        let depth = self.depth.get();
        if depth >= self.l.ctx.max_trace_depth {
            rt_std::cpu::raise(EXCEPTION_TRACE_DEPTH_EXCEEDED);
            return;
        }
        let ctx = self.l.ctx;
        let node = NodeId(object.id);
        if object.id as usize >= ctx.nodes.len() || ray.ray_type >= ctx.ray_type_count() {
            rt_std::cpu::raise(EXCEPTION_INVALID_RAY);
            return;
        }
        self.depth.set(depth + 1);
        self.rays.set(self.rays.get() + 1);
        let outer = self.search.replace(Some(Search {
            ray_type: ray.ray_type,
            flags,
            world_ray: ray,
            tmax: ray.tmax,
            payload: payload as *mut dyn Any,
            committed: None,
            candidate: None,
            done: false,
        }));
        self.traverse(node, Mat4::IDENTITY, Mat4::IDENTITY, mask & 0xff);
        let search = self.search.replace(outer).expect("search in progress");
        match search.committed {
            Some(hit) => {
                let (closest, _) = &self.l.hits[hit.instance as usize][hit.material as usize][ray.ray_type as usize];
                if let Some(ch) = closest
                    && flags & RAY_FLAG_DISABLE_CLOSESTHIT == 0
                {
                    let mut attrs = hit.attributes.materialise(ch.desc);
                    let ctx = ExecutionContext {
                        current_ray: Ray { tmax: hit.t, ..ray },
                        t_hit: hit.t,
                        primitive_index: hit.primitive,
                        object_to_world: hit.object_to_world,
                        world_to_object: hit.world_to_object,
                        ..self.base_context()
                    };
                    self.invoke(ch, ctx, Some(payload), attrs.as_mut().map(|a| a.as_any_mut()), hit.primitive);
                }
            }
            None => {
                let ctx = ExecutionContext { current_ray: ray, ..self.base_context() };
                self.invoke(&self.l.miss[ray.ray_type as usize], ctx, Some(payload), None, 0);
            }
        }
        self.depth.set(depth);
    }

    fn potential_intersection(&self, t: f32) -> bool {
        let mut s = self.search.borrow_mut();
        let Some(s) = s.as_mut() else { return false };
        let tmax = s.tmax;
        let Some(c) = s.candidate.as_mut() else { return false };
        let ok = t > c.object_ray.tmin && t < tmax;
        c.t = if ok { Some(t) } else { None };
        if ok {
            rt_std::cpu::context_mut(|ctx| ctx.t_hit = t);
        }
        ok
    }

    fn report_intersection(&self, material: u32, attributes: Option<&dyn AnyAttributes>) -> bool {
        let cand = {
            let s = self.search.borrow();
            s.as_ref().and_then(|s| {
                s.candidate
                    .as_ref()
                    .map(|c| (c.instance, c.primitive, c.t, c.object_ray, c.object_to_world, c.world_to_object))
            })
        };
        let Some((gi, prim, Some(t), object_ray, o2w, w2o)) = cand else { return false };
        if t >= self.tmax() {
            return false;
        }
        let attrs = match attributes {
            Some(a) => HitAttributes::Custom(a.clone_box()),
            None => HitAttributes::Custom(Box::new(NoAttributes)),
        };
        self.candidate_hit(gi, prim, material, t, attrs, object_ray, o2w, w2o)
    }

    fn print(&self, text: &str) {
        let ctx = self.l.ctx;
        if ctx.print_enabled && ctx.print_launch_index.is_none_or(|i| i == self.index) {
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

/// Watertight ray/triangle intersection (Woop, Benthin and Wald, JCGT 2013):
/// no cracks between triangles sharing an edge. Returns `(t, u, v,
/// front_facing)` for `t` in `(tmin, tmax)`; `u`, `v` weight vertices 1 and 2.
fn intersect_triangle(mesh: &TriangleMesh, t: usize, ray: &Ray, tmax: f32) -> Option<(f32, f32, f32, bool)> {
    let [a, b, c] = mesh.indices[t].map(|i| mesh.positions[i as usize]);
    let d = ray.direction;
    let abs = d.abs();
    let kz = if abs.x > abs.y {
        if abs.x > abs.z { 0 } else { 2 }
    } else if abs.y > abs.z {
        1
    } else {
        2
    };
    let mut kx = (kz + 1) % 3;
    let mut ky = (kx + 1) % 3;
    if d[kz] < 0.0 {
        std::mem::swap(&mut kx, &mut ky);
    }
    if d[kz] == 0.0 {
        return None;
    }
    let sx = d[kx] / d[kz];
    let sy = d[ky] / d[kz];
    let sz = 1.0 / d[kz];
    let (pa, pb, pc) = (a - ray.origin, b - ray.origin, c - ray.origin);
    let ax = pa[kx] - sx * pa[kz];
    let ay = pa[ky] - sy * pa[kz];
    let bx = pb[kx] - sx * pb[kz];
    let by = pb[ky] - sy * pb[kz];
    let cx = pc[kx] - sx * pc[kz];
    let cy = pc[ky] - sy * pc[kz];
    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    if u == 0.0 || v == 0.0 || w == 0.0 {
        // Fall back to double precision on edges.
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
    let az = sz * pa[kz];
    let bz = sz * pb[kz];
    let cz = sz * pc[kz];
    let t_scaled = u * az + v * bz + w * cz;
    let t = t_scaled / det;
    if !(t > ray.tmin && t < tmax && t.is_finite()) {
        return None;
    }
    // u weights vertex a here; report weights of b and c.
    let (wa, wb, wc) = (u / det, v / det, w / det);
    let _ = wa;
    let front = d.dot((b - a).cross(c - a)) < 0.0;
    Some((t, wb, wc, front))
}
