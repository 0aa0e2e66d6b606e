//! Command lists: OptiX 6's `RTcommandlist`, a renderer's frame as one
//! object: launches (1D, 2D, 3D) and post-processing stages
//! ([`crate::postprocess`]) appended in order, checked once by
//! [`CommandList::finalize`], run as often as wanted by
//! [`CommandList::execute`].
//!
//! ```text
//! let mut list = CommandList::new();
//! list.append_launch_2d(0, width, height)?;
//! list.append_stage(denoiser, width, height)?;
//! list.append_stage(tonemapper, width, height)?;
//! list.finalize(&ctx)?;
//! list.execute(&mut ctx)?;   // every frame
//! ```
//!
//! What a list gives is what running its commands one by one gives
//! ([`Context::launch_3d`], [`Context::run_stage`]): each launch runs
//! through the one launch path, tiled under the context's budget, with
//! progress and cancellation between tiles, and each stage on the
//! backend the context launches on.
//!
//! On the wgpu backend, the submissions: a launch is one a tile (so that
//! its progress is reported and it can be cancelled between tiles), and
//! the run of stages that follows it in the list rides in its last
//! tile's submission, recorded after the dispatches
//! (`backend::wgpu::tail`): a launch of one tile and the stages after
//! it are one submission, a launch of `T` tiles and its stages `T`. The
//! stages read what the launch wrote where it lies in the device's heap;
//! those buffers are not read back (the device holds them, newer than
//! the host, as it holds device-local ones, and
//! [`Context::read_buffer`] copies one when asked), while the stages'
//! outputs come back with the launch's other outputs, in its one read;
//! a temporal denoiser's history is read and written in the same
//! submission and stays on the device, frame after frame.
//! A run of stages with no launch before it (at the list's start) is one
//! submission of its own ([`Context::stage_submissions`]). A launch that
//! logs exceptions or prints reads its log in one more
//! ([`Context::wgpu_submissions`] counts every submission). A launch
//! cancelled before its last tile runs none of its stages.

use crate::backend::LaunchReport;
use crate::backend::tiles::{LaunchControl, LaunchProgress};
use crate::context::Context;
use crate::error::{PostProcessError, Result, RtError};
use crate::postprocess::{Plan, StageId};

/// One command of a list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// A launch of entry point `entry` over `width` x `height` x `depth`
    /// indices (`depth` 1 for 1D and 2D launches, `height` 1 for 1D).
    Launch {
        /// The entry point.
        entry: u32,
        /// Launch indices along x.
        width: u32,
        /// Along y (1 for a 1D launch).
        height: u32,
        /// Along z (1 for 1D and 2D launches).
        depth: u32,
    },
    /// A post-processing stage run over `width` x `height` pixels.
    Stage {
        /// The stage.
        stage: StageId,
        /// Pixels per row.
        width: u32,
        /// Rows.
        height: u32,
    },
}

/// A list of launches and stages (OptiX's `RTcommandlist`): appended to,
/// then finalized, then executed.
#[derive(Clone, Debug, Default)]
pub struct CommandList {
    commands: Vec<Command>,
    finalized: bool,
}

/// Where [`CommandList::execute_with_progress`] stands: in command
/// `command` of `commands` (a launch), with that launch's progress.
#[derive(Clone, Copy, Debug)]
pub struct CommandProgress {
    /// The command running, from 0.
    pub command: usize,
    /// The list's commands.
    pub commands: usize,
    /// The running launch's own progress.
    pub launch: LaunchProgress,
}

impl CommandList {
    /// An empty list.
    #[doc(alias = "rtCommandListCreate")]
    pub fn new() -> CommandList {
        CommandList::default()
    }

    /// The commands, in order.
    pub fn commands(&self) -> &[Command] {
        &self.commands
    }

    /// Whether [`CommandList::finalize`] succeeded.
    pub fn is_finalized(&self) -> bool {
        self.finalized
    }

    /// Appends a 1D launch.
    #[doc(alias = "rtCommandListAppendLaunch1D")]
    pub fn append_launch_1d(&mut self, entry: u32, width: u32) -> Result<()> {
        self.append(Command::Launch { entry, width, height: 1, depth: 1 })
    }

    /// Appends a 2D launch.
    #[doc(alias = "rtCommandListAppendLaunch2D")]
    pub fn append_launch_2d(&mut self, entry: u32, width: u32, height: u32) -> Result<()> {
        self.append(Command::Launch { entry, width, height, depth: 1 })
    }

    /// Appends a 3D launch.
    #[doc(alias = "rtCommandListAppendLaunch3D")]
    pub fn append_launch_3d(&mut self, entry: u32, width: u32, height: u32, depth: u32) -> Result<()> {
        self.append(Command::Launch { entry, width, height, depth })
    }

    /// Appends stage `stage`, run over `width` x `height` pixels.
    #[doc(alias = "rtCommandListAppendPostprocessingStage")]
    pub fn append_stage(&mut self, stage: StageId, width: u32, height: u32) -> Result<()> {
        self.append(Command::Stage { stage, width, height })
    }

    /// Adds a command, unless the list is finalized: then the error names
    /// the command, and the list is unchanged.
    fn append(&mut self, command: Command) -> Result<()> {
        if self.finalized {
            let what = match command {
                Command::Launch { entry, .. } => format!("a launch of entry point {entry}"),
                Command::Stage { stage, .. } => format!("post-processing stage {}", stage.index()),
            };
            return Err(PostProcessError::BadCommandList {
                problem: format!(
                    "{what} was appended after the list was finalized; a finalized list is fixed: make a new one"
                ),
            }
            .into());
        }
        self.commands.push(command);
        Ok(())
    }

    /// Checks every command against `ctx` and fixes the list: launches
    /// name existing entry points with a ray generation program and at
    /// least one index a dimension; stages' buffers are set, float RGBA
    /// and at least of the size appended ([`PostProcessError::BadStage`] names the stage
    /// and the variable at fault). A list that fails stays open.
    #[doc(alias = "rtCommandListFinalize")]
    pub fn finalize(&mut self, ctx: &Context) -> Result<()> {
        for (i, command) in self.commands.iter().enumerate() {
            check(ctx, i, *command)?;
        }
        self.finalized = true;
        Ok(())
    }

    /// Runs the commands in order on `ctx`, returning each launch's
    /// report. The list must be finalized. Stages are checked again as
    /// they run (their buffers may have changed since); a command that
    /// fails stops the list there, with the commands before it done, as
    /// running them one by one would leave them (but a run of stages that
    /// fails on the wgpu device, one submission, writes none of its
    /// outputs).
    #[doc(alias = "rtCommandListExecute")]
    pub fn execute(&self, ctx: &mut Context) -> Result<Vec<LaunchReport>> {
        self.execute_with_progress(ctx, |_| LaunchControl::Continue)
    }

    /// [`CommandList::execute`], calling `progress` after every tile of
    /// every launch; its answer may cancel the launch (which then fails
    /// with [`LaunchError::LaunchCancelled`](crate::LaunchError::LaunchCancelled), its buffers as they were) and
    /// with it the rest of the list.
    pub fn execute_with_progress(
        &self,
        ctx: &mut Context,
        mut progress: impl FnMut(CommandProgress) -> LaunchControl,
    ) -> Result<Vec<LaunchReport>> {
        crate::backend::futures::block(self.run(ctx, &mut progress))
    }

    /// [`CommandList::execute`] for a caller that must not block, as
    /// [`Context::launch_async`] is [`Context::launch`]'s: a browser page
    /// (wasm32 over WebGPU) awaits its launches and stages, whose device
    /// work and read-backs it cannot wait for. Natively it is the same
    /// run, and awaiting it blocks as `execute` does.
    pub async fn execute_async(&self, ctx: &mut Context) -> Result<Vec<LaunchReport>> {
        self.run(ctx, &mut |_| LaunchControl::Continue).await
    }

    /// Every execution: the commands in order, each launch's and stage's
    /// device work awaited.
    async fn run(
        &self,
        ctx: &mut Context,
        progress: &mut dyn FnMut(CommandProgress) -> LaunchControl,
    ) -> Result<Vec<LaunchReport>> {
        if !self.finalized {
            return Err(PostProcessError::BadCommandList { problem: "executed before it was finalized".into() }.into());
        }
        let mut reports = Vec::new();
        let commands = self.commands.len();
        let mut command = 0;
        while command < commands {
            // The run of stages from here (after a launch, from the next
            // command): planned first; a stage that fails its check stops
            // the run there, the commands before it done.
            let launch = match self.commands[command] {
                Command::Launch { entry, width, height, depth } => Some((entry, width, height, depth)),
                Command::Stage { .. } => None,
            };
            let first = command + launch.is_some() as usize;
            let (plans, failed) = plan_run(ctx, &self.commands[first..]);
            match launch {
                Some(size) => {
                    let mut each = |launch| progress(CommandProgress { command, commands, launch });
                    reports.push(ctx.launch_then_stages(size, &mut each, &plans).await?);
                }
                None => ctx.run_plans(&plans).await?,
            }
            if let Some(e) = failed {
                return Err(e);
            }
            command = first + plans.len();
        }
        Ok(reports)
    }
}

/// The plans of the stages `commands` starts with, up to the first
/// launch or the first stage that fails its check (then its error too).
fn plan_run(ctx: &Context, commands: &[Command]) -> (Vec<Plan>, Option<RtError>) {
    let mut plans = Vec::new();
    for command in commands {
        let Command::Stage { stage, width, height } = *command else { break };
        match ctx.plan_stage(stage, Some((width, height))) {
            Ok(plan) => plans.push(plan),
            Err(e) => return (plans, Some(e)),
        }
    }
    (plans, None)
}

/// Checks command `i` against `ctx`.
fn check(ctx: &Context, i: usize, command: Command) -> Result<()> {
    match command {
        Command::Launch { entry, width, height, depth } => {
            let count = ctx.entry_point_count();
            let problem = if entry >= count {
                Some(format!("entry point {entry} does not exist: the context has {count}"))
            } else if !ctx.has_ray_generation_program(entry) {
                Some(format!("entry point {entry} has no ray generation program"))
            } else if width == 0 || height == 0 || depth == 0 {
                Some(format!("{width}x{height}x{depth} has no index; a launch needs at least one a dimension"))
            } else {
                None
            };
            match problem {
                Some(p) => {
                    Err(PostProcessError::BadCommandList { problem: format!("command {i} (a launch): {p}") }.into())
                }
                None => Ok(()),
            }
        }
        Command::Stage { stage, width, height } => ctx.plan_stage(stage, Some((width, height))).map(|_| ()),
    }
}
