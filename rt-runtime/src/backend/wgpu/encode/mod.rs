//! The scene as words, which both of the wgpu backend's traversals read:
//! instances (transform chains flattened), groups' BVHs and leaf tables,
//! the node table of the graph traversal, the geometry instances' hit and
//! intersection records, miss records ([`encoder`]), around the geometry
//! part ([`geometry`]); the kernel's spec; and what of it the device holds
//! across launches.

mod encoder;
pub(crate) mod geometry;

use super::Launch;
use super::heap::{Records, encode_heap};
use super::kernel::{self, KernelProgram, KernelSpec, SCENE_HEADER_BASES, SCENE_SECTIONS};
use crate::accel::cache::AccelCache;
use crate::error::{LaunchError, LinkError, Result};
use crate::link::instances::Numbering;
use crate::link::{self, Record};
use crate::scene::Scene;
use geometry::{GeometryKey, GeometryLayout, SCENE_HEADER, encode_geometry};
use rt_std::program::{ProgramDescriptor, ProgramKind};

use encoder::{Encoder, Groups, case};
pub(crate) use encoder::{instances, kept_masks};

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

/// Encodes launch `l` for a device with `scene_bindings` scene bindings
/// (see [`kernel::SCENE_SECTIONS`]), around `held_geometry` when the device
/// keeps it.
pub(crate) fn encode(l: &Launch, scene_bindings: usize, held_geometry: Option<&GeometryLayout>) -> Result<Encoded> {
    let (scene, entry) = (l.scene, l.entry);
    let count = scene.entry_points.len() as u32;
    let ep = scene.entry_points.get(entry as usize).ok_or(LinkError::NoSuchEntryPoint { entry, count })?;
    let rg = ep.ray_generation.ok_or(LinkError::NoRayGeneration { entry })?;
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
        return Err(LaunchError::Internal {
            backend: "wgpu",
            problem: format!(
                "internal: the kernel's programs say triangles only: {triangles_only}, the scene's: {}",
                geometry.key.triangles_only
            ),
        }
        .into());
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
