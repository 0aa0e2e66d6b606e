//! The tests one lane at a time: the path for targets without SSE4.1 or
//! AVX2 (and `RT_CPU_SIMD=scalar`), and the definition the SIMD paths
//! match.

use super::{FAR_SCALE, Hits, Kernels, NEAR_SLACK, WalkRay, max_sse, min_sse};
use crate::accel::wide::watertight::WatertightRay;
use crate::accel::wide::{Node, PACKET, Packet, WIDTH};
use glam::Vec3;

pub(crate) struct Scalar;

pub(crate) struct ScalarRay<'a> {
    origin: [f32; 3],
    inv: [f32; 3],
    tmin: f32,
    near: [usize; 3],
    triangle: Option<&'a WatertightRay>,
}

impl Kernels for Scalar {
    type Ray<'a> = ScalarRay<'a>;

    fn ray<'a>(ray: &WalkRay<'a>) -> ScalarRay<'a> {
        ScalarRay {
            origin: ray.origin.to_array(),
            inv: ray.inv_dir.to_array(),
            tmin: ray.tmin,
            near: ray.near_rows(),
            triangle: ray.triangle,
        }
    }

    #[inline(always)]
    fn node(node: &Node, ray: &ScalarRay, tmax: f32) -> (u32, [f32; WIDTH]) {
        let mut tnear = [0.0; WIDTH];
        let mut mask = 0;
        for (i, out) in tnear.iter_mut().enumerate() {
            let (mut near, mut far) = (ray.tmin, f32::INFINITY);
            for axis in (0..3).rev() {
                let n = ray.near[axis];
                let f = n ^ 1;
                let tn = (node.planes[n][i] - ray.origin[axis]) * ray.inv[axis];
                let tf = (node.planes[f][i] - ray.origin[axis]) * ray.inv[axis];
                near = max_sse(tn, near);
                far = min_sse(tf, far);
            }
            let far = min_sse(far * FAR_SCALE, tmax);
            let near = near - near.abs() * NEAR_SLACK;
            *out = near;
            mask |= ((near <= far) as u32) << i;
        }
        (mask, tnear)
    }

    #[inline(always)]
    fn packet(packet: &Packet, ray: &ScalarRay, tmax: f32) -> Hits {
        let mut hits = Hits::default();
        let Some(tri) = ray.triangle else { return hits };
        for lane in 0..PACKET {
            let [a, b, c]: [Vec3; 3] = packet.vertices(lane);
            if let Some((t, u, v)) = tri.intersect(a, b, c, tmax) {
                hits.mask |= 1 << lane;
                (hits.t[lane], hits.u[lane], hits.v[lane]) = (t, u, v);
            }
        }
        hits
    }
}
