//! The watertight ray/triangle test (Woop, Benthin and Wald, JCGT 2013) for
//! one triangle: the CPU backend's reference, which the packet test of
//! [`super::kernels`] reproduces bit for bit four triangles at a time.

use glam::{Vec3, Vec3A, Vec3Swizzles};

/// A ray prepared for watertight ray/triangle intersection (Woop, Benthin
/// and Wald, JCGT 2013: no cracks between triangles sharing an edge): the
/// axis permutation and shear depend on the direction only, so they are
/// computed once per ray and geometry group.
///
/// A vertex `p` relative to the origin is permuted so `kz`, the axis of the
/// direction's largest component, comes last (`kx`, `ky` the other two in
/// cyclic order), then sheared: `(p[kx] - sx p[kz], p[ky] - sy p[kz], sz
/// p[kz])`, three products and two differences, as the paper writes it.
pub(crate) struct WatertightRay {
    pub(crate) origin: Vec3A,
    // (Read by the CPU backend, which a browser build leaves out.)
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    pub(crate) direction: Vec3,
    pub(crate) tmin: f32,
    /// `kz`, 0 to 2 (`kx` is `kz + 1`, `ky` is `kz + 2`, modulo 3).
    pub(crate) kz: usize,
    /// `(sx, sy, sz)`: `d[kx] / d[kz]`, `d[ky] / d[kz]`, `1 / d[kz]`.
    pub(crate) shear: Vec3A,
}

impl WatertightRay {
    /// None for a direction without a non-zero component.
    ///
    /// The paper swaps `kx` and `ky` when `d[kz]` is negative, to keep the
    /// sign of the determinant for back-face culling. Here the swap would
    /// only negate `u`, `v`, `w`, the determinant and the scaled distance,
    /// exactly, leaving `t` and the barycentrics as they are (culling takes
    /// the facing from the geometric normal), so there is none.
    ///
    /// (Inlined: out of line, it cost the CPU backend 2% of its
    /// instructions and more of its time, once the packet walk called it
    /// too and the compiler stopped inlining it into `traverse`.)
    #[inline(always)]
    pub(crate) fn new(origin: Vec3, d: Vec3, tmin: f32) -> Option<Self> {
        let abs = d.abs();
        let kz = if abs.x > abs.y {
            if abs.x > abs.z { 0 } else { 2 }
        } else if abs.y > abs.z {
            1
        } else {
            2
        };
        let [dx, dy, dz] = Self::permuted(kz, d.into()).to_array();
        if dz == 0.0 {
            return None;
        }
        Some(WatertightRay {
            origin: origin.into(),
            direction: d,
            tmin,
            kz,
            shear: Vec3A::new(dx / dz, dy / dz, 1.0 / dz),
        })
    }

    /// `p` as `(p[kx], p[ky], p[kz])`. (A branch per call, but on a value
    /// fixed per ray: predicted.)
    #[inline(always)]
    pub(crate) fn permuted(kz: usize, p: Vec3A) -> Vec3A {
        match kz {
            0 => p.yzx(),
            1 => p.zxy(),
            _ => p,
        }
    }

    /// The rows of [`crate::accel::wide::Packet`] (and axes) holding a
    /// vertex's `kx`, `ky` and `kz` coordinates. (Read by the x86-64
    /// kernels only.)
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    pub(crate) fn axes(&self) -> [usize; 3] {
        [(self.kz + 1) % 3, (self.kz + 2) % 3, self.kz]
    }

    /// The hit with triangle `(a, b, c)` as `(t, u, v)` for `t` in `(tmin,
    /// tmax)`; `u`, `v` weight vertices `b` and `c`.
    #[inline(always)]
    pub(crate) fn intersect(&self, a: Vec3, b: Vec3, c: Vec3, tmax: f32) -> Option<(f32, f32, f32)> {
        let s = self.shear;
        let shear = |p: Vec3| {
            let q = Self::permuted(self.kz, Vec3A::from(p) - self.origin);
            Vec3A::new(q.x - s.x * q.z, q.y - s.y * q.z, s.z * q.z)
        };
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
