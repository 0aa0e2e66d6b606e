//! Acceleration structures: OptiX's builder names mapped onto obvhs.
//!
//! | builder | obvhs | why |
//! | --- | --- | --- |
//! | `Bvh` | BVH2, `medium_build` (PLOC + reinsertion) | the general-purpose default; refits |
//! | `Sbvh` | BVH2 from triangles, `slow_build` (spatial pre-splits) | highest quality; needs triangles |
//! | `MedianBvh` | BVH2, `fast_build` | fast build, lower quality |
//! | `Lbvh` | BVH2, `fastest_build` (PLOC, minimum search: Morton-order merging, like an LBVH) | fastest build |
//! | `TriangleKdTree` | — | obvhs builds no kd-trees: an error, not a silent remap |
//! | `NoAccel` | a single leaf holding every primitive | linear scan |

use glam::{Mat4, Vec3};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as OAabb;
use obvhs::bvh2::Bvh2;

/// An acceleration builder, by OptiX's names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Builder {
    Bvh,
    Sbvh,
    MedianBvh,
    Lbvh,
    TriangleKdTree,
    NoAccel,
}

impl Builder {
    pub fn name(self) -> &'static str {
        match self {
            Builder::Bvh => "Bvh",
            Builder::Sbvh => "Sbvh",
            Builder::MedianBvh => "MedianBvh",
            Builder::Lbvh => "Lbvh",
            Builder::TriangleKdTree => "TriangleKdTree",
            Builder::NoAccel => "NoAccel",
        }
    }

    /// Parses OptiX's builder names.
    pub fn from_name(name: &str) -> Option<Builder> {
        [Builder::Bvh, Builder::Sbvh, Builder::MedianBvh, Builder::Lbvh, Builder::TriangleKdTree, Builder::NoAccel]
            .into_iter()
            .find(|b| b.name() == name)
    }
}

/// An acceleration structure attached to a geometry group or group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Acceleration {
    pub builder: Builder,
}

impl Acceleration {
    pub fn new(builder: Builder) -> Self {
        Acceleration { builder }
    }
}

impl Default for Acceleration {
    fn default() -> Self {
        Acceleration::new(Builder::Bvh)
    }
}

/// A built BVH over primitives with known bounds.
pub(crate) struct Bvh {
    pub bvh: Bvh2,
}

pub(crate) fn to_oaabb(min: Vec3, max: Vec3) -> OAabb {
    OAabb::new(min.into(), max.into())
}

/// Which tree a backend walks.
///
/// Both backends walk obvhs's CWBVH of every geometry group (the wgpu
/// backend where its kernel searches triangles only; else the BVH2),
/// converted from a BVH2 that gets only what obvhs's own `build_cwbvh`
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

/// Builds a BVH over `bounds` in the form `form` needs; `triangles`, when
/// every primitive is a triangle, enables spatial splits for `Sbvh`.
pub(crate) fn build(
    builder: Builder,
    bounds: &[OAabb],
    triangles: Option<&[obvhs::triangle::Triangle]>,
    form: TreeForm,
) -> Result<Bvh, crate::RtError> {
    let mut t = std::time::Duration::ZERO;
    let bvh = match builder {
        Builder::TriangleKdTree => {
            return Err(crate::RtError::UnsupportedBuilder {
                builder: "TriangleKdTree",
                reason: "obvhs builds BVHs, not kd-trees; use Sbvh for the same trace quality",
            });
        }
        Builder::NoAccel => {
            let mut bvh = Bvh2::zeroed(bounds.len());
            let mut all = OAabb::empty();
            for b in bounds {
                all = all.union(b);
            }
            bvh.nodes = vec![obvhs::bvh2::node::Bvh2Node::new(all, bounds.len() as u32, 0)];
            bvh.primitive_indices = (0..bounds.len() as u32).collect();
            bvh
        }
        Builder::Sbvh => match triangles {
            Some(tris) => {
                obvhs::bvh2::builder::build_bvh2_from_tris(tris, params(BvhBuildParams::slow_build(), form), &mut t)
            }
            None => {
                return Err(crate::RtError::UnsupportedBuilder {
                    builder: "Sbvh",
                    reason: "spatial splits need triangles, and this group holds custom primitives or instances; use Bvh",
                });
            }
        },
        Builder::Bvh => obvhs::bvh2::builder::build_bvh2(bounds, params(BvhBuildParams::medium_build(), form), &mut t),
        Builder::MedianBvh => {
            obvhs::bvh2::builder::build_bvh2(bounds, params(BvhBuildParams::fast_build(), form), &mut t)
        }
        Builder::Lbvh => {
            obvhs::bvh2::builder::build_bvh2(bounds, params(BvhBuildParams::fastest_build(), form), &mut t)
        }
    };
    Ok(Bvh { bvh })
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
        // (node, entry distance): a node is skipped if a closer hit was found
        // after it was pushed.
        let mut stack: [(u32, f32); 128] = [(0, 0.0); 128];
        let root = hit(&nodes[0], tmax());
        if root == f32::INFINITY {
            return;
        }
        stack[0] = (0, root);
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let (index, t) = stack[sp];
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
                    stack[sp] = (n, t);
                    sp += 1;
                }
            }
        }
    }
}

// ---- per-node structures of a context, shared by the backends ----

use crate::backend::link::{self, Record};
use crate::context::Context;
use crate::error::Result;
use crate::scene::{GeometryKind, NodeKind, TriangleMesh};
use rt_std::cpu::{CpuArgs, CpuResult, ExecutionContext};

/// Built acceleration structures, kept across launches.
///
/// Nodes never change their children once created, so an entry stays valid
/// until something under it moves: a new node is built at the next launch
/// and the others are kept; moved geometry refits the geometry groups over
/// it (and the groups above refit to their children's new bounds). The
/// CWBVH form is added to kept entries the first time the CPU backend
/// launches ([`TreeForm`]).
#[derive(Default)]
pub(crate) struct AccelCache {
    pub(crate) nodes: Vec<Option<NodeAccel>>,
    /// Geometries moved since the last launch, and whether any transform
    /// changed.
    moved_geometries: Vec<u32>,
    moved: bool,
    /// How many launches built new structures and how many refit moved
    /// ones (for tests).
    pub builds: u64,
    pub refits: u64,
    /// How many geometry groups were built or refit (the wgpu backend keeps
    /// the geometry part of the scene on the device until this moves).
    pub geometry_group_changes: u64,
}

impl AccelCache {
    /// Geometry `g`'s vertices moved.
    pub fn geometry_moved(&mut self, g: u32) {
        self.moved = true;
        if !self.moved_geometries.contains(&g) {
            self.moved_geometries.push(g);
        }
    }

    /// A transform changed.
    pub fn transform_moved(&mut self) {
        self.moved = true;
    }
}

pub(crate) enum NodeAccel {
    /// A geometry group: a BVH over `(instance, primitive)` pairs.
    Prims {
        bvh: Bvh,
        /// The same tree converted to obvhs's 8-wide compressed BVH, which
        /// the CPU backend traverses (None for `NoAccel`'s single leaf).
        wide: Option<obvhs::cwbvh::CwBvh>,
        /// The vertices of each primitive of `wide` in its slot order, when
        /// all are triangles (else empty): the CPU backend's triangle test
        /// reads them without the index and position lookups. None until
        /// the CPU backend launches (the wgpu backend encodes its own).
        triangles: Option<Vec<[Vec3; 3]>>,
        prims: Vec<(u32, u32)>,
        bounds: OAabb,
    },
    /// A group: a BVH over its children's bounds.
    Children { bvh: Bvh, bounds: OAabb },
    /// Transforms and selectors: just bounds.
    Bounds(OAabb),
}

impl NodeAccel {
    pub(crate) fn bounds(&self) -> OAabb {
        match self {
            NodeAccel::Prims { bounds, .. } | NodeAccel::Children { bounds, .. } | NodeAccel::Bounds(bounds) => *bounds,
        }
    }
}

fn triangle_bounds(mesh: &TriangleMesh, t: usize) -> OAabb {
    let [a, b, c] = mesh.triangle(t);
    to_oaabb(a.min(b).min(c), a.max(b).max(c))
}

fn transform_bounds(m: Mat4, b: &OAabb) -> OAabb {
    if b.min.x > b.max.x {
        return *b;
    }
    let mut out = OAabb::empty();
    for i in 0..8 {
        let p = Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        );
        out.extend(m.transform_point3(p).into());
    }
    out
}

/// Primitive bounds of a geometry group, in the order of `prims`.
/// `(instance, primitive)` pairs, their bounds, and whether all are triangles.
type PrimBounds = (Vec<(u32, u32)>, Vec<OAabb>, bool);

fn prim_bounds(ctx: &Context, children: &[crate::GeometryInstanceId]) -> Result<PrimBounds> {
    let mut prims = Vec::new();
    let mut bounds = Vec::new();
    let mut all_triangles = true;
    for gi in children {
        let rec = &ctx.instances[gi.index() as usize];
        let geometry = &ctx.geometries[rec.geometry.index() as usize];
        match &geometry.kind {
            GeometryKind::Triangles(mesh) => {
                use rayon::prelude::*;
                let n = mesh.indices.len();
                prims.extend((0..n as u32).map(|t| (gi.index(), t)));
                bounds.par_extend((0..n).into_par_iter().with_min_len(4096).map(|t| triangle_bounds(mesh, t)));
            }
            GeometryKind::Custom { primitive_count, bounding_box, .. } => {
                all_triangles = false;
                let call = link::resolve(
                    ctx,
                    *bounding_box,
                    Record { instance: Some(*gi), geometry: Some(rec.geometry), ..Record::default() },
                )?;
                let refs = link::var_refs(&call);
                let vars = (call.desc.cpu_bind)(&refs[..call.vars.len()]).map_err(|e| link::bind_error(&call, e))?;
                for p in 0..*primitive_count {
                    let mut args = CpuArgs { payload: None, attributes: None, primitive: p, variables: &vars };
                    let (r, _) = rt_std::cpu::with_context(ExecutionContext::DEFAULT, || (call.desc.cpu)(&mut args));
                    let b = match r {
                        CpuResult::Aabb(b) if b.min.is_finite() && b.max.is_finite() => to_oaabb(b.min, b.max),
                        // A primitive without finite bounds can never be hit.
                        _ => OAabb::empty(),
                    };
                    prims.push((gi.index(), p));
                    bounds.push(b);
                }
            }
        }
    }
    Ok((prims, bounds, all_triangles))
}

/// The triangles of a geometry group's primitives, for `Sbvh`'s spatial
/// splits (`None` unless every primitive is a triangle).
fn group_triangles(ctx: &Context, prims: &[(u32, u32)]) -> Vec<obvhs::triangle::Triangle> {
    prims
        .iter()
        .map(|&(gi, t)| {
            let [a, b, c] = instance_mesh(ctx, gi).expect(ALL_TRIANGLES).triangle(t as usize).map(Into::into);
            obvhs::triangle::Triangle { v0: a, v1: b, v2: c }
        })
        .collect()
}

/// The triangles of geometry instance `gi` (None: custom primitives).
pub(crate) fn instance_mesh(ctx: &Context, gi: u32) -> Option<&TriangleMesh> {
    match &ctx.geometries[ctx.instances[gi as usize].geometry.index() as usize].kind {
        GeometryKind::Triangles(mesh) => Some(mesh),
        GeometryKind::Custom { .. } => None,
    }
}

/// What the callers of [`instance_mesh`] that read triangles have checked.
const ALL_TRIANGLES: &str = "all primitives are triangles";

/// Builds what is missing and refits what moved, in the form the context's
/// backend walks (see [`AccelCache`]).
pub(crate) fn build_accels(ctx: &Context, cache: &mut AccelCache) -> Result<()> {
    let form = match ctx.backend {
        crate::Backend::Cpu => TreeForm::Wide,
        _ => TreeForm::Binary,
    };
    // Geometry groups get a CWBVH where it is walked: always on the CPU
    // backend, on wgpu when the kernel searches triangles only (its BVH2 is
    // then built as the widened form's, with one reinsertion pass).
    let cpu = ctx.backend == crate::Backend::Cpu;
    let widened = cpu || ctx.searches_triangles_only();
    let gg_form = if widened { TreeForm::Wide } else { form };
    let order = link::nodes_post_order(ctx)?;
    let mut built: Vec<Option<NodeAccel>> = std::mem::take(&mut cache.nodes);
    built.resize_with(ctx.nodes.len(), || None);
    let (mut any_built, mut any_refit) = (false, false);
    let union = |bounds: &[OAabb]| bounds.iter().fold(OAabb::empty(), |acc, b| acc.union(b));
    for n in order {
        let i = n.index() as usize;
        let node = &ctx.nodes[i];
        let old = built[i].take();
        let new = match &node.kind {
            NodeKind::GeometryGroup { children, accel: a } => {
                // The CWBVH of a single leaf (`NoAccel`) or of nothing is
                // pointless: both backends walk the BVH2 then.
                let wants_wide = |prims: &[(u32, u32)]| widened && a.builder != Builder::NoAccel && !prims.is_empty();
                // Every primitive a triangle: the CPU backend's triangles in
                // CWBVH slot order (the wgpu backend encodes its own).
                let all_triangles =
                    |prims: &[(u32, u32)]| prims.iter().all(|(gi, _)| instance_mesh(ctx, *gi).is_some());
                match old {
                    Some(NodeAccel::Prims { mut bvh, mut wide, mut triangles, prims, mut bounds }) => {
                        let moved = cache.moved
                            && children.iter().any(|gi| {
                                let g = ctx.instances[gi.index() as usize].geometry.index();
                                cache.moved_geometries.contains(&g)
                            });
                        let had_wide = wide.is_some();
                        if moved {
                            let (_, prim_bounds, _) = prim_bounds(ctx, children)?;
                            cache.geometry_group_changes += 1;
                            bvh.refit(&prim_bounds);
                            if let Some(cw) = wide.as_mut() {
                                refit_wide(cw, &prim_bounds);
                            }
                            bounds = union(&prim_bounds);
                            any_refit = true;
                        }
                        if wide.is_none() && wants_wide(&prims) {
                            wide = Some(widen(&bvh));
                        }
                        if moved || (wide.is_some() && !had_wide) {
                            triangles = None;
                        }
                        if cpu && triangles.is_none() {
                            triangles = Some(slot_triangles(ctx, &prims, wide.as_ref(), all_triangles(&prims)));
                        }
                        NodeAccel::Prims { bvh, wide, triangles, prims, bounds }
                    }
                    _ => {
                        let (prims, bounds, all_tris) = prim_bounds(ctx, children)?;
                        let tris = (a.builder == Builder::Sbvh && all_tris).then(|| group_triangles(ctx, &prims));
                        let bvh = build(a.builder, &bounds, tris.as_deref(), gg_form)?;
                        let wide = wants_wide(&prims).then(|| widen(&bvh));
                        let triangles = cpu.then(|| slot_triangles(ctx, &prims, wide.as_ref(), all_tris));
                        any_built = true;
                        cache.geometry_group_changes += 1;
                        NodeAccel::Prims { bvh, wide, triangles, prims, bounds: union(&bounds) }
                    }
                }
            }
            NodeKind::Group { children, accel: a } => {
                let bounds: Vec<OAabb> = children
                    .iter()
                    .map(|c| built[c.index() as usize].as_ref().map(|b| b.bounds()).unwrap_or(OAabb::empty()))
                    .collect();
                match old {
                    Some(NodeAccel::Children { mut bvh, .. }) => {
                        if cache.moved {
                            bvh.refit(&bounds);
                            any_refit = true;
                        }
                        NodeAccel::Children { bvh, bounds: union(&bounds) }
                    }
                    _ => {
                        any_built = true;
                        NodeAccel::Children { bvh: build(a.builder, &bounds, None, form)?, bounds: union(&bounds) }
                    }
                }
            }
            NodeKind::Transform { matrix, child, .. } => {
                let b = built[child.index() as usize].as_ref().map(|b| b.bounds()).unwrap_or(OAabb::empty());
                NodeAccel::Bounds(transform_bounds(*matrix, &b))
            }
            NodeKind::Selector { children, .. } => NodeAccel::Bounds(
                children
                    .iter()
                    .filter_map(|c| built[c.index() as usize].as_ref().map(|b| b.bounds()))
                    .fold(OAabb::empty(), |acc, b| acc.union(&b)),
            ),
        };
        built[i] = Some(new);
    }
    cache.builds += any_built as u64;
    cache.refits += any_refit as u64;
    cache.nodes = built;
    cache.moved = false;
    cache.moved_geometries.clear();
    Ok(())
}

/// The vertices of `prims` in `wide`'s slot order (empty unless all are
/// triangles).
fn slot_triangles(
    ctx: &Context,
    prims: &[(u32, u32)],
    wide: Option<&obvhs::cwbvh::CwBvh>,
    all: bool,
) -> Vec<[Vec3; 3]> {
    use rayon::prelude::*;
    let Some(cw) = wide.filter(|_| all) else { return Vec::new() };
    // Each instance's mesh looked up once, not once per triangle.
    let meshes: Vec<Option<&TriangleMesh>> = (0..ctx.instances.len() as u32).map(|gi| instance_mesh(ctx, gi)).collect();
    cw.primitive_indices
        .par_iter()
        .with_min_len(4096)
        .map(|&p| {
            let (gi, t) = prims[p as usize];
            meshes[gi as usize].expect(ALL_TRIANGLES).triangle(t as usize)
        })
        .collect()
}

/// obvhs's CWBVH of a built BVH2 (at most 3 primitives per leaf, children
/// ordered for traversal).
fn widen(bvh: &Bvh) -> obvhs::cwbvh::CwBvh {
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
