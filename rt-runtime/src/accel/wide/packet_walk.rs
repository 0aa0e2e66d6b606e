//! A packet of up to [`PACKET_RAYS`] rays walked through a [`WideBvh`]
//! together (Embree's `rtcIntersect16` idea on the CPU backend's tree): at
//! each node every child box is tested against all the packet's active
//! rays at once (eight rays a register), the children entered by some ray
//! are visited with the rays that enter them, and at a leaf each triangle
//! is tested against eight rays at once where those rays share the
//! watertight test's `kz` (coherent rays do); otherwise, or where a ray
//! meets a triangle on an edge, each ray that reached the leaf runs the
//! single-ray triangle test of [`super::kernels`]. Where fewer than six
//! of an entry's rays are left (rays that diverged, or passed their
//! closest hit), each walks the entry's subtree alone by the single-ray
//! walk (Embree's switch from packets to single rays). Where the packet's
//! rays share the direction's signs, a node's children are first tested
//! all at once against the packet as intervals of origins and inverse
//! directions (a frustum test that culls no child a ray enters), and only
//! the children it meets are tested ray by ray.
//!
//! The box test is the single-ray walk's, lane by lane (the near plane by
//! the sign of each ray's inverse direction, SSE's NaN rules, the same
//! slack), the eight-ray triangle test is that test's operations a ray a
//! lane, and leaves commit as the single-ray walk commits (a hit closer
//! than the ray's closest so far), so a packet finds each ray's closest hit
//! of the single-ray walk; only the order of leaves differs, which matters
//! for exact ties between two triangles only.
//!
//! AVX2 only: this is the measurement of what packets gain on this tree
//! (`rt-bench`'s `cpu_packet_walk_only`); another instruction set walks the
//! rays one by one.

use super::WideBvh;
use super::kernels::{Hits, WalkRay};

/// Rays in a packet.
pub const PACKET_RAYS: usize = 16;

/// Walks `tree` with `rays` (at most [`PACKET_RAYS`]), each up to its
/// `tmax`. Each leaf a ray enters with a triangle hit goes to
/// `leaf(ray, leaf, hits)`, which returns the ray's new `tmax` (the
/// closest hit so far). The tree must have packets, and each ray's
/// triangle setup must be of that ray (its origin and tmin).
pub(crate) fn walk_packet<F: FnMut(usize, u32, &Hits) -> f32>(
    isa: super::isa::Isa,
    tree: &WideBvh,
    rays: &[WalkRay],
    tmax: &mut [f32],
    leaf: F,
) {
    debug_assert!(rays.len() <= PACKET_RAYS && rays.len() == tmax.len() && tree.has_packets());
    if rays.is_empty() {
        return;
    }
    #[cfg(target_arch = "x86_64")]
    if isa == super::isa::Isa::Avx2 && one_octant(rays) {
        // SAFETY: `Isa::Avx2` is only chosen where the CPU has AVX2 and FMA.
        unsafe { avx2::walk(tree, rays, tmax, leaf) };
        return;
    }
    one_by_one(isa, tree, rays, tmax, leaf);
}

/// Whether `rays` share the sign of their direction on every axis: only
/// then does the packet walk pay. Rays of several octants (ambient
/// occlusion, diffuse bounces) have no frustum and enter boxes apart, so
/// the packet's set-up and its per-ray box tests cost more than walking
/// each ray alone (on the bunny's AO rays, 1,461 instructions a ray as
/// packets against 579 alone, callgrind; BENCHMARKS.md).
#[cfg(target_arch = "x86_64")]
fn one_octant(rays: &[WalkRay]) -> bool {
    let signs = |r: &WalkRay| r.inv_dir.is_negative_bitmask();
    let first = signs(&rays[0]);
    rays[1..].iter().all(|r| signs(r) == first)
}

/// The rays walked one at a time by the single-ray walk.
fn one_by_one<F: FnMut(usize, u32, &Hits) -> f32>(
    isa: super::isa::Isa,
    tree: &WideBvh,
    rays: &[WalkRay],
    tmax: &mut [f32],
    mut leaf: F,
) {
    for (i, ray) in rays.iter().enumerate() {
        super::isa::walk_on(isa, tree, ray, tmax[i], |r, hits| {
            let t = leaf(i, r, hits?);
            tmax[i] = t;
            Some(t)
        });
    }
}

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::super::kernels::x86::{Avx2, TriangleRay, packet4, triangle_ray};
    use super::super::kernels::{FAR_SCALE, Hits, NEAR_SLACK, WalkRay};
    use super::super::walk::{Entry, stack_len, walk_from};
    use super::super::{LEAF, PACKET, Packet, WideBvh, leaf_of};
    use super::PACKET_RAYS;
    use glam::Vec3;
    use std::arch::x86_64::*;
    use std::mem::MaybeUninit;

    /// A pushed child: its reference, the rays that enter it (a bit a
    /// ray), and the nearest of their entry distances.
    type PacketEntry = (u32, u32, f32);

    /// Stack entries kept on the stack (deeper trees take the heap).
    const ON_STACK: usize = 7 * 48 + 1;

    /// The rays an entry must have to be walked on as a packet: with fewer,
    /// each ray walks the entry's subtree alone (Embree's switch from
    /// packets to single rays where they diverge).
    const PACKET_BELOW: u32 = 6;

    /// Halves of the packet: eight rays a register.
    const HALVES: usize = PACKET_RAYS / 8;

    /// The packet's rays by lane: origin, inverse direction, tmin.
    struct Lanes {
        origin: [[__m256; 3]; HALVES],
        inv: [[__m256; 3]; HALVES],
        tmin: [__m256; HALVES],
    }

    /// # Safety
    /// The CPU has AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn walk<F: FnMut(usize, u32, &Hits) -> f32>(
        tree: &WideBvh,
        rays: &[WalkRay],
        tmax: &mut [f32],
        mut leaf: F,
    ) {
        let n = rays.len();
        let (lanes, soa) = packet_lanes(rays);
        let zero = _mm256_setzero_ps();
        let all = if n == PACKET_RAYS { u32::MAX >> (32 - PACKET_RAYS) } else { (1u32 << n) - 1 };
        let frustum = Frustum::of(&lanes, all);
        let mut setups: [Option<TriangleRay>; PACKET_RAYS] = [None; PACKET_RAYS];
        // Entries: (reference, rays, the nearest entry of those rays); a
        // node pushes at most its children less the one popped next, as
        // the single-ray walk does, so `stack_len` bounds them, and the
        // single rays a subtree is handed to need no more.
        let need = stack_len(tree);
        let mut small = [const { MaybeUninit::<PacketEntry>::uninit() }; ON_STACK];
        let mut small_single = [const { MaybeUninit::<Entry>::uninit() }; ON_STACK];
        let (mut large, mut large_single) = (Vec::new(), Vec::new());
        let (stack, single_stack): (&mut [MaybeUninit<PacketEntry>], &mut [MaybeUninit<Entry>]) = if need <= ON_STACK {
            (&mut small, &mut small_single)
        } else {
            large.resize(need, MaybeUninit::uninit());
            large_single.resize(need, MaybeUninit::uninit());
            (&mut large, &mut large_single)
        };
        stack[0].write((tree.root, all, f32::NEG_INFINITY));
        let mut sp = 1;
        let mut limits = [f32::INFINITY; PACKET_RAYS];
        limits[..n].copy_from_slice(tmax);
        while sp > 0 {
            sp -= 1;
            // SAFETY: entries below `sp` were written.
            let (current, mask, near) = unsafe { stack[sp].assume_init() };
            // Rays whose closest hit is nearer than the entry need not go in.
            let mut mask = mask;
            for h in 0..HALVES {
                // SAFETY: `limits` holds eight floats from `8 * h`.
                let l = unsafe { _mm256_loadu_ps(limits[8 * h..].as_ptr()) };
                let passed = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LT_OQ>(l, _mm256_set1_ps(near))) as u32;
                mask &= !(passed << (8 * h));
            }
            if mask == 0 {
                continue;
            }
            if mask.count_ones() < PACKET_BELOW {
                // Too few rays left to share the tests: each goes on alone.
                alone(tree, current, mask, rays, &mut limits, single_stack, &mut leaf);
                continue;
            }
            if current & LEAF != 0 {
                leaf_entry(tree, current, mask, &soa, rays, &mut limits, &mut setups, &mut leaf);
                continue;
            }
            let node = &tree.nodes[current as usize];
            let mut limit = [zero; HALVES];
            for (h, l) in limit.iter_mut().enumerate() {
                // SAFETY: `limits` holds eight floats from `8 * h`.
                *l = unsafe { _mm256_loadu_ps(limits[8 * h..].as_ptr()) };
            }
            // The children the packet's frustum meets (all of them without
            // a frustum): no ray enters another.
            let mut children = match &frustum {
                Some(f) => {
                    let mut far = _mm256_set1_ps(f32::NEG_INFINITY);
                    for (h, &l) in limit.iter().enumerate() {
                        far = _mm256_max_ps(_mm256_blendv_ps(far, l, active_lanes((mask >> (8 * h)) & 0xff)), far);
                    }
                    f.children(node, horizontal_max(far))
                }
                None => 0xff,
            };
            // Per child: the rays entering it and the nearest entry, pushed
            // far to near so the nearest is popped next.
            let base = sp;
            while children != 0 {
                let c = children.trailing_zeros() as usize & 7;
                children &= children - 1;
                let child = node.child[c];
                if child == u32::MAX {
                    continue;
                }
                let mut hit = 0u32;
                let mut nearest = _mm256_set1_ps(f32::INFINITY);
                for (h, &limit) in limit.iter().enumerate() {
                    let active = (mask >> (8 * h)) & 0xff;
                    if active == 0 {
                        continue;
                    }
                    let (m, near) = box_lanes(node, c, &lanes, h, limit, active_lanes(active));
                    hit |= m << (8 * h);
                    nearest = _mm256_min_ps(near, nearest);
                }
                if hit != 0 {
                    let e = (child, hit, horizontal_min(nearest));
                    // Insertion by descending distance.
                    let mut j = sp;
                    // SAFETY: entries from `base` to `sp` were written.
                    while j > base && unsafe { stack[j - 1].assume_init().2 } < e.2 {
                        stack[j] = stack[j - 1];
                        j -= 1;
                    }
                    stack[j].write(e);
                    sp += 1;
                }
            }
        }
        tmax.copy_from_slice(&limits[..n]);
    }

    /// The packet's rays by lane, and each half's triangle setups by lane
    /// where its rays share `kz` (coherent rays do): a triangle is then
    /// tested against eight rays at once.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn packet_lanes(rays: &[WalkRay]) -> (Lanes, [Option<SoaRays>; HALVES]) {
        let n = rays.len();
        let mut lane_values = [[[f32::NAN; 8]; 7]; HALVES];
        for (i, r) in rays.iter().enumerate() {
            let v = &mut lane_values[i / 8];
            let l = i % 8;
            (v[0][l], v[1][l], v[2][l]) = (r.origin.x, r.origin.y, r.origin.z);
            (v[3][l], v[4][l], v[5][l]) = (r.inv_dir.x, r.inv_dir.y, r.inv_dir.z);
            v[6][l] = r.tmin;
        }
        // (Loops, not closures: a closure does not take the function's
        // target features, and its intrinsics would not inline.)
        let zero = _mm256_setzero_ps();
        let mut lanes = Lanes { origin: [[zero; 3]; HALVES], inv: [[zero; 3]; HALVES], tmin: [zero; HALVES] };
        for (h, values) in lane_values.iter().enumerate() {
            // SAFETY: each row is eight floats.
            unsafe {
                for k in 0..3 {
                    lanes.origin[h][k] = _mm256_loadu_ps(values[k].as_ptr());
                    lanes.inv[h][k] = _mm256_loadu_ps(values[3 + k].as_ptr());
                }
                lanes.tmin[h] = _mm256_loadu_ps(values[6].as_ptr());
            }
        }
        // Each half's triangle setups by lane, where its rays share `kz`
        // (coherent rays do): a triangle is then tested against eight rays
        // at once.
        let mut soa: [Option<SoaRays>; HALVES] = [None; HALVES];
        for (h, slot) in soa.iter_mut().enumerate() {
            let half = &rays[(8 * h).min(n)..(8 * h + 8).min(n)];
            let Some(first) = half.first().and_then(|r| r.triangle) else { continue };
            if half.iter().all(|r| r.triangle.is_some_and(|t| t.kz == first.kz)) {
                *slot = Some(soa_rays(half, &lanes, h));
            }
        }
        (lanes, soa)
    }

    /// The rays of `mask` walked on from `current` one at a time, each to
    /// its own closest hit.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn alone<F: FnMut(usize, u32, &Hits) -> f32>(
        tree: &WideBvh,
        current: u32,
        mask: u32,
        rays: &[WalkRay],
        limits: &mut [f32; PACKET_RAYS],
        single_stack: &mut [MaybeUninit<Entry>],
        leaf: &mut F,
    ) {
        let mut m = mask;
        while m != 0 {
            let i = m.trailing_zeros() as usize;
            m &= m - 1;
            let limit = &mut limits[i];
            walk_from::<Avx2, _>(tree, current, &rays[i], *limit, single_stack, |r, hits| {
                *limit = leaf(i, r, hits?);
                Some(*limit)
            });
        }
    }

    /// Leaf `current` tested against the rays of `mask`: eight at a time
    /// in each half whose rays share a triangle setup, the rest one by one.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    #[allow(clippy::too_many_arguments)]
    fn leaf_entry<F: FnMut(usize, u32, &Hits) -> f32>(
        tree: &WideBvh,
        current: u32,
        mask: u32,
        soa: &[Option<SoaRays>; HALVES],
        rays: &[WalkRay],
        limits: &mut [f32; PACKET_RAYS],
        setups: &mut [Option<TriangleRay>; PACKET_RAYS],
        leaf: &mut F,
    ) {
        let (index, _) = leaf_of(current);
        let packet = &tree.packets[index as usize];
        let mut m = mask;
        for (h, rays) in soa.iter().enumerate() {
            let active = (mask >> (8 * h)) & 0xff;
            let Some(rays) = rays else { continue };
            if active.count_ones() < 2 {
                continue;
            }
            let Some(hits) = leaf_lanes(packet, rays, &limits[8 * h..8 * h + 8]) else { continue };
            m &= !(active << (8 * h));
            let mut b = active;
            while b != 0 {
                let l = b.trailing_zeros() as usize;
                b &= b - 1;
                if hits[l].mask != 0 {
                    limits[8 * h + l] = leaf(8 * h + l, current, &hits[l]);
                }
            }
        }
        while m != 0 {
            let i = m.trailing_zeros() as usize;
            m &= m - 1;
            // (Each ray's setup made once, when a leaf first needs it.)
            let r = setups[i].get_or_insert_with(|| triangle_ray(&rays[i]));
            // SAFETY: the CPU has SSE (x86_64).
            let hits = unsafe { packet4(packet, r, limits[i]) };
            if hits.mask != 0 {
                limits[i] = leaf(i, current, &hits);
            }
        }
    }

    /// Eight rays' triangle setups by lane, sharing `kz` (`axes`): the
    /// origin's coordinates and the shear in the permuted order, and tmin.
    #[derive(Clone, Copy)]
    struct SoaRays {
        origin: [__m256; 3],
        shear: [__m256; 3],
        tmin: __m256,
        axes: [usize; 3],
    }

    /// `rays` (one to eight, half `h` of the packet, each with a triangle
    /// setup of one `kz`) by lane. A setup's origin and tmin are its ray's
    /// (see [`walk_packet`](super::walk_packet)), so they are the half's
    /// lanes, permuted; only the shear is gathered.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn soa_rays(rays: &[WalkRay], lanes: &Lanes, h: usize) -> SoaRays {
        let mut shear = [[0.0f32; 8]; 3];
        let axes = rays.first().and_then(|r| r.triangle).map_or([0, 1, 2], |t| t.axes());
        for (l, r) in rays.iter().enumerate() {
            let Some(t) = r.triangle else { continue };
            debug_assert!(
                Vec3::from(t.origin).to_array().map(f32::to_bits) == r.origin.to_array().map(f32::to_bits)
                    && t.tmin.to_bits() == r.tmin.to_bits()
            );
            for (k, row) in shear.iter_mut().enumerate() {
                row[l] = t.shear[k];
            }
        }
        // SAFETY: each row is eight floats.
        let load = |row: &[f32; 8]| unsafe { _mm256_loadu_ps(row.as_ptr()) };
        SoaRays {
            origin: axes.map(|a| lanes.origin[h][a]),
            shear: [load(&shear[0]), load(&shear[1]), load(&shear[2])],
            tmin: lanes.tmin[h],
            axes,
        }
    }

    /// Each of eight rays' hits with the (up to four) triangles of
    /// `packet` before its `limit`, as `packet4` finds them one ray at a
    /// time: the same operations on the same values, a ray a lane instead
    /// of a triangle a lane. None where a ray meets a triangle on an edge
    /// (the single-ray test's double-precision case: the caller tests
    /// those rays one by one).
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn leaf_lanes(packet: &Packet, r: &SoaRays, limit: &[f32]) -> Option<[Hits; 8]> {
        let (origin, shear, tmin) = (r.origin, r.shear, r.tmin);
        // SAFETY: `limit` holds eight floats.
        let tmax = unsafe { _mm256_loadu_ps(limit.as_ptr()) };
        let zero = _mm256_setzero_ps();
        let mut out = [Hits::default(); 8];
        for lane in 0..PACKET {
            let v = |k: usize| _mm256_set1_ps(packet.v[k][lane]);
            let sheared = |k: usize| {
                let x = _mm256_sub_ps(v(k + r.axes[0]), origin[0]);
                let y = _mm256_sub_ps(v(k + r.axes[1]), origin[1]);
                let z = _mm256_sub_ps(v(k + r.axes[2]), origin[2]);
                [
                    _mm256_sub_ps(x, _mm256_mul_ps(shear[0], z)),
                    _mm256_sub_ps(y, _mm256_mul_ps(shear[1], z)),
                    _mm256_mul_ps(shear[2], z),
                ]
            };
            let [ax, ay, az] = sheared(0);
            let [bx, by, bz] = sheared(3);
            let [cx, cy, cz] = sheared(6);
            let u = _mm256_sub_ps(_mm256_mul_ps(cx, by), _mm256_mul_ps(cy, bx));
            let v_ = _mm256_sub_ps(_mm256_mul_ps(ax, cy), _mm256_mul_ps(ay, cx));
            let w = _mm256_sub_ps(_mm256_mul_ps(bx, ay), _mm256_mul_ps(by, ax));
            let on_edge = _mm256_or_ps(
                _mm256_or_ps(_mm256_cmp_ps::<_CMP_EQ_OQ>(u, zero), _mm256_cmp_ps::<_CMP_EQ_OQ>(v_, zero)),
                _mm256_cmp_ps::<_CMP_EQ_OQ>(w, zero),
            );
            if _mm256_movemask_ps(on_edge) != 0 {
                return None;
            }
            let neg = _mm256_or_ps(
                _mm256_or_ps(_mm256_cmp_ps::<_CMP_LT_OQ>(u, zero), _mm256_cmp_ps::<_CMP_LT_OQ>(v_, zero)),
                _mm256_cmp_ps::<_CMP_LT_OQ>(w, zero),
            );
            let pos = _mm256_or_ps(
                _mm256_or_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(u, zero), _mm256_cmp_ps::<_CMP_GT_OQ>(v_, zero)),
                _mm256_cmp_ps::<_CMP_GT_OQ>(w, zero),
            );
            let outside = _mm256_and_ps(neg, pos);
            if _mm256_movemask_ps(outside) == 0xff {
                continue;
            }
            let det = _mm256_add_ps(_mm256_add_ps(u, v_), w);
            let t_scaled =
                _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(u, az), _mm256_mul_ps(v_, bz)), _mm256_mul_ps(w, cz));
            let t = _mm256_div_ps(t_scaled, det);
            let abs = _mm256_andnot_ps(_mm256_set1_ps(-0.0), t);
            let ok = _mm256_and_ps(
                _mm256_and_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(t, tmin), _mm256_cmp_ps::<_CMP_LT_OQ>(t, tmax)),
                _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_LT_OQ>(abs, _mm256_set1_ps(f32::INFINITY)),
                    _mm256_cmp_ps::<_CMP_NEQ_UQ>(det, zero),
                ),
            );
            let hit = _mm256_movemask_ps(_mm256_andnot_ps(outside, ok)) as u32;
            if hit == 0 {
                continue;
            }
            let (mut ts, mut us, mut vs) = ([0.0f32; 8], [0.0f32; 8], [0.0f32; 8]);
            // SAFETY: each array holds eight floats.
            unsafe {
                _mm256_storeu_ps(ts.as_mut_ptr(), t);
                _mm256_storeu_ps(us.as_mut_ptr(), _mm256_div_ps(v_, det));
                _mm256_storeu_ps(vs.as_mut_ptr(), _mm256_div_ps(w, det));
            }
            let mut b = hit;
            while b != 0 {
                let l = b.trailing_zeros() as usize;
                b &= b - 1;
                let h = &mut out[l];
                h.mask |= 1 << lane;
                (h.t[lane], h.u[lane], h.v[lane]) = (ts[l], us[l], vs[l]);
            }
        }
        Some(out)
    }

    /// A lane mask of `bits` (all ones in the lanes whose bit is set).
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn active_lanes(bits: u32) -> __m256 {
        let lane_bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
        let set = _mm256_and_si256(_mm256_set1_epi32(bits as i32), lane_bits);
        _mm256_castsi256_ps(_mm256_cmpeq_epi32(set, lane_bits))
    }

    /// The packet's rays as intervals (per axis the least and greatest
    /// origin and inverse direction, and the least `tmin`), where they
    /// share the direction's sign on every axis and have finite origins
    /// and finite, non-zero inverse directions. A node's child boxes are
    /// tested against it with interval arithmetic, all eight at once,
    /// before its rays are tested one by one.
    ///
    /// The test culls no child a ray enters: a ray's computed entry on an
    /// axis is `(plane - o) * inv`, rounded twice, which is monotonic in
    /// `o` and in `inv` (for a fixed sign of the other factor), so over the
    /// packet's box of origins and inverse directions it is least (and its
    /// exit greatest) at a corner of that box, and the test takes the least
    /// (greatest) of the four corners' values, computed by the same
    /// operations; the max, min, slack and scale that follow are monotonic
    /// too.
    struct Frustum {
        /// The near plane's row of each axis (see `WalkRay::near_rows`).
        rows: [usize; 3],
        origin: [[__m256; 3]; 2],
        inv: [[__m256; 3]; 2],
        tmin: __m256,
    }

    impl Frustum {
        /// The frustum of the rays of `lanes` whose bits `all` has (at
        /// least one).
        #[inline]
        #[target_feature(enable = "avx2,fma")]
        fn of(lanes: &Lanes, all: u32) -> Option<Frustum> {
            let (inf, neg_inf) = (_mm256_set1_ps(f32::INFINITY), _mm256_set1_ps(f32::NEG_INFINITY));
            let zero = _mm256_setzero_ps();
            let abs = |v: __m256| _mm256_andnot_ps(_mm256_set1_ps(-0.0), v);
            // Each half's lanes that hold a ray.
            let bits = |h: usize| (all >> (8 * h)) & 0xff;
            let mut rows = [0usize; 3];
            let (mut lo, mut hi) = ([[zero; 3]; 2], [[zero; 3]; 2]);
            let mut tmin = inf;
            for k in 0..3 {
                let mut negative = 0u32;
                let (mut olo, mut ohi, mut ilo, mut ihi) = (inf, neg_inf, inf, neg_inf);
                for h in 0..HALVES {
                    let b = bits(h);
                    if b == 0 {
                        continue;
                    }
                    let active = active_lanes(b);
                    let (o, i) = (lanes.origin[h][k], lanes.inv[h][k]);
                    // Finite origins, finite and non-zero inverse directions.
                    let ok = _mm256_and_ps(
                        _mm256_and_ps(
                            _mm256_cmp_ps::<_CMP_LT_OQ>(abs(o), inf),
                            _mm256_cmp_ps::<_CMP_LT_OQ>(abs(i), inf),
                        ),
                        _mm256_cmp_ps::<_CMP_NEQ_UQ>(i, zero),
                    );
                    if (_mm256_movemask_ps(ok) as u32) & b != b {
                        return None;
                    }
                    negative |= (_mm256_movemask_ps(i) as u32 & b) << (8 * h);
                    olo = _mm256_min_ps(olo, _mm256_blendv_ps(inf, o, active));
                    ohi = _mm256_max_ps(ohi, _mm256_blendv_ps(neg_inf, o, active));
                    ilo = _mm256_min_ps(ilo, _mm256_blendv_ps(inf, i, active));
                    ihi = _mm256_max_ps(ihi, _mm256_blendv_ps(neg_inf, i, active));
                }
                // One sign of the direction on the axis for all rays.
                rows[k] = match negative {
                    0 => 2 * k,
                    m if m == all => 2 * k + 1,
                    _ => return None,
                };
                lo[0][k] = _mm256_set1_ps(horizontal_min(olo));
                hi[0][k] = _mm256_set1_ps(horizontal_max(ohi));
                lo[1][k] = _mm256_set1_ps(horizontal_min(ilo));
                hi[1][k] = _mm256_set1_ps(horizontal_max(ihi));
            }
            for h in 0..HALVES {
                let b = bits(h);
                if b != 0 {
                    // (A NaN tmin is passed over, as `f32::min` does.)
                    let t = lanes.tmin[h];
                    let valid = _mm256_and_ps(active_lanes(b), _mm256_cmp_ps::<_CMP_ORD_Q>(t, t));
                    tmin = _mm256_min_ps(tmin, _mm256_blendv_ps(inf, t, valid));
                }
            }
            Some(Frustum {
                rows,
                origin: [lo[0], hi[0]],
                inv: [lo[1], hi[1]],
                tmin: _mm256_set1_ps(horizontal_min(tmin)),
            })
        }

        /// The children of `node` some ray of the packet may enter before
        /// `limit` (the greatest closest hit so far of its rays): a bit a
        /// child.
        #[inline]
        #[target_feature(enable = "avx2,fma")]
        fn children(&self, node: &super::super::Node, limit: f32) -> u32 {
            // SAFETY: the rows are 32-byte aligned.
            let row = |r: usize| unsafe { _mm256_load_ps(node.planes[r].as_ptr()) };
            let (mut near, mut far) = (self.tmin, _mm256_set1_ps(f32::INFINITY));
            for axis in (0..3).rev() {
                let n = self.rows[axis];
                let [ilo, ihi] = [self.inv[0][axis], self.inv[1][axis]];
                // The four corners of (plane - origin) * inv.
                let corners = |plane: __m256| {
                    let (a, b) =
                        (_mm256_sub_ps(plane, self.origin[1][axis]), _mm256_sub_ps(plane, self.origin[0][axis]));
                    [_mm256_mul_ps(a, ilo), _mm256_mul_ps(a, ihi), _mm256_mul_ps(b, ilo), _mm256_mul_ps(b, ihi)]
                };
                let [a, b, c, d] = corners(row(n));
                near = _mm256_max_ps(_mm256_min_ps(_mm256_min_ps(a, b), _mm256_min_ps(c, d)), near);
                let [a, b, c, d] = corners(row(n ^ 1));
                far = _mm256_min_ps(_mm256_max_ps(_mm256_max_ps(a, b), _mm256_max_ps(c, d)), far);
            }
            let far = _mm256_min_ps(_mm256_mul_ps(far, _mm256_set1_ps(FAR_SCALE)), _mm256_set1_ps(limit));
            let slack = _mm256_mul_ps(_mm256_andnot_ps(_mm256_set1_ps(-0.0), near), _mm256_set1_ps(NEAR_SLACK));
            let near = _mm256_sub_ps(near, slack);
            _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32
        }
    }

    /// The greatest of eight lanes.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn horizontal_max(v: __m256) -> f32 {
        let m = _mm_max_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps::<1>(v));
        let m = _mm_max_ps(m, _mm_movehl_ps(m, m));
        let m = _mm_max_ss(m, _mm_shuffle_ps::<1>(m, m));
        _mm_cvtss_f32(m)
    }

    /// The least of eight lanes.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn horizontal_min(v: __m256) -> f32 {
        let m = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps::<1>(v));
        let m = _mm_min_ps(m, _mm_movehl_ps(m, m));
        let m = _mm_min_ss(m, _mm_shuffle_ps::<1>(m, m));
        _mm_cvtss_f32(m)
    }

    /// Child `c` against the `active` lanes of half `h`: the lanes that enter
    /// it before their `limit`, and their entry distances (+inf in the
    /// others).
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    fn box_lanes(
        node: &super::super::Node,
        c: usize,
        lanes: &Lanes,
        h: usize,
        limit: __m256,
        active: __m256,
    ) -> (u32, __m256) {
        {
            let (mut near, mut far) = (lanes.tmin[h], _mm256_set1_ps(f32::INFINITY));
            for axis in (0..3).rev() {
                let lo = _mm256_set1_ps(node.planes[2 * axis][c]);
                let hi = _mm256_set1_ps(node.planes[2 * axis + 1][c]);
                let inv = lanes.inv[h][axis];
                let o = lanes.origin[h][axis];
                // The near plane by the sign of the inverse direction.
                let (pn, pf) = (_mm256_blendv_ps(lo, hi, inv), _mm256_blendv_ps(hi, lo, inv));
                let tn = _mm256_mul_ps(_mm256_sub_ps(pn, o), inv);
                let tf = _mm256_mul_ps(_mm256_sub_ps(pf, o), inv);
                near = _mm256_max_ps(tn, near);
                far = _mm256_min_ps(tf, far);
            }
            let far = _mm256_min_ps(_mm256_mul_ps(far, _mm256_set1_ps(FAR_SCALE)), limit);
            let slack = _mm256_mul_ps(_mm256_andnot_ps(_mm256_set1_ps(-0.0), near), _mm256_set1_ps(NEAR_SLACK));
            let near = _mm256_sub_ps(near, slack);
            let enter = _mm256_and_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far), active);
            (_mm256_movemask_ps(enter) as u32, _mm256_blendv_ps(_mm256_set1_ps(f32::INFINITY), near, enter))
        }
    }

    const _: () = assert!(PACKET_RAYS.is_multiple_of(8));
}
