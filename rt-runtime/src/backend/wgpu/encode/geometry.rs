//! The geometry part of the compute traversal's scene: per geometry group
//! its BVH (BVH2 or CWBVH nodes), primitive table and triangle slots (none
//! for a group without a host tree: the ray-query traversal's), per
//! geometry its mesh arrays. It leads each section and stays on the device
//! until geometry changes ([`GeometryKey`]).

use super::super::kernel::{SCENE_HEADER_BASES, SCENE_SECTIONS};
use crate::accel::cache::{AccelCache, NodeAccel};
use crate::scene::{GeometryKind, NodeKind, Scene};
use std::collections::HashMap;

/// No index (the kernel's `RT_NONE`).
pub(crate) const RT_NONE: u32 = u32::MAX;

/// Words of the tables' header.
pub(crate) const SCENE_HEADER: usize = SCENE_HEADER_BASES + SCENE_SECTIONS.len();

/// Where the geometry part of the scene ([`encode_geometry`]) put things.
#[derive(Clone)]
pub(crate) struct GeometryLayout {
    pub(crate) key: GeometryKey,
    /// Per geometry group (node index): where its words start.
    pub(crate) gg_bvh: HashMap<u32, GroupWords>,
    /// Per geometry: its kind (0 triangles, 1 custom, 2 triangles with
    /// vertex motion) and the offsets of its positions (kind 2: its motion
    /// keys), indices, normals, texture coordinates and material indices in
    /// the tables.
    pub(crate) geometry_words: Vec<[u32; 6]>,
    /// The deepest BVH of a geometry group.
    pub(crate) deepest_bvh: u32,
    /// Whether geometry groups are encoded as CWBVHs (for a kernel that
    /// searches triangles only, where every geometry group with primitives
    /// has one), and the deepest.
    pub(crate) cwbvh: bool,
    pub(crate) deepest_cwbvh: u32,
    /// Where the part ends in each section (the tables' header included).
    pub(crate) ends: [usize; SCENE_SECTIONS.len()],
}

/// Where a geometry group's words start: its BVH's nodes (BVH2 or CWBVH,
/// see [`GeometryLayout::cwbvh`]; `RT_NONE` for an empty CWBVH), its
/// primitive table and its triangle slots (both in the BVH's order).
#[derive(Clone, Copy, PartialEq, Debug)]
pub(crate) struct GroupWords {
    pub(crate) bvh: u32,
    pub(crate) table: u32,
    pub(crate) tri_slots: u32,
}

/// What the geometry part of the scene depends on: geometries, geometry
/// instances and geometry groups, and the geometry groups' acceleration
/// structures.
#[derive(Clone, Copy, PartialEq, Debug)]
pub(crate) struct GeometryKey {
    pub(crate) geometry: u64,
    pub(crate) accels: u64,
    pub(crate) scene_bindings: usize,
    /// No intersection and no any-hit program in use (the kernel's lean
    /// search, which may walk CWBVHs instead of BVH2s).
    pub(crate) triangles_only: bool,
}

impl GeometryKey {
    pub(crate) fn of(scene: &Scene, accels: &AccelCache, scene_bindings: usize) -> GeometryKey {
        let triangles_only = scene.searches_triangles_only();
        GeometryKey {
            geometry: scene.geometry_version,
            accels: accels.geometry_group_changes,
            scene_bindings,
            triangles_only,
        }
    }
}

pub(crate) fn f(x: f32) -> u32 {
    x.to_bits()
}

/// Levels of a BVH2 (1 for a lone leaf): a near-first traversal keeps at
/// most one pending entry per level, so this sizes the kernel's stacks.
pub(crate) fn bvh_depth(bvh: &crate::accel::bvh::Bvh) -> u32 {
    let nodes = &bvh.bvh.nodes;
    if nodes.is_empty() {
        return 1;
    }
    let mut deepest = 0;
    let mut stack = vec![(0usize, 1u32)];
    while let Some((i, d)) = stack.pop() {
        deepest = deepest.max(d);
        let n = &nodes[i];
        if n.prim_count == 0 {
            let c = n.first_index as usize;
            for child in [c, c + 1] {
                if child < nodes.len() {
                    stack.push((child, d + 1));
                }
            }
        }
    }
    deepest
}

/// Appends `bvh`'s nodes to `out`, which starts at word `base` of its
/// section; returns where they start and the BVH's depth ([`bvh_depth`]).
pub(crate) fn push_bvh(out: &mut Vec<u32>, base: usize, bvh: &crate::accel::bvh::Bvh) -> (u32, u32) {
    let depth = bvh_depth(bvh);
    let at = (base + out.len()) as u32;
    for n in &bvh.bvh.nodes {
        let b = n.aabb();
        out.extend([
            f(b.min.x),
            f(b.min.y),
            f(b.min.z),
            f(b.max.x),
            f(b.max.y),
            f(b.max.z),
            n.prim_count,
            n.first_index,
        ]);
    }
    if bvh.bvh.nodes.is_empty() {
        // An empty group: a root that no ray enters.
        out.extend([f(1.0), f(1.0), f(1.0), f(-1.0), f(-1.0), f(-1.0), 0, 0]);
    }
    (at, depth)
}

/// The triangle slot of primitive `p` of geometry instance `gi` (10 words,
/// see traverse.wgsl): its vertices, then its material index. When no hit
/// on it can commit (a custom primitive; a material index past the
/// instance's materials), NaN vertices, which the triangle test never
/// hits, and `RT_NONE`: the lean search checks nothing per candidate.
pub(crate) fn push_triangle_slot(scene: &Scene, out: &mut Vec<u32>, gi: u32, p: u32) {
    let instance = &scene.instances[gi as usize];
    let never = [f(f32::NAN); 9].into_iter().chain([RT_NONE]);
    match &scene.geometries[instance.geometry.index() as usize].kind {
        GeometryKind::Triangles(mesh) => {
            let m = mesh.material_indices.as_ref().map_or(0, |m| m.get(p as usize).copied().unwrap_or(0));
            if (m as usize) >= instance.materials.len() {
                out.extend(never);
                return;
            }
            for i in mesh.indices[p as usize] {
                let v = mesh.positions[i as usize];
                out.extend([f(v.x), f(v.y), f(v.z)]);
            }
            out.push(m);
        }
        GeometryKind::Custom { .. } => out.extend(never),
    }
}

/// The part of the scene that comes from geometry alone: per geometry
/// group its BVH nodes, its primitive table (in the tables, after room for
/// the header) and its triangle slots; per geometry its mesh arrays (in the
/// tables). Returns its layout and its words in each section.
pub(crate) fn encode_geometry(
    scene: &Scene,
    accels: &AccelCache,
    key: GeometryKey,
) -> (GeometryLayout, [Vec<u32>; SCENE_SECTIONS.len()]) {
    let (mut tables, mut nodes, mut tris) = (vec![0; SCENE_HEADER], Vec::new(), Vec::new());
    let table_at = |tables: &Vec<u32>| tables.len() as u32;
    let mut gg_bvh = HashMap::new();
    let mut deepest_bvh = 1;
    let mut deepest_cwbvh = 1;
    let groups = || {
        scene.nodes.iter().enumerate().filter_map(|(n, rec)| match (&rec.kind, accels.nodes.get(n)?.as_ref()?) {
            (NodeKind::GeometryGroup { .. }, NodeAccel::Prims { bvh, wide, prims, .. }) => Some((n, bvh, wide, prims)),
            _ => None,
        })
    };
    // A kernel searching triangles only walks CWBVHs where every geometry
    // group with primitives has one (none is `NoAccel`): their nodes, their
    // primitive tables and triangle slots in CWBVH order. Otherwise BVH2s:
    // their nodes, primitive tables in leaf order, and (for the lean
    // search) triangle slots in leaf order.
    let cwbvh = key.triangles_only && groups().all(|(_, _, wide, prims)| prims.is_empty() || wide.is_some());
    for (n, bvh, wide, prims) in groups() {
        let tri_slots = tris.len() as u32;
        let Some(bvh) = bvh else {
            // No tree on the host: the launch walks the device's structures
            // (ray queries), which read no node, primitive table or slot.
            gg_bvh.insert(n as u32, GroupWords { bvh: RT_NONE, table: table_at(&tables), tri_slots });
            continue;
        };
        let (at, table, order) = match wide {
            Some(cw) if cwbvh => {
                let at = nodes.len() as u32;
                for node in &cw.nodes {
                    nodes.extend(cwbvh_node_words(node));
                }
                deepest_cwbvh = deepest_cwbvh.max(cwbvh_depth(cw));
                (at, table_at(&tables), &cw.primitive_indices)
            }
            // A geometry group without primitives.
            None if cwbvh => (RT_NONE, table_at(&tables), &bvh.bvh.primitive_indices),
            _ => {
                let (at, depth) = push_bvh(&mut nodes, 0, bvh);
                deepest_bvh = deepest_bvh.max(depth);
                (at, table_at(&tables), &bvh.bvh.primitive_indices)
            }
        };
        for slot in order {
            let (gi, p) = prims[*slot as usize];
            tables.extend([gi, p]);
            push_triangle_slot(scene, &mut tris, gi, p);
        }
        gg_bvh.insert(n as u32, GroupWords { bvh: at, table, tri_slots });
    }
    let mut geometry_words = Vec::with_capacity(scene.geometries.len());
    for g in &scene.geometries {
        match &g.kind {
            GeometryKind::Triangles(mesh) => {
                let pos = table_at(&tables);
                // Kind 2: moving vertices, `pos` their keys (`rt_tri_corner`).
                let kind = match &g.vertex_motion {
                    Some(motion) => {
                        motion.encode(&mut tables);
                        2
                    }
                    None => {
                        tables.extend(mesh.positions.iter().flat_map(|p| [f(p.x), f(p.y), f(p.z)]));
                        0
                    }
                };
                let idx = table_at(&tables);
                tables.extend(mesh.indices.iter().flatten());
                let nrm = match &mesh.normals {
                    Some(ns) => {
                        let at = table_at(&tables);
                        tables.extend(ns.iter().flat_map(|n| [f(n.x), f(n.y), f(n.z)]));
                        at
                    }
                    None => u32::MAX,
                };
                let uv = match &mesh.texcoords {
                    Some(ts) => {
                        let at = table_at(&tables);
                        tables.extend(ts.iter().flat_map(|t| [f(t.x), f(t.y)]));
                        at
                    }
                    None => u32::MAX,
                };
                let mi = match &mesh.material_indices {
                    Some(m) => {
                        let at = table_at(&tables);
                        tables.extend(m);
                        at
                    }
                    None => u32::MAX,
                };
                geometry_words.push([kind, pos, idx, nrm, uv, mi]);
            }
            GeometryKind::Custom { .. } => geometry_words.push([1, 0, 0, u32::MAX, u32::MAX, u32::MAX]),
        }
    }
    // A binding needs a word.
    for section in [&mut nodes, &mut tris] {
        if section.is_empty() {
            section.push(0);
        }
    }
    let ends = [tables.len(), nodes.len(), tris.len()];
    let layout = GeometryLayout { key, gg_bvh, geometry_words, deepest_bvh, cwbvh, deepest_cwbvh, ends };
    (layout, [tables, nodes, tris])
}

/// A CWBVH node's 20 words as it lies in memory (obvhs's `CwBvhNode`,
/// little-endian): p, then e0 e1 e2 imask, child base, primitive base, then
/// two words each of child meta, min x, max x, min y, max y, min z, max z.
/// The layout the kernel reads (`rt_cw_node_hits`); public for other WGSL
/// over the same nodes (rt-bench's hand-written kernel).
pub fn cwbvh_node_words(n: &obvhs::cwbvh::node::CwBvhNode) -> [u32; 20] {
    let mut w = [0u32; 20];
    w[..3].copy_from_slice(&[f(n.p.x), f(n.p.y), f(n.p.z)]);
    w[3] = u32::from_le_bytes([n.e[0], n.e[1], n.e[2], n.imask]);
    w[4] = n.child_base_idx;
    w[5] = n.primitive_base_idx;
    let arrays =
        [n.child_meta, n.child_min_x, n.child_max_x, n.child_min_y, n.child_max_y, n.child_min_z, n.child_max_z];
    for (k, b) in arrays.into_iter().enumerate() {
        w[6 + 2 * k] = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        w[7 + 2 * k] = u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
    }
    w
}

/// Levels of a CWBVH's internal nodes: a traversal keeps at most one
/// pending group of children per level, so this sizes its stack.
pub(crate) fn cwbvh_depth(cw: &obvhs::cwbvh::CwBvh) -> u32 {
    if cw.nodes.is_empty() {
        return 1;
    }
    let mut deepest = 0;
    let mut stack = vec![(0usize, 1u32)];
    while let Some((i, d)) = stack.pop() {
        deepest = deepest.max(d);
        let n = &cw.nodes[i];
        for k in 0..n.imask.count_ones() {
            let child = (n.child_base_idx + k) as usize;
            if child < cw.nodes.len() {
                stack.push((child, d + 1));
            }
        }
    }
    deepest
}
