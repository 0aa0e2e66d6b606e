//! Triangles: the watertight ray/triangle test and the built-in attributes
//! of a triangle hit.

use crate::scene::TriangleMesh;
use glam::{Mat3A, Vec2, Vec3, Vec3A, Vec3Swizzles};
use rt_std::cpu::TriangleBuiltins;

/// The built-in attributes of triangle `prim` of `mesh`, with vertices `[a,
/// b, c]`, hit at barycentrics `(u, v)` (weights of vertices 1 and 2).
///
/// The vertices come by reference: copied as an argument, they went through
/// the stack in stores and loads of other widths (a stall).
pub(crate) fn triangle_builtins(
    mesh: &TriangleMesh,
    prim: u32,
    &[a, b, c]: &[Vec3; 3],
    u: f32,
    v: f32,
) -> TriangleBuiltins {
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
pub(crate) struct WatertightRay {
    pub(crate) origin: Vec3A,
    pub(crate) direction: Vec3,
    pub(crate) tmin: f32,
    /// The rows `e[kx] - sx * e[kz]` (a point's sheared x), `e[ky] - sy *
    /// e[kz]` (its sheared y) and `sz * e[kz]` (its scaled z). A vertex is
    /// sheared in one four-lane product, `(x * c0 + y * c1) + z * c2` over
    /// the columns, which sums each lane in the order of `Vec3::dot` over a
    /// row: the same values as three dot products, in a third of the
    /// instructions.
    pub(crate) shear: Mat3A,
}

impl WatertightRay {
    /// None for a direction without a non-zero component.
    ///
    /// The paper swaps `kx` and `ky` when `d[kz]` is negative, to keep the
    /// sign of the determinant for back-face culling. Here the swap would
    /// only negate `u`, `v`, `w`, the determinant and the scaled distance,
    /// exactly, leaving `t` and the barycentrics as they are (culling takes
    /// the facing from the geometric normal), so there is none.
    pub(crate) fn new(origin: Vec3, d: Vec3, tmin: f32) -> Option<Self> {
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
    pub(crate) fn intersect(&self, a: Vec3, b: Vec3, c: Vec3, tmax: f32) -> Option<(f32, f32, f32)> {
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
