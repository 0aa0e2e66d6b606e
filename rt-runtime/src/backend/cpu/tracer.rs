//! A lane as rt-std's [`Tracer`]: `rt_trace` and the other intrinsics that
//! need the runtime (reporting intersections, callables, bindless ids,
//! prints), served while its programs run as Rust.

use super::bind::Program;
use super::lane::{Hit, Lane, NoAttributes, Search, set_current_ray, set_transforms};
use super::triangle::front_or_back;
use super::triangle::{geometric_normal, triangle_builtins};
use crate::handles::{BufferId, SamplerId};
use crate::link::instances::{self, InstancePath};
use crate::scene::{NodeId, ProgramId};
use glam::{Vec2, Vec3};
use rt_std::cpu::lanes::LANES;
use rt_std::cpu::{AnyAttributes, ExecutionContext, HIT_CUSTOM, Tracer};
use rt_std::*;
use std::any::Any;
use std::cell::{Cell, RefCell};

impl Tracer for Lane<'_> {
    fn trace(&self, object: Object, ray: &Ray, payload: &mut dyn Any, flags: u32, mask: u32, time: f32) {
        self.sync_block_lane();
        if !self.may_trace(object, ray) {
            return;
        }
        let node = NodeId(object.id);
        let mut search = Search::new(ray, payload, flags, mask, node);
        // The pointer's lifetime is erased; it is restored below, before
        // `search` (and the ray it borrows) go away.
        let outer = self.search.replace((&search as *const Search<'_>).cast());
        self.rays.set(self.rays.get() + 1);
        let (depth, outer_time) = self.enter_trace(time);
        self.traverse(&search, node, None, mask & 0xff, InstancePath::ROOT);
        self.search.set(outer);
        self.hand_over(&mut search, ray, payload, flags, mask);
        self.leave_trace(depth, outer_time);
    }

    #[allow(clippy::too_many_arguments)]
    fn trace_lanes(
        &self,
        mask: &rt_std::cpu::lanes::Mask,
        objects: &[Object; LANES],
        rays: &[Ray; LANES],
        payloads: &mut [Option<&mut dyn Any>; LANES],
        flags: u32,
        ray_mask: u32,
        time: f32,
    ) {
        self.trace_packet(mask, objects, rays, payloads, flags, ray_mask, time);
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

    fn callable(&self, id: u32, caller: u32) -> Option<&'static (dyn std::any::Any + Send + Sync)> {
        let program = |id| self.l.scene.programs.get(ProgramId::from_callable_id(id)?.index() as usize);
        let rec = program(id)?;
        // As the wgpu kernel's dispatch functions do, a callable's calls
        // leave its own program out (`link::callables`).
        if program(caller).is_some_and(|c| crate::link::callables::calls_itself(c.desc, rec.desc)) {
            return None;
        }
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
        self.sync_block_lane();
        let settings = self.l.settings;
        if settings.print_enabled && settings.print_launch_index.is_none_or(|i| i == self.index.get()) {
            self.prints.borrow_mut().push(text.to_string());
        }
    }
}

impl<'r> Search<'r> {
    /// A search for `ray` from `node`, nothing found yet.
    pub(crate) fn new(ray: &'r Ray, payload: &mut dyn Any, flags: u32, mask: u32, node: NodeId) -> Search<'r> {
        Search {
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
        }
    }
}

impl<'a> Lane<'a> {
    /// Whether a trace of `ray` against `object` goes ahead: not after an
    /// exception, not past the depth limit (raised), not of a node or ray
    /// type the scene lacks (raised).
    pub(crate) fn may_trace(&self, object: Object, ray: &Ray) -> bool {
        self.may_trace_after(self.exception.get().is_some(), object, ray)
    }

    /// [`Lane::may_trace`] for a launch index whose programs raised an
    /// exception already, or not (`raised`).
    pub(crate) fn may_trace_after(&self, raised: bool, object: Object, ray: &Ray) -> bool {
        if raised || rt_std::cpu::pending_exception().is_some() {
            return false;
        }
        let l = self.l;
        if self.depth.get() >= l.settings.max_trace_depth {
            rt_std::cpu::raise(EXCEPTION_TRACE_DEPTH_EXCEEDED);
            return false;
        }
        if object.id as usize >= l.scene.nodes.len() || ray.ray_type >= l.scene.ray_type_count() {
            rt_std::cpu::raise(EXCEPTION_INVALID_RAY);
            return false;
        }
        true
    }

    /// A trace's start: one level deeper, at `time`; the depth and time to
    /// go back to. (The caller counts its rays.)
    pub(crate) fn enter_trace(&self, time: f32) -> (u32, f32) {
        let depth = self.depth.get();
        self.depth.set(depth + 1);
        (depth, self.time.replace(time))
    }

    /// A trace's end (see [`Lane::enter_trace`]).
    pub(crate) fn leave_trace(&self, depth: u32, time: f32) {
        self.time.set(time);
        self.depth.set(depth);
    }

    /// The end of a search: its closest hit to the closest-hit program of
    /// the hit's material and the ray's type, or the ray to the ray type's
    /// miss program.
    pub(crate) fn hand_over(&self, search: &mut Search<'_>, ray: &Ray, payload: &mut dyn Any, flags: u32, mask: u32) {
        let mut attributes = search.attributes.take();
        if let Some((program, mut ctx)) = self.handed_to(search, ray, flags, mask, &mut attributes) {
            self.invoke(program, &mut ctx, Some(payload), attributes.as_mut());
        }
        if let Some(a) = attributes {
            self.return_attributes(a);
        }
    }

    /// The program a finished search goes to (the closest-hit program of
    /// the hit's material and the ray's type, or the ray type's miss
    /// program; none where there is none or the ray's flags skip it) and
    /// its call's context, at the loaded launch index. A triangle hit's
    /// attributes are made into `attributes` where the program takes them.
    pub(crate) fn handed_to<'s>(
        &self,
        search: &'s mut Search<'_>,
        ray: &Ray,
        flags: u32,
        mask: u32,
        attributes: &mut Option<Box<dyn AnyAttributes>>,
    ) -> Option<(&'a Program<'a>, ExecutionContext<'s>)> {
        let l = self.l;
        // Read in place: a copy of the hit would load the fields its last
        // commit stored one by one in wider words (a stall).
        let Some(hit) = search.committed.get_mut() else {
            let miss = l.miss[ray.ray_type as usize].as_ref()?;
            let mut ctx = self.context();
            ctx.ray_flags = flags;
            ctx.ray_mask = mask & 0xff;
            set_current_ray(&mut ctx, ray, ray.tmax);
            return Some((miss, ctx));
        };
        let (closest, _) = &l.hits[hit.instance as usize][hit.material as usize][ray.ray_type as usize];
        let ch = closest.as_ref().filter(|_| flags & RAY_FLAG_DISABLE_CLOSESTHIT == 0)?;
        let mesh = l.meshes[hit.instance as usize];
        // The geometric normal, once: the attributes and the side of the
        // triangle both take it.
        let normal = mesh.map(|_| geometric_normal(&hit.vertices));
        if let (Some(mesh), Some(normal), Some(ty)) = (mesh, normal, &ch.attributes) {
            let (u, v) = hit.barycentrics.into();
            let values = triangle_builtins(mesh, hit.primitive, normal, u, v);
            if let Some(old) = attributes.replace(self.attributes_of(ty, Some(&values))) {
                self.return_attributes(old);
            }
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
        Some((ch, ctx))
    }
}
