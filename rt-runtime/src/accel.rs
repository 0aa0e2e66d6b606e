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

/// One primitive per BVH2 leaf: the CPU backend converts the tree to
/// obvhs's CWBVH, which needs that, and the GPU walks BVH2 leaves anyway.
fn single(p: BvhBuildParams) -> BvhBuildParams {
    BvhBuildParams { max_prims_per_leaf: 1, ..p }
}

/// Builds a BVH over `bounds`; `triangles`, when every primitive is a
/// triangle, enables spatial splits for `Sbvh`.
pub(crate) fn build(
    builder: Builder,
    bounds: &[OAabb],
    triangles: Option<&[obvhs::triangle::Triangle]>,
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
                obvhs::bvh2::builder::build_bvh2_from_tris(tris, single(BvhBuildParams::slow_build()), &mut t)
            }
            None => {
                return Err(crate::RtError::UnsupportedBuilder {
                    builder: "Sbvh",
                    reason: "spatial splits need triangles, and this group holds custom primitives or instances; use Bvh",
                });
            }
        },
        Builder::Bvh => obvhs::bvh2::builder::build_bvh2(bounds, single(BvhBuildParams::medium_build()), &mut t),
        Builder::MedianBvh => obvhs::bvh2::builder::build_bvh2(bounds, single(BvhBuildParams::fast_build()), &mut t),
        Builder::Lbvh => obvhs::bvh2::builder::build_bvh2(bounds, single(BvhBuildParams::fastest_build()), &mut t),
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

/// Built acceleration structures, kept across launches and rebuilt only
/// when the graph's shape changes (refit when geometry moves).
#[derive(Default)]
pub(crate) struct AccelCache {
    pub(crate) nodes: Vec<Option<NodeAccel>>,
    shape_version: u64,
    built_version: Option<u64>,
    moved: bool,
    /// How many full builds and refits happened (for tests).
    pub builds: u64,
    pub refits: u64,
}

impl AccelCache {
    pub fn shape_changed(&mut self) {
        self.shape_version += 1;
    }

    pub fn geometry_moved(&mut self) {
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
        /// reads them without the index and position lookups.
        triangles: Vec<[Vec3; 3]>,
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
    let [a, b, c] = mesh.indices[t].map(|i| mesh.positions[i as usize]);
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
                for t in 0..mesh.indices.len() {
                    prims.push((gi.index(), t as u32));
                    bounds.push(triangle_bounds(mesh, t));
                }
            }
            GeometryKind::Custom { primitive_count, bounding_box, .. } => {
                all_triangles = false;
                let call = link::resolve(
                    ctx,
                    *bounding_box,
                    Record { instance: Some(*gi), geometry: Some(rec.geometry), ..Record::default() },
                )?;
                for p in 0..*primitive_count {
                    let refs = link::var_refs(&call);
                    let mut args =
                        CpuArgs { payload: None, attributes: None, primitive: p, variables: &refs[..call.vars.len()] };
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

pub(crate) fn build_accels(ctx: &Context, cache: &mut AccelCache) -> Result<()> {
    let order = link::nodes_post_order(ctx)?;
    let refit = cache.built_version == Some(cache.shape_version) && cache.nodes.len() == ctx.nodes.len();
    if refit && !cache.moved {
        return Ok(());
    }
    let mut built: Vec<Option<NodeAccel>> = std::mem::take(&mut cache.nodes);
    built.resize_with(ctx.nodes.len(), || None);
    for n in order {
        let i = n.index() as usize;
        let node = &ctx.nodes[i];
        let new = match &node.kind {
            NodeKind::GeometryGroup { children, accel: a } => {
                let (prims, bounds, all_tris) = prim_bounds(ctx, children)?;
                let total = bounds.iter().fold(OAabb::empty(), |acc, b| acc.union(b));
                match built[i].take() {
                    Some(NodeAccel::Prims { mut bvh, prims: old, wide, .. }) if refit && old == prims => {
                        bvh.refit(&bounds);
                        let wide = wide.map(|_| widen(&bvh));
                        let triangles = slot_triangles(ctx, &prims, wide.as_ref(), all_tris);
                        NodeAccel::Prims { bvh, wide, triangles, prims, bounds: total }
                    }
                    _ => {
                        let tris: Option<Vec<obvhs::triangle::Triangle>> = all_tris.then(|| {
                            prims
                                .iter()
                                .map(|(gi, t)| {
                                    let rec = &ctx.instances[*gi as usize];
                                    let GeometryKind::Triangles(mesh) =
                                        &ctx.geometries[rec.geometry.index() as usize].kind
                                    else {
                                        unreachable!("all primitives are triangles")
                                    };
                                    let [a, b, c] =
                                        mesh.indices[*t as usize].map(|v| mesh.positions[v as usize].into());
                                    obvhs::triangle::Triangle { v0: a, v1: b, v2: c }
                                })
                                .collect()
                        });
                        let bvh = build(a.builder, &bounds, tris.as_deref())?;
                        let wide = (a.builder != Builder::NoAccel && !prims.is_empty()).then(|| widen(&bvh));
                        let triangles = slot_triangles(ctx, &prims, wide.as_ref(), all_tris);
                        NodeAccel::Prims { bvh, wide, triangles, prims, bounds: total }
                    }
                }
            }
            NodeKind::Group { children, accel: a } => {
                let bounds: Vec<OAabb> = children
                    .iter()
                    .map(|c| built[c.index() as usize].as_ref().map(|b| b.bounds()).unwrap_or(OAabb::empty()))
                    .collect();
                let total = bounds.iter().fold(OAabb::empty(), |acc, b| acc.union(b));
                match built[i].take() {
                    Some(NodeAccel::Children { mut bvh, .. }) if refit => {
                        bvh.refit(&bounds);
                        NodeAccel::Children { bvh, bounds: total }
                    }
                    _ => NodeAccel::Children { bvh: build(a.builder, &bounds, None)?, bounds: total },
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
    if refit {
        cache.refits += 1;
    } else {
        cache.builds += 1;
    }
    cache.nodes = built;
    cache.built_version = Some(cache.shape_version);
    cache.moved = false;
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
    let Some(cw) = wide.filter(|_| all) else { return Vec::new() };
    cw.primitive_indices
        .iter()
        .map(|&p| {
            let (gi, t) = prims[p as usize];
            match &ctx.geometries[ctx.instances[gi as usize].geometry.index() as usize].kind {
                GeometryKind::Triangles(mesh) => mesh.indices[t as usize].map(|v| mesh.positions[v as usize]),
                GeometryKind::Custom { .. } => unreachable!("all primitives are triangles"),
            }
        })
        .collect()
}

/// obvhs's CWBVH of a built BVH2 (at most 3 primitives per leaf, children
/// ordered for traversal).
fn widen(bvh: &Bvh) -> obvhs::cwbvh::CwBvh {
    obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh(&bvh.bvh, 3, true, false)
}
