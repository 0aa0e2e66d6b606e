//! Per-node structures of a scene, shared by the backends, kept across
//! launches.

use super::Builder;
use super::bvh::{Bvh, TreeForm, build, refit_wide, refusal, to_oaabb, widen};
use super::wide::WideBvh;
use super::wide::collapse::collapse;
use crate::error::{LaunchError, Result, SceneError};
use crate::link::{self, Record};
use crate::scene::{GeometryKind, NodeKind, Scene, TriangleMesh};
use glam::{Mat4, Vec3};
use obvhs::aabb::Aabb as OAabb;
use rt_std::cpu::{CpuArgs, CpuResult, ExecutionContext};

/// Built acceleration structures, kept across launches.
///
/// Nodes never change their children once created, so an entry stays valid
/// until something under it moves: a new node is built at the next launch
/// and the others are kept; moved geometry refits the geometry groups over
/// it (and the groups above refit to their children's new bounds). A
/// geometry group's tree is built only for a launch that walks it (not for
/// the ray-query traversal, [`Trees::geometry`]), and its CWBVH and SIMD
/// forms the first time a launch walks those ([`TreeForm`]).
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
    /// The last stamp given to a geometry group's tree (see
    /// [`NodeAccel::Prims`]'s `stamp`).
    stamps: u64,
    /// How many geometry groups' BVHs were built on the host.
    pub geometry_trees: u64,
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
    /// A geometry group: a BVH over `(instance, primitive)` pairs (None
    /// until a launch walks it: the ray-query traversal walks the
    /// device's BLASes instead).
    Prims {
        bvh: Option<Bvh>,
        /// The same tree converted to obvhs's 8-wide compressed BVH, which
        /// the wgpu backend's compute kernel walks (None until it launches,
        /// and for `NoAccel`'s single leaf).
        wide: Option<obvhs::cwbvh::CwBvh>,
        /// The same tree in the CPU backend's SIMD layout, with the
        /// triangles' vertices in its leaves when all primitives are
        /// triangles. None until the CPU backend launches (and for
        /// `NoAccel`'s single leaf).
        simd: Option<Box<WideBvh>>,
        prims: Vec<(u32, u32)>,
        bounds: OAabb,
        /// Changes whenever the tree is built or refit: what a backend
        /// that builds its own structure per geometry group from it (the
        /// ray-query traversal's BLASes) keys that structure on.
        stamp: u64,
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
/// `(instance, primitive)` pairs, their bounds, and whether all are triangles
/// with fixed vertices (no vertex motion).
type PrimBounds = (Vec<(u32, u32)>, Vec<OAabb>, bool);

pub(crate) fn prim_bounds(scene: &Scene, children: &[crate::handles::GeometryInstanceId]) -> Result<PrimBounds> {
    let mut prims = Vec::new();
    let mut bounds = Vec::new();
    let mut all_triangles = true;
    for gi in children {
        let rec = &scene.instances[gi.index() as usize];
        let geometry = &scene.geometries[rec.geometry.index() as usize];
        match &geometry.kind {
            GeometryKind::Triangles(mesh) => {
                let n = mesh.indices.len();
                prims.extend((0..n as u32).map(|t| (gi.index(), t)));
                let motion = geometry.vertex_motion.as_deref();
                all_triangles &= motion.is_none();
                // A moving triangle's box holds it at every key.
                let bound = |t: usize| match motion {
                    Some(m) => {
                        let (lo, hi) = m.triangle_bounds(mesh.indices[t]);
                        to_oaabb(lo, hi)
                    }
                    None => triangle_bounds(mesh, t),
                };
                #[cfg(not(target_arch = "wasm32"))]
                {
                    use rayon::prelude::*;
                    bounds.par_extend((0..n).into_par_iter().with_min_len(4096).map(bound));
                }
                #[cfg(target_arch = "wasm32")]
                bounds.extend((0..n).map(bound));
            }
            GeometryKind::Custom { primitive_count, bounding_box, .. } => {
                all_triangles = false;
                let call = link::resolve(
                    scene,
                    *bounding_box,
                    Record { instance: Some(*gi), geometry: Some(rec.geometry), ..Record::default() },
                )?;
                let refs = link::var_refs(&call);
                let vars = (call.desc.cpu_bind)(&refs[..call.vars.len()]).map_err(|e| link::bind_error(&call, e))?;
                for p in 0..*primitive_count {
                    let mut args = CpuArgs { payload: None, attributes: None, primitive: p, variables: &vars };
                    let run = || rt_std::cpu::with_context(ExecutionContext::DEFAULT, || (call.desc.cpu)(&mut args));
                    let (r, _) = crate::panics::catching(run).map_err(|caught| LaunchError::BoundsPanicked {
                        program: call.desc.name,
                        location: format!("{}:{}", call.desc.file, call.desc.line),
                        primitive: p,
                        message: caught.message,
                        at: caught.at,
                    })?;
                    // A box that is not one (NaN, infinite, inverted) is the
                    // program's error: the backends' trees and the
                    // ray-query BLASes need real boxes.
                    let b = match r {
                        CpuResult::Aabb(b) if b.min.is_finite() && b.max.is_finite() && b.min.cmple(b.max).all() => {
                            to_oaabb(b.min, b.max)
                        }
                        CpuResult::Aabb(b) => {
                            let problem = if b.min.is_nan() || b.max.is_nan() {
                                "a NaN bound"
                            } else if !(b.min.is_finite() && b.max.is_finite()) {
                                "an infinite bound"
                            } else {
                                "min above max"
                            };
                            return Err(SceneError::BadBounds {
                                program: call.desc.name,
                                location: format!("{}:{}", call.desc.file, call.desc.line),
                                geometry: rec.geometry.index(),
                                primitive: p,
                                bounds: format!("min {} max {}", b.min, b.max),
                                problem,
                            }
                            .into());
                        }
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
fn group_triangles(scene: &Scene, prims: &[(u32, u32)]) -> Vec<obvhs::triangle::Triangle> {
    prims
        .iter()
        .map(|&(gi, t)| {
            let [a, b, c] = instance_mesh(scene, gi).expect(ALL_TRIANGLES).triangle(t as usize).map(Into::into);
            obvhs::triangle::Triangle { v0: a, v1: b, v2: c }
        })
        .collect()
}

/// The triangles of geometry instance `gi` (None: custom primitives).
pub(crate) fn instance_mesh(scene: &Scene, gi: u32) -> Option<&TriangleMesh> {
    match &scene.geometries[scene.instances[gi as usize].geometry.index() as usize].kind {
        GeometryKind::Triangles(mesh) => Some(mesh),
        GeometryKind::Custom { .. } => None,
    }
}

/// What the callers of [`instance_mesh`] that read triangles have checked.
const ALL_TRIANGLES: &str = "all primitives are triangles";

/// The trees a backend walks, which it tells the builder
/// ([`crate::backend::LaunchBackend::trees`]); see [`TreeForm`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Trees {
    /// The form of groups' BVH2s.
    pub groups: TreeForm,
    /// Whether geometry groups get a BVH at all: not for the ray-query
    /// traversal, which walks the device's BLASes (built from the
    /// triangles) and needs of a geometry group only its primitives, its
    /// bounds and its stamp. (Their builders are still checked.)
    pub geometry: bool,
    /// Whether geometry groups get obvhs's CWBVH (their BVH2 then built in
    /// the widened form, with one reinsertion pass).
    pub cwbvh: bool,
    /// Whether geometry groups get the CPU backend's SIMD layout
    /// ([`NodeAccel::Prims`]'s `simd`; their BVH2 then built in the
    /// widened form too).
    pub simd: bool,
}

/// Builds what is missing and refits what moved, in the forms `trees` asks
/// for (see [`AccelCache`]).
pub(crate) fn build_accels(scene: &Scene, cache: &mut AccelCache, trees: Trees) -> Result<()> {
    let form = trees.groups;
    let order = crate::scene::nodes_post_order(scene)?;
    let mut built: Vec<Option<NodeAccel>> = std::mem::take(&mut cache.nodes);
    built.resize_with(scene.nodes.len(), || None);
    let mut done = Done::default();
    for n in order {
        let i = n.index() as usize;
        let node = &scene.nodes[i];
        let old = built[i].take();
        let new = match &node.kind {
            NodeKind::GeometryGroup { children, accel: a } => {
                geometry_group(scene, cache, (children, a.builder), old, trees, &mut done)?
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
                            done.refit = true;
                        }
                        NodeAccel::Children { bvh, bounds: union(&bounds) }
                    }
                    _ => {
                        done.built = true;
                        NodeAccel::Children { bvh: build(a.builder, &bounds, None, form)?, bounds: union(&bounds) }
                    }
                }
            }
            NodeKind::Transform { matrix, child, motion, .. } => {
                let b = built[child.index() as usize].as_ref().map(|b| b.bounds()).unwrap_or(OAabb::empty());
                match motion {
                    Some(m) => NodeAccel::Bounds(m.bounds(&b)),
                    None => NodeAccel::Bounds(transform_bounds(*matrix, &b)),
                }
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
    cache.builds += done.built as u64;
    cache.refits += done.refit as u64;
    cache.nodes = built;
    cache.moved = false;
    cache.moved_geometries.clear();
    Ok(())
}

/// Whether a launch's [`build_accels`] built anything and refit anything.
#[derive(Default)]
struct Done {
    built: bool,
    refit: bool,
}

/// The union of `bounds`.
fn union(bounds: &[OAabb]) -> OAabb {
    bounds.iter().fold(OAabb::empty(), |acc, b| acc.union(b))
}

/// A geometry group's entry (its geometry instances `children`, its
/// builder) for a launch walking `trees`: `old` kept, refit where its
/// geometry moved and given the forms it lacks, or a new one.
fn geometry_group(
    scene: &Scene,
    cache: &mut AccelCache,
    (children, builder): (&[crate::handles::GeometryInstanceId], Builder),
    old: Option<NodeAccel>,
    trees: Trees,
    done: &mut Done,
) -> Result<NodeAccel> {
    let form = if trees.cwbvh || trees.simd { TreeForm::Wide } else { trees.groups };
    // The wide forms of a single leaf (`NoAccel`) or of nothing are
    // pointless: both backends walk the BVH2 then.
    let widens = |prims: &[(u32, u32)]| builder != Builder::NoAccel && !prims.is_empty();
    let Some(NodeAccel::Prims { mut bvh, mut wide, mut simd, prims, mut bounds, mut stamp }) = old else {
        let (prims, boxes, all_tris) = prim_bounds(scene, children)?;
        let bvh = match trees.geometry {
            true => Some(group_tree(scene, cache, builder, (&prims, &boxes, all_tris), form)?),
            false => match refusal(builder, all_tris) {
                Some(refused) => return Err(refused),
                None => None,
            },
        };
        let wide = bvh.as_ref().filter(|_| trees.cwbvh && widens(&prims)).map(widen);
        let simd = bvh.as_ref().filter(|_| trees.simd && widens(&prims)).map(|t| Box::new(simd_tree(scene, t, &prims)));
        done.built = true;
        cache.geometry_group_changes += 1;
        cache.stamps += 1;
        return Ok(NodeAccel::Prims { bvh, wide, simd, prims, bounds: union(&boxes), stamp: cache.stamps });
    };
    let moved = cache.moved
        && children.iter().any(|gi| {
            let g = scene.instances[gi.index() as usize].geometry.index();
            cache.moved_geometries.contains(&g)
        });
    let mut moved_bounds = None;
    if moved {
        let (_, boxes, all_tris) = prim_bounds(scene, children)?;
        cache.geometry_group_changes += 1;
        if let Some(tree) = bvh.as_mut() {
            tree.refit(&boxes);
        }
        if let Some(cw) = wide.as_mut() {
            refit_wide(cw, &boxes);
        }
        bounds = union(&boxes);
        done.refit = true;
        cache.stamps += 1;
        stamp = cache.stamps;
        // Collapsed again from the refit BVH2 (a linear pass), its packets
        // holding the new vertices.
        simd = None;
        moved_bounds = Some((boxes, all_tris));
    }
    if bvh.is_none() && trees.geometry {
        // Earlier launches walked the device's structures; this one walks
        // the host's tree, built now.
        let (boxes, all_tris) = match moved_bounds {
            Some(b) => b,
            None => {
                let (_, boxes, all_tris) = prim_bounds(scene, children)?;
                (boxes, all_tris)
            }
        };
        bvh = Some(group_tree(scene, cache, builder, (&prims, &boxes, all_tris), form)?);
        cache.geometry_group_changes += 1;
        done.built = true;
    }
    if let Some(tree) = &bvh {
        if wide.is_none() && trees.cwbvh && widens(&prims) {
            wide = Some(widen(tree));
        }
        if simd.is_none() && trees.simd && widens(&prims) {
            simd = Some(Box::new(simd_tree(scene, tree, &prims)));
        }
    }
    Ok(NodeAccel::Prims { bvh, wide, simd, prims, bounds, stamp })
}

/// A geometry group's BVH2 over its primitives (`prims`, their bounds,
/// and whether all are fixed triangles, which `Sbvh` splits), counted in
/// `cache`.
fn group_tree(
    scene: &Scene,
    cache: &mut AccelCache,
    builder: Builder,
    (prims, bounds, all_tris): (&[(u32, u32)], &[OAabb], bool),
    form: TreeForm,
) -> Result<Bvh> {
    let tris = (builder == Builder::Sbvh && all_tris).then(|| group_triangles(scene, prims));
    cache.geometry_trees += 1;
    build(builder, bounds, tris.as_deref(), form)
}

/// `bvh` in the CPU backend's SIMD layout, its leaves holding the
/// triangles' vertices when every primitive of `prims` is a triangle with
/// fixed vertices (moving ones are interpolated per ray by the walk's
/// callback).
fn simd_tree(scene: &Scene, bvh: &Bvh, prims: &[(u32, u32)]) -> WideBvh {
    // Each instance's mesh looked up once, not once per triangle.
    let meshes: Vec<Option<&TriangleMesh>> = (0..scene.instances.len() as u32)
        .map(|gi| {
            let geometry = scene.instances[gi as usize].geometry.index() as usize;
            instance_mesh(scene, gi).filter(|_| scene.geometries[geometry].vertex_motion.is_none())
        })
        .collect();
    let all = prims.iter().all(|(gi, _)| meshes[*gi as usize].is_some());
    let triangle = |p: u32| {
        let (gi, t) = prims[p as usize];
        meshes[gi as usize].expect(ALL_TRIANGLES).triangle(t as usize)
    };
    collapse(&bvh.bvh, all.then_some(&triangle as &(dyn Fn(u32) -> [Vec3; 3] + Sync)))
}
