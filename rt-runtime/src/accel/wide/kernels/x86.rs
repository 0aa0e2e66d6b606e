//! The tests in SSE4.1 (four lanes; a node's boxes as two halves) and AVX2
//! (a node's eight boxes in one register; the triangle packet in four
//! lanes, VEX-encoded). No fused multiply-adds: the answers stay the
//! scalar path's, bit for bit.
//!
//! These functions are `#[inline(always)]` without target features of
//! their own: they are only called from the walk's entry points in
//! [`super::super::isa`], compiled with the features, into which they are
//! inlined; only those entry points are reached, after detection.

use super::{FAR_SCALE, Hits, Kernels, NEAR_SLACK, WalkRay};
use crate::accel::wide::watertight::WatertightRay;
use crate::accel::wide::{Node, Packet, WIDTH};
use std::arch::x86_64::*;

pub(crate) struct Sse41;
pub(crate) struct Avx2;

/// The packet test's ray: the origin's coordinates and the shear in the
/// permuted order (`kx`, `ky`, `kz`), broadcast, and the packet rows of a
/// vertex's `kx`, `ky`, `kz` coordinates.
#[derive(Clone, Copy)]
pub(crate) struct TriangleRay {
    origin: [__m128; 3],
    shear: [__m128; 3],
    axes: [usize; 3],
    tmin: __m128,
    ready: bool,
}

/// The box test's ray, in lanes of width `V`.
#[derive(Clone, Copy)]
pub(crate) struct BoxRay<V> {
    origin: [V; 3],
    inv: [V; 3],
    tmin: V,
    near: [usize; 3],
}

pub(crate) struct X86Ray<V> {
    boxes: BoxRay<V>,
    triangle: TriangleRay,
}

#[inline(always)]
pub(crate) fn triangle_ray(ray: &WalkRay) -> TriangleRay {
    // SAFETY: SSE is part of x86_64.
    unsafe {
        match ray.triangle {
            Some(t) => {
                let o = WatertightRay::permuted(t.kz, t.origin);
                let s = t.shear;
                TriangleRay {
                    origin: [_mm_set1_ps(o.x), _mm_set1_ps(o.y), _mm_set1_ps(o.z)],
                    shear: [_mm_set1_ps(s.x), _mm_set1_ps(s.y), _mm_set1_ps(s.z)],
                    axes: t.axes(),
                    tmin: _mm_set1_ps(t.tmin),
                    ready: true,
                }
            }
            None => {
                let z = _mm_setzero_ps();
                TriangleRay { origin: [z; 3], shear: [z; 3], axes: [0, 1, 2], tmin: z, ready: false }
            }
        }
    }
}

/// The watertight test of four triangles, lane by lane as
/// `WatertightRay::intersect` computes one.
#[inline(always)]
pub(crate) unsafe fn packet4(packet: &Packet, r: &TriangleRay, tmax: f32) -> Hits {
    let mut hits = Hits::default();
    if !r.ready {
        return hits;
    }
    unsafe {
        let row = |k: usize| _mm_load_ps(packet.v[k].as_ptr());
        // A vertex (rows `k..k + 3`) relative to the origin, permuted and
        // sheared as `WatertightRay::intersect` does one.
        let shear = |k: usize| {
            let x = _mm_sub_ps(row(k + r.axes[0]), r.origin[0]);
            let y = _mm_sub_ps(row(k + r.axes[1]), r.origin[1]);
            let z = _mm_sub_ps(row(k + r.axes[2]), r.origin[2]);
            [
                _mm_sub_ps(x, _mm_mul_ps(r.shear[0], z)),
                _mm_sub_ps(y, _mm_mul_ps(r.shear[1], z)),
                _mm_mul_ps(r.shear[2], z),
            ]
        };
        let [ax, ay, az] = shear(0);
        let [bx, by, bz] = shear(3);
        let [cx, cy, cz] = shear(6);
        let mut u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
        let mut v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
        let mut w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
        let zero = _mm_setzero_ps();
        let on_edge =
            _mm_movemask_ps(_mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero)));
        if on_edge != 0 {
            // Double precision on edges, for the lanes there.
            let lanes = |x: __m128| {
                let mut a = [0.0f32; 4];
                _mm_storeu_ps(a.as_mut_ptr(), x);
                a
            };
            let (lax, lay, lbx, lby, lcx, lcy) = (lanes(ax), lanes(ay), lanes(bx), lanes(by), lanes(cx), lanes(cy));
            let (mut lu, mut lv, mut lw) = (lanes(u), lanes(v), lanes(w));
            for l in 0..4 {
                if on_edge & (1 << l) != 0 {
                    let (ax, ay, bx, by, cx, cy) =
                        (lax[l] as f64, lay[l] as f64, lbx[l] as f64, lby[l] as f64, lcx[l] as f64, lcy[l] as f64);
                    lu[l] = (cx * by - cy * bx) as f32;
                    lv[l] = (ax * cy - ay * cx) as f32;
                    lw[l] = (bx * ay - by * ax) as f32;
                }
            }
            u = _mm_loadu_ps(lu.as_ptr());
            v = _mm_loadu_ps(lv.as_ptr());
            w = _mm_loadu_ps(lw.as_ptr());
        }
        let neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)), _mm_cmplt_ps(w, zero));
        let pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)), _mm_cmpgt_ps(w, zero));
        let outside = _mm_and_ps(neg, pos);
        if _mm_movemask_ps(outside) == 0xf {
            return hits;
        }
        let det = _mm_add_ps(_mm_add_ps(u, v), w);
        let t_scaled = _mm_add_ps(_mm_add_ps(_mm_mul_ps(u, az), _mm_mul_ps(v, bz)), _mm_mul_ps(w, cz));
        let t = _mm_div_ps(t_scaled, det);
        let abs = _mm_andnot_ps(_mm_set1_ps(-0.0), t);
        let ok = _mm_and_ps(
            _mm_and_ps(_mm_cmpgt_ps(t, r.tmin), _mm_cmplt_ps(t, _mm_set1_ps(tmax))),
            _mm_and_ps(_mm_cmplt_ps(abs, _mm_set1_ps(f32::INFINITY)), _mm_cmpneq_ps(det, zero)),
        );
        hits.mask = (_mm_movemask_ps(_mm_andnot_ps(outside, ok)) & 0xf) as u32;
        if hits.mask != 0 {
            _mm_storeu_ps(hits.t.as_mut_ptr(), t);
            _mm_storeu_ps(hits.u.as_mut_ptr(), _mm_div_ps(v, det));
            _mm_storeu_ps(hits.v.as_mut_ptr(), _mm_div_ps(w, det));
        }
        hits
    }
}

impl Kernels for Sse41 {
    type Ray<'a> = X86Ray<__m128>;

    #[inline(always)]
    fn ray(ray: &WalkRay) -> X86Ray<__m128> {
        // SAFETY: SSE is part of x86_64.
        unsafe {
            let (o, i) = (ray.origin, ray.inv_dir);
            X86Ray {
                boxes: BoxRay {
                    origin: [_mm_set1_ps(o.x), _mm_set1_ps(o.y), _mm_set1_ps(o.z)],
                    inv: [_mm_set1_ps(i.x), _mm_set1_ps(i.y), _mm_set1_ps(i.z)],
                    tmin: _mm_set1_ps(ray.tmin),
                    near: ray.near_rows(),
                },
                triangle: triangle_ray(ray),
            }
        }
    }

    #[inline(always)]
    fn node(node: &Node, ray: &X86Ray<__m128>, tmax: f32) -> (u32, [f32; WIDTH]) {
        let b = &ray.boxes;
        let mut tnear = [0.0f32; WIDTH];
        let mut mask = 0;
        // SAFETY: SSE is part of x86_64; the rows are 32-byte aligned.
        unsafe {
            let tmax = _mm_set1_ps(tmax);
            for half in 0..2 {
                let row = |r: usize| _mm_load_ps(node.planes[r].as_ptr().add(4 * half));
                let (mut near, mut far) = (b.tmin, _mm_set1_ps(f32::INFINITY));
                for axis in (0..3).rev() {
                    let n = b.near[axis];
                    let tn = _mm_mul_ps(_mm_sub_ps(row(n), b.origin[axis]), b.inv[axis]);
                    let tf = _mm_mul_ps(_mm_sub_ps(row(n ^ 1), b.origin[axis]), b.inv[axis]);
                    near = _mm_max_ps(tn, near);
                    far = _mm_min_ps(tf, far);
                }
                let far = _mm_min_ps(_mm_mul_ps(far, _mm_set1_ps(FAR_SCALE)), tmax);
                let slack = _mm_mul_ps(_mm_andnot_ps(_mm_set1_ps(-0.0), near), _mm_set1_ps(NEAR_SLACK));
                let near = _mm_sub_ps(near, slack);
                _mm_storeu_ps(tnear.as_mut_ptr().add(4 * half), near);
                mask |= (_mm_movemask_ps(_mm_cmple_ps(near, far)) as u32) << (4 * half);
            }
        }
        (mask, tnear)
    }

    #[inline(always)]
    fn packet(packet: &Packet, ray: &X86Ray<__m128>, tmax: f32) -> Hits {
        // SAFETY: SSE is part of x86_64.
        unsafe { packet4(packet, &ray.triangle, tmax) }
    }
}

impl Kernels for Avx2 {
    type Ray<'a> = X86Ray<__m256>;

    #[inline(always)]
    fn ray(ray: &WalkRay) -> X86Ray<__m256> {
        // SAFETY: only reached from the AVX2 entry point, after detection.
        unsafe {
            let (o, i) = (ray.origin, ray.inv_dir);
            X86Ray {
                boxes: BoxRay {
                    origin: [_mm256_set1_ps(o.x), _mm256_set1_ps(o.y), _mm256_set1_ps(o.z)],
                    inv: [_mm256_set1_ps(i.x), _mm256_set1_ps(i.y), _mm256_set1_ps(i.z)],
                    tmin: _mm256_set1_ps(ray.tmin),
                    near: ray.near_rows(),
                },
                triangle: triangle_ray(ray),
            }
        }
    }

    #[inline(always)]
    fn node(node: &Node, ray: &X86Ray<__m256>, tmax: f32) -> (u32, [f32; WIDTH]) {
        let b = &ray.boxes;
        let mut tnear = [0.0f32; WIDTH];
        // SAFETY: only reached from the AVX2 entry point, after detection;
        // the rows are 32-byte aligned.
        unsafe {
            let row = |r: usize| _mm256_load_ps(node.planes[r].as_ptr());
            let (mut near, mut far) = (b.tmin, _mm256_set1_ps(f32::INFINITY));
            for axis in (0..3).rev() {
                let n = b.near[axis];
                let tn = _mm256_mul_ps(_mm256_sub_ps(row(n), b.origin[axis]), b.inv[axis]);
                let tf = _mm256_mul_ps(_mm256_sub_ps(row(n ^ 1), b.origin[axis]), b.inv[axis]);
                near = _mm256_max_ps(tn, near);
                far = _mm256_min_ps(tf, far);
            }
            let far = _mm256_min_ps(_mm256_mul_ps(far, _mm256_set1_ps(FAR_SCALE)), _mm256_set1_ps(tmax));
            let slack = _mm256_mul_ps(_mm256_andnot_ps(_mm256_set1_ps(-0.0), near), _mm256_set1_ps(NEAR_SLACK));
            let near = _mm256_sub_ps(near, slack);
            _mm256_storeu_ps(tnear.as_mut_ptr(), near);
            let mask = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32;
            (mask, tnear)
        }
    }

    #[inline(always)]
    fn packet(packet: &Packet, ray: &X86Ray<__m256>, tmax: f32) -> Hits {
        // SAFETY: SSE is part of x86_64.
        unsafe { packet4(packet, &ray.triangle, tmax) }
    }
}
