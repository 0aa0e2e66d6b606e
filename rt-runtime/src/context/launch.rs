//! Launches: whole, in parts, with progress and cancellation, blocking or
//! awaited, in one, two or three dimensions; the tile budget and the usage
//! report every launch ends with.

use super::{Context, UsageCallback};
use crate::backend::tiles::{LaunchControl, LaunchProgress, Tile, TileBudget};
use crate::backend::{self, Backend, LaunchReport, Pacing};
use crate::error::Result;
use crate::usage::UsageReport;

impl Context {
    /// Runs entry point `entry` over `width` x `height` launch indices, as
    /// tiles under the context's budget ([`Context::set_tile_budget`]).
    pub fn launch(&mut self, entry: u32, width: u32, height: u32) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, 1), None, None)
    }

    /// [`Context::launch`] for a caller that must not block: a browser
    /// page (wasm32 over WebGPU), whose one thread cannot wait for the GPU,
    /// awaits it, and its device opens asynchronously too. Natively it is
    /// the same launch, and awaiting it (with any executor) blocks as
    /// [`Context::launch`] does. The blocking calls in a browser fail,
    /// saying to use this instead, where they would wait for the GPU.
    ///
    /// ```no_run
    /// # async fn f(ctx: &mut rt_runtime::Context, out: rt_runtime::BufferId) -> rt_runtime::Result<()> {
    /// let report = ctx.launch_async(0, 640, 480).await?;
    /// let pixels = ctx.read_buffer::<glam::Vec4>(out)?;
    /// # Ok(()) }
    /// ```
    pub async fn launch_async(&mut self, entry: u32, width: u32, height: u32) -> Result<LaunchReport> {
        self.run_launch_async((entry, width, height, 1), None, None).await
    }

    /// [`Context::launch`], calling `progress` after every tile with where
    /// the launch stands. Its answer may cancel the launch before the next
    /// tile ([`LaunchControl::Cancel`]): the launch then fails with
    /// [`crate::LaunchError::LaunchCancelled`] and every buffer is as it was before
    /// it. A cancel after the last tile changes nothing: the launch is
    /// done. OptiX 6's `rtContextSetTimeoutCallback` asks the same
    /// question between the pieces of a launch.
    #[doc(alias = "rtContextSetTimeoutCallback")]
    pub fn launch_with_progress(
        &mut self,
        entry: u32,
        width: u32,
        height: u32,
        mut progress: impl FnMut(LaunchProgress) -> LaunchControl,
    ) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, 1), None, Some(&mut progress))
    }

    /// Runs only `part` of a `width` x `height` launch of entry point
    /// `entry`: programs see the whole size as their launch dimensions and
    /// their own place in it as their launch index, so parts launched
    /// apart (on several machines: `render --tile K/N`) give, put
    /// together, what one launch gives. Indices outside the part do not
    /// run. The part must lie on the 8 x 8 grid of launch indices (its
    /// origin, and its far edges unless they are the launch's, multiples
    /// of 8); else the launch fails with [`crate::LaunchError::BadLaunch`]. Tiles and
    /// progress are as [`Context::launch_with_progress`]'s, within the part.
    pub fn launch_part(
        &mut self,
        entry: u32,
        width: u32,
        height: u32,
        part: Tile,
        mut progress: impl FnMut(LaunchProgress) -> LaunchControl,
    ) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, 1), Some(part), Some(&mut progress))
    }

    /// Calls `report` after every launch, failed or not, with what it did:
    /// acceleration builds and refits, encodes, pipelines linked, bytes
    /// uploaded and the time of each phase ([`UsageReport`], whose
    /// `Display` is one line of text). `None` stops the reports.
    #[doc(alias = "rtContextSetUsageReportCallback")]
    pub fn set_usage_report(&mut self, report: Option<UsageCallback>) {
        self.usage_report = report;
    }

    /// Every blocking launch: [`Context::run_launch_async`] run to its end.
    fn run_launch(
        &mut self,
        size: (u32, u32, u32, u32),
        part: Option<Tile>,
        progress: Option<&mut dyn FnMut(LaunchProgress) -> LaunchControl>,
    ) -> Result<LaunchReport> {
        backend::futures::block(self.run_launch_async(size, part, progress))
    }

    /// Every launch: the backend's run, then the usage report.
    pub(super) async fn run_launch_async(
        &mut self,
        (entry, width, height, depth): (u32, u32, u32, u32),
        part: Option<Tile>,
        progress: Option<&mut dyn FnMut(LaunchProgress) -> LaunchControl>,
    ) -> Result<LaunchReport> {
        let before = self.usage_counters();
        // Device-local buffers another backend holds come to the host first.
        let settled = self.settle_device_buffers(Some(self.backend.kind()));
        let pacing = Pacing { part, pace: &mut self.pace, progress };
        let (scene, settings, accels) = (&mut self.scene, &self.settings, &mut self.accels);
        let result = match settled {
            Ok(()) => {
                let size = (entry, width, height, depth);
                backend::launch(&mut *self.backend, scene, settings, accels, size, pacing).await
            }
            Err(e) => Err(e),
        };
        if let Some(mut callback) = self.usage_report.take() {
            let after = self.usage_counters();
            let report = UsageReport {
                entry,
                size: glam::UVec2::new(width, height.saturating_mul(depth)),
                backend: self.backend.kind(),
                outcome: result.as_ref(),
                acceleration_builds: after[0] - before[0],
                acceleration_refits: after[1] - before[1],
                scene_encoded: after[2] > before[2],
                geometry_encoded: after[3] > before[3],
                pipelines_created: after[4] - before[4],
                upload_bytes: if self.backend.kind() == Backend::Wgpu && result.is_ok() { after[5] } else { 0 },
                traversal: (&*self.backend as &dyn std::any::Any)
                    .downcast_ref::<crate::backend::wgpu::WgpuBackend>()
                    .and_then(|b| b.stats().traversal),
            };
            callback(&report);
            self.usage_report = Some(callback);
        }
        result
    }

    /// The counters a usage report takes the difference of: builds,
    /// refits, scene and geometry encodes, pipelines, the last upload.
    fn usage_counters(&self) -> [u64; 6] {
        let (builds, refits) = self.acceleration_builds();
        [
            builds,
            refits,
            self.scene_encodes(),
            self.geometry_encodes(),
            self.pipelines_created(),
            self.last_upload_bytes(),
        ]
    }

    /// How launches are cut into tiles, each one submission (see
    /// [`crate::backend::tiles`]): by default tiles sized to run in about a
    /// quarter second each ([`TileBudget::Time`] of
    /// [`DEFAULT_TILE_BUDGET`](crate::backend::tiles::DEFAULT_TILE_BUDGET)),
    /// well inside the two seconds after which desktop drivers reset a
    /// GPU. Results are the same whatever the cut.
    pub fn set_tile_budget(&mut self, budget: TileBudget) {
        self.settings.tile_budget = budget;
    }

    /// The budget set by [`Context::set_tile_budget`].
    pub fn tile_budget(&self) -> TileBudget {
        self.settings.tile_budget
    }

    /// [`Context::launch_3d`], calling `progress` after every tile as
    /// [`Context::launch_with_progress`] does (which may cancel it).
    pub fn launch_3d_with_progress(
        &mut self,
        entry: u32,
        width: u32,
        height: u32,
        depth: u32,
        progress: &mut dyn FnMut(LaunchProgress) -> LaunchControl,
    ) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, depth), None, Some(progress))
    }

    /// Whether entry point `entry` exists and has a ray generation program.
    pub fn has_ray_generation_program(&self, entry: u32) -> bool {
        self.scene.entry_points.get(entry as usize).is_some_and(|e| e.ray_generation.is_some())
    }

    /// A 1D launch of `width` indices.
    pub fn launch_1d(&mut self, entry: u32, width: u32) -> Result<LaunchReport> {
        self.launch(entry, width, 1)
    }

    /// A 3D launch of `width` x `height` x `depth` indices (OptiX's
    /// `rtContextLaunch3D`): programs read their index with
    /// `launch_index_3d()` and the size with `launch_dim_3d()`
    /// (`launch_index()` and `launch_dim()` give the first two axes). It
    /// runs as a 2D launch of `width` x `height * depth` indices, the
    /// slices' rows in turn, tiled as any launch; exception records, prints
    /// and the print filter ([`set_print`](Self::set_print)) name indices
    /// of that grid: `(x, y + z * height)`.
    #[doc(alias = "rtContextLaunch3D")]
    pub fn launch_3d(&mut self, entry: u32, width: u32, height: u32, depth: u32) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, depth), None, None)
    }
}
