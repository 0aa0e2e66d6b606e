//! A lane's search for a ray's hits: the node graph walked (groups' BVH2s,
//! transforms, selectors, geometry groups' SIMD trees), triangles tested
//! and committed, any-hit and intersection programs called in place.

use super::bind::Program;
use super::lane::{Candidate, Hit, Lane, Search, Xf, set_current_ray, set_transforms, under};
use super::triangle::{geometric_normal, triangle_builtins};
use crate::accel::cache::NodeAccel;
use crate::accel::wide::isa::walk_on;
use crate::accel::wide::kernels::{Hits, WalkRay};
use crate::accel::wide::watertight::WatertightRay;
use crate::accel::wide::{PACKET, WideBvh, leaf_of};
use crate::link::instances::{self, InstancePath};
use crate::motion::MotionTransform;
use crate::scene::{NodeId, NodeKind, NodeRec, TriangleMesh};
use glam::{Vec2, Vec3};
use rt_std::cpu::{AnyAttributes, CpuResult, HIT_TRIANGLE_BACK, HIT_TRIANGLE_FRONT};
use rt_std::*;

impl Lane<'_> {
    /// The instance index and id of geometry instance `gi` in the geometry
    /// group being searched.
    fn instance_of(&self, s: &Search, gi: u32) -> (u32, u32) {
        let (path, group) = s.group.get();
        instances::resolve(self.l.scene, path, group, gi)
    }

    pub(crate) fn traverse(&self, s: &Search, node: NodeId, xf: Option<&Xf>, mask: u32, path: InstancePath) {
        let l = self.l;
        let Some((node, rec)) = self.entered(s, node, mask) else { return };
        let world_ray = s.world_ray;
        let (origin, direction) = match xf {
            None => (world_ray.origin, world_ray.direction),
            Some(x) => (
                x.world_to_object.transform_point3(world_ray.origin),
                x.world_to_object.transform_vector3(world_ray.direction),
            ),
        };
        match &rec.kind {
            NodeKind::Transform { motion, child, .. } => {
                self.enter_transform(s, node, motion.as_deref(), *child, xf, mask, path.through(rec.instance_id))
            }
            NodeKind::Group { children, .. } => {
                self.search_group(s, node, children, xf, mask, path, (origin, direction))
            }
            NodeKind::Selector { children, .. } => {
                self.visit_selector(s, node, children, xf, mask, path, (origin, direction))
            }
            NodeKind::GeometryGroup { .. } => {
                let Some(Some(NodeAccel::Prims { bvh: Some(bvh), simd, prims, .. })) =
                    l.accels.get(node.index() as usize)
                else {
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
                        // (The walk tests packets only with a setup.)
                        Some(hits) => {
                            if self.leaf_hits(s, prepared.as_ref()?, tree, prims, leaf, hits, xf) {
                                return None;
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

    /// A leaf's triangle hits (a packet's lanes) for search `s`: each, in
    /// lane order, against the closest hit so far (an earlier lane may have
    /// committed a closer one); whether the search is done.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn leaf_hits(
        &self,
        s: &Search,
        ray: &WatertightRay,
        tree: &WideBvh,
        prims: &[(u32, u32)],
        leaf: u32,
        hits: &Hits,
        xf: Option<&Xf>,
    ) -> bool {
        let (index, count) = leaf_of(leaf);
        let slots = &tree.slots[index as usize * PACKET..][..count as usize];
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
            if let Some(mesh) = self.l.meshes[gi as usize] {
                let vertices = tree.packets[index as usize].vertices(lane);
                self.triangle_hit(s, ray, mesh, gi, prim, (t, hits.u[lane], hits.v[lane]), vertices, xf);
            }
            if s.done.get() {
                return true;
            }
        }
        false
    }

    /// The node the search enters at `node`: past groups of one child (a
    /// scene's usual top group: its own tree tests the ray first thing, so
    /// the group's box test would be repeated; the child is searched in
    /// this call, not a nested one); none where the ray's `mask` hides it
    /// or the search is done.
    #[inline(always)]
    fn entered(&self, s: &Search, mut node: NodeId, mask: u32) -> Option<(NodeId, &'_ NodeRec)> {
        loop {
            let rec = &self.l.scene.nodes[node.index() as usize];
            if (rec.visibility_mask as u32) & mask == 0 || s.done.get() {
                return None;
            }
            match &rec.kind {
                NodeKind::Group { children, .. } if children.len() == 1 => node = children[0],
                _ => return Some((node, rec)),
            }
        }
    }

    /// The search through group `node`'s BVH2 over its children, the ray in
    /// the group's space (`ray`: origin and direction).
    #[allow(clippy::too_many_arguments)]
    fn search_group(
        &self,
        s: &Search,
        node: NodeId,
        children: &[NodeId],
        xf: Option<&Xf>,
        mask: u32,
        path: InstancePath,
        (origin, direction): (Vec3, Vec3),
    ) {
        let l = self.l;
        let Some(Some(NodeAccel::Children { bvh, .. })) = l.accels.get(node.index() as usize) else {
            return;
        };
        let offsets = &l.instance_offsets[node.index() as usize];
        bvh.traverse(origin, direction.recip(), s.world_ray.tmin, &|| s.tmax.get(), &mut |c| {
            self.traverse(s, children[c as usize], xf, mask, path.child(offsets[c as usize]));
            !s.done.get()
        });
    }

    /// The search below transform `node` (of motion `motion`, if it
    /// moves): the child under the transform composed with `xf`.
    #[allow(clippy::too_many_arguments)]
    fn enter_transform(
        &self,
        s: &Search,
        node: NodeId,
        motion: Option<&MotionTransform>,
        child: NodeId,
        xf: Option<&Xf>,
        mask: u32,
        path: InstancePath,
    ) {
        match motion {
            Some(motion) => {
                // The transform at the ray's time; an instant where it has no
                // inverse hides the child.
                let m = motion.matrix_at(self.time.get());
                let det = m.determinant();
                if det == 0.0 || !det.is_finite() {
                    return;
                }
                let own = Xf { object_to_world: m, world_to_object: m.inverse() };
                let composed = xf.map_or(own, |x| under(x, &own));
                self.traverse(s, child, Some(&composed), mask, path)
            }
            None => {
                // The launch holds every static transform's matrices.
                let Some(own) = self.l.transforms.get(node.index() as usize).and_then(Option::as_ref) else { return };
                match xf {
                    // Under no other transform: the node's own matrices,
                    // borrowed, not their products with the identity.
                    None => self.traverse(s, child, Some(own), mask, path),
                    Some(x) => self.traverse(s, child, Some(&under(x, own)), mask, path),
                }
            }
        }
    }

    /// The search below selector `node`: its visit program, run on the ray
    /// in the selector's space (`ray`: origin and direction), chooses the
    /// child searched.
    #[allow(clippy::too_many_arguments)]
    fn visit_selector(
        &self,
        s: &Search,
        node: NodeId,
        children: &[NodeId],
        xf: Option<&Xf>,
        mask: u32,
        path: InstancePath,
        (origin, direction): (Vec3, Vec3),
    ) {
        let l = self.l;
        let Some(call) = &l.visit[node.index() as usize] else { return };
        // The ray in the selector's space, `tmax` the closest hit so far.
        let mut ctx = self.context();
        ctx.current_ray = Ray { origin, direction, tmax: s.tmax.get(), ..*s.world_ray };
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
