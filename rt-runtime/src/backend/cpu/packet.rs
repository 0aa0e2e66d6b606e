//! The rays of a lane-wise trace (`Tracer::trace_lanes`) searched as one
//! packet where the scene allows: every lane's ray against the same
//! geometry group of fixed triangles with no any-hit program for the ray
//! type, in a SIMD tree with packets, walked by
//! [`walk_packet`](crate::accel::wide::packet_walk::walk_packet). The
//! lanes' hits then go to their closest-hit (or miss) programs, lane-wise
//! where a program has the form (`hit_block.rs`). Anything else (a
//! transform, a group over several children, custom primitives, any-hit
//! programs, moving vertices) is traced lane by lane.

use super::lane::{Lane, Search};
use crate::accel::cache::NodeAccel;
use crate::accel::wide::kernels::WalkRay;
use crate::accel::wide::packet_walk::walk_packet;
use crate::accel::wide::watertight::WatertightRay;
use crate::link::instances::InstancePath;
use crate::scene::{NodeId, NodeKind};
use rt_std::cpu::Tracer;
use rt_std::cpu::lanes::{LANES, Mask, enter_lane};
use rt_std::{Object, Ray};
use std::any::Any;

impl Lane<'_> {
    /// [`Tracer::trace_lanes`]: see the module's doc.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn trace_packet(
        &self,
        mask: &Mask,
        objects: &[Object; LANES],
        rays: &[Ray; LANES],
        payloads: &mut [Option<&mut dyn Any>; LANES],
        flags: u32,
        ray_mask: u32,
        time: f32,
    ) {
        // The lanes whose trace goes ahead, each checked in its own
        // context against its first exception (kept in the block, so no
        // lane's state is loaded for it).
        self.store_block_lane();
        let mut go: Mask = [false; LANES];
        for l in 0..LANES {
            if mask[l] && payloads[l].is_some() {
                enter_lane(l);
                go[l] = self.may_trace_after(self.block.exceptions[l].get().is_some(), objects[l], &rays[l]);
            }
        }
        let Some(group) = self.packet_group(&go, objects, rays, ray_mask) else {
            for l in 0..LANES {
                if let (true, Some(p)) = (go[l], payloads[l].as_deref_mut()) {
                    // (`trace` loads the lane's state.)
                    enter_lane(l);
                    self.trace(objects[l], &rays[l], p, flags, ray_mask, time);
                }
            }
            return;
        };
        let l = self.l;
        let Some(Some(NodeAccel::Prims { simd: Some(tree), prims, .. })) = l.accels.get(group.index() as usize) else {
            return;
        };
        let mut lanes = [0usize; LANES];
        let mut n = 0;
        for (i, g) in go.iter().enumerate() {
            if *g {
                lanes[n] = i;
                n += 1;
            }
        }
        let lanes = &lanes[..n];
        let mut searches: [Option<Search<'_>>; LANES] = Default::default();
        for (k, &i) in lanes.iter().enumerate() {
            let payload = payloads[i].as_deref_mut().expect("a lane that traces has a payload");
            let s = Search::new(&rays[i], payload, flags, ray_mask, NodeId(objects[i].id));
            s.group.set((InstancePath::ROOT, group));
            searches[k] = Some(s);
        }
        let prepared: [Option<WatertightRay>; LANES] = std::array::from_fn(|k| {
            let r = &rays[lanes[k.min(n - 1)]];
            WatertightRay::new(r.origin, r.direction, r.tmin)
        });
        let walk: [WalkRay; LANES] = std::array::from_fn(|k| {
            let r = &rays[lanes[k.min(n - 1)]];
            WalkRay { origin: r.origin, inv_dir: r.direction.recip(), tmin: r.tmin, triangle: prepared[k].as_ref() }
        });
        let mut limits: [f32; LANES] = std::array::from_fn(|k| rays[lanes[k.min(n - 1)]].tmax);
        self.rays.set(self.rays.get() + n as u64);
        let (depth, outer_time) = self.enter_trace(time);
        walk_packet(self.isa, tree, &walk[..n], &mut limits[..n], |k, leaf, hits| {
            let (Some(s), Some(ray)) = (searches[k].as_ref(), prepared[k].as_ref()) else { return f32::NEG_INFINITY };
            self.leaf_hits(s, ray, tree, prims, leaf, hits, None);
            s.tmax.get()
        });
        self.leave_trace(depth, outer_time);
        self.hand_over_lanes(lanes, &mut searches, rays, payloads, flags, ray_mask, time);
    }

    /// The geometry group the lanes of `go` all search as a packet, if
    /// there is one (see the module's doc).
    fn packet_group(&self, go: &Mask, objects: &[Object; LANES], rays: &[Ray; LANES], ray_mask: u32) -> Option<NodeId> {
        let first = go.iter().position(|&g| g)?;
        let (object, ray_type) = (objects[first].id, rays[first].ray_type);
        if (0..LANES).any(|l| go[l] && (objects[l].id != object || rays[l].ray_type != ray_type)) {
            return None;
        }
        let l = self.l;
        let mut node = NodeId(object);
        let children = loop {
            let rec = &l.scene.nodes[node.index() as usize];
            if (rec.visibility_mask as u32) & ray_mask & 0xff == 0 {
                return None;
            }
            match &rec.kind {
                NodeKind::Group { children, .. } if children.len() == 1 => node = children[0],
                NodeKind::GeometryGroup { children, .. } => break children,
                _ => return None,
            }
        };
        let Some(Some(NodeAccel::Prims { simd: Some(tree), .. })) = l.accels.get(node.index() as usize) else {
            return None;
        };
        let plain = children.iter().all(|c| {
            let gi = c.index() as usize;
            l.meshes[gi].is_some() && l.vertex_motion[gi].is_none() && !l.any_hit[gi][ray_type as usize]
        });
        (plain && tree.has_packets()).then_some(node)
    }
}
