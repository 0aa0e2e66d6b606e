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
//! The ray-query traversal walks none of them: its launches build no
//! geometry group's tree on the host (`WgpuBackend::trees`).
//!
//! Large scenes: each section is its own binding, so a scene renders when
//! each section fits the adapter's `max_storage_buffer_binding_size` (128
//! MiB on lavapipe) rather than the whole; a section that does not fit is
//! a [`DeviceError::BindingLimit`] naming it, its size, the adapter and the limit. The
//! device asks for one storage buffer per section (5 in all) up to the
//! adapter's own limit; on a device with fewer (an application's, through
//! `Context::use_wgpu_device`), the sections without a binding follow the
//! tables in `rt_scene`'s and are read at a base from the tables' header.
//! Tests force both with devices of smaller limits (`device_with` in
//! tests/tests/runtime.rs). The heap is one binding.
//!
//! Traversal: two, each a folder, sharing the megakernel linker
//! ([`kernel`], with the candidate and hit code both use in
//! `kernel/hits.wgsl`), the heap (`heap`) and the dispatch
//! (`dispatch`): the compute traversal (`compute`: the scene's
//! encoding and the WGSL that walks it, on every adapter) and hardware ray
//! queries (`rayquery`: BLASes and TLASes the device builds, a
//! `rayQueryProceed` loop running any-hit and intersection programs, on
//! adapters with `EXPERIMENTAL_RAY_QUERY`). [`Traversal`] chooses; the
//! ray-query traversal still reads the compute encoding's tables (geometry
//! instances, materials, hit records).
//!
//! Files: `device` (the device and its health, ray queries requested
//! where the adapter has them), `device_mirror` (buffers
//! kept on the device, uploads of changed pages), `device_local` (buffers
//! whose words stay on the device, never read back), `heap` (variables'
//! records, buffers, textures), [`kernel`] (the megakernel's WGSL),
//! `pipeline` (pipelines by WGSL), `dispatch` (a tile's dispatches,
//! uniforms, bind groups, the compute pass), `chain` (transform chains
//! composed and inverted in f64), `readback` (results and the log back to the
//! host, `rt_printf!` formatting); this file runs a launch through them
//! (`launch_on_device`).
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

pub mod capture;
pub(crate) mod compute;
pub(crate) mod device;
pub(crate) mod device_local;
pub(crate) mod device_mirror;
pub(crate) mod dispatch;
pub(crate) mod encode;
pub(crate) mod heap;
pub mod kernel;
pub(crate) mod pipeline;
pub(crate) mod rayquery;
pub(crate) mod readback;
pub(crate) mod tail;
pub(crate) mod transform_chain;

pub use capture::capture_launches_to;
pub use device::{Gpu, WgpuDevice, instance, probe, probe_ray_queries};
pub use device_local::DeviceBuffer;
pub use encode::geometry::cwbvh_node_words;
pub use rayquery::Traversal;

use super::futures::{self, LocalBoxFuture};
use super::{ExceptionRecord, Failure, Launch, LaunchBackend, LaunchReport};
use crate::accel::bvh::TreeForm;
use crate::accel::cache::Trees;
use crate::buffer::BufferRec;
use crate::error::{DeviceError, Result, RtError, size};
use crate::scene::Scene;
use device_mirror::DeviceLocal;
use encode::{Encoding, SceneKey};
use glam::UVec2;
use readback::{LOG_EXCEPTIONS, LOG_PRINT_WORDS};
use tail::{Ran, Recorded, Tail, TailState};

/// The wgpu backend: its device (opened at the first launch, dropped when
/// lost), the last launch's kernel and the outputs it read back.
#[derive(Default)]
pub(crate) struct WgpuBackend {
    gpu: Option<Gpu>,
    last_wgsl: Option<String>,
    /// The last launch's traversal and why it was chosen.
    last_traversal: Option<(Traversal, String)>,
    lose_device_in_next_launch: bool,
    pending: Option<ReadOutputs>,
    /// How launches walk the scene.
    traversal: Traversal,
    /// The traversal of the launch running now, chosen when it asked for
    /// its trees ([`LaunchBackend::trees`]).
    plan: Option<rayquery::Plan>,
    /// Work for the next launch's last submission ([`tail`]), or what it
    /// read back.
    tail: TailState,
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

    /// Where `buffer` lies on the device, after a launch placed it.
    pub(crate) fn placed(&self, buffer: usize) -> Option<DeviceBuffer> {
        DeviceLocal::placed(self.gpu.as_ref()?, buffer)
    }

    /// Where the device holds `buffer`'s words newer than the host's copy
    /// at `host_version` (a device-local buffer a launch wrote).
    pub(crate) fn held(&self, buffer: usize, host_version: u64) -> Option<DeviceBuffer> {
        DeviceLocal::held(self.gpu.as_ref()?, buffer, host_version)
    }

    /// Which device is open, unique in the process (a new one after a
    /// loss has another).
    pub(crate) fn serial(&self) -> Option<u64> {
        self.gpu.as_ref().map(|g| g.serial)
    }

    /// The open device's handles.
    pub(crate) fn handles(&self) -> Option<WgpuDevice> {
        let gpu = self.gpu.as_ref()?;
        Some(WgpuDevice {
            adapter: gpu.adapter.clone(),
            device: gpu.device.clone(),
            queue: gpu.queue.clone(),
            info: gpu.info.clone(),
        })
    }

    /// Opens the device now, unless it is open; describes its adapter.
    pub(crate) fn open(&mut self) -> Result<String> {
        futures::block(self.open_async())
    }

    /// [`WgpuBackend::open`], awaiting the adapter and the device.
    pub(crate) async fn open_async(&mut self) -> Result<String> {
        if self.gpu.is_none() {
            self.gpu = Some(Gpu::open_async(&instance(), None).await?);
        }
        Ok(self.gpu.as_ref().map(|g| g.describe()).unwrap_or_default())
    }

    /// The next launch destroys its device once its work is submitted.
    pub(crate) fn lose_device_in_next_launch(&mut self) {
        self.lose_device_in_next_launch = true;
    }
    /// Writes the words of the device-local buffers this backend holds
    /// newer than the host into `buffers`, and holds them no longer.
    pub(crate) fn settle(&mut self, buffers: &mut [BufferRec]) -> Result<()> {
        match self.gpu.as_mut() {
            Some(gpu) => DeviceLocal::settle(gpu, buffers),
            None => Ok(()),
        }
    }

    /// The words of buffer `buffer` where this backend holds them newer
    /// than the host, whose copy is at `host_version`: a read of the
    /// device to await (a blocking caller runs it to the end).
    pub(crate) fn device_words_async(
        &self,
        buffer: usize,
        host_version: u64,
    ) -> Option<LocalBoxFuture<'_, Result<Vec<u32>>>> {
        DeviceLocal::words(self.gpu.as_ref()?, buffer, host_version)
    }

    /// Records `tail` into the next launch's last submission
    /// ([`tail`]); [`WgpuBackend::take_tail`] gives what it read back.
    pub(crate) fn arm_tail(&mut self, tail: Box<dyn Tail>) {
        self.tail = TailState::Armed(tail);
    }

    /// The armed tail, with what it read back, once a launch's last tile
    /// ran it; `None` when none did (the launch failed or was cancelled
    /// first). Disarms the tail.
    pub(crate) fn take_tail(&mut self) -> Option<Ran> {
        match std::mem::take(&mut self.tail) {
            TailState::Done(ran) => Some(ran),
            _ => None,
        }
    }

    /// Queue submissions the runtime made on the open device.
    pub(crate) fn submissions(&self) -> u64 {
        self.gpu.as_ref().map_or(0, |g| g.health.submissions.load(std::sync::atomic::Ordering::Relaxed))
    }

    /// Counts a submission the context made on the device itself.
    pub(crate) fn count_submission(&self) {
        if let Some(g) = self.gpu.as_ref() {
            g.health.submitted();
        }
    }

    /// How the launches walk the scene ([`Traversal`]).
    pub(crate) fn set_traversal(&mut self, traversal: Traversal) {
        self.traversal = traversal;
    }

    /// The traversal [`WgpuBackend::set_traversal`] asked for.
    pub(crate) fn traversal_setting(&self) -> Traversal {
        self.traversal
    }

    /// What this backend counted.
    pub(crate) fn stats(&self) -> WgpuStats<'_> {
        let gpu = self.gpu.as_ref();
        WgpuStats {
            scene_encodes: gpu.map_or(0, |g| g.scene_encodes),
            geometry_encodes: gpu.map_or(0, |g| g.geometry_encodes),
            pipelines_created: gpu.map_or(0, |g| g.pipelines_created),
            last_upload_bytes: gpu.map_or(0, |g| g.last_upload_bytes()),
            last_read_back_bytes: gpu.map_or(0, |g| g.resident.downloaded),
            linked_wgsl: self.last_wgsl.as_deref(),
            traversal: self.last_traversal.as_ref().map(|(t, why)| (*t, why.as_str())),
            blas_builds: gpu.map_or(0, |g| g.ray_query_accels.blas_builds),
            tlas_builds: gpu.map_or(0, |g| g.ray_query_accels.tlas_builds),
            opaque_ray_types: gpu
                .filter(|_| matches!(self.last_traversal, Some((Traversal::RayQuery, _))))
                .map(|g| &g.ray_query_accels.opaque_ray_types[..]),
        }
    }
}

impl LaunchBackend for WgpuBackend {
    fn kind(&self) -> super::Backend {
        super::Backend::Wgpu
    }

    /// The device's words are the launch's, not the host's.
    fn writes_host_buffers(&self) -> bool {
        false
    }

    /// After a panic, the device is dropped with everything it held, so
    /// the next launch opens a new one and uploads the scene from the host
    /// again. After tiles whose outputs were not read back, the device's
    /// heap holds outputs no mirror knows of: a new heap buffer, uploaded
    /// whole, at the next launch (device-local buffers' words from before
    /// the launch go to the host first).
    fn recover(&mut self, failure: Failure<'_>) {
        match failure {
            Failure::Panicked => self.gpu = None,
            Failure::Abandoned(buffers) => {
                if let Some(gpu) = self.gpu.as_mut() {
                    DeviceLocal::restore(gpu, buffers);
                    gpu.resident.heap = None;
                }
            }
        }
        self.pending = None;
    }

    fn prepare(&mut self) -> Result<()> {
        futures::block(self.prepare_async())
    }

    fn prepare_async(&mut self) -> LocalBoxFuture<'_, Result<()>> {
        Box::pin(async move {
            if self.gpu.as_ref().is_some_and(|g| g.health.lost_reason().is_some()) {
                self.gpu = None;
            }
            if self.gpu.is_none() {
                self.gpu = Some(Gpu::open_async(&instance(), None).await?);
            }
            Ok(())
        })
    }

    /// Chooses the launch's traversal ([`rayquery::plan`]) and keeps it
    /// for the launch's tiles. The compute traversal walks groups' BVH2s
    /// and geometry groups' CWBVHs where the kernel searches triangles
    /// only, else their BVH2s. The ray-query traversal walks the device's
    /// structures, built from the triangles and the custom primitives'
    /// boxes: geometry groups get no tree (groups keep their BVH2s, small,
    /// which the scene's node table points at).
    fn trees(&mut self, scene: &Scene) -> Result<Trees> {
        let gpu = self.gpu.as_ref().expect("opened by prepare");
        let plan = rayquery::plan(scene, gpu, self.traversal)?;
        let geometry = matches!(plan, rayquery::Plan::Compute(_));
        self.plan = Some(plan);
        let cwbvh = geometry && scene.searches_triangles_only();
        Ok(Trees { groups: TreeForm::Binary, geometry, cwbvh, simd: false })
    }

    /// Runs the launch on the device. A device lost during it is dropped
    /// (see [`LaunchBackend::prepare`]); the host's copies of buffers are
    /// only written from a read-back that completed.
    fn launch(&mut self, l: &Launch) -> Result<LaunchReport> {
        futures::block(self.launch_async(l))
    }

    fn launch_async<'a>(&'a mut self, l: &'a Launch<'a>) -> LocalBoxFuture<'a, Result<LaunchReport>> {
        Box::pin(async move {
            self.pending = None;
            let WgpuBackend {
                gpu,
                last_wgsl,
                last_traversal,
                lose_device_in_next_launch,
                pending,
                traversal,
                plan: kept,
                tail,
            } = self;
            let device = gpu.as_mut().expect("opened by prepare");
            let plan = match kept.take() {
                Some(plan) => plan,
                None => rayquery::plan(l.scene, device, *traversal)?,
            };
            let last = (last_wgsl, last_traversal);
            let result = launch_on_device(device, last, &plan, lose_device_in_next_launch, (pending, tail), l).await;
            *kept = Some(plan);
            if matches!(result, Err(RtError::Device(DeviceError::DeviceLost { .. }))) {
                self.gpu = None;
            }
            result
        })
    }

    fn read_back_outputs(&mut self, buffers: &mut [BufferRec]) {
        let Some(ReadOutputs { words, outputs }) = self.pending.take() else { return };
        let mut at = 0;
        for (i, _, n) in outputs {
            buffers[i].storage.read_words(&words[at..at + n]);
            at += n;
        }
    }
}

/// Runs launch `l` on `gpu`, phase by phase: encode (the scene unless the
/// device holds it, and the heap), link (the megakernel's WGSL and its
/// pipeline), upload (the pages that changed), dispatch, an armed
/// [`tail`] after it in the last tile, read back. The outputs' words are
/// left in `pending` once read back whole, the tail's in `tail`.
async fn launch_on_device(
    gpu: &mut Gpu,
    (last_wgsl, last_traversal): (&mut Option<String>, &mut Option<(Traversal, String)>),
    plan: &rayquery::Plan,
    lose_device: &mut bool,
    (pending, tail): (&mut Option<ReadOutputs>, &mut TailState),
    l: &Launch<'_>,
) -> Result<LaunchReport> {
    let t1 = web_time::Instant::now();
    let scene_bindings = gpu.scene_bindings;
    // The scene, unless the device holds this one already (same structure,
    // same acceleration structures): then only the heap is encoded.
    let slots = match plan {
        rayquery::Plan::RayQuery(flat) => flat.roots.len() as u32,
        rayquery::Plan::Compute(_) => 0,
    };
    *last_traversal = Some(match plan {
        rayquery::Plan::RayQuery(_) => (Traversal::RayQuery, format!("{} has ray queries", gpu.describe())),
        rayquery::Plan::Compute(why) => (Traversal::Compute, why.clone()),
    });
    let key = SceneKey::of(l.scene, l.accels, l.entry, scene_bindings, slots);
    let device_sections: Vec<Option<&[u32]>> =
        gpu.resident.scene.iter().map(|m| m.as_ref().map(|m| &m.words[..])).collect();
    let encoding = encode::encode_launch(l, key, gpu.resident.held.as_ref(), &device_sections)?;
    let t2 = web_time::Instant::now();
    let (wgsl, warning) = link_kernel(l.entry, &encoding)?;
    *last_wgsl = Some(wgsl.clone());
    let Encoding { fresh, heap, outputs, placed, samplers_placed, buffer_table, rg_vars, ex_vars, .. } = encoding;
    gpu.scene_encodes += fresh.is_some() as u64;
    gpu.geometry_encodes += fresh.as_ref().is_some_and(|e| e.geometry_words.is_some()) as u64;
    // The scene's bindings: the sections with one of their own, the others
    // after the tables (their bases in the tables' header).
    // A heap past one binding: the sampler that crosses the limit, by name,
    // where one does.
    let max_words = (gpu.limits.max_storage_buffer_binding_size / 4) as usize;
    if heap.len() > max_words {
        let limit = || format!("{} binds at most {} per storage buffer", gpu.describe(), size(max_words as u64 * 4));
        if let Some(e) = heap::sampler_past(max_words, &placed, &samplers_placed, limit) {
            return Err(e);
        }
    }
    let mut parts = vec![("the heap (variables, buffers, textures)".to_string(), heap.len())];
    let max_buffers = gpu.limits.max_storage_buffers_per_shader_stage;
    let fresh = fresh.map(|e| encode::place_scene(e, key, &wgsl, scene_bindings, max_buffers, &mut parts));
    check_bindings(gpu, &parts)?;
    pipeline::ensure(gpu, &wgsl, slots, warning.as_deref()).await?;
    let t3 = web_time::Instant::now();
    let lose = std::mem::take(lose_device);
    let log_words = 4 + LOG_EXCEPTIONS * 3 + LOG_PRINT_WORDS;
    let moves = match l.first_tile {
        true => DeviceLocal::before_upload(gpu, l.scene, placed, &heap, !l.last_tile),
        false => Vec::new(),
    };
    let kept = gpu.resident.device_local.held_ranges();
    let mut replaced =
        device_mirror::upload(&gpu.device, &gpu.queue, &mut gpu.resident, (heap, &kept), fresh, log_words);
    DeviceLocal::after_upload(gpu, &moves);
    let mut accel = std::time::Duration::ZERO;
    if let rayquery::Plan::RayQuery(flat) = plan {
        let t = web_time::Instant::now();
        let adapter = gpu.describe();
        let Gpu { device, queue, limits, ray_query_accels, .. } = gpu;
        let (new_bindings, built) =
            rayquery::accel::sync((device, queue, limits, &adapter), ray_query_accels, l.scene, l.accels, flat)?;
        replaced |= new_bindings;
        if built {
            gpu.health.submitted();
            accel = t.elapsed();
        }
    }
    let held = gpu.resident.held.as_ref().expect("held or synced above");
    let (rg_case, ex_case) = (held.spec.ray_generation.case, held.spec.exception.map_or(0, |e| e.case));
    let tiles = dispatch::tiles(l, &gpu.limits, [rg_case, rg_vars], [ex_case, ex_vars], buffer_table);
    let capture = capture::folder().map(|folder| capture_before(folder, &wgsl, &gpu.resident, log_words, &tiles));
    let mut encoder = dispatch::record(gpu, &wgsl, slots, &tiles, replaced);
    let mut armed = tail.take_if_last(l.last_tile);
    // Outputs stay on the device until the launch's last tile (the mirror
    // still holds what the host does, so no tile uploads them again), and
    // device-local ones and those the tail takes there after it too.
    let kept = |armed: &Option<Box<dyn Tail>>, i: usize| {
        l.scene.buffers[i].device_local || armed.as_ref().is_some_and(|t| t.keeps(i))
    };
    let read: Vec<_> = match l.last_tile {
        true => outputs.iter().copied().filter(|&(i, ..)| !kept(&armed, i)).collect(),
        false => Vec::new(),
    };
    let recorded = match armed.as_mut() {
        Some(t) => Some(record_tail(gpu, t.as_mut(), &mut encoder, l.scene, &outputs)?),
        None => None,
    };
    let extra = recorded.as_ref().map_or(&[][..], |r| &r.read_back[..]);
    // Everything before the dispatch is recorded; it is submitted next.
    let setup = t1.elapsed();
    let mut results = readback::results(gpu, encoder, &read, extra, lose).await?;
    let (header, kernel) = (results.header, results.kernel);
    if let Some(before) = &capture {
        capture::write(before, &read, &results.words, header[2]);
    }
    // The outputs go to the host's buffers now, whatever happens next.
    *pending = Some(ReadOutputs { words: results.words, outputs: read });
    if l.last_tile {
        gpu.resident.device_local.after_launch(l.scene, &outputs, &|i| kept(&armed, i));
    }
    if let (Some(r), Some(armed)) = (&recorded, armed) {
        let words = std::mem::take(&mut results.extra);
        *tail = TailState::Done(Ran { tail: armed, words, from_device: r.from_device });
    }
    let (exception_words, print_words) = readback::log(gpu, header).await?;
    let mut report = logged(l.scene, &exception_words, &print_words, header);
    report.timings = super::Timings {
        build: Default::default(),
        encode: t2 - t1,
        link: t3 - t2,
        run: t3.elapsed(),
        kernel,
        accel,
        setup,
    };
    Ok(report)
}

/// A launch's report of what its log held: its exception records and
/// prints, and the rays its header counted.
fn logged(scene: &Scene, exception_words: &[u32], print_words: &[u32], header: [u32; 4]) -> LaunchReport {
    let mut report = LaunchReport::default();
    for w in exception_words.chunks_exact(3) {
        report.exceptions.push(ExceptionRecord { launch_index: UVec2::new(w[0], w[1]), code: w[2], location: None });
    }
    report.exceptions.sort_by_key(|e| (e.launch_index.y, e.launch_index.x));
    report.prints = readback::decode_prints(scene, print_words, print_words.len());
    report.rays = header[2] as u64;
    report
}

/// Records `tail` into `encoder`: a buffer the launch wrote (`outputs`:
/// `(buffer index, heap offset, words)`) or the device holds is where it
/// lies in the heap.
fn record_tail(
    gpu: &Gpu,
    tail: &mut dyn Tail,
    encoder: &mut wgpu::CommandEncoder,
    scene: &Scene,
    outputs: &[(usize, usize, usize)],
) -> Result<Recorded> {
    let heap = &gpu.resident.heap.as_ref().expect("uploaded before the dispatch").buffer;
    let on_device = |b: usize| match outputs.iter().find(|o| o.0 == b) {
        Some(&(_, offset, words)) => {
            Some(DeviceBuffer { buffer: heap.clone(), offset: offset as u64 * 4, size: words as u64 * 4 })
        }
        None => DeviceLocal::held(gpu, b, scene.buffers.get(b)?.host_version),
    };
    tail.record((&gpu.device, gpu.serial), encoder, scene, &on_device)
}

/// What [`capture`] keeps of a launch before it runs: the kernel, the heap,
/// the log (its header reset, as the upload leaves it) and the scene's
/// bindings (1, then 4 up), as the device holds them.
fn capture_before(
    folder: std::path::PathBuf,
    wgsl: &str,
    res: &device_mirror::Resident,
    log_words: u32,
    tiles: &[dispatch::Tile],
) -> capture::Before {
    let mut bindings = vec![(0, res.heap.as_ref().map(|m| m.words.clone()).unwrap_or_default())];
    bindings.push((2, vec![0; log_words as usize]));
    for (s, m) in res.scene.iter().enumerate() {
        let binding = if s == 0 { 1 } else { 3 + s as u32 };
        bindings.push((binding, m.as_ref().map(|m| m.words.clone()).unwrap_or_default()));
    }
    capture::Before { folder, kernel: wgsl.to_string(), bindings, tiles: tiles.to_vec() }
}

/// The variable naming a directory where every linked megakernel is kept,
/// once per text (`<hash>.wgsl`): scripts/test.sh sets it so that
/// tests/tests/tint.rs can give the kernels of the whole suite to Tint.
pub const KERNEL_DIR_VAR: &str = "RT_WGSL_KERNEL_DIR";

/// Keeps `wgsl` in `dir` (best effort: a collection for tests, never a
/// reason for a launch to fail). Many test threads link at once: the file
/// is written under a temporary name and renamed, so a reader never sees
/// half a kernel.
fn collect_kernel(dir: &std::path::Path, wgsl: &str) {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    wgsl.hash(&mut h);
    let name = format!("{:016x}.wgsl", h.finish());
    let path = dir.join(&name);
    if path.exists() || std::fs::create_dir_all(dir).is_err() {
        return;
    }
    static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = dir.join(format!("{name}.{}-{n}.tmp", std::process::id()));
    if std::fs::write(&tmp, wgsl).is_ok() {
        let _ = std::fs::rename(&tmp, &path);
    }
}

/// The megakernel's WGSL for the launch: generated from a fresh encoding's
/// spec, else the held scene's (`RT_DUMP_WGSL=1` writes it to the
/// temporary directory). Also any warning the generator gave.
fn link_kernel(entry: u32, encoding: &Encoding) -> Result<(String, Option<String>)> {
    let (wgsl, warning) = match (&encoding.fresh, &encoding.held_wgsl) {
        (Some(e), _) => {
            let kernel::Generated { wgsl, warning } = kernel::generate(&e.spec)?;
            (wgsl, warning)
        }
        (None, Some(wgsl)) => (wgsl.clone(), None),
        (None, None) => unreachable!("encoded when none is held"),
    };
    if std::env::var_os("RT_DUMP_WGSL").is_some() {
        let path = std::env::temp_dir().join(format!("rt_megakernel_entry{entry}.wgsl"));
        let _ = std::fs::write(&path, &wgsl);
        eprintln!("rt-runtime: linked WGSL written to {}", path.display());
    }
    // (Set but empty: unset, not the working directory.)
    if let Some(dir) = std::env::var_os(KERNEL_DIR_VAR).filter(|d| !d.is_empty()) {
        collect_kernel(std::path::Path::new(&dir), &wgsl);
    }
    Ok((wgsl, warning))
}

/// Fails unless each of `parts` (what a binding holds, its words) fits the
/// device's largest storage binding.
fn check_bindings(gpu: &Gpu, parts: &[(String, usize)]) -> Result<()> {
    let max_binding = gpu.limits.max_storage_buffer_binding_size;
    for (what, len) in parts {
        let bytes = *len as u64 * 4;
        if bytes > max_binding {
            return Err(DeviceError::BindingLimit {
                what: what.clone(),
                bytes,
                adapter: gpu.describe(),
                limit: max_binding,
            }
            .into());
        }
    }
    Ok(())
}

/// What the wgpu backend counts ([`WgpuBackend::stats`]).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct WgpuStats<'a> {
    /// Launches that encoded and uploaded the scene.
    pub scene_encodes: u64,
    /// Of those, the ones that encoded the geometry part too.
    pub geometry_encodes: u64,
    /// Pipelines (megakernel links) created.
    pub pipelines_created: u64,
    /// Bytes the last launch wrote to a device.
    pub last_upload_bytes: u64,
    /// Bytes the last launch read back from the device (wgpu).
    pub last_read_back_bytes: u64,
    /// The last launch's linked kernel source.
    pub linked_wgsl: Option<&'a str>,
    /// The wgpu backend's last traversal and why.
    pub traversal: Option<(Traversal, &'a str)>,
    /// BLASes and TLASes the ray-query traversal built.
    pub blas_builds: u64,
    pub tlas_builds: u64,
    /// Per ray type, whether the last ray-query launch forced its traces
    /// opaque (none when it took the compute traversal).
    pub opaque_ray_types: Option<&'a [bool]>,
}
