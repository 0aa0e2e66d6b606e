//! One tree: obvhs's BVH2 built by a builder's preset, refit, walked (the
//! CPU backend's groups), and widened to obvhs's CWBVH.

use super::Builder;
use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as OAabb;
use obvhs::bvh2::Bvh2;

/// A built BVH over primitives with known bounds.
pub(crate) struct Bvh {
    pub bvh: Bvh2,
}

pub(crate) fn to_oaabb(min: Vec3, max: Vec3) -> OAabb {
    OAabb::new(min.into(), max.into())
}

/// Which tree a backend walks.
///
/// Both backends walk 8-wide trees of geometry groups: the wgpu backend
/// obvhs's CWBVH (where its kernel searches triangles only; else the
/// BVH2), the CPU backend its SIMD layout ([`crate::accel::wide`]). Both
/// are converted from a BVH2 that gets only what obvhs's own `build_cwbvh`
/// gives it (PLOC and one reinsertion pass): the conversion regroups the
/// tree into 8-wide nodes, so a second pass would be paid for and mostly
/// undone. BVH2s that are walked as they are (groups', and geometry
/// groups' on wgpu with any-hit or intersection programs) are built as
/// obvhs's `build_bvh2` builds them (PLOC, reinsertion, leaf collapse — a
/// no-op at one primitive a leaf — and a second reinsertion pass), except
/// groups' on the CPU backend, which get the wide form's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TreeForm {
    /// A BVH2 with a second reinsertion pass (walked as it is on wgpu).
    Binary,
    /// A BVH2 with one pass (widened; groups on the CPU backend).
    Wide,
}

/// One primitive per BVH2 leaf: the GPU walks BVH2 leaves, and the CWBVH
/// conversion regroups leaves itself. `Wide` trees skip the second
/// reinsertion pass (see [`TreeForm`]).
fn params(p: BvhBuildParams, form: TreeForm) -> BvhBuildParams {
    match form {
        TreeForm::Binary => BvhBuildParams { max_prims_per_leaf: 1, ..p },
        TreeForm::Wide => {
            BvhBuildParams { max_prims_per_leaf: 1, post_collapse_reinsertion_batch_ratio_multiplier: 0.0, ..p }
        }
    }
}

/// Why `builder` cannot build a tree over primitives of which all are
/// fixed triangles or not (`triangles`); None where it can.
pub(crate) fn refusal(builder: Builder, triangles: bool) -> Option<crate::error::RtError> {
    match builder {
        Builder::TriangleKdTree => Some(
            crate::error::SceneError::UnsupportedBuilder {
                builder: "TriangleKdTree",
                reason: "obvhs builds BVHs, not kd-trees; use Sbvh for the same trace quality",
            }
            .into(),
        ),
        Builder::Sbvh if !triangles => Some(
            crate::error::SceneError::UnsupportedBuilder {
                builder: "Sbvh",
                reason: "spatial splits need triangles, and this group holds custom primitives or instances; use Bvh",
            }
            .into(),
        ),
        _ => None,
    }
}

/// Builds a BVH over `bounds` in the form `form` needs; `triangles`, when
/// every primitive is a triangle, enables spatial splits for `Sbvh`.
pub(crate) fn build(
    builder: Builder,
    bounds: &[OAabb],
    triangles: Option<&[obvhs::triangle::Triangle]>,
    form: TreeForm,
) -> Result<Bvh, crate::error::RtError> {
    if let Some(refused) = refusal(builder, triangles.is_some()) {
        return Err(refused);
    }
    let bvh = match (builder, triangles) {
        (Builder::NoAccel, _) => {
            let mut bvh = Bvh2::zeroed(bounds.len());
            let mut all = OAabb::empty();
            for b in bounds {
                all = all.union(b);
            }
            bvh.nodes = vec![obvhs::bvh2::node::Bvh2Node::new(all, bounds.len() as u32, 0)];
            bvh.primitive_indices = (0..bounds.len() as u32).collect();
            bvh
        }
        (Builder::Sbvh, Some(tris)) => ploc(bounds, Some(tris), params(BvhBuildParams::slow_build(), form)),
        (Builder::MedianBvh, _) => ploc(bounds, None, params(BvhBuildParams::fast_build(), form)),
        (Builder::Lbvh, _) => ploc(bounds, None, params(BvhBuildParams::fastest_build(), form)),
        // `Bvh` (what `refusal` refused cannot come here).
        _ => ploc(bounds, None, params(BvhBuildParams::medium_build(), form)),
    };
    Ok(Bvh { bvh })
}

/// obvhs's BVH2 build as its `build_bvh2` and `build_bvh2_from_tris`
/// helpers do it (PLOC over the bounds, with spatial pre-splits when
/// `triangles` are given and `config` asks; reinsertion, leaf collapse and
/// a second reinsertion pass), step by step through its public API: the
/// helpers time themselves with `std::time::Instant`, which panics in a
/// browser (wasm32).
fn ploc(bounds: &[OAabb], triangles: Option<&[obvhs::triangle::Triangle]>, config: BvhBuildParams) -> Bvh2 {
    let ploc = |aabbs: &[OAabb], indices: Vec<u32>| {
        obvhs::ploc::PlocBuilder::with_capacity(aabbs.len()).build(
            config.ploc_search_distance,
            aabbs,
            indices,
            config.sort_precision,
            config.search_depth_threshold,
        )
    };
    let mut bvh2 = match triangles.filter(|_| config.pre_split) {
        Some(tris) => {
            let mut aabbs: Vec<OAabb> = tris.iter().map(|t| t.aabb()).collect();
            let largest_half_area = aabbs.iter().map(|a| a.half_area()).fold(0.0, f32::max);
            let avg_area = aabbs.iter().map(|a| a.half_area()).sum::<f32>() / tris.len() as f32;
            let mut indices = (0..tris.len() as u32).collect();
            obvhs::splits::split_aabbs_preset(&mut aabbs, &mut indices, tris, avg_area, largest_half_area);
            let mut bvh2 = ploc(&aabbs, indices);
            bvh2.uses_spatial_splits = true;
            bvh2
        }
        None => ploc(bounds, (0..bounds.len() as u32).collect()),
    };
    let mut reinsertion = obvhs::bvh2::reinsertion::ReinsertionOptimizer::default();
    reinsertion.run(&mut bvh2, config.reinsertion_batch_ratio, None);
    obvhs::bvh2::leaf_collapser::collapse(
        &mut bvh2,
        config.max_prims_per_leaf.clamp(1, 255),
        config.collapse_traversal_cost,
    );
    reinsertion.run(
        &mut bvh2,
        config.reinsertion_batch_ratio * config.post_collapse_reinsertion_batch_ratio_multiplier,
        None,
    );
    bvh2
}

impl Bvh {
    /// Refits to new primitive bounds (same primitives, moved).
    pub fn refit(&mut self, bounds: &[OAabb]) {
        for node in self.bvh.nodes.iter_mut() {
            if node.is_leaf() {
                let mut b = OAabb::empty();
                for i in node.first_index..node.first_index + node.prim_count {
                    b = b.union(&bounds[self.bvh.primitive_indices[i as usize] as usize]);
                }
                node.set_aabb(b);
            }
        }
        self.bvh.refit_all();
    }

    /// Visits the primitives whose leaves the ray segment `(tmin, tmax())`
    /// enters, nearest leaves first; `visit` returns false to stop.
    /// `tmax` is re-read after every leaf so closer hits prune the search.
    /// (The CPU backend's walk: not built for wasm32.)
    #[cfg(not(target_arch = "wasm32"))]
    pub fn traverse(
        &self,
        origin: Vec3,
        inv_dir: Vec3,
        tmin: f32,
        tmax: &dyn Fn() -> f32,
        visit: &mut dyn FnMut(u32) -> bool,
    ) {
        let nodes = &self.bvh.nodes;
        if nodes.is_empty() {
            return;
        }
        let hit = |n: &obvhs::bvh2::node::Bvh2Node, tmax: f32| -> f32 {
            let b = n.aabb();
            let t0 = (Vec3::from(b.min) - origin) * inv_dir;
            let t1 = (Vec3::from(b.max) - origin) * inv_dir;
            let near = t0.min(t1).max_element().max(tmin);
            let far = t0.max(t1).min_element().min(tmax);
            if near <= far { near } else { f32::INFINITY }
        };
        let root = hit(&nodes[0], tmax());
        if root == f32::INFINITY {
            return;
        }
        // (node, entry distance): a node is skipped if a closer hit was found
        // after it was pushed. Left uninitialised: zeroing 1 KiB cost more
        // than walking a small group.
        let mut stack = [const { std::mem::MaybeUninit::<(u32, f32)>::uninit() }; 128];
        stack[0].write((0, root));
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            // SAFETY: entries below `sp` were written.
            let (index, t) = unsafe { stack[sp].assume_init() };
            if t > tmax() {
                continue;
            }
            let node = &nodes[index as usize];
            if node.is_leaf() {
                for i in node.first_index..node.first_index + node.prim_count {
                    if !visit(self.bvh.primitive_indices[i as usize]) {
                        return;
                    }
                }
                continue;
            }
            let (a, b) = (node.first_index, node.first_index + 1);
            let limit = tmax();
            let (ta, tb) = (hit(&nodes[a as usize], limit), hit(&nodes[b as usize], limit));
            // Push the far child first so the near one is visited first.
            let ((near, tn), (far, tf)) = if ta <= tb { ((a, ta), (b, tb)) } else { ((b, tb), (a, ta)) };
            for (n, t) in [(far, tf), (near, tn)] {
                if t != f32::INFINITY && sp < stack.len() {
                    stack[sp].write((n, t));
                    sp += 1;
                }
            }
        }
    }
}

/// obvhs's CWBVH of a built BVH2 (at most 3 primitives per leaf, children
/// ordered for traversal).
pub(crate) fn widen(bvh: &Bvh) -> obvhs::cwbvh::CwBvh {
    obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh(&bvh.bvh, 3, true, false)
}

/// Refits a CWBVH to new primitive bounds (same primitives, moved): the
/// tree keeps its shape; every node's origin, scale and quantized child
/// boxes are computed again bottom-up from its children's exact bounds, as
/// the conversion computes them (origin at the node's minimum, a power-of-2
/// scale per axis spanning 255 steps, child boxes rounded outwards). A
/// fraction of converting the refit BVH2 again.
pub(crate) fn refit_wide(cw: &mut obvhs::cwbvh::CwBvh, prim_bounds: &[OAabb]) {
    use glam::Vec3A;
    let mut exact = vec![OAabb::empty(); cw.nodes.len()];
    // Children come after their parent: bottom-up is back to front.
    for n in (0..cw.nodes.len()).rev() {
        let node = cw.nodes[n];
        let mut children = [OAabb::empty(); 8];
        let mut rank = 0;
        for (i, child) in children.iter_mut().enumerate() {
            let meta = node.child_meta[i];
            if meta == 0 {
                continue;
            }
            if node.imask & (1 << i) != 0 {
                *child = exact[(node.child_base_idx + rank) as usize];
                rank += 1;
            } else {
                let first = node.primitive_base_idx + (meta & 0b1_1111) as u32;
                for slot in first..first + (meta & 0b1110_0000).count_ones() {
                    *child = child.union(&prim_bounds[cw.primitive_indices[slot as usize] as usize]);
                }
            }
        }
        let aabb = children.iter().fold(OAabb::empty(), |a, c| a.union(c));
        exact[n] = aabb;
        let p: Vec3A = aabb.min;
        let e = ((aabb.max - aabb.min).max(Vec3A::splat(1e-20)) * (1.0 / 255.0)).log2().ceil().exp2();
        let rcp = 1.0 / e;
        let node = &mut cw.nodes[n];
        node.p = p.into();
        node.e = [e.x, e.y, e.z].map(|c| (c.to_bits() >> 23) as u8);
        for (i, child) in children.iter().enumerate() {
            if node.child_meta[i] == 0 {
                continue;
            }
            let lo = ((child.min - p) * rcp).floor().clamp(Vec3A::ZERO, Vec3A::splat(255.0));
            let hi = ((child.max - p) * rcp).ceil().clamp(Vec3A::ZERO, Vec3A::splat(255.0));
            (node.child_min_x[i], node.child_min_y[i], node.child_min_z[i]) = (lo.x as u8, lo.y as u8, lo.z as u8);
            (node.child_max_x[i], node.child_max_y[i], node.child_max_z[i]) = (hi.x as u8, hi.y as u8, hi.z as u8);
        }
    }
    if let Some(root) = exact.first() {
        cw.total_aabb = *root;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid_bounds(n: u32, lift: f32) -> Vec<OAabb> {
        (0..n * n)
            .map(|i| {
                let (x, y) = ((i % n) as f32, (i / n) as f32);
                let z = lift * (x * 0.7).sin() * (y * 0.3).cos();
                to_oaabb(Vec3::new(x, y, z), Vec3::new(x + 1.0, y + 1.0, z + 0.1))
            })
            .collect()
    }

    /// Refitting to the bounds it was built from gives the conversion's own
    /// nodes, bit for bit.
    #[test]
    fn refitting_a_cwbvh_to_its_own_bounds_changes_nothing() {
        let bounds = grid_bounds(40, 2.0);
        let bvh = build(Builder::Bvh, &bounds, None, TreeForm::Wide).unwrap();
        let wide = widen(&bvh);
        let mut refit = wide.clone();
        refit_wide(&mut refit, &bounds);
        assert_eq!(refit.nodes, wide.nodes);
    }

    /// After a move, every child box still holds what lies under it.
    #[test]
    fn a_refit_cwbvh_holds_the_moved_bounds() {
        let mut bvh = build(Builder::Bvh, &grid_bounds(40, 2.0), None, TreeForm::Wide).unwrap();
        let mut wide = widen(&bvh);
        let moved = grid_bounds(40, -5.0);
        bvh.refit(&moved);
        refit_wide(&mut wide, &moved);
        // The exact bounds of what lies under child i of node n.
        fn under(wide: &obvhs::cwbvh::CwBvh, bounds: &[OAabb], n: usize, i: usize) -> OAabb {
            let node = &wide.nodes[n];
            let meta = node.child_meta[i];
            if node.imask & (1 << i) != 0 {
                let child = (node.child_base_idx + (node.imask as u32 & ((1 << i) - 1)).count_ones()) as usize;
                (0..8)
                    .filter(|&k| wide.nodes[child].child_meta[k] != 0)
                    .fold(OAabb::empty(), |a, k| a.union(&under(wide, bounds, child, k)))
            } else {
                let first = node.primitive_base_idx + (meta & 0b1_1111) as u32;
                (first..first + (meta & 0b1110_0000).count_ones())
                    .map(|s| bounds[wide.primitive_indices[s as usize] as usize])
                    .fold(OAabb::empty(), |a, c| a.union(&c))
            }
        }
        for (n, node) in wide.nodes.iter().enumerate() {
            for i in 0..8 {
                if node.child_meta[i] == 0 {
                    continue;
                }
                let b = node.child_aabb(i);
                let under = under(&wide, &moved, n, i);
                let slack = 1e-4 * (1.0 + under.max.abs().max_element());
                assert!(
                    (b.min - under.min).max_element() <= slack && (under.max - b.max).max_element() <= slack,
                    "child {i}: {b:?} does not hold {under:?}"
                );
            }
        }
    }
}
