//! A seam for the test suite (not an API): one flat triangle mesh as the
//! CPU backend lays it out, walked on a chosen instruction set, beside the
//! traversal it replaced (obvhs's CWBVH walk with the same watertight
//! test), so the two can be compared on real scenes ray by ray.

use super::collapse::collapse;
use super::isa::{Isa, walk_on};
use super::kernels::WalkRay;
pub use super::packet_walk::PACKET_RAYS;
use super::watertight::WatertightRay;
use super::{PACKET, WideBvh, leaf_of};
use crate::accel::Builder;
use crate::accel::bvh::{Bvh, TreeForm, build, to_oaabb, widen};
use glam::Vec3;

/// A mesh's trees: its BVH2 (built as the CPU backend builds a geometry
/// group's), that BVH2 collapsed to the SIMD layout and widened to
/// obvhs's CWBVH.
pub struct Triangles {
    triangles: Vec<[Vec3; 3]>,
    #[allow(dead_code)]
    bvh: Bvh,
    wide: WideBvh,
    cw: obvhs::cwbvh::CwBvh,
}

/// A closest hit: distance, triangle, barycentrics.
pub type Closest = (f32, u32, f32, f32);

impl Triangles {
    pub fn new(triangles: Vec<[Vec3; 3]>) -> Triangles {
        // Bounds over the finite coordinates (a test's NaN triangles are
        // still built into the tree; the runtime refuses NaN vertices).
        let finite = |v: Vec3, keep: Vec3| Vec3::select(v.cmpeq(v), v, keep);
        let bounds: Vec<_> = triangles
            .iter()
            .map(|&[a, b, c]| {
                let (b, c) = (finite(b, a), finite(c, a));
                to_oaabb(a.min(b).min(c), a.max(b).max(c))
            })
            .collect();
        let bvh = build(Builder::Bvh, &bounds, None, TreeForm::Wide).expect("Bvh builds any bounds");
        let wide = collapse(&bvh.bvh, Some(&|p: u32| triangles[p as usize]));
        let cw = widen(&bvh);
        Triangles { triangles, bvh, wide, cw }
    }

    /// (nodes, leaves, depth) of the SIMD layout.
    pub fn shape(&self) -> (usize, usize, u32) {
        (self.wide.nodes.len(), self.wide.slots.len() / PACKET, self.wide.depth)
    }

    /// The closest hit in `(tmin, tmax)` by the SIMD layout's walk on `isa`
    /// (which must be supported), committed as the CPU backend commits:
    /// lane by lane, a hit closer than the closest so far.
    pub fn closest(&self, isa: Isa, origin: Vec3, direction: Vec3, tmin: f32, tmax: f32) -> Option<Closest> {
        assert!(isa.supported(), "{} is not supported here", isa.name());
        let prepared = WatertightRay::new(origin, direction, tmin);
        let ray = WalkRay { origin, inv_dir: direction.recip(), tmin, triangle: prepared.as_ref() };
        let mut best: Option<Closest> = None;
        let mut limit = tmax;
        walk_on(isa, &self.wide, &ray, tmax, |leaf, hits| {
            let (index, _) = leaf_of(leaf);
            let hits = hits?;
            for lane in 0..PACKET {
                if hits.mask & (1 << lane) != 0 && hits.t[lane] < limit {
                    limit = hits.t[lane];
                    best = Some((limit, self.wide.slots[index as usize * PACKET + lane], hits.u[lane], hits.v[lane]));
                }
            }
            Some(limit)
        });
        best
    }

    /// The closest hits of up to [`PACKET_RAYS`](super::packet_walk::PACKET_RAYS)
    /// rays `(origin, direction, tmin)` walked as one packet on `isa` (which
    /// must be supported; a packet on AVX2, else one by one), each up to
    /// infinity, into `out`.
    pub fn closest_packet(&self, isa: Isa, rays: &[(Vec3, Vec3, f32)], out: &mut [Option<Closest>]) {
        assert!(isa.supported(), "{} is not supported here", isa.name());
        assert!(rays.len() <= PACKET_RAYS && out.len() >= rays.len());
        let n = rays.len();
        if n == 0 {
            return;
        }
        // (On the stack: this is what rt-bench times.)
        let prepared: [Option<WatertightRay>; PACKET_RAYS] = std::array::from_fn(|i| {
            let (o, d, tmin) = rays[i.min(n - 1)];
            WatertightRay::new(o, d, tmin)
        });
        let walk: [WalkRay; PACKET_RAYS] = std::array::from_fn(|i| {
            let (origin, d, tmin) = rays[i.min(n - 1)];
            WalkRay { origin, inv_dir: d.recip(), tmin, triangle: prepared[i].as_ref() }
        });
        let mut limits = [f32::INFINITY; PACKET_RAYS];
        out[..n].fill(None);
        super::packet_walk::walk_packet(isa, &self.wide, &walk[..n], &mut limits[..n], |ray, leaf, hits| {
            let (index, _) = leaf_of(leaf);
            // The ray's closest hit so far is the one in `out`.
            let mut limit = out[ray].map_or(f32::INFINITY, |h| h.0);
            for lane in 0..PACKET {
                if hits.mask & (1 << lane) != 0 && hits.t[lane] < limit {
                    limit = hits.t[lane];
                    out[ray] =
                        Some((limit, self.wide.slots[index as usize * PACKET + lane], hits.u[lane], hits.v[lane]));
                }
            }
            limit
        });
    }

    /// The same by the traversal the CPU backend had before: obvhs's CWBVH
    /// walk, one watertight test per triangle.
    pub fn closest_cwbvh(&self, origin: Vec3, direction: Vec3, tmin: f32, tmax: f32) -> Option<Closest> {
        let prepared = WatertightRay::new(origin, direction, tmin)?;
        let mut best: Option<Closest> = None;
        let mut limit = tmax;
        let mut hit = obvhs::ray::RayHit::none();
        let ray = obvhs::ray::Ray::new(origin.into(), direction.into(), tmin, tmax);
        self.cw.ray_traverse(ray, &mut hit, |_, slot| {
            let p = self.cw.primitive_indices[slot];
            let [a, b, c] = self.triangles[p as usize];
            if let Some((t, u, v)) = prepared.intersect(a, b, c, limit) {
                limit = t;
                best = Some((t, p, u, v));
            }
            limit
        });
        best
    }

    /// The same by testing every triangle in index order.
    pub fn closest_brute_force(&self, origin: Vec3, direction: Vec3, tmin: f32, tmax: f32) -> Option<Closest> {
        let prepared = WatertightRay::new(origin, direction, tmin)?;
        let mut best: Option<Closest> = None;
        let mut limit = tmax;
        for (p, [a, b, c]) in self.triangles.iter().enumerate() {
            if let Some((t, u, v)) = prepared.intersect(*a, *b, *c, limit) {
                limit = t;
                best = Some((t, p as u32, u, v));
            }
        }
        best
    }

    /// The triangles, in primitive order.
    pub fn triangles(&self) -> &[[Vec3; 3]] {
        &self.triangles
    }

    /// Whether triangle `p` is hit at exactly `t` (a tie with another
    /// triangle's hit: two traversals may commit either).
    pub fn hits_at(&self, p: u32, origin: Vec3, direction: Vec3, tmin: f32, t: f32) -> bool {
        let [a, b, c] = self.triangles[p as usize];
        WatertightRay::new(origin, direction, tmin)
            .and_then(|r| r.intersect(a, b, c, f32::INFINITY))
            .is_some_and(|(th, _, _)| th == t)
    }
}
