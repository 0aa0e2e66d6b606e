//! The compute traversal's scene: instances (transform chains flattened),
//! groups' BVHs and leaf tables, the node table of the graph traversal, the
//! geometry instances' hit and intersection records, miss records, around
//! the geometry part ([`super::geometry`]); and the kernel's spec.

use super::super::Launch;
use super::super::heap::{Records, encode_heap};
use super::super::kernel::{self, KernelProgram, KernelSpec, SCENE_HEADER_BASES, SCENE_SECTIONS};
use super::geometry::{GeometryKey, GeometryLayout, GroupWords, SCENE_HEADER, encode_geometry, f, push_bvh};
use crate::accel::cache::{AccelCache, NodeAccel};
use crate::backend::wgpu::chain::Chain;
use crate::error::{Result, RtError};
use crate::link::instances::{Numbering, chain_id, group_words};
use crate::link::{self, Record};
use crate::scene::{GeometryKind, NodeId, NodeKind, ProgramId, Scene};
use glam::Mat4;
use rt_abi::records::{InstanceRecord, NodeEntry};
use rt_std::program::{ProgramDescriptor, ProgramKind};
use std::collections::HashMap;

/// Marks a group's leaf that is a node (group, selector, transform above
/// one), not an instance (`RT_NODE_BIT` in traverse.wgsl).
pub(crate) const NODE_BIT: u32 = 0x8000_0000;

/// The scene a launch uploads: everything but the variables' values and the
/// buffers' contents (the heap, [`encode_heap`]). It depends only on the
/// context's structure ([`SceneKey`]), so an unchanged scene is neither
/// encoded nor compared again; and each section is led by the part that
/// comes from geometry alone ([`GeometryLayout`]), so a launch that changed
/// something else (a transform, a program, a node) encodes and uploads only
/// what follows it.
pub(crate) struct Encoded {
    /// The tables' header: where the tables start, counts, and the bases of
    /// sections that share the tables' binding.
    pub(crate) header: [u32; SCENE_HEADER],
    /// Each section's words after its geometry part.
    pub(crate) tails: [Vec<u32>; SCENE_SECTIONS.len()],
    pub(crate) geometry: GeometryLayout,
    /// The geometry part's words in each section, when it was encoded now
    /// (`None`: the device holds it); the tables' words begin with room for
    /// the header.
    pub(crate) geometry_words: Option<[Vec<u32>; SCENE_SECTIONS.len()]>,
    pub(crate) spec: KernelSpec,
    pub(crate) rg_vars: u32,
    pub(crate) ex_vars: u32,
    /// The records the scene points at, in heap order.
    pub(crate) records: Records,
}

impl Encoded {
    /// The whole sections, when the geometry part was encoded now (its
    /// tables begin with room for the header).
    pub(crate) fn whole_sections(&mut self) -> Option<[Vec<u32>; SCENE_SECTIONS.len()]> {
        let mut sections = self.geometry_words.take()?;
        sections[0][..SCENE_HEADER].copy_from_slice(&self.header);
        for (words, tail) in sections.iter_mut().zip(&mut self.tails) {
            words.append(tail);
        }
        Some(sections)
    }
}

/// A section's words from `base` on (what precedes them is encoded
/// separately).
pub(crate) struct Tail {
    pub(crate) base: usize,
    pub(crate) words: Vec<u32>,
}

impl Tail {
    pub(crate) fn new(base: usize) -> Tail {
        Tail { base, words: Vec::new() }
    }

    /// The offset in the section of the next word.
    pub(crate) fn at(&self) -> u32 {
        (self.base + self.words.len()) as u32
    }
}

/// What a scene's encoding depends on: the context's structure (programs,
/// geometry, materials, nodes, entry points: anything but variable values
/// and buffer contents), its acceleration structures, the entry point and
/// the device's scene bindings.
#[derive(Clone, Copy, PartialEq, Debug)]
pub(crate) struct SceneKey {
    pub(crate) structure: u64,
    pub(crate) builds: u64,
    pub(crate) refits: u64,
    pub(crate) entry: u32,
    pub(crate) scene_bindings: usize,
    /// The ray-query traversal's TLAS slots (0: the compute traversal).
    pub(crate) ray_query_slots: u32,
}

impl SceneKey {
    pub(crate) fn of(
        scene: &Scene,
        accels: &AccelCache,
        entry: u32,
        scene_bindings: usize,
        ray_query_slots: u32,
    ) -> SceneKey {
        SceneKey {
            structure: scene.structure_version,
            builds: accels.builds,
            refits: accels.refits,
            entry,
            scene_bindings,
            ray_query_slots,
        }
    }
}

/// The scene the device holds, and what its launches need of it.
pub(crate) struct ResidentScene {
    pub(crate) key: SceneKey,
    pub(crate) geometry: GeometryLayout,
    pub(crate) records: Records,
    pub(crate) rg_vars: u32,
    pub(crate) ex_vars: u32,
    pub(crate) wgsl: String,
    pub(crate) spec: KernelSpec,
}

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
        return Err(RtError::BadTransform {
            problem: format!(
                "the chain of transforms from node {} has {} visibility masks none of which contains another ({:02x?}); the wgpu backend tests at most 4 per chain",
                node.index(),
                kept.len(),
                kept
            ),
        });
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
    Err(RtError::GraphCycle { node: node.index() })
}

/// The scene's words as they are encoded: the tables and the BVH nodes
/// after the geometry part, and the records and programs they point at.
struct Encoder<'a> {
    scene: &'a Scene,
    header: [u32; SCENE_HEADER],
    tables: Tail,
    nodes: Tail,
    records: Records,
    /// The programs the kernel dispatches to, in first-use order.
    programs: Vec<KernelProgram>,
}

/// Where groups' BVHs went ([`Encoder::groups`]).
struct Groups {
    /// Per group (node index): its BVH, its leaf table, and whether every
    /// leaf is an instance.
    bvh: HashMap<u32, (u32, u32, bool)>,
    /// The most instances and nodes a leaf of a group's BVH holds.
    widest_leaf: u32,
    /// The deepest BVH of a group of instances (`None`: no group).
    deepest: Option<u32>,
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
    fn callable_records(&mut self, callers: &[&ProgramDescriptor]) -> Result<()> {
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
    fn groups(
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
    fn instances(&mut self, instances: &[Instance], geometry: &GeometryLayout) {
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
    fn node_table(
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
        for n in link::nodes_post_order(scene)? {
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
    fn geometry_instances(&mut self, geometry: &GeometryLayout) -> Result<()> {
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
        for (r, m) in scene.miss.iter().enumerate() {
            let p = m.ok_or(RtError::NoMissProgram { ray_type: r as u32 })?;
            let kp = self.use_program(p)?;
            let vars = self.record(p, Record::default())?;
            self.tables.words.extend([kp.case, vars]);
        }
        self.header[6] = self.tables.at();
        self.tables.words.extend(isect);
        self.header[7] = scene.nodes.len() as u32;
        Ok(())
    }
}

/// Program `p`'s case in the kernel's dispatch (0 is none): its callable id,
/// so that a callable's case is the id programs call it through.
fn case(p: ProgramId) -> u32 {
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

/// Encodes launch `l` for a device with `scene_bindings` scene bindings
/// (see [`kernel::SCENE_SECTIONS`]), around `held_geometry` when the device
/// keeps it.
pub(crate) fn encode(l: &Launch, scene_bindings: usize, held_geometry: Option<&GeometryLayout>) -> Result<Encoded> {
    let (scene, entry) = (l.scene, l.entry);
    let count = scene.entry_points.len() as u32;
    let ep = scene.entry_points.get(entry as usize).ok_or(RtError::NoSuchEntryPoint { entry, count })?;
    let rg = ep.ray_generation.ok_or(RtError::NoRayGeneration { entry })?;
    link::check_types(scene)?;
    let mut records = Records::default();
    let rg_vars = records.add(scene, rg, Record::default())?;
    let rg_prog = KernelProgram { case: case(rg), desc: scene.program(rg)?.desc };
    let (ex_prog, ex_vars) = match ep.exception {
        Some(e) => (
            Some(KernelProgram { case: case(e), desc: scene.program(e)?.desc }),
            records.add(scene, e, Record::default())?,
        ),
        None => (None, 0),
    };

    // Scene: the tables, BVH nodes and the triangles in leaf order in
    // their own sections, each led by the part that comes from geometry
    // alone (held on the device across launches that change the rest).
    let (geometry, geometry_words) = match held_geometry {
        Some(g) => (g.clone(), None),
        None => {
            let (layout, words) = encode_geometry(scene, l.accels, GeometryKey::of(scene, l.accels, scene_bindings));
            (layout, Some(words))
        }
    };
    let mut deepest_bvh = geometry.deepest_bvh;
    let mut e = Encoder {
        scene,
        header: [0u32; SCENE_HEADER],
        tables: Tail::new(geometry.ends[0]),
        nodes: Tail::new(geometry.ends[1]),
        records,
        programs: Vec::new(),
    };
    let (instance_of_node, instances) = instances(scene)?;
    let numbering = Numbering::of(scene)?;
    let groups = e.groups(l.accels, &instance_of_node, &numbering, &mut deepest_bvh);
    e.instances(&instances, &geometry);
    let graph_levels = e.node_table(&instance_of_node, &instances, &groups, &numbering)?;
    e.geometry_instances(&geometry)?;
    let callers: Vec<&ProgramDescriptor> =
        std::iter::once(rg_prog).chain(ex_prog).chain(e.programs.iter().copied()).map(|p| p.desc).collect();
    e.callable_records(&callers)?;
    let Encoder { header, tables, nodes, records, programs, .. } = e;
    let shape = Shape { deepest_bvh, groups: &groups, graph_levels, geometry: &geometry, scene_bindings };
    let spec = kernel_spec(l, rg_prog, ex_prog, programs, shape)?;
    Ok(Encoded {
        header,
        tails: [tables.words, nodes.words, Vec::new()],
        geometry,
        geometry_words,
        spec,
        rg_vars,
        ex_vars,
        records,
    })
}

/// What sizes the kernel's stacks: the scene's shape.
struct Shape<'a> {
    deepest_bvh: u32,
    groups: &'a Groups,
    graph_levels: u32,
    geometry: &'a GeometryLayout,
    scene_bindings: usize,
}

/// The kernel for the encoded scene: its programs, the default exception
/// program's output, stacks sized for the scene's shape.
fn kernel_spec(
    l: &Launch,
    rg_prog: KernelProgram,
    ex_prog: Option<KernelProgram>,
    programs: Vec<KernelProgram>,
    shape: Shape,
) -> Result<KernelSpec> {
    let Shape { deepest_bvh, groups, graph_levels, geometry, scene_bindings } = shape;
    // The default exception program's image: its offset in the record.
    let default_exception = match ex_prog {
        Some(_) => None,
        None => link::default_exception_output(rg_prog.desc).map(|v| {
            rg_prog.desc.variables[..v].iter().map(|var| kernel::variable_words(&var.kind, &var.ty)).sum::<u32>()
        }),
    };
    // Stacks sized so that no entry is ever dropped: a BVH traversal keeps
    // at most one pending entry per level; graph traversal, one BVH's worth
    // per transform level. Powers of two, so small changes do not relink.
    let bvh_stack = (deepest_bvh + 2).max(64).next_power_of_two();
    let tlas_stack = match groups.deepest {
        Some(depth) => (depth + 2 + groups.widest_leaf).max(64).next_power_of_two(),
        None => 0,
    };
    let graph_stack = ((deepest_bvh + 2) * (graph_levels + 1)).max(96).next_power_of_two();
    // (Moving triangles need the full search too: the lean one reads fixed
    // vertices from triangle slots.)
    let triangles_only =
        !programs.iter().any(|p| matches!(p.desc.kind, ProgramKind::AnyHit | ProgramKind::Intersection))
            && l.scene.geometries.iter().all(|g| g.vertex_motion.is_none());
    if triangles_only != geometry.key.triangles_only {
        return Err(RtError::Gpu(format!(
            "internal: the kernel's programs say triangles only: {triangles_only}, the scene's: {}",
            geometry.key.triangles_only
        )));
    }
    Ok(KernelSpec {
        triangles_only,
        bvh_stack,
        tlas_stack,
        graph_stack,
        ray_generation: rg_prog,
        exception: ex_prog,
        programs,
        max_depth: l.settings.max_trace_depth,
        graph_levels,
        default_exception,
        scene_bindings,
        ray_query_slots: 0,
        callables: link::callables::scene_callables(l.scene),
        cwbvh_stack: if geometry.cwbvh { (geometry.deepest_cwbvh + 2).max(32).next_power_of_two() } else { 0 },
    })
}

/// The sections of `scene` as bound on a device with `scene_bindings`
/// scene bindings: those past the bindings appended to the tables (their
/// bases in the tables' header). Also returns what the appended ones hold.
pub(crate) fn place_sections(
    scene: [Vec<u32>; SCENE_SECTIONS.len()],
    scene_bindings: usize,
) -> (Vec<Vec<u32>>, Vec<&'static str>) {
    let mut sections = Vec::from(scene);
    let shared = sections.split_off(scene_bindings);
    let mut shared_names = Vec::new();
    for (k, words) in shared.into_iter().enumerate() {
        let s = scene_bindings + k;
        sections[0][SCENE_HEADER_BASES + s] = sections[0].len() as u32;
        sections[0].extend(words);
        shared_names.push(SCENE_SECTIONS[s].what);
    }
    (sections, shared_names)
}

/// A launch's new scene for the device: whole sections, or the header and
/// the words after the geometry part the device keeps.
pub(crate) enum NewScene {
    Whole(Vec<Vec<u32>>),
    AroundGeometry { header: [u32; SCENE_HEADER], tails: [Vec<u32>; SCENE_SECTIONS.len()] },
}

/// Debug builds (the tests) check that what the device keeps is what
/// encoding the context now gives: the whole scene when `held` is to be
/// reused, the geometry part when `held_geometry` is. A change that does
/// not bump `Context::structure_version` or `geometry_version` would
/// otherwise leave stale words on the device.
#[cfg(debug_assertions)]
pub(crate) fn check_held_scene(
    l: &Launch,
    scene_bindings: usize,
    device_sections: &[Option<&[u32]>],
    held: Option<&ResidentScene>,
    held_geometry: Option<&GeometryLayout>,
) -> Result<()> {
    if held.is_none() && held_geometry.is_none() {
        return Ok(());
    }
    let mut e = encode(l, scene_bindings, None)?;
    let device = |s: usize| device_sections.get(s).copied().flatten();
    if let Some(h) = held {
        let (sections, _) = place_sections(e.whole_sections().expect("encoded whole"), scene_bindings);
        for (s, words) in sections.iter().enumerate() {
            assert!(device(s) == Some(&words[..]), "stale scene on the device: {}", SCENE_SECTIONS[s].what);
        }
        let same = e.records.uses.len() == h.records.uses.len()
            && e.records.words == h.records.words
            && (e.rg_vars, e.ex_vars) == (h.rg_vars, h.ex_vars);
        assert!(same, "stale records");
    } else if let Some(g) = held_geometry {
        assert!(e.geometry.ends == g.ends && e.geometry.gg_bvh == g.gg_bvh, "stale geometry layout");
        let words = e.geometry_words.take().expect("encoded whole");
        for (s, words) in words.iter().enumerate() {
            // The header is not geometry.
            let start = if s == 0 { SCENE_HEADER } else { 0 };
            let kept = device(s).map(|d| &d[start..g.ends[s]]);
            assert!(kept == Some(&words[start..]), "stale geometry on the device: {}", SCENE_SECTIONS[s].what);
        }
    }
    Ok(())
}

/// What a launch encoded: the scene (`fresh`) unless the device holds it
/// (then `held_wgsl` is its kernel), and the heap with its output buffers'
/// `(buffer index, heap offset, words)`.
pub(crate) struct Encoding {
    pub fresh: Option<Encoded>,
    pub held_wgsl: Option<String>,
    pub heap: Vec<u32>,
    pub outputs: Vec<(usize, usize, usize)>,
    /// Every buffer's `(heap offset, words)`.
    pub placed: Vec<(usize, usize)>,
    /// Every sampler's `(heap offset, words)`.
    pub samplers_placed: Vec<(usize, usize)>,
    /// The heap word of the bindless buffer table.
    pub buffer_table: u32,
    pub rg_vars: u32,
    pub ex_vars: u32,
}

/// Encodes launch `l`: the scene unless `resident` (what the device holds,
/// `device_sections` its words) is the scene of `key`; around its geometry
/// part where that is the same (every section in a binding of its own);
/// then the heap.
pub(crate) fn encode_launch(
    l: &Launch,
    key: SceneKey,
    resident: Option<&ResidentScene>,
    device_sections: &[Option<&[u32]>],
) -> Result<Encoding> {
    let scene_bindings = key.scene_bindings;
    let held = resident.filter(|h| h.key == key);
    let held_geometry = resident
        .filter(|_| held.is_none() && scene_bindings == SCENE_SECTIONS.len())
        .map(|h| &h.geometry)
        .filter(|g| g.key == GeometryKey::of(l.scene, l.accels, scene_bindings));
    #[cfg(debug_assertions)]
    check_held_scene(l, scene_bindings, device_sections, held, held_geometry)?;
    #[cfg(not(debug_assertions))]
    let _ = device_sections;
    let fresh = match held {
        Some(_) => None,
        None => {
            let mut e = encode(l, scene_bindings, held_geometry)?;
            // Ray queries walk no graph: they need neither its stacks nor
            // the selectors' visit dispatch (they refuse selectors).
            e.spec.ray_query_slots = key.ray_query_slots;
            if key.ray_query_slots > 0 {
                e.spec.graph_levels = 0;
            }
            Some(e)
        }
    };
    let (records, rg_vars, ex_vars) = match (&fresh, held) {
        (Some(e), _) => (&e.records, e.rg_vars, e.ex_vars),
        (None, Some(h)) => (&h.records, h.rg_vars, h.ex_vars),
        (None, None) => unreachable!("encoded when none is held"),
    };
    let heap = encode_heap(l.scene, records)?;
    let held_wgsl = if fresh.is_some() { None } else { held.map(|h| h.wgsl.clone()) };
    Ok(Encoding {
        fresh,
        held_wgsl,
        heap: heap.words,
        outputs: heap.outputs,
        placed: heap.placed,
        samplers_placed: heap.samplers_placed,
        buffer_table: heap.buffer_table,
        rg_vars,
        ex_vars,
    })
}

/// A freshly encoded scene placed in the device's bindings: whole
/// sections, or the words around the geometry part the device keeps; and
/// the scene the device then holds. Appends what each binding holds to
/// `parts` (for the binding-size check).
pub(crate) fn place_scene(
    mut e: Encoded,
    key: SceneKey,
    wgsl: &str,
    scene_bindings: usize,
    max_storage_buffers: u32,
    parts: &mut Vec<(String, usize)>,
) -> (NewScene, ResidentScene) {
    let sections = match e.whole_sections() {
        Some(whole) => {
            let (sections, shared_names) = place_sections(whole, scene_bindings);
            let tables_what = if shared_names.is_empty() {
                SCENE_SECTIONS[0].what.to_string()
            } else {
                format!(
                    "{} with {} (one binding: the device allows {} storage buffers per shader stage)",
                    SCENE_SECTIONS[0].what,
                    shared_names.join(" and "),
                    max_storage_buffers
                )
            };
            parts.push((tables_what, sections[0].len()));
            parts.extend(
                sections.iter().enumerate().skip(1).map(|(s, w)| (SCENE_SECTIONS[s].what.to_string(), w.len())),
            );
            NewScene::Whole(sections)
        }
        None => {
            parts.extend(
                SCENE_SECTIONS
                    .iter()
                    .zip(&e.tails)
                    .zip(e.geometry.ends)
                    .map(|((sec, tail), end)| (sec.what.to_string(), end + tail.len())),
            );
            NewScene::AroundGeometry { header: e.header, tails: e.tails }
        }
    };
    let held = ResidentScene {
        key,
        geometry: e.geometry,
        records: e.records,
        rg_vars: e.rg_vars,
        ex_vars: e.ex_vars,
        wgsl: wgsl.to_string(),
        spec: e.spec,
    };
    (sections, held)
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
