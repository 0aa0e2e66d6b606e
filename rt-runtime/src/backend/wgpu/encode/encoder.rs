//! The scene's nodes as words: instances (each transform chain down to a
//! geometry group flattened into one), groups, the node table the graph
//! traversal walks, geometry instances and the callables' records.

use super::super::heap::Records;
use super::super::kernel::KernelProgram;
use super::geometry::{GeometryLayout, GroupWords, SCENE_HEADER, f, push_bvh};
use super::{NODE_BIT, Tail};
use crate::accel::cache::{AccelCache, NodeAccel};
use crate::backend::wgpu::transform_chain::Chain;
use crate::error::{Result, SceneError};
use crate::link::instances::{Numbering, chain_id, group_words};
use crate::link::{self, Record};
use crate::scene::{GeometryKind, NodeId, NodeKind, ProgramId, Scene};
use glam::Mat4;
use rt_abi::records::{InstanceRecord, NodeEntry};
use rt_std::program::ProgramDescriptor;
use std::collections::HashMap;

pub(crate) fn push_mat(out: &mut Vec<u32>, m: Mat4) {
    out.extend(m.to_cols_array().map(f));
}

/// The visibility word of a chain of nodes with visibility `masks`: a ray
/// with mask `r` enters the chain when *each* node's mask shares a bit
/// with `r` (as on the CPU backend), which one AND of the masks cannot say
/// (0x01 and 0xfe share no bit, yet each shares one with 0x03). The word
/// holds up to four masks, one per byte, unused bytes 0xff; the kernel's
/// `rt_visible` tests every byte. A mask that contains another is implied
/// by it and dropped, so only chains of more than four masks none of
/// which contains another are refused.
pub(crate) fn visibility(masks: &[u8], node: NodeId) -> Result<u32> {
    let mut kept = kept_masks(masks);
    if kept.len() > 4 {
        return Err(SceneError::BadTransform {
            problem: format!(
                "the chain of transforms from node {} has {} visibility masks none of which contains another ({:02x?}); the wgpu backend tests at most 4 per chain",
                node.index(),
                kept.len(),
                kept
            ),
        }.into());
    }
    kept.resize(4, 0xff);
    Ok(u32::from_le_bytes([kept[0], kept[1], kept[2], kept[3]]))
}

/// The masks of a chain that a ray must each share a bit with, less those
/// implied by another: a mask containing another (`a & !b == 0`: a ray
/// sharing a bit with `a` shares one with `b`) is dropped.
pub(crate) fn kept_masks(masks: &[u8]) -> Vec<u8> {
    let within = |a: u8, b: u8| a & !b == 0;
    let mut kept: Vec<u8> = Vec::new();
    for &m in masks {
        if kept.iter().any(|&k| within(k, m)) {
            continue;
        }
        kept.retain(|&k| !within(m, k));
        kept.push(m);
    }
    kept
}

/// Follows transforms down to a geometry group: (group, object-to-world,
/// visibility word).
pub(crate) fn instance_of(scene: &Scene, node: NodeId) -> Result<Option<Instance>> {
    let mut m = Chain::IDENTITY;
    let mut masks = Vec::new();
    let mut n = node;
    for _ in 0..=scene.nodes.len() {
        let rec = &scene.nodes[n.index() as usize];
        masks.push(rec.visibility_mask);
        match &rec.kind {
            NodeKind::GeometryGroup { .. } => {
                return Ok(Some((n, m, visibility(&masks, node)?, chain_id(scene, node).0)));
            }
            NodeKind::Transform { matrix, child, motion: None, .. } => {
                m = m.then(*matrix);
                n = *child;
            }
            // A motion transform has no one matrix: the graph walk
            // evaluates it at the ray's time.
            NodeKind::Transform { motion: Some(_), .. } | NodeKind::Group { .. } | NodeKind::Selector { .. } => {
                return Ok(None);
            }
        }
    }
    Err(SceneError::GraphCycle { node: node.index() }.into())
}

/// The scene's words as they are encoded: the tables and the BVH nodes
/// after the geometry part, and the records and programs they point at.
pub(super) struct Encoder<'a> {
    pub(super) scene: &'a Scene,
    pub(super) header: [u32; SCENE_HEADER],
    pub(super) tables: Tail,
    pub(super) nodes: Tail,
    pub(super) records: Records,
    /// The programs the kernel dispatches to, in first-use order.
    pub(super) programs: Vec<KernelProgram>,
}

/// Where groups' BVHs went ([`Encoder::groups`]).
pub(super) struct Groups {
    /// Per group (node index): its BVH, its leaf table, and whether every
    /// leaf is an instance.
    bvh: HashMap<u32, (u32, u32, bool)>,
    /// The most instances and nodes a leaf of a group's BVH holds.
    pub(super) widest_leaf: u32,
    /// The deepest BVH of a group of instances (`None`: no group).
    pub(super) deepest: Option<u32>,
}

/// An instance: a geometry group, its transform chain, mask and instance
/// id (the chain's innermost, or `INSTANCE_ID_NONE`).
pub(crate) type Instance = (NodeId, Chain, u32, u32);

impl Encoder<'_> {
    /// Program `p`'s case in the kernel's dispatch, added to the kernel's
    /// programs.
    fn use_program(&mut self, p: ProgramId) -> Result<KernelProgram> {
        let kp = KernelProgram { case: case(p), desc: self.scene.program(p)?.desc };
        if !self.programs.iter().any(|q| q.case == kp.case) {
            self.programs.push(kp);
        }
        Ok(kp)
    }

    /// The records of the `#[var]` variables of the callables `callers`
    /// link (resolved in the callable's scope, then the context's), in a
    /// table by program index that header word 3 locates (0: no callable
    /// has variables).
    pub(super) fn callable_records(&mut self, callers: &[&ProgramDescriptor]) -> Result<()> {
        let all = link::callables::scene_callables(self.scene);
        let (_, linked) = link::callables::linked(callers.iter().copied(), &all)?;
        let users: Vec<ProgramId> = link::callables::with_variables(&linked).collect();
        if users.is_empty() {
            self.header[3] = 0;
            return Ok(());
        }
        let mut table = vec![0; self.scene.programs.len()];
        for p in users {
            table[p.index() as usize] = self.record(p, Record::default())?;
        }
        self.header[3] = self.tables.at();
        self.tables.words.extend(table);
        Ok(())
    }

    /// A record for `p` used as `r`: its offset in the heap.
    fn record(&mut self, p: ProgramId, r: Record) -> Result<u32> {
        self.records.add(self.scene, p, r)
    }

    /// BVHs of groups, and their leaf tables: instances, or other nodes
    /// with `NODE_BIT`. Raises `deepest_bvh` to theirs.
    pub(super) fn groups(
        &mut self,
        accels: &AccelCache,
        instance_of_node: &[Option<u32>],
        numbering: &Numbering,
        deepest_bvh: &mut u32,
    ) -> Groups {
        let mut groups = Groups { bvh: HashMap::new(), widest_leaf: 1, deepest: None };
        for (n, rec) in self.scene.nodes.iter().enumerate() {
            if let (NodeKind::Group { children, .. }, Some(NodeAccel::Children { bvh, .. })) =
                (&rec.kind, accels.nodes.get(n).and_then(|a| a.as_ref()))
            {
                let (at, depth) = push_bvh(&mut self.nodes.words, self.nodes.base, bvh);
                *deepest_bvh = (*deepest_bvh).max(depth);
                groups.widest_leaf = bvh.bvh.nodes.iter().map(|n| n.prim_count).fold(groups.widest_leaf, u32::max);
                groups.deepest = Some(groups.deepest.unwrap_or(1).max(depth));
                let table = self.tables.at();
                let mut instances_only = true;
                let offsets = numbering.offsets(children);
                for slot in &bvh.bvh.primitive_indices {
                    let child = children[*slot as usize];
                    match instance_of_node[child.index() as usize] {
                        Some(inst) => self.tables.words.push(inst),
                        None => {
                            instances_only = false;
                            self.tables.words.push(child.index() | NODE_BIT);
                        }
                    }
                    self.tables.words.push(offsets[*slot as usize]);
                }
                groups.bvh.insert(n as u32, (at, table, instances_only));
            }
        }
        groups
    }

    /// The instance records.
    pub(super) fn instances(&mut self, instances: &[Instance], geometry: &GeometryLayout) {
        // Each geometry group's geometry instances, once.
        let mut gis: HashMap<u32, u32> = HashMap::new();
        for (gg, ..) in instances {
            if let std::collections::hash_map::Entry::Vacant(slot) = gis.entry(gg.index()) {
                slot.insert(self.tables.at());
                self.tables.words.extend(group_words(self.scene, *gg));
            }
        }
        self.header[1] = self.tables.at();
        for (gg, o2w, mask, id) in instances {
            let w = geometry.gg_bvh.get(&gg.index()).copied().unwrap_or(GroupWords { bvh: 0, table: 0, tri_slots: 0 });
            let record = InstanceRecord {
                object_to_world: o2w.object_to_world().to_cols_array(),
                world_to_object: o2w.world_to_object().to_cols_array(),
                bvh: w.bvh,
                primitives: w.table,
                mask: *mask,
                geometry_group: gg.index(),
                triangles: w.tri_slots,
                geometry_instances: gis[&gg.index()],
                instance_id: *id,
            };
            self.tables.words.extend(record.words());
        }
    }

    /// The node table (after the side data of transforms and selectors);
    /// returns how many transform levels the graph traversal keeps (0: the
    /// scene needs no graph traversal).
    pub(super) fn node_table(
        &mut self,
        instance_of_node: &[Option<u32>],
        instances: &[Instance],
        groups: &Groups,
        numbering: &Numbering,
    ) -> Result<u32> {
        let scene = self.scene;
        let mut node_entries: Vec<[u32; 4]> = vec![[0; 4]; scene.nodes.len()];
        // How deep transforms above groups and selectors nest (in post
        // order: children before parents).
        let mut levels: Vec<u32> = vec![0; scene.nodes.len()];
        let mut graph = false;
        for n in crate::scene::nodes_post_order(scene)? {
            let i = n.index() as usize;
            let rec = &scene.nodes[i];
            if let Some(inst) = instance_of_node[i] {
                node_entries[i] = [NodeEntry::Instance as u32, inst, 0, instances[inst as usize].2];
                continue;
            }
            let mask = visibility(&[rec.visibility_mask], n)?;
            match &rec.kind {
                NodeKind::Group { children, .. } => {
                    let (bvh, table, instances_only) = groups.bvh[&n.index()];
                    let kind = if instances_only { NodeEntry::InstanceGroup } else { NodeEntry::Group };
                    node_entries[i] = [kind as u32, bvh, table, mask];
                    levels[i] = children.iter().map(|c| levels[c.index() as usize]).max().unwrap_or(0);
                    graph |= !instances_only;
                }
                NodeKind::Transform { motion: Some(motion), child, .. } => {
                    let at = self.tables.at();
                    self.tables.words.push(chain_id(scene, n).0);
                    motion.encode(&mut self.tables.words);
                    node_entries[i] = [NodeEntry::MotionTransform as u32, at, child.index(), mask];
                    levels[i] = 1 + levels[child.index() as usize];
                    graph = true;
                }
                NodeKind::Transform { .. } => {
                    // A chain of static transforms down to a group, selector
                    // or motion transform.
                    let (mut m, mut masks, mut below) = (Chain::IDENTITY, Vec::new(), n);
                    while let NodeKind::Transform { matrix, child, motion: None, .. } =
                        &scene.nodes[below.index() as usize].kind
                    {
                        m = m.then(*matrix);
                        masks.push(scene.nodes[below.index() as usize].visibility_mask);
                        below = *child;
                    }
                    let mask = visibility(&masks, n)?;
                    let at = self.tables.at();
                    push_mat(&mut self.tables.words, m.object_to_world());
                    push_mat(&mut self.tables.words, m.world_to_object());
                    self.tables.words.push(chain_id(scene, n).0);
                    node_entries[i] = [NodeEntry::Transform as u32, at, below.index(), mask];
                    levels[i] = 1 + levels[below.index() as usize];
                    graph = true;
                }
                NodeKind::Selector { visit, children } => {
                    let kp = self.use_program(*visit)?;
                    let vars = self.record(*visit, Record { node: Some(n), ..Record::default() })?;
                    let at = self.tables.at();
                    self.tables.words.extend([kp.case, vars, children.len() as u32]);
                    self.tables.words.extend(children.iter().map(|c| c.index()));
                    self.tables.words.extend(numbering.offsets(children));
                    node_entries[i] = [NodeEntry::Selector as u32, at, 0, mask];
                    levels[i] = children.iter().map(|c| levels[c.index() as usize]).max().unwrap_or(0);
                    graph = true;
                }
                NodeKind::GeometryGroup { .. } => unreachable!("a geometry group is an instance"),
            }
        }
        self.header[0] = self.tables.at();
        self.tables.words.extend(node_entries.into_iter().flatten());
        Ok(if graph { 1 + levels.iter().copied().max().unwrap_or(0) } else { 0 })
    }

    /// Geometry instances, their hit records and intersection records, then
    /// the miss records.
    pub(super) fn geometry_instances(&mut self, geometry: &GeometryLayout) -> Result<()> {
        let scene = self.scene;
        let gi_table = self.tables.words.len();
        self.header[2] = self.tables.at();
        self.tables.words.resize(gi_table + scene.instances.len() * 8, 0);
        let mut isect = Vec::with_capacity(scene.instances.len() * 2);
        for (i, gi) in scene.instances.iter().enumerate() {
            let instance = Some(crate::handles::GeometryInstanceId(i as u32));
            let hit_base = self.tables.at();
            for m in &gi.materials {
                let mat = &scene.materials[m.index() as usize];
                let r = Record { instance, material: Some(*m), ..Record::default() };
                for (ch, ah) in mat.closest_hit.iter().zip(&mat.any_hit) {
                    let mut words = [0u32; 4];
                    if let Some(p) = ch {
                        words[0] = self.use_program(*p)?.case;
                        words[1] = self.record(*p, r)?;
                    }
                    if let Some(p) = ah {
                        words[2] = self.use_program(*p)?.case;
                        words[3] = self.record(*p, r)?;
                    }
                    self.tables.words.extend(words);
                }
            }
            let [kind, pos, idx, nrm, uv, mi] = geometry.geometry_words[gi.geometry.index() as usize];
            let entry = [kind, pos, idx, nrm, uv, mi, gi.materials.len() as u32, hit_base];
            self.tables.words[gi_table + i * 8..gi_table + i * 8 + 8].copy_from_slice(&entry);
            match scene.geometries[gi.geometry.index() as usize].kind {
                GeometryKind::Custom { intersection, .. } => {
                    let kp = self.use_program(intersection)?;
                    let r = Record { instance, geometry: Some(gi.geometry), ..Record::default() };
                    let vars = self.record(intersection, r)?;
                    isect.extend([kp.case, vars]);
                }
                GeometryKind::Triangles(_) => isect.extend([0, 0]),
            }
        }
        self.header[4] = scene.ray_type_count();
        self.header[5] = self.tables.at();
        // Case 0 where a ray type has no miss program: a miss does nothing.
        for m in &scene.miss {
            match *m {
                Some(p) => {
                    let kp = self.use_program(p)?;
                    let vars = self.record(p, Record::default())?;
                    self.tables.words.extend([kp.case, vars]);
                }
                None => self.tables.words.extend([0, 0]),
            }
        }
        self.header[6] = self.tables.at();
        self.tables.words.extend(isect);
        self.header[7] = scene.nodes.len() as u32;
        Ok(())
    }
}

/// Program `p`'s case in the kernel's dispatch (0 is none): its callable id,
/// so that a callable's case is the id programs call it through.
pub(super) fn case(p: ProgramId) -> u32 {
    p.callable_id()
}

/// Instances: one per geometry group and per transform chain; and each
/// node's instance, if it is one.
pub(crate) fn instances(scene: &Scene) -> Result<(Vec<Option<u32>>, Vec<Instance>)> {
    let mut instance_of_node: Vec<Option<u32>> = vec![None; scene.nodes.len()];
    let mut instances: Vec<Instance> = Vec::new();
    for (n, slot) in instance_of_node.iter_mut().enumerate() {
        if let Some(inst) = instance_of(scene, NodeId(n as u32))? {
            *slot = Some(instances.len() as u32);
            instances.push(inst);
        }
    }
    Ok((instance_of_node, instances))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CPU backend's rule: each mask shares a bit with the ray's.
    fn enters(masks: &[u8], ray: u32) -> bool {
        masks.iter().all(|&m| m as u32 & ray != 0)
    }

    /// The kernel's `rt_visible`, in Rust.
    fn visible(word: u32, ray: u32) -> bool {
        let m = word & ((ray & 0xff) * 0x0101_0101);
        (0..4).all(|b| (m >> (8 * b)) & 0xff != 0)
    }

    #[test]
    fn the_visibility_word_tests_every_mask_of_a_chain() {
        let chains: [&[u8]; 6] = [
            &[0xff],
            &[0x01, 0xfe],
            &[0x03, 0x01, 0x07],
            &[0x00, 0xff],
            &[0x10, 0x20, 0x40, 0x80],
            &[0xf0, 0x0f, 0x3c],
        ];
        for chain in chains {
            let word = visibility(chain, NodeId(0)).unwrap();
            for ray in 0..=0xffu32 {
                assert_eq!(visible(word, ray), enters(chain, ray), "chain {chain:02x?}, ray {ray:#x}");
            }
        }
        assert!(
            visibility(&[1, 2, 4, 8, 16], NodeId(3))
                .unwrap_err()
                .to_string()
                .contains("from node 3 has 5 visibility masks")
        );
        assert!(visibility(&[1, 3, 7, 15, 31, 63], NodeId(0)).is_ok(), "masks containing another are implied");
    }
}
