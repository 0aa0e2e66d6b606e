//! Backends: where launches run.
//!
//! A backend implements `LaunchBackend`: it says which trees it walks
//! (`LaunchBackend::trees`), gets ready (`LaunchBackend::prepare`: the
//! wgpu backend opens its device), runs a launch over the scene
//! (`LaunchBackend::launch`), hands what programs wrote to the host's
//! buffers (`LaunchBackend::read_back_outputs`) and counts what it did
//! (`LaunchBackend::stats`). What every launch does around that (the
//! size check, the acceleration structures' build, the cut into tiles
//! that each stay under a time budget, [`tiles`]) is written once, in
//! `launch`. The link step (variable resolution by scope, payload and
//! attribute agreement) is shared too: `crate::link`.
//!
//! The backends: [`cpu`] runs programs natively; [`wgpu`] links them into
//! one megakernel (its traversal in `wgpu/compute/`).

#[cfg(not(target_arch = "wasm32"))]
pub mod cpu;
pub mod cpu_execution;
pub(crate) mod futures;
pub mod tiles;
pub mod wgpu;

use crate::accel::cache::{AccelCache, Trees, build_accels};
use crate::buffer::BufferRec;
use crate::error::{ConfigError, LaunchError, Result, RtError};
use crate::scene::Scene;
use futures::{Catching, LocalBoxFuture};
use glam::UVec2;
use std::any::Any;
use tiles::{LaunchControl, LaunchProgress, Pace, Tile, TileBudget, Tiler};
use web_time::Instant;

/// Where a context's launches run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Backend {
    /// Programs run natively as Rust over obvhs BVHs, on all cores (rayon).
    Cpu,
    /// Programs linked into one WGSL megakernel on a wgpu adapter (a GPU,
    /// or Mesa's lavapipe on machines without one).
    Wgpu,
}

impl Backend {
    /// The backend to use by default, and why: `RT_BACKEND=cpu|wgpu` when
    /// set; otherwise a discrete or integrated GPU when wgpu finds one (the
    /// reason then names the traversal its launches take, see
    /// [`wgpu::Traversal::choose`]);
    /// otherwise the CPU backend, which outruns Mesa's lavapipe on CPU-only
    /// machines (3.7 vs 0.9 Mrays/s for the bunny's primary rays on a 2-core
    /// VM, BENCHMARKS.md).
    pub fn choose() -> Result<(Backend, String), RtError> {
        if let Some(v) = crate::env_settings::setting("RT_BACKEND") {
            return match v.as_str() {
                "cpu" => Ok((Backend::Cpu, "RT_BACKEND=cpu".into())),
                "wgpu" => Ok((Backend::Wgpu, "RT_BACKEND=wgpu".into())),
                other => Err(ConfigError::Setting {
                    setting: "RT_BACKEND",
                    value: other.into(),
                    expected: "`cpu` or `wgpu`",
                }
                .into()),
            };
        }
        match wgpu::probe() {
            Some(info)
                if matches!(info.device_type, ::wgpu::DeviceType::DiscreteGpu | ::wgpu::DeviceType::IntegratedGpu) =>
            {
                let traversal = match wgpu::Traversal::choose() {
                    Ok((t, why)) => format!("{} traversal: {why}", t.name()),
                    Err(e) => e.to_string(),
                };
                Ok((Backend::Wgpu, format!("GPU adapter {} ({:?}), {traversal}", info.name, info.device_type)))
            }
            Some(info) => Ok((
                Backend::Cpu,
                format!(
                    "no GPU adapter (only {}, {:?}); the CPU backend is faster than it",
                    info.name, info.device_type
                ),
            )),
            None => Ok((Backend::Cpu, "no wgpu adapter".into())),
        }
    }

    /// Parses `cpu` or `wgpu`.
    pub fn from_name(name: &str) -> Option<Backend> {
        match name {
            "cpu" => Some(Backend::Cpu),
            "wgpu" => Some(Backend::Wgpu),
            _ => None,
        }
    }

    /// The backend's name as `from_name` (and `RT_BACKEND`) take it.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Cpu => "cpu",
            Backend::Wgpu => "wgpu",
        }
    }
}

/// An exception raised during a launch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ExceptionRecord {
    /// The launch index that raised it.
    pub launch_index: UVec2,
    /// `EXCEPTION_*` code, or a user code from `rt_throw`.
    pub code: u32,
    /// Where in the program's source the exception was raised, when the
    /// backend knows: the operator of an integer exception on the CPU
    /// backend ([`Context::set_integer_exceptions`](crate::Context::set_integer_exceptions)); `None` otherwise.
    pub location: Option<&'static std::panic::Location<'static>>,
}

/// What a launch did besides writing its buffers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LaunchReport {
    /// Exceptions, in launch-index order.
    pub exceptions: Vec<ExceptionRecord>,
    /// `rt_printf!` output with its launch index, in launch-index order.
    pub prints: Vec<(UVec2, String)>,
    /// Rays traced (calls of `rt_trace` that reached traversal).
    pub rays: u64,
    /// The tiles the launch ran as, one submission each
    /// ([`Context::set_tile_budget`](crate::Context::set_tile_budget)).
    pub tiles: u32,
    /// Where the launch's time went.
    pub timings: Timings,
}

/// Wall-clock time of the phases of a launch.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Building or refitting acceleration structures.
    pub build: std::time::Duration,
    /// Resolving variables and encoding records and the scene.
    pub encode: std::time::Duration,
    /// Generating the megakernel and creating its pipeline (zero when the
    /// cached pipeline was reused, and on the CPU backend).
    pub link: std::time::Duration,
    /// Running the launch and reading results back.
    pub run: std::time::Duration,
    /// Building the ray-query traversal's acceleration structures on the
    /// device (BLASes, TLASes), until the device finished them; part of
    /// `run`. Zero when nothing was built, and off the ray-query traversal.
    pub accel: std::time::Duration,
    /// The device's own time for the launch's dispatches, from timestamp
    /// queries: what the kernel took, without submission, waiting and
    /// read-back. `None` on the CPU backend and on devices without
    /// `wgpu::Features::TIMESTAMP_QUERY`.
    pub kernel: Option<std::time::Duration>,
    /// From the launch's start (after the device is open) to its first
    /// dispatch: the acceleration builds (`build`), the encoding, the
    /// link, the uploads and the ray-query traversal's device builds;
    /// what the launch did before its kernel started. On the CPU backend,
    /// `build` and the programs' binding (`encode`).
    pub setup: std::time::Duration,
}

/// How a context's launches run, besides its scene: set by the context,
/// read by every backend.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    pub max_trace_depth: u32,
    pub print_enabled: bool,
    pub print_launch_index: Option<UVec2>,
    /// Integer overflow and division by zero raise exceptions (CPU backend).
    pub integer_exceptions: bool,
    /// The exception kinds raised (`rt_abi::constants::exception_kind_bit`s).
    pub exceptions: u32,
    /// How launches are cut into tiles.
    pub tile_budget: TileBudget,
    /// How the CPU backend runs programs.
    pub cpu_execution: cpu_execution::CpuExecution,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            max_trace_depth: 5,
            print_enabled: true,
            print_launch_index: None,
            integer_exceptions: false,
            exceptions: rt_abi::constants::ALL_EXCEPTION_KINDS,
            tile_budget: TileBudget::default(),
            cpu_execution: cpu_execution::CpuExecution::from_env(),
        }
    }
}

/// One launch, as a backend receives it: the scene, the settings, the
/// acceleration structures built for it ([`LaunchBackend::trees`]), the
/// entry point, the launch's size (at least 1 x 1) and the tile of it to
/// run now (the launch indices a backend runs; every program still sees
/// the whole size as its launch dimensions).
pub(crate) struct Launch<'a> {
    pub scene: &'a Scene,
    pub settings: &'a Settings,
    pub accels: &'a AccelCache,
    pub entry: u32,
    /// The launch grid's width and height: a 3D launch's grid has `height *
    /// depth` rows, each slice's in turn (programs see `height / depth`).
    pub width: u32,
    pub height: u32,
    /// 1 but for 3D launches.
    pub depth: u32,
    pub tile: Tile,
    /// Whether this is the launch's first tile, and its last: the wgpu
    /// backend reads the outputs back after the last only, keeping them on
    /// the device in between.
    pub first_tile: bool,
    pub last_tile: bool,
}

/// Where launches run: implemented by the CPU backend and the wgpu
/// megakernel; a context holds one and calls it through [`launch`].
pub(crate) trait LaunchBackend: Any + Send + Sync {
    /// Which backend this is.
    fn kind(&self) -> Backend;
    /// Gets ready for a launch, before anything is built (the wgpu backend
    /// drops a lost device and opens one).
    fn prepare(&mut self) -> Result<()>;
    /// The trees this backend walks in the launch about to run (after
    /// [`LaunchBackend::prepare`]), which the acceleration builder builds
    /// for it; the wgpu backend chooses the launch's traversal here, and
    /// fails where the one asked for cannot run.
    fn trees(&mut self, scene: &Scene) -> Result<Trees>;
    /// Runs a launch's tile. Outputs wait for
    /// [`LaunchBackend::read_back_outputs`].
    fn launch(&mut self, launch: &Launch) -> Result<LaunchReport>;
    /// [`LaunchBackend::prepare`] for a caller that awaits rather than
    /// blocks (a browser page): the wgpu backend opens its device so.
    fn prepare_async(&mut self) -> LocalBoxFuture<'_, Result<()>> {
        Box::pin(std::future::ready(self.prepare()))
    }
    /// [`LaunchBackend::launch`] for a caller that awaits rather than
    /// blocks: the wgpu backend waits for its read-backs so; the others
    /// run the blocking launch when first polled (inside the poll that
    /// catches a panic, [`futures::Catching`]).
    fn launch_async<'a>(&'a mut self, launch: &'a Launch<'a>) -> LocalBoxFuture<'a, Result<LaunchReport>> {
        Box::pin(async move { self.launch(launch) })
    }
    /// Writes what the last launch's programs wrote into the host's
    /// buffers (called after every launch, failed or not; a backend writes
    /// only what it read back whole).
    fn read_back_outputs(&mut self, buffers: &mut [BufferRec]);
    /// Whether programs write the host's buffers in place during
    /// [`LaunchBackend::launch`] (the CPU backend): the launch keeps a copy
    /// of the writable buffers to put back if it fails. (A launch of
    /// several tiles keeps one on every backend: each tile's outputs reach
    /// the host's buffers before the next tile runs.)
    fn writes_host_buffers(&self) -> bool;
    /// Forgets what a failed launch may have left half done: after a panic
    /// in the runtime, or after tiles whose outputs were not read back
    /// (the wgpu backend drops its device, or its heap, so that the next
    /// launch starts over).
    fn recover(&mut self, failure: Failure<'_>);
}

/// How a launch failed, for [`LaunchBackend::recover`].
pub(crate) enum Failure<'b> {
    /// The runtime panicked inside a tile.
    Panicked,
    /// The launch failed or was cancelled after tiles ran whose outputs
    /// were not read back; `buffers` are the host's, already put back as
    /// they were before the launch.
    Abandoned(&'b mut [BufferRec]),
}

impl Backend {
    /// A new backend of this kind (nothing opened yet).
    pub(crate) fn create(self) -> Box<dyn LaunchBackend> {
        match self {
            #[cfg(not(target_arch = "wasm32"))]
            Backend::Cpu => Box::new(cpu::CpuBackend),
            #[cfg(target_arch = "wasm32")]
            Backend::Cpu => Box::new(NoCpuBackend),
            Backend::Wgpu => Box::new(wgpu::WgpuBackend::default()),
        }
    }
}

/// What `Backend::Cpu` is on wasm32, where the CPU backend is not built
/// (it runs launches on threads, which a browser page does not have): a
/// launch fails, naming the backend to use instead.
#[cfg(target_arch = "wasm32")]
struct NoCpuBackend;

#[cfg(target_arch = "wasm32")]
impl LaunchBackend for NoCpuBackend {
    fn kind(&self) -> Backend {
        Backend::Cpu
    }
    fn prepare(&mut self) -> Result<()> {
        Err(ConfigError::Unsupported {
            asked: "the CPU backend",
            why: "it is not built for wasm32 (no threads there): use Backend::Wgpu".into(),
        }
        .into())
    }
    fn trees(&mut self, _: &Scene) -> Result<Trees> {
        Ok(Trees { groups: crate::accel::bvh::TreeForm::Binary, geometry: true, cwbvh: false, simd: false })
    }
    fn launch(&mut self, _: &Launch) -> Result<LaunchReport> {
        self.prepare().map(|_| LaunchReport::default())
    }
    fn read_back_outputs(&mut self, _: &mut [BufferRec]) {}
    fn writes_host_buffers(&self) -> bool {
        false
    }
    fn recover(&mut self, _: Failure<'_>) {}
}

/// The words of every buffer programs may write, by index.
fn keep_writable(buffers: &[BufferRec]) -> Vec<(usize, Vec<u32>)> {
    let writable = buffers.iter().enumerate().filter(|(_, b)| b.ty.writable_by_programs());
    writable
        .map(|(i, b)| {
            let mut words = Vec::new();
            b.storage.to_words(&mut words);
            (i, words)
        })
        .collect()
}

/// Puts back what [`keep_writable`] kept: a failed launch leaves the
/// buffers as they were.
fn put_back(buffers: &mut [BufferRec], kept: Vec<(usize, Vec<u32>)>) {
    for (i, words) in kept {
        buffers[i].storage.read_words(&words);
    }
}

/// How a launch is cut and watched: the part of it to run (`None`: all),
/// the pace earlier tiles measured (updated by the launch), and the
/// callback between tiles.
pub(crate) struct Pacing<'a, 'p> {
    pub part: Option<Tile>,
    pub pace: &'a mut Pace,
    pub progress: Option<&'p mut dyn FnMut(LaunchProgress) -> LaunchControl>,
}

/// Runs entry point `entry` over `width` x `height` launch indices on
/// `backend`: checks the size, gets the backend ready, builds or refits the
/// acceleration structures in the forms it walks, runs it tile by tile
/// ([`tiles`]) and takes each tile's outputs. A failed or cancelled launch
/// leaves every buffer programs may write as it was. (A future: a browser
/// page awaits it; the blocking launch runs it to the end.)
pub(crate) async fn launch(
    backend: &mut dyn LaunchBackend,
    scene: &mut Scene,
    settings: &Settings,
    accels: &mut AccelCache,
    (entry, width, height, depth): (u32, u32, u32, u32),
    pacing: Pacing<'_, '_>,
) -> Result<LaunchReport> {
    if width == 0 || height == 0 || depth == 0 {
        let problem = "a launch needs at least one index in each dimension".into();
        return Err(LaunchError::BadLaunch { width, height, problem }.into());
    }
    // A 3D launch runs as a 2D grid of its slices' rows.
    let Some(height) = height.checked_mul(depth) else {
        let problem = format!("a depth of {depth} slices of {height} rows: more rows than 32-bit indices number");
        return Err(LaunchError::BadLaunch { width, height, problem }.into());
    };
    let Pacing { part, pace, mut progress } = pacing;
    let part = part.unwrap_or(Tile::whole(width, height));
    if let Some(problem) = tiles::part_problem(width, height, part) {
        return Err(LaunchError::BadLaunch { width, height, problem }.into());
    }
    backend.prepare_async().await?;
    let t0 = Instant::now();
    let trees = backend.trees(scene)?;
    build_accels(scene, accels, trees)?;
    let build = t0.elapsed();
    let budget = settings.tile_budget;
    let total = part.count();
    let mut tiler = Tiler::new(part);
    let first = pace.next_size(budget, entry, None);
    let kept = (backend.writes_host_buffers() || first < total).then(|| keep_writable(&scene.buffers));
    let mut report = LaunchReport::default();
    let (mut last, mut done) = (None, 0);
    let result = loop {
        let size = pace.next_size(budget, entry, last);
        let Some(tile) = tiler.next_tile(size) else { break Ok(()) };
        let (first_tile, last_tile) = (last.is_none(), tiler.finished());
        let launch = Launch { scene, settings, accels, entry, width, height, depth, tile, first_tile, last_tile };
        let ran = run_tile(backend, &launch).await;
        backend.read_back_outputs(&mut scene.buffers);
        let ran = match ran {
            Ok(ran) => ran,
            Err(e) => break Err(e),
        };
        let t = &ran.timings;
        pace.record(entry, tile.count(), t.kernel.unwrap_or(t.run.saturating_sub(t.accel)));
        merge(&mut report, ran);
        last = Some(tile.count());
        done += tile.count();
        if let Some(progress) = progress.as_deref_mut() {
            let at = LaunchProgress { entry, done, total, tiles: report.tiles, elapsed: t0.elapsed() };
            if progress(at) == LaunchControl::Cancel && !tiler.finished() {
                break Err(LaunchError::LaunchCancelled { entry, done, total }.into());
            }
        }
    };
    if let Err(e) = result {
        if let Some(kept) = kept {
            put_back(&mut scene.buffers, kept);
        }
        if last.is_some() {
            backend.recover(Failure::Abandoned(&mut scene.buffers));
        }
        return Err(e);
    }
    if report.tiles > 1 {
        // Each tile's records are in index order; the tiles' are not.
        report.exceptions.sort_by_key(|e| (e.launch_index.y, e.launch_index.x));
        report.prints.sort_by_key(|(at, _)| (at.y, at.x));
    }
    report.timings.build = build;
    report.timings.setup += build;
    Ok(report)
}

/// Runs one tile on `backend`, catching a panic in the runtime (a panic in
/// a program the backend reports itself, naming it).
async fn run_tile(backend: &mut dyn LaunchBackend, launch: &Launch<'_>) -> Result<LaunchReport> {
    let name = backend.kind().name();
    let result = Catching(backend.launch_async(launch)).await.unwrap_or_else(|caught| {
        Err(LaunchError::RuntimePanicked { backend: name, message: caught.message, at: caught.at }.into())
    });
    if matches!(result, Err(RtError::Launch(LaunchError::RuntimePanicked { .. }))) {
        backend.recover(Failure::Panicked);
    }
    result
}

/// Adds a tile's report to the launch's.
fn merge(report: &mut LaunchReport, tile: LaunchReport) {
    report.exceptions.extend(tile.exceptions);
    report.prints.extend(tile.prints);
    report.rays += tile.rays;
    report.tiles += 1;
    let (a, b) = (&mut report.timings, tile.timings);
    a.encode += b.encode;
    a.link += b.link;
    a.run += b.run;
    a.accel += b.accel;
    // The first tile's: the launch's first dispatch.
    if report.tiles == 1 {
        a.setup = b.setup;
    }
    a.kernel = match (report.tiles, a.kernel, b.kernel) {
        (1, _, k) => k,
        (_, Some(x), Some(y)) => Some(x + y),
        _ => None,
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A backend whose launch panics, as a bug in the runtime would.
    struct Panicking;

    impl LaunchBackend for Panicking {
        fn kind(&self) -> Backend {
            Backend::Cpu
        }
        fn prepare(&mut self) -> Result<()> {
            Ok(())
        }
        fn trees(&mut self, _: &Scene) -> Result<Trees> {
            Ok(Trees { groups: crate::accel::bvh::TreeForm::Binary, geometry: true, cwbvh: false, simd: false })
        }
        fn launch(&mut self, _: &Launch) -> Result<LaunchReport> {
            panic!("a bug in a backend")
        }
        fn read_back_outputs(&mut self, _: &mut [BufferRec]) {}
        fn writes_host_buffers(&self) -> bool {
            false
        }
        fn recover(&mut self, _: Failure<'_>) {}
    }

    #[test]
    fn a_panic_in_a_backends_blocking_launch_is_caught_through_the_async_path() {
        let (scene, settings, accels) = (Scene::default(), Settings::default(), AccelCache::default());
        let tile = Tile::whole(4, 4);
        let launch = Launch {
            scene: &scene,
            settings: &settings,
            accels: &accels,
            entry: 0,
            width: 4,
            height: 4,
            depth: 1,
            tile,
            first_tile: true,
            last_tile: true,
        };
        let result = futures::now(run_tile(&mut Panicking, &launch)).expect("ready natively");
        match result {
            Err(RtError::Launch(LaunchError::RuntimePanicked { backend: "cpu", message, .. })) => {
                assert_eq!(message, "a bug in a backend")
            }
            other => panic!("{other:?}"),
        }
    }
}
