//! The wgpu backend: every program linked into one compute shader (see
//! [`kernel`]), the scene and all user data in a few storage buffers.
//!
//! Bindings: `rt_heap` (read-write: scope records of variables, then user
//! buffers, then sampler texels — addressed by word offset, so a scene uses
//! the same bindings however many buffers it has), the scene's sections
//! (read-only, [`kernel::SCENE_SECTIONS`]: `rt_scene` with the geometry,
//! instance and record tables, `rt_bvh` with every BVH's nodes, `rt_tris`
//! with every triangle's vertices and material in BVH order), `rt_log`
//! (exceptions and `rt_printf!` output) and the launch uniform.
//!
//! Trees: groups' BVHs are BVH2s. Geometry groups are CWBVHs (obvhs's
//! compressed 8-wide BVH, 20 words a node) where the kernel searches
//! triangles only (no any-hit or intersection program) and every geometry
//! group has one (`RT_CWBVH`), else the BVH2s they are converted from.
//!
//! Large scenes: each section is its own binding, so a scene renders when
//! each section fits the adapter's `max_storage_buffer_binding_size` (128
//! MiB on lavapipe) rather than the whole; a section that does not fit is
//! an [`RtError::Gpu`] naming it, its size, the adapter and the limit. The
//! device asks for one storage buffer per section (5 in all) up to the
//! adapter's own limit; on a device with fewer (an application's, through
//! `Context::use_wgpu_device`), the sections without a binding follow the
//! tables in `rt_scene`'s and are read at a base from the tables' header.
//! Tests force both with devices of smaller limits (`device_with` in
//! tests/tests/runtime.rs). The heap is one binding.
//!
//! Traversal: every transform chain down to a geometry group is flattened
//! into an instance (one matrix, its inverse, the AND of the chain's
//! visibility masks). A group of instances is the two-level fast path
//! (`rt_search` in traverse.wgsl). Anything deeper — groups of groups,
//! transforms above groups or selectors, selectors — gets a node-table entry
//! that the graph traversal (graph.wgsl) walks with one explicit stack of
//! graph nodes and BVH nodes, keeping a small array of transform levels
//! instead of recursing; selectors call the generated `rt_visit_dispatch`.
//! The graph traversal is linked only into kernels whose scene needs it, so
//! two-level scenes keep the lean kernel. Semantics are the CPU backend's.
//!
//! Speed on lavapipe: llvmpipe runs a workgroup's invocations as SIMD lanes
//! and both sides of a divergent branch under a mask, so a search costs
//! about the code it holds, taken or not. Kernels link the lean forms the
//! scene allows: without intersection and any-hit programs, instances are
//! searched by a loop over their CWBVH (or leaf-ordered BVH2) triangles
//! with its state in locals (`RT_TRIANGLES_ONLY`); without groups of
//! instances, `rt_search` has no loop over one (`RT_GROUPS`). Both are
//! fixed by the program set and the graph's shape, like the rest of the
//! kernel. (BENCHMARKS.md: the AO workload from 0.46 to 0.8 of the
//! hand-written kernel over BVH2s; the CWBVH then made both 1.4-2.5x
//! faster.)
//!
//! Caching: the pipeline is keyed by the generated WGSL, which depends on the
//! program set and the graph's shape but never on variable values or buffer
//! contents; those only change the uploaded words.
//!
//! Residency: buffers stay on the device between launches, and a launch
//! writes only the 4 KiB pages that changed. The scene is encoded only when
//! the context's structure changed (`SceneKey`: a launch that changed
//! only variable values and buffer contents encodes the heap alone), and
//! then around the geometry part that leads each section (`GeometryKey`:
//! geometry groups' BVH nodes, primitive tables and triangles, meshes),
//! which stays as it is until geometry changes. A moving transform over a
//! 2M-triangle mesh costs under a millisecond of host work a launch.
//! `Context::scene_encodes` and `geometry_encodes` count both; debug builds
//! check every kept word against a fresh encoding.

pub mod kernel;

use super::{BackendStats, ExceptionRecord, Launch, LaunchBackend, LaunchReport};
use crate::accel::bvh::TreeForm;
use crate::accel::cache::{AccelCache, NodeAccel, Trees};
use crate::buffer::BufferRec;
use crate::error::{Result, RtError};
use crate::link::{self, Record};
use crate::scene::{GeometryKind, NodeId, NodeKind, ProgramId, Scene};
use crate::vars::VarValue;
use glam::{Mat4, UVec2};
use kernel::{KernelProgram, KernelSpec, SCENE_HEADER_BASES, SCENE_SECTIONS};
use rt_abi::records::{InstanceRecord, LaunchUniform, NodeEntry};
use rt_std::program::{ProgramKind, VariableKind};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use wgpu::util::DeviceExt;

/// Capacity of the exception log (records past it are counted, not kept).
const LOG_EXCEPTIONS: u32 = 4096;
/// Words for `rt_printf!` records.
const LOG_PRINT_WORDS: u32 = 1 << 16;
/// Marks a group's leaf that is a node (group, selector, transform above
/// one), not an instance (`RT_NODE_BIT` in traverse.wgsl).
const NODE_BIT: u32 = 0x8000_0000;

/// A wgpu device and what the backend keeps on it between launches.
pub struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    limits: wgpu::Limits,
    /// How many of the scene's sections get their own binding (see
    /// [`kernel::SCENE_SECTIONS`]): all of them where the device allows
    /// enough storage buffers per stage.
    scene_bindings: usize,
    /// The one bind-group layout of every megakernel, so bind groups outlive
    /// pipelines.
    layout: wgpu::BindGroupLayout,
    pipelines: HashMap<String, wgpu::ComputePipeline>,
    /// How many pipelines were created (links); for tests of the cache.
    pub pipelines_created: u64,
    /// How many launches encoded the scene (see `SceneKey`), and how many
    /// of those its geometry part too (`GeometryKey`).
    pub scene_encodes: u64,
    pub geometry_encodes: u64,
    resident: Resident,
    health: Arc<Health>,
}

/// What the device's callbacks report.
#[derive(Default)]
struct Health {
    /// Why the device was lost, once it is (its lost callback writes it).
    lost: Mutex<Option<String>>,
    /// Errors outside any error scope (wgpu's default handler would panic
    /// on them); a launch that finds one fails with it.
    uncaptured: Mutex<Vec<String>>,
}

impl Health {
    fn lost_reason(&self) -> Option<String> {
        self.lost.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// The error for a launch that failed on the device `adapter`:
    /// `DeviceLost` when the device is gone, else `what` with any uncaptured
    /// wgpu errors.
    fn failure(&self, adapter: String, what: String) -> RtError {
        if let Some(reason) = self.lost_reason() {
            return RtError::DeviceLost { adapter, reason };
        }
        match self.take_errors() {
            Some(errors) => RtError::Gpu(format!("{what}: {errors}")),
            None => RtError::Gpu(what),
        }
    }

    /// The uncaptured errors since the last call, joined.
    fn take_errors(&self) -> Option<String> {
        let errors = std::mem::take(&mut *self.uncaptured.lock().unwrap_or_else(|e| e.into_inner()));
        (!errors.is_empty()).then(|| errors.join("; "))
    }
}

/// The buffers a context keeps on its device between launches.
///
/// The heap and the scene are mirrored: the host keeps a copy of the words
/// the device buffer holds, so a launch writes only the 4 KiB pages whose
/// words changed (none, when only the camera moved but one page of records)
/// and allocates a new buffer only when the size changed. After a launch
/// the output buffers' words are read back into both the context and the
/// mirror, so the mirror stays what the device holds. The log is reset by
/// writing its four header words; only the words a launch wrote (output
/// buffers, the log header, then the exceptions and prints it counted) come
/// back.
#[derive(Default)]
struct Resident {
    heap: Option<Mirrored>,
    /// One per scene binding.
    scene: Vec<Option<Mirrored>>,
    log: Option<wgpu::Buffer>,
    /// One 256-byte-aligned launch uniform per dispatch tile.
    uniforms: Option<(wgpu::Buffer, u32)>,
    readback: Option<wgpu::Buffer>,
    /// The scene the `scene` buffers hold, and its records' layout.
    held: Option<ResidentScene>,
    /// Two timestamps (start and end of the launch's compute pass) and the
    /// buffer they resolve to, on devices with timestamp queries.
    timestamps: Option<(wgpu::QuerySet, wgpu::Buffer)>,
    /// Bind groups per tile, over the buffers above (cleared when one of
    /// them is replaced).
    bind_groups: Vec<wgpu::BindGroup>,
    /// Bytes written to the device by the last launch (for tests).
    uploaded: u64,
}

/// A device storage buffer and the words it holds.
struct Mirrored {
    buffer: wgpu::Buffer,
    words: Vec<u32>,
}

/// Diff granularity of mirrored buffers, in words.
const PAGE_WORDS: usize = 1024;

impl Resident {
    /// Makes `slot`'s device buffer hold `words`; returns true if it had to
    /// be replaced (a new size).
    fn sync(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        slot: &mut Option<Mirrored>,
        words: Vec<u32>,
        label: &str,
        uploaded: &mut u64,
    ) -> bool {
        if let Some(m) = slot
            && m.words.len() == words.len()
        {
            write_changed(queue, &m.buffer, &mut m.words, &words, 0, uploaded);
            return false;
        }
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: words_to_bytes(&words),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        });
        *uploaded += (words.len() * 4) as u64;
        *slot = Some(Mirrored { buffer, words });
        true
    }

    /// Makes `slot`'s device buffer hold `head`, then what it holds now from
    /// `head.len()` to `keep_end`, then `tail`: the words in between are
    /// neither compared nor written. Returns true if the buffer had to be
    /// replaced (a new size: then all of it is uploaded).
    #[allow(clippy::too_many_arguments)]
    fn sync_around(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        slot: &mut Option<Mirrored>,
        head: &[u32],
        keep_end: usize,
        tail: Vec<u32>,
        label: &str,
        uploaded: &mut u64,
    ) -> bool {
        let Some(m) = slot.as_mut().filter(|m| m.words.len() >= keep_end) else {
            unreachable!("a section kept on the device is mirrored")
        };
        if m.words.len() == keep_end + tail.len() {
            write_changed(queue, &m.buffer, &mut m.words[..head.len()], head, 0, uploaded);
            write_changed(queue, &m.buffer, &mut m.words[keep_end..], &tail, keep_end, uploaded);
            return false;
        }
        let mut words = std::mem::take(&mut m.words);
        words[..head.len()].copy_from_slice(head);
        words.truncate(keep_end);
        words.extend(tail);
        *slot = None;
        Resident::sync(device, queue, slot, words, label, uploaded)
    }
}

/// Writes the pages of `new` that differ from `old` (the device's words
/// from word `at` of `buffer` on, same length) into the buffer, a run of
/// changed pages at a time, and copies them into `old`.
fn write_changed(
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
    old: &mut [u32],
    new: &[u32],
    at: usize,
    uploaded: &mut u64,
) {
    let end = |p: usize| (p * PAGE_WORDS).min(new.len());
    let mut page = 0;
    while page * PAGE_WORDS < new.len() {
        let start = page * PAGE_WORDS;
        if old[start..end(page + 1)] == new[start..end(page + 1)] {
            page += 1;
            continue;
        }
        // A run of changed pages: one write.
        let mut last = page + 1;
        while last * PAGE_WORDS < new.len() && old[end(last)..end(last + 1)] != new[end(last)..end(last + 1)] {
            last += 1;
        }
        let run = start..end(last);
        queue.write_buffer(buffer, ((at + start) * 4) as u64, words_to_bytes(&new[run.clone()]));
        *uploaded += (run.len() * 4) as u64;
        old[run.clone()].copy_from_slice(&new[run]);
        page = last;
    }
}

impl Gpu {
    /// Opens the first adapter wgpu finds (a GPU, else lavapipe).
    pub fn new() -> Result<Gpu> {
        let instance = instance();
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        }))
        .map_err(|e| {
            RtError::Gpu(format!(
                "no wgpu adapter ({e}); on a machine without a GPU install Mesa's lavapipe (`apt-get install mesa-vulkan-drivers`)"
            ))
        })?;
        // Heap, log and one binding per scene section, where the adapter
        // has that many.
        let storage = (2 + SCENE_SECTIONS.len() as u32).min(adapter.limits().max_storage_buffers_per_shader_stage);
        let limits =
            wgpu::Limits { max_storage_buffers_per_shader_stage: storage, ..wgpu::Limits::downlevel_defaults() }
                .using_resolution(adapter.limits());
        let limits = wgpu::Limits {
            max_storage_buffer_binding_size: adapter.limits().max_storage_buffer_binding_size,
            max_buffer_size: adapter.limits().max_buffer_size,
            ..limits
        };
        // Timestamps, where the adapter has them: the device's own time of
        // a launch ([`super::Timings::kernel`]).
        let required_features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("rt-runtime"),
            required_limits: limits.clone(),
            required_features,
            ..Default::default()
        }))
        .map_err(|e| RtError::Gpu(format!("cannot open a device on {}: {e}", adapter.get_info().name)))?;
        Ok(Gpu::from_parts(device, queue, adapter.get_info(), limits))
    }

    /// Uses a device the application already has.
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue, info: wgpu::AdapterInfo) -> Gpu {
        let limits = device.limits();
        Gpu::from_parts(device, queue, info, limits)
    }

    fn from_parts(device: wgpu::Device, queue: wgpu::Queue, info: wgpu::AdapterInfo, limits: wgpu::Limits) -> Gpu {
        // An explicit layout: a kernel that never reads a binding (no
        // traces: no `rt_scene`) still takes them all. Heap, log: 2 storage
        // buffers; the rest go to the scene's sections.
        let scene_bindings =
            (limits.max_storage_buffers_per_shader_stage.saturating_sub(2) as usize).clamp(1, SCENE_SECTIONS.len());
        let buffer = |binding: u32, ty: wgpu::BufferBindingType| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
            count: None,
        };
        let storage = |read_only| wgpu::BufferBindingType::Storage { read_only };
        let mut entries = vec![
            buffer(0, storage(false)),
            buffer(1, storage(true)),
            buffer(2, storage(false)),
            buffer(3, wgpu::BufferBindingType::Uniform),
        ];
        entries.extend((1..scene_bindings).map(|s| buffer(3 + s as u32, storage(true))));
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rt bindings"),
            entries: &entries,
        });
        let health = Arc::new(Health::default());
        let on_lost = Arc::clone(&health);
        device.set_device_lost_callback(move |reason, message| {
            let why = if message.is_empty() { format!("{reason:?}") } else { format!("{reason:?}: {message}") };
            *on_lost.lost.lock().unwrap_or_else(|e| e.into_inner()) = Some(why);
        });
        let on_error = Arc::clone(&health);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            on_error.uncaptured.lock().unwrap_or_else(|e| e.into_inner()).push(e.to_string());
        }));
        Gpu {
            device,
            queue,
            info,
            limits,
            scene_bindings,
            layout,
            pipelines: HashMap::new(),
            pipelines_created: 0,
            scene_encodes: 0,
            geometry_encodes: 0,
            resident: Resident::default(),
            health,
        }
    }

    /// Bytes the last launch wrote to the device (scene, heap pages, log
    /// header, launch uniforms).
    pub fn last_upload_bytes(&self) -> u64 {
        self.resident.uploaded
    }

    /// The adapter's name and type, for messages ("llvmpipe (Cpu)").
    pub fn describe(&self) -> String {
        format!("{} ({:?}, {:?})", self.info.name, self.info.device_type, self.info.backend)
    }

    /// Whether the adapter is a software rasteriser (lavapipe).
    pub fn is_cpu(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }
}

/// A wgpu instance for headless compute, as every device of the runtime is
/// opened.
///
/// On a machine without a window system (no `XDG_RUNTIME_DIR`), Mesa's
/// implicit Vulkan layer `VK_LAYER_MESA_device_select` tries to reach a
/// Wayland compositor while adapters are enumerated, and libwayland prints
/// "error: XDG_RUNTIME_DIR is invalid or not set in the environment." to
/// stderr each time. The layer only reorders devices, which wgpu's own
/// power preference decides anyway, so there the runtime turns it off the
/// way its manifest offers (`NODEVICE_SELECT=1`), once, before it creates
/// its first instance. A user's own setting of either variable wins.
pub fn instance() -> wgpu::Instance {
    static QUIET: std::sync::Once = std::sync::Once::new();
    QUIET.call_once(|| {
        if std::env::var_os("XDG_RUNTIME_DIR").is_none() && std::env::var_os("NODEVICE_SELECT").is_none() {
            // SAFETY: runs once, before the runtime has created any Vulkan
            // instance (so before any driver thread of ours reads the
            // environment); std's own environment accesses are locked.
            unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
        }
    });
    wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env())
}

/// The adapter wgpu would pick, without opening a device.
pub fn probe() -> Option<wgpu::AdapterInfo> {
    let instance = instance();
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        ..Default::default()
    }))
    .ok()?;
    Some(adapter.get_info())
}

/// The scene a launch uploads: everything but the variables' values and the
/// buffers' contents (the heap, [`encode_heap`]). It depends only on the
/// context's structure ([`SceneKey`]), so an unchanged scene is neither
/// encoded nor compared again; and each section is led by the part that
/// comes from geometry alone ([`GeometryLayout`]), so a launch that changed
/// something else (a transform, a program, a node) encodes and uploads only
/// what follows it.
struct Encoded {
    /// The tables' header: where the tables start, counts, and the bases of
    /// sections that share the tables' binding.
    header: [u32; SCENE_HEADER],
    /// Each section's words after its geometry part.
    tails: [Vec<u32>; SCENE_SECTIONS.len()],
    geometry: GeometryLayout,
    /// The geometry part's words in each section, when it was encoded now
    /// (`None`: the device holds it); the tables' words begin with room for
    /// the header.
    geometry_words: Option<[Vec<u32>; SCENE_SECTIONS.len()]>,
    spec: KernelSpec,
    rg_vars: u32,
    ex_vars: u32,
    /// The records the scene points at, in heap order.
    records: Records,
}

impl Encoded {
    /// The whole sections, when the geometry part was encoded now (its
    /// tables begin with room for the header).
    fn whole_sections(&mut self) -> Option<[Vec<u32>; SCENE_SECTIONS.len()]> {
        let mut sections = self.geometry_words.take()?;
        sections[0][..SCENE_HEADER].copy_from_slice(&self.header);
        for (words, tail) in sections.iter_mut().zip(&mut self.tails) {
            words.append(tail);
        }
        Some(sections)
    }
}

/// No index (the kernel's `RT_NONE`).
const RT_NONE: u32 = u32::MAX;

/// Words of the tables' header.
const SCENE_HEADER: usize = SCENE_HEADER_BASES + SCENE_SECTIONS.len();

/// A section's words from `base` on (what precedes them is encoded
/// separately).
struct Tail {
    base: usize,
    words: Vec<u32>,
}

impl Tail {
    fn new(base: usize) -> Tail {
        Tail { base, words: Vec::new() }
    }

    /// The offset in the section of the next word.
    fn at(&self) -> u32 {
        (self.base + self.words.len()) as u32
    }
}

/// Where the geometry part of the scene ([`encode_geometry`]) put things.
#[derive(Clone)]
struct GeometryLayout {
    key: GeometryKey,
    /// Per geometry group (node index): where its words start.
    gg_bvh: HashMap<u32, GroupWords>,
    /// Per geometry: its kind and the offsets of its positions, indices,
    /// normals, texture coordinates and material indices in the tables.
    geometry_words: Vec<[u32; 6]>,
    /// The deepest BVH of a geometry group.
    deepest_bvh: u32,
    /// Whether geometry groups are encoded as CWBVHs (for a kernel that
    /// searches triangles only, where every geometry group with primitives
    /// has one), and the deepest.
    cwbvh: bool,
    deepest_cwbvh: u32,
    /// Where the part ends in each section (the tables' header included).
    ends: [usize; SCENE_SECTIONS.len()],
}

/// Where a geometry group's words start: its BVH's nodes (BVH2 or CWBVH,
/// see [`GeometryLayout::cwbvh`]; `RT_NONE` for an empty CWBVH), its
/// primitive table and its triangle slots (both in the BVH's order).
#[derive(Clone, Copy, PartialEq, Debug)]
struct GroupWords {
    bvh: u32,
    table: u32,
    tri_slots: u32,
}

/// What the geometry part of the scene depends on: geometries, geometry
/// instances and geometry groups, and the geometry groups' acceleration
/// structures.
#[derive(Clone, Copy, PartialEq, Debug)]
struct GeometryKey {
    geometry: u64,
    accels: u64,
    scene_bindings: usize,
    /// No intersection and no any-hit program in use (the kernel's lean
    /// search, which may walk CWBVHs instead of BVH2s).
    triangles_only: bool,
}

impl GeometryKey {
    fn of(scene: &Scene, accels: &AccelCache, scene_bindings: usize) -> GeometryKey {
        let triangles_only = scene.searches_triangles_only();
        GeometryKey {
            geometry: scene.geometry_version,
            accels: accels.geometry_group_changes,
            scene_bindings,
            triangles_only,
        }
    }
}

/// The records of a launch's program uses, laid out before their values
/// are known: a record's size is fixed by its program's variables.
#[derive(Clone, Default)]
struct Records {
    uses: Vec<(ProgramId, Record)>,
    words: u32,
}

impl Records {
    /// A record for `p` used as `r`; returns its offset in the heap.
    fn add(&mut self, scene: &Scene, p: ProgramId, r: Record) -> Result<u32> {
        let at = self.words;
        let desc = scene.program(p)?.desc;
        self.words += desc.variables.iter().map(|v| kernel::variable_words(&v.kind, &v.ty)).sum::<u32>();
        self.uses.push((p, r));
        Ok(at)
    }
}

/// What a scene's encoding depends on: the context's structure (programs,
/// geometry, materials, nodes, entry points: anything but variable values
/// and buffer contents), its acceleration structures, the entry point and
/// the device's scene bindings.
#[derive(Clone, Copy, PartialEq, Debug)]
struct SceneKey {
    structure: u64,
    builds: u64,
    refits: u64,
    entry: u32,
    scene_bindings: usize,
}

impl SceneKey {
    fn of(scene: &Scene, accels: &AccelCache, entry: u32, scene_bindings: usize) -> SceneKey {
        SceneKey {
            structure: scene.structure_version,
            builds: accels.builds,
            refits: accels.refits,
            entry,
            scene_bindings,
        }
    }
}

/// The scene the device holds, and what its launches need of it.
struct ResidentScene {
    key: SceneKey,
    geometry: GeometryLayout,
    records: Records,
    rg_vars: u32,
    ex_vars: u32,
    wgsl: String,
    spec: KernelSpec,
}

fn f(x: f32) -> u32 {
    x.to_bits()
}

fn push_mat(out: &mut Vec<u32>, m: Mat4) {
    out.extend(m.to_cols_array().map(f));
}

/// Levels of a BVH2 (1 for a lone leaf): a near-first traversal keeps at
/// most one pending entry per level, so this sizes the kernel's stacks.
fn bvh_depth(bvh: &crate::accel::bvh::Bvh) -> u32 {
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
fn push_bvh(out: &mut Vec<u32>, base: usize, bvh: &crate::accel::bvh::Bvh) -> (u32, u32) {
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
fn push_triangle_slot(scene: &Scene, out: &mut Vec<u32>, gi: u32, p: u32) {
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

/// Follows transforms down to a geometry group: (group, object-to-world, mask).
fn instance_of(scene: &Scene, node: NodeId) -> Result<Option<(NodeId, Mat4, u32)>> {
    let mut m = Mat4::IDENTITY;
    let mut mask = 0xffu32;
    let mut n = node;
    for _ in 0..=scene.nodes.len() {
        let rec = &scene.nodes[n.index() as usize];
        mask &= rec.visibility_mask as u32;
        match &rec.kind {
            NodeKind::GeometryGroup { .. } => return Ok(Some((n, m, mask))),
            NodeKind::Transform { matrix, child, .. } => {
                m *= *matrix;
                n = *child;
            }
            NodeKind::Group { .. } | NodeKind::Selector { .. } => return Ok(None),
        }
    }
    Err(RtError::GraphCycle { node: node.index() })
}

/// Encodes launch `l` for a device with `scene_bindings` tables
/// bindings (see [`kernel::SCENE_SECTIONS`]).
fn encode(l: &Launch, scene_bindings: usize, held_geometry: Option<&GeometryLayout>) -> Result<Encoded> {
    let (scene, entry) = (l.scene, l.entry);
    let count = scene.entry_points.len() as u32;
    let ep = scene.entry_points.get(entry as usize).ok_or(RtError::NoSuchEntryPoint { entry, count })?;
    let rg = ep.ray_generation.ok_or(RtError::NoRayGeneration { entry })?;
    link::check_types(scene)?;
    let ray_types = scene.ray_type_count();
    let mut records = Records::default();
    let record = |p: ProgramId, r: Record, records: &mut Records| records.add(scene, p, r);
    let case = |p: ProgramId| p.index() + 1;
    let mut programs: Vec<KernelProgram> = Vec::new();
    let use_program = |p: ProgramId, programs: &mut Vec<KernelProgram>| -> Result<KernelProgram> {
        let kp = KernelProgram { case: case(p), desc: scene.program(p)?.desc };
        if !programs.iter().any(|q| q.case == kp.case) {
            programs.push(kp);
        }
        Ok(kp)
    };
    let rg_vars = record(rg, Record::default(), &mut records)?;
    let rg_prog = KernelProgram { case: case(rg), desc: scene.program(rg)?.desc };
    let (ex_prog, ex_vars) = match ep.exception {
        Some(e) => (
            Some(KernelProgram { case: case(e), desc: scene.program(e)?.desc }),
            record(e, Record::default(), &mut records)?,
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
    let mut header = [0u32; SCENE_HEADER];
    let mut tables = Tail::new(geometry.ends[0]);
    let mut nodes = Tail::new(geometry.ends[1]);
    let accels: &[Option<NodeAccel>] = &l.accels.nodes;
    // Instances: one per geometry group and per transform chain.
    let mut instance_of_node: Vec<Option<u32>> = vec![None; scene.nodes.len()];
    let mut instances: Vec<(NodeId, Mat4, u32)> = Vec::new();
    for (n, slot) in instance_of_node.iter_mut().enumerate() {
        if let Some(inst) = instance_of(scene, NodeId(n as u32))? {
            *slot = Some(instances.len() as u32);
            instances.push(inst);
        }
    }
    // BVHs of groups, and their leaf tables: instances, or other nodes with
    // NODE_BIT.
    // The most instances and nodes a leaf of a group's BVH holds.
    let mut widest_group_leaf = 1;
    // The deepest BVH of a group of instances (`None`: no group).
    let mut deepest_group: Option<u32> = None;
    let mut group_bvh: HashMap<u32, (u32, u32, bool)> = HashMap::new();
    for (n, rec) in scene.nodes.iter().enumerate() {
        if let (NodeKind::Group { children, .. }, Some(NodeAccel::Children { bvh, .. })) =
            (&rec.kind, accels.get(n).and_then(|a| a.as_ref()))
        {
            let (at, depth) = push_bvh(&mut nodes.words, nodes.base, bvh);
            deepest_bvh = deepest_bvh.max(depth);
            widest_group_leaf = bvh.bvh.nodes.iter().map(|n| n.prim_count).fold(widest_group_leaf, u32::max);
            deepest_group = Some(deepest_group.unwrap_or(1).max(depth));
            let table = tables.at();
            let mut instances_only = true;
            for slot in &bvh.bvh.primitive_indices {
                let child = children[*slot as usize];
                match instance_of_node[child.index() as usize] {
                    Some(inst) => tables.words.push(inst),
                    None => {
                        instances_only = false;
                        tables.words.push(child.index() | NODE_BIT);
                    }
                }
            }
            group_bvh.insert(n as u32, (at, table, instances_only));
        }
    }
    header[1] = tables.at();
    for (gg, o2w, mask) in &instances {
        let w = geometry.gg_bvh.get(&gg.index()).copied().unwrap_or(GroupWords { bvh: 0, table: 0, tri_slots: 0 });
        let record = InstanceRecord {
            object_to_world: o2w.to_cols_array(),
            world_to_object: o2w.inverse().to_cols_array(),
            bvh: w.bvh,
            primitives: w.table,
            mask: *mask,
            geometry_group: gg.index(),
            triangles: w.tri_slots,
        };
        tables.words.extend(record.words());
    }
    // The node table (after the side data of transforms and selectors), and
    // how deep transforms above groups and selectors nest (in post order:
    // children before parents).
    let mut node_entries: Vec<[u32; 4]> = vec![[0; 4]; scene.nodes.len()];
    let mut levels: Vec<u32> = vec![0; scene.nodes.len()];
    let mut graph = false;
    for n in link::nodes_post_order(scene)? {
        let i = n.index() as usize;
        let rec = &scene.nodes[i];
        if let Some(inst) = instance_of_node[i] {
            node_entries[i] = [NodeEntry::Instance as u32, inst, 0, instances[inst as usize].2];
            continue;
        }
        let mask = rec.visibility_mask as u32;
        match &rec.kind {
            NodeKind::Group { children, .. } => {
                let (bvh, table, instances_only) = group_bvh[&n.index()];
                let kind = if instances_only { NodeEntry::InstanceGroup } else { NodeEntry::Group };
                node_entries[i] = [kind as u32, bvh, table, mask];
                levels[i] = children.iter().map(|c| levels[c.index() as usize]).max().unwrap_or(0);
                graph |= !instances_only;
            }
            NodeKind::Transform { .. } => {
                // A chain of transforms down to a group or selector.
                let (mut m, mut mask, mut below) = (Mat4::IDENTITY, 0xffu32, n);
                while let NodeKind::Transform { matrix, child, .. } = &scene.nodes[below.index() as usize].kind {
                    m *= *matrix;
                    mask &= scene.nodes[below.index() as usize].visibility_mask as u32;
                    below = *child;
                }
                let at = tables.at();
                push_mat(&mut tables.words, m);
                push_mat(&mut tables.words, m.inverse());
                node_entries[i] = [NodeEntry::Transform as u32, at, below.index(), mask];
                levels[i] = 1 + levels[below.index() as usize];
                graph = true;
            }
            NodeKind::Selector { visit, children } => {
                let kp = use_program(*visit, &mut programs)?;
                let vars = record(*visit, Record { node: Some(n), ..Record::default() }, &mut records)?;
                let at = tables.at();
                tables.words.extend([kp.case, vars, children.len() as u32]);
                tables.words.extend(children.iter().map(|c| c.index()));
                node_entries[i] = [NodeEntry::Selector as u32, at, 0, mask];
                levels[i] = children.iter().map(|c| levels[c.index() as usize]).max().unwrap_or(0);
                graph = true;
            }
            NodeKind::GeometryGroup { .. } => unreachable!("a geometry group is an instance"),
        }
    }
    let graph_levels = if graph { 1 + levels.iter().copied().max().unwrap_or(0) } else { 0 };
    header[0] = tables.at();
    tables.words.extend(node_entries.into_iter().flatten());
    // Geometry instances, their hit records and intersection records.
    let gi_table = tables.words.len();
    header[2] = tables.at();
    tables.words.resize(gi_table + scene.instances.len() * 8, 0);
    let mut isect = Vec::with_capacity(scene.instances.len() * 2);
    for (i, gi) in scene.instances.iter().enumerate() {
        let instance = Some(crate::handles::GeometryInstanceId(i as u32));
        let hit_base = tables.at();
        for m in &gi.materials {
            let mat = &scene.materials[m.index() as usize];
            let r = Record { instance, material: Some(*m), ..Record::default() };
            for (ch, ah) in mat.closest_hit.iter().zip(&mat.any_hit) {
                let mut words = [0u32; 4];
                if let Some(p) = ch {
                    let kp = use_program(*p, &mut programs)?;
                    words[0] = kp.case;
                    words[1] = record(*p, r, &mut records)?;
                }
                if let Some(p) = ah {
                    let kp = use_program(*p, &mut programs)?;
                    words[2] = kp.case;
                    words[3] = record(*p, r, &mut records)?;
                }
                tables.words.extend(words);
            }
        }
        let [kind, pos, idx, nrm, uv, mi] = geometry.geometry_words[gi.geometry.index() as usize];
        tables.words[gi_table + i * 8..gi_table + i * 8 + 8].copy_from_slice(&[
            kind,
            pos,
            idx,
            nrm,
            uv,
            mi,
            gi.materials.len() as u32,
            hit_base,
        ]);
        match scene.geometries[gi.geometry.index() as usize].kind {
            GeometryKind::Custom { intersection, .. } => {
                let kp = use_program(intersection, &mut programs)?;
                let vars = record(
                    intersection,
                    Record { instance, geometry: Some(gi.geometry), ..Record::default() },
                    &mut records,
                )?;
                isect.extend([kp.case, vars]);
            }
            GeometryKind::Triangles(_) => isect.extend([0, 0]),
        }
    }
    header[3] = 0;
    header[4] = ray_types;
    header[5] = tables.at();
    for (r, m) in scene.miss.iter().enumerate() {
        let p = m.ok_or(RtError::NoMissProgram { ray_type: r as u32 })?;
        let kp = use_program(p, &mut programs)?;
        let vars = record(p, Record::default(), &mut records)?;
        tables.words.extend([kp.case, vars]);
    }
    header[6] = tables.at();
    tables.words.extend(isect);
    header[7] = scene.nodes.len() as u32;

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
    let tlas_stack = match deepest_group {
        Some(depth) => (depth + 2 + widest_group_leaf).max(64).next_power_of_two(),
        None => 0,
    };
    let graph_stack = ((deepest_bvh + 2) * (graph_levels + 1)).max(96).next_power_of_two();
    let triangles_only =
        !programs.iter().any(|p| matches!(p.desc.kind, ProgramKind::AnyHit | ProgramKind::Intersection));
    if triangles_only != geometry.key.triangles_only {
        return Err(RtError::Gpu(format!(
            "internal: the kernel's programs say triangles only: {triangles_only}, the tables's: {}",
            geometry.key.triangles_only
        )));
    }
    let spec = KernelSpec {
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
        cwbvh_stack: if geometry.cwbvh { (geometry.deepest_cwbvh + 2).max(32).next_power_of_two() } else { 0 },
    };
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

/// The part of the scene that comes from geometry alone: per geometry
/// group its BVH nodes, its primitive table (in the tables, after room for
/// the header) and its triangle slots; per geometry its mesh arrays (in the
/// tables). Returns its layout and its words in each section.
fn encode_geometry(
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
                tables.extend(mesh.positions.iter().flat_map(|p| [f(p.x), f(p.y), f(p.z)]));
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
                geometry_words.push([0, pos, idx, nrm, uv, mi]);
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
fn cwbvh_depth(cw: &obvhs::cwbvh::CwBvh) -> u32 {
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

/// The sections of `scene` as bound on a device with `scene_bindings`
/// scene bindings: those past the bindings appended to the tables (their
/// bases in the tables' header). Also returns what the appended ones hold.
fn place_sections(
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
enum NewScene {
    Whole(Vec<Vec<u32>>),
    AroundGeometry { header: [u32; SCENE_HEADER], tails: [Vec<u32>; SCENE_SECTIONS.len()] },
}

/// Debug builds (the tests) check that what the device keeps is what
/// encoding the context now gives: the whole scene when `held` is to be
/// reused, the geometry part when `held_geometry` is. A change that does
/// not bump `Context::structure_version` or `geometry_version` would
/// otherwise leave stale words on the device.
#[cfg(debug_assertions)]
fn check_held_scene(
    l: &Launch,
    gpu: &Gpu,
    held: Option<&ResidentScene>,
    held_geometry: Option<&GeometryLayout>,
) -> Result<()> {
    if held.is_none() && held_geometry.is_none() {
        return Ok(());
    }
    let mut e = encode(l, gpu.scene_bindings, None)?;
    let device = |s: usize| gpu.resident.scene.get(s).and_then(|m| m.as_ref()).map(|m| &m.words[..]);
    if let Some(h) = held {
        let (sections, _) = place_sections(e.whole_sections().expect("encoded whole"), gpu.scene_bindings);
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

/// The heap of a launch: the values of `records` (resolved now, so a
/// changed variable takes effect), then the buffers' words, then sampler
/// texels. Also returns the `(buffer index, heap offset, words)` of the
/// buffers programs may write.
#[allow(clippy::type_complexity)]
fn encode_heap(scene: &Scene, records: &Records) -> Result<(Vec<u32>, Vec<(usize, usize, usize)>)> {
    let base = records.words as usize;
    let mut heap: Vec<u32> = Vec::with_capacity(base);
    // Data follows the records: buffers, then sampler texels.
    let mut data: Vec<u32> = Vec::new();
    let mut buffer_offsets = Vec::with_capacity(scene.buffers.len());
    let mut outputs = Vec::new();
    for (i, b) in scene.buffers.iter().enumerate() {
        let start = data.len();
        b.storage.to_words(&mut data);
        buffer_offsets.push(base + start);
        if b.ty.writable_by_programs() {
            outputs.push((i, base + start, data.len() - start));
        }
    }
    let mut sampler_offsets = Vec::with_capacity(scene.samplers.len());
    for s in &scene.samplers {
        sampler_offsets.push(base + data.len());
        for t in s.texels.iter() {
            data.extend(t.to_array().map(f));
        }
    }
    for &(p, r) in &records.uses {
        let desc = scene.program(p)?.desc;
        let values = link::resolve_values(scene, p, r)?;
        for (value, v) in values.into_iter().zip(desc.variables) {
            match (value, v.kind) {
                (VarValue::Data { words, .. }, _) => heap.extend(words),
                (VarValue::Buffer(b), VariableKind::Buffer { .. }) => {
                    let rec = &scene.buffers[b.index() as usize];
                    heap.extend([
                        buffer_offsets[b.index() as usize] as u32,
                        rec.width * rec.height,
                        rec.width,
                        rec.height,
                    ]);
                }
                (VarValue::Sampler(s), _) => {
                    let rec = &scene.samplers[s.index() as usize];
                    let wrap = match rec.wrap {
                        rt_std::WrapMode::Repeat => 0,
                        rt_std::WrapMode::Clamp => 1,
                        rt_std::WrapMode::Mirror => 2,
                    };
                    let filter = match rec.filter {
                        rt_std::FilterMode::Nearest => 0,
                        rt_std::FilterMode::Linear => 1,
                    };
                    heap.extend([
                        sampler_offsets[s.index() as usize] as u32,
                        rec.width,
                        rec.height,
                        wrap | (filter << 8),
                    ]);
                }
                (VarValue::Object(n), _) => heap.push(n.index()),
                (VarValue::Buffer(_), _) => unreachable!("checked by resolve_values"),
            }
        }
    }
    // Sizes come from the programs' descriptors; resolved values have the
    // declared layouts (resolve_values checks), so the records fill exactly
    // the space laid out for them.
    if heap.len() != base {
        return Err(RtError::Gpu(format!(
            "internal: the records take {} words where {base} were laid out for them",
            heap.len()
        )));
    }
    heap.extend(data);
    if heap.is_empty() {
        heap.push(0);
    }
    Ok((heap, outputs))
}

/// A size for messages: MiB (one decimal unless whole) from 1 MiB up,
/// KiB below.
fn size(bytes: u64) -> String {
    const MIB: u64 = 1 << 20;
    match bytes {
        b if b >= MIB && b % MIB == 0 => format!("{} MiB", b / MIB),
        b if b >= MIB => format!("{:.1} MiB", b as f64 / MIB as f64),
        b => format!("{} KiB", b.div_ceil(1 << 10)),
    }
}

fn words_to_bytes(w: &[u32]) -> &[u8] {
    // SAFETY: u32 has no padding and any byte pattern is a valid u8.
    unsafe { std::slice::from_raw_parts(w.as_ptr() as *const u8, std::mem::size_of_val(w)) }
}

/// The wgpu backend: its device (opened at the first launch, dropped when
/// lost), the last launch's kernel and the outputs it read back.
#[derive(Default)]
pub(crate) struct WgpuBackend {
    gpu: Option<Gpu>,
    last_wgsl: Option<String>,
    lose_device_in_next_launch: bool,
    pending: Option<ReadOutputs>,
}

/// What a launch read back of its output buffers, for the host's copies.
struct ReadOutputs {
    /// The output buffers' words, in the order of `outputs` (then the log's
    /// header and the timestamps).
    words: Vec<u32>,
    /// `(buffer index, heap offset, words)` of each output buffer.
    outputs: Vec<(usize, usize, usize)>,
}

impl WgpuBackend {
    /// Runs launches on `gpu` from now on.
    pub(crate) fn use_device(&mut self, gpu: Gpu) {
        self.gpu = Some(gpu);
    }

    /// Opens the device now, unless it is open; describes its adapter.
    pub(crate) fn open(&mut self) -> Result<String> {
        if self.gpu.is_none() {
            self.gpu = Some(Gpu::new()?);
        }
        Ok(self.gpu.as_ref().map(|g| g.describe()).unwrap_or_default())
    }

    /// The next launch destroys its device once its work is submitted.
    pub(crate) fn lose_device_in_next_launch(&mut self) {
        self.lose_device_in_next_launch = true;
    }
}

impl LaunchBackend for WgpuBackend {
    fn kind(&self) -> super::Backend {
        super::Backend::Wgpu
    }

    /// A device that was lost is dropped with everything it held, so this
    /// launch opens a new one and uploads the scene from the host again.
    fn prepare(&mut self) -> Result<()> {
        if self.gpu.as_ref().is_some_and(|g| g.health.lost_reason().is_some()) {
            self.gpu = None;
        }
        if self.gpu.is_none() {
            self.gpu = Some(Gpu::new()?);
        }
        Ok(())
    }

    /// Groups' BVH2s as they are walked; geometry groups' CWBVHs where the
    /// kernel searches triangles only.
    fn trees(&self, scene: &Scene) -> Trees {
        Trees { groups: TreeForm::Binary, cwbvh: scene.searches_triangles_only(), slot_triangles: false }
    }

    /// Runs the launch on the device. A device lost during it is dropped
    /// (see [`LaunchBackend::prepare`]); the host's copies of buffers are
    /// only written from a read-back that completed.
    fn launch(&mut self, l: &Launch) -> Result<LaunchReport> {
        self.pending = None;
        let WgpuBackend { gpu, last_wgsl, lose_device_in_next_launch, pending } = self;
        let device = gpu.as_mut().expect("opened by prepare");
        let result = launch_on_device(device, last_wgsl, lose_device_in_next_launch, pending, l);
        if matches!(result, Err(RtError::DeviceLost { .. })) {
            self.gpu = None;
        }
        result
    }

    fn read_back_outputs(&mut self, buffers: &mut [BufferRec]) {
        let Some(ReadOutputs { words, outputs }) = self.pending.take() else { return };
        let mut at = 0;
        for (i, _, n) in outputs {
            buffers[i].storage.read_words(&words[at..at + n]);
            at += n;
        }
    }

    fn stats(&self) -> BackendStats<'_> {
        let gpu = self.gpu.as_ref();
        BackendStats {
            scene_encodes: gpu.map_or(0, |g| g.scene_encodes),
            geometry_encodes: gpu.map_or(0, |g| g.geometry_encodes),
            pipelines_created: gpu.map_or(0, |g| g.pipelines_created),
            last_upload_bytes: gpu.map_or(0, |g| g.last_upload_bytes()),
            linked_wgsl: self.last_wgsl.as_deref(),
        }
    }
}

fn launch_on_device(
    gpu: &mut Gpu,
    last_wgsl: &mut Option<String>,
    lose_device: &mut bool,
    pending: &mut Option<ReadOutputs>,
    l: &Launch,
) -> Result<LaunchReport> {
    let (entry, width, height) = (l.entry, l.width, l.height);
    let t1 = std::time::Instant::now();
    let scene_bindings = gpu.scene_bindings;
    // The scene, unless the device holds this one already (same structure,
    // same acceleration structures): then only the heap is encoded.
    let key = SceneKey::of(l.scene, l.accels, entry, scene_bindings);
    let resident = gpu.resident.held.as_ref();
    let held = resident.filter(|h| h.key == key);
    // Else the geometry part the device holds, where the rest can be
    // encoded around it (every section in a binding of its own).
    let held_geometry = resident
        .filter(|_| held.is_none() && scene_bindings == SCENE_SECTIONS.len())
        .map(|h| &h.geometry)
        .filter(|g| g.key == GeometryKey::of(l.scene, l.accels, scene_bindings));
    #[cfg(debug_assertions)]
    check_held_scene(l, gpu, held, held_geometry)?;
    let fresh = if held.is_some() { None } else { Some(encode(l, scene_bindings, held_geometry)?) };
    let (records, rg_vars, ex_vars) = match (&fresh, held) {
        (Some(e), _) => (&e.records, e.rg_vars, e.ex_vars),
        (None, Some(h)) => (&h.records, h.rg_vars, h.ex_vars),
        (None, None) => unreachable!("encoded when none is held"),
    };
    let (heap, outputs) = encode_heap(l.scene, records)?;
    let t2 = std::time::Instant::now();
    let (wgsl, warning) = match (&fresh, held) {
        (Some(e), _) => {
            let kernel::Generated { wgsl, warning } = kernel::generate(&e.spec)?;
            (wgsl, warning)
        }
        (None, Some(h)) => (h.wgsl.clone(), None),
        (None, None) => unreachable!("encoded when none is held"),
    };
    if std::env::var_os("RT_DUMP_WGSL").is_some() {
        let path = std::env::temp_dir().join(format!("rt_megakernel_entry{entry}.wgsl"));
        let _ = std::fs::write(&path, &wgsl);
        eprintln!("rt-runtime: linked WGSL written to {}", path.display());
    }
    *last_wgsl = Some(wgsl.clone());
    let print_filter = l.settings.print_launch_index.unwrap_or(UVec2::splat(u32::MAX));
    let print_enabled = l.settings.print_enabled as u32;
    gpu.scene_encodes += fresh.is_some() as u64;
    gpu.geometry_encodes += fresh.as_ref().is_some_and(|e| e.geometry_words.is_some()) as u64;

    // The scene's bindings: the sections with one of their own, the others
    // after the tables (their bases in the tables' header).
    let max_binding = gpu.limits.max_storage_buffer_binding_size;
    let mut parts = vec![("the heap (variables, buffers, textures)".to_string(), heap.len())];
    let fresh = fresh.map(|mut e| {
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
                        gpu.limits.max_storage_buffers_per_shader_stage
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
            wgsl: wgsl.clone(),
            spec: e.spec,
        };
        (sections, held)
    });
    for (what, len) in parts {
        let bytes = len as u64 * 4;
        if bytes > max_binding {
            return Err(RtError::Gpu(format!(
                "{what} needs {} but {} binds at most {} per storage buffer",
                size(bytes),
                gpu.describe(),
                size(max_binding)
            )));
        }
    }
    if !gpu.pipelines.contains_key(&wgsl) {
        if let Some(w) = &warning {
            eprintln!("{w}");
        }
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = gpu.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("rt megakernel"),
            source: wgpu::ShaderSource::Wgsl(wgsl.clone().into()),
        });
        let pipeline_layout = gpu.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("rt megakernel"),
            bind_group_layouts: &[Some(&gpu.layout)],
            immediate_size: 0,
        });
        let pipeline = gpu.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("rt megakernel"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("rt_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(RtError::Gpu(format!(
                "the linked megakernel does not compile (set RT_DUMP_WGSL=1 to see it): {e}"
            )));
        }
        gpu.pipelines.insert(wgsl.clone(), pipeline);
        gpu.pipelines_created += 1;
    }
    let t3 = std::time::Instant::now();
    let adapter = gpu.describe();
    let lose = std::mem::take(lose_device);
    let Gpu { device, queue, limits, layout, pipelines, resident: res, health, .. } = gpu;
    let health = &**health;
    let pipeline = &pipelines[&wgsl];
    res.uploaded = 0;
    let mut replaced = Resident::sync(device, queue, &mut res.heap, heap, "rt_heap", &mut res.uploaded);
    if let Some((sections, held)) = fresh {
        res.held = None;
        match sections {
            NewScene::Whole(sections) => {
                res.scene.resize_with(sections.len(), || None);
                for (s, words) in sections.into_iter().enumerate() {
                    let label = SCENE_SECTIONS[s].binding;
                    replaced |= Resident::sync(device, queue, &mut res.scene[s], words, label, &mut res.uploaded);
                }
            }
            NewScene::AroundGeometry { header, tails } => {
                for (s, tail) in tails.into_iter().enumerate() {
                    let head: &[u32] = if s == 0 { &header } else { &[] };
                    let (end, label) = (held.geometry.ends[s], SCENE_SECTIONS[s].binding);
                    replaced |= Resident::sync_around(
                        device,
                        queue,
                        &mut res.scene[s],
                        head,
                        end,
                        tail,
                        label,
                        &mut res.uploaded,
                    );
                }
            }
        }
        res.held = Some(held);
    }
    let held = res.held.as_ref().expect("held or synced above");
    let (rg_case, ex_case) = (held.spec.ray_generation.case, held.spec.exception.map_or(0, |e| e.case));
    let log_words = 4 + LOG_EXCEPTIONS * 3 + LOG_PRINT_WORDS;
    if res.log.is_none() {
        res.log = Some(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rt_log"),
            size: log_words as u64 * 4,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
        replaced = true;
    }
    let log = res.log.as_ref().expect("created above");
    // Counters: exceptions, print words, rays, (unused).
    queue.write_buffer(log, 0, words_to_bytes(&[0u32; 4]));
    res.uploaded += 16;

    // Launches over the dispatch limit run as tiles, each with its uniform.
    let tiles_x = width.div_ceil(8);
    let tiles_y = height.div_ceil(8);
    let max_groups = limits.max_compute_workgroups_per_dimension.max(1);
    let mut tiles: Vec<([u32; LaunchUniform::WORDS], u32, u32)> = Vec::new();
    let mut y0 = 0;
    while y0 < tiles_y {
        let gy = (tiles_y - y0).min(max_groups);
        let mut x0 = 0;
        while x0 < tiles_x {
            let gx = (tiles_x - x0).min(max_groups);
            let uniform = LaunchUniform {
                dim: [width, height],
                origin: [x0 * 8, y0 * 8],
                ray_generation: [rg_case, rg_vars],
                exception: [ex_case, ex_vars],
                log_capacity: LOG_EXCEPTIONS,
                print_enabled,
                print_filter: print_filter.to_array(),
            }
            .words();
            tiles.push((uniform, gx, gy));
            x0 += gx;
        }
        y0 += gy;
    }
    let uniform_bytes = (LaunchUniform::WORDS * 4) as u32;
    let stride = limits.min_uniform_buffer_offset_alignment.max(uniform_bytes) as u64;
    if res.uniforms.as_ref().is_none_or(|(_, slots)| (*slots as usize) < tiles.len()) {
        let slots = tiles.len() as u32;
        res.uniforms = Some((
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("rt_launch"),
                size: stride * slots as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            slots,
        ));
        replaced = true;
    }
    let (uniforms, _) = res.uniforms.as_ref().expect("created above");
    for (i, (uniform, _, _)) in tiles.iter().enumerate() {
        queue.write_buffer(uniforms, i as u64 * stride, words_to_bytes(uniform));
        res.uploaded += uniform_bytes as u64;
    }
    if replaced {
        res.bind_groups.clear();
    }
    let heap_buffer = &res.heap.as_ref().expect("synced above").buffer;
    let scene_buffers: Vec<&wgpu::Buffer> =
        res.scene.iter().map(|m| &m.as_ref().expect("synced above").buffer).collect();
    while res.bind_groups.len() < tiles.len() {
        let slot = res.bind_groups.len() as u64;
        let mut entries = vec![
            wgpu::BindGroupEntry { binding: 0, resource: heap_buffer.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: scene_buffers[0].as_entire_binding() },
            wgpu::BindGroupEntry { binding: 2, resource: log.as_entire_binding() },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: uniforms,
                    offset: slot * stride,
                    size: std::num::NonZeroU64::new(48),
                }),
            },
        ];
        for (s, b) in scene_buffers.iter().enumerate().skip(1) {
            entries.push(wgpu::BindGroupEntry { binding: 3 + s as u32, resource: b.as_entire_binding() });
        }
        res.bind_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rt bindings"),
            layout,
            entries: &entries,
        }));
    }
    if res.timestamps.is_none() && device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("rt launch time"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let resolved = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rt launch time"),
            size: 16,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        res.timestamps = Some((set, resolved));
    }
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt launch") });
    {
        let timestamp_writes = res.timestamps.as_ref().map(|(set, _)| wgpu::ComputePassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        });
        let mut pass =
            encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("rt launch"), timestamp_writes });
        pass.set_pipeline(pipeline);
        for ((_, gx, gy), bind) in tiles.iter().zip(&res.bind_groups) {
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(*gx, *gy, 1);
        }
    }
    // Read back: the output buffers' words, then the log's header, then
    // the timestamps.
    let mut copies: Vec<(&wgpu::Buffer, u64, u64)> =
        outputs.iter().map(|&(_, offset, n)| (heap_buffer, offset as u64 * 4, n as u64 * 4)).collect();
    copies.push((log, 0, 16));
    if let Some((set, resolved)) = &res.timestamps {
        encoder.resolve_query_set(set, 0..2, resolved, 0);
        copies.push((resolved, 0, 16));
    }
    let words = read_back(device, queue, &mut res.readback, encoder, &copies, lose)
        .map_err(|what| health.failure(adapter.clone(), what))?;
    if let Some(errors) = health.take_errors() {
        // wgpu refused part of the launch: its results cannot be trusted.
        return Err(RtError::Gpu(format!("the launch on {adapter} failed: {errors}")));
    }
    let mut at = 0;
    let heap_mirror = &mut res.heap.as_mut().expect("synced above").words;
    for (_, offset, n) in &outputs {
        heap_mirror[*offset..offset + n].copy_from_slice(&words[at..at + n]);
        at += n;
    }
    let header = [words[at], words[at + 1], words[at + 2], words[at + 3]];
    let kernel = res.timestamps.as_ref().map(|_| {
        let t = &words[at + 4..at + 8];
        let (start, end) = (t[0] as u64 | (t[1] as u64) << 32, t[2] as u64 | (t[3] as u64) << 32);
        let ns = end.saturating_sub(start) as f64 * queue.get_timestamp_period() as f64;
        std::time::Duration::from_nanos(ns as u64)
    });
    // The outputs go to the host's buffers now, whatever happens next.
    *pending = Some(ReadOutputs { words, outputs });
    // Exceptions and prints, when the launch logged any: a second, small
    // read.
    let exceptions = header[0].min(LOG_EXCEPTIONS) as u64;
    let print_used = (header[1] as u64).min(LOG_PRINT_WORDS as u64);
    let (exception_words, print_words) = if exceptions + print_used > 0 {
        let encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt log") });
        let print_base = (4 + LOG_EXCEPTIONS * 3) as u64 * 4;
        let mut copies = vec![(log, 16, exceptions * 12)];
        copies.push((log, print_base, print_used * 4));
        let mut words = read_back(device, queue, &mut res.readback, encoder, &copies, false)
            .map_err(|what| health.failure(adapter.clone(), what))?;
        let prints = words.split_off(exceptions as usize * 3);
        (words, prints)
    } else {
        (Vec::new(), Vec::new())
    };

    let mut report = LaunchReport::default();
    for w in exception_words.chunks_exact(3) {
        report.exceptions.push(ExceptionRecord { launch_index: UVec2::new(w[0], w[1]), code: w[2] });
    }
    report.exceptions.sort_by_key(|e| (e.launch_index.y, e.launch_index.x));
    report.prints = decode_prints(l.scene, &print_words, print_words.len());
    report.rays = header[2] as u64;
    report.timings =
        super::Timings { build: Default::default(), encode: t2 - t1, link: t3 - t2, run: t3.elapsed(), kernel };
    Ok(report)
}

/// Submits `encoder` with copies of `(buffer, byte offset, bytes)` ranges
/// appended, waits, and returns their words, concatenated. The staging
/// buffer is kept and grown as needed. `lose` destroys the device once the
/// work is submitted (a simulated device loss, for tests). Errors are
/// described for [`Health::failure`].
fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    staging: &mut Option<wgpu::Buffer>,
    mut encoder: wgpu::CommandEncoder,
    copies: &[(&wgpu::Buffer, u64, u64)],
    lose: bool,
) -> std::result::Result<Vec<u32>, String> {
    let total: u64 = copies.iter().map(|c| c.2).sum();
    if staging.as_ref().is_none_or(|b| b.size() < total) {
        *staging = Some(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rt readback"),
            size: total.max(16).next_power_of_two(),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
    }
    let dst = staging.as_ref().expect("created above");
    let mut at = 0;
    for &(src, offset, bytes) in copies {
        if bytes > 0 {
            encoder.copy_buffer_to_buffer(src, offset, dst, at, bytes);
        }
        at += bytes;
    }
    queue.submit([encoder.finish()]);
    if lose {
        device.destroy();
    }
    if total == 0 {
        return Ok(Vec::new());
    }
    let slice = dst.slice(..total);
    let mapped = Arc::new(Mutex::new(None));
    let on_mapped = Arc::clone(&mapped);
    slice.map_async(wgpu::MapMode::Read, move |r| *on_mapped.lock().unwrap_or_else(|e| e.into_inner()) = Some(r));
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| format!("waiting for the launch: {e}"))?;
    match mapped.lock().unwrap_or_else(|e| e.into_inner()).take() {
        Some(Ok(())) => {}
        Some(Err(e)) => return Err(format!("reading results back: {e}")),
        None => return Err("reading results back: the device never finished the launch".into()),
    }
    let bytes = slice.get_mapped_range().map_err(|e| format!("reading results back: {e}"))?;
    let words = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    drop(bytes);
    dst.unmap();
    Ok(words)
}

/// Formats `rt_printf!` records with the formats of every program.
fn decode_prints(scene: &Scene, words: &[u32], used: usize) -> Vec<(UVec2, String)> {
    let formats: HashMap<u32, &rt_std::program::PrintfFormat> =
        scene.programs.iter().flat_map(|p| p.desc.printf.iter().map(|f| (f.id, f))).collect();
    let mut out = Vec::new();
    let mut at = 0;
    let used = used.min(words.len());
    while at + 4 <= used {
        let (id, x, y, n) = (words[at], words[at + 1], words[at + 2], words[at + 3] as usize);
        let args = &words[(at + 4).min(used)..(at + 4 + n).min(used)];
        at += 4 + n;
        let Some(fmt) = formats.get(&id) else { continue };
        out.push((UVec2::new(x, y), format_print(fmt, args)));
    }
    out.sort_by_key(|(i, _)| (i.y, i.x));
    out
}

/// Formats like the CPU's `format!`: scalars with `{}`, vectors as glam
/// prints them.
fn format_print(fmt: &rt_std::program::PrintfFormat, words: &[u32]) -> String {
    let mut values = Vec::new();
    let mut w = words.iter().copied();
    for ty in fmt.args {
        let (n, scalar) = match *ty {
            "f32" | "i32" | "u32" | "bool" => (1, *ty),
            t => {
                let n = t[3..4].parse::<usize>().unwrap_or(1);
                (n, &t[5..t.len() - 1])
            }
        };
        let comps: Vec<String> = (0..n)
            .map(|_| {
                let v = w.next().unwrap_or(0);
                match scalar {
                    "f32" => format!("{}", f32::from_bits(v)),
                    "i32" => format!("{}", v as i32),
                    "bool" => format!("{}", v != 0),
                    _ => format!("{v}"),
                }
            })
            .collect();
        values.push(if n == 1 && !ty.starts_with("vec") {
            comps[0].clone()
        } else {
            format!("[{}]", comps.join(", "))
        });
    }
    let mut out = String::new();
    let mut vals = values.into_iter();
    let mut chars = fmt.format.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '{' if chars.peek() == Some(&'{') => {
                chars.next();
                out.push('{');
            }
            '{' if chars.peek() == Some(&'}') => {
                chars.next();
                out.push_str(&vals.next().unwrap_or_default());
            }
            '}' if chars.peek() == Some(&'}') => {
                chars.next();
                out.push('}');
            }
            c => out.push(c),
        }
    }
    out
}
