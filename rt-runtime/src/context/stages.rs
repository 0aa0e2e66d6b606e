//! Post-processing stages ([`crate::postprocess`]): creating them, setting
//! their variables, running one.

use super::Context;
use crate::backend::tiles::{LaunchControl, LaunchProgress};
use crate::backend::{self, Backend, LaunchReport};
use crate::error::{ConfigError, LaunchError, Result, SceneError};
use crate::postprocess::gpu::{DeviceHistory, Pipelines, Source, StageTail, pixels, read_history};
use crate::postprocess::temporal::TEXELS;
use crate::postprocess::{
    History, Pixels, Plan, Stage, StageId, StageKind, StageValue, Texels, crop, merge, runs_together,
};
use crate::scene::BufferId;
use glam::Vec4;
use std::any::Any;
use std::sync::Arc;

impl Context {
    /// A built-in post-processing stage of kind `kind`, its variables
    /// unset (settings at their defaults).
    pub fn create_postprocessing_stage(&mut self, kind: StageKind) -> StageId {
        self.stages.push(Stage::new(kind));
        StageId(self.stages.len() as u32 - 1)
    }

    /// A built-in stage by OptiX's name (`DLDenoiser`, `TonemapperSimple`)
    /// or this project's (`denoiser`, `tonemapper`); an unknown name is an
    /// error naming it.
    #[doc(alias = "rtPostProcessingStageCreateBuiltin")]
    pub fn create_builtin_postprocessing_stage(&mut self, name: &str) -> Result<StageId> {
        match StageKind::from_name(name) {
            Some(kind) => Ok(self.create_postprocessing_stage(kind)),
            None => Err(ConfigError::Unsupported {
                asked: "a built-in post-processing stage",
                why: format!(
                    "there is none named `{name}`: the built-ins are `DLDenoiser` (`denoiser`) and `TonemapperSimple` (`tonemapper`)"
                ),
            }.into()),
        }
    }

    /// Sets variable `name` of `stage` (OptiX's
    /// `rtPostProcessingStageDeclareVariable` and `rtVariableSet*`): a
    /// buffer (`input_buffer`, ...), a number (`blend`, `exposure`,
    /// `gamma`, `temporal`, `alpha_min`) or a `Vec3` (the temporal
    /// denoiser's `camera_eye`, `camera_u`, `camera_v`, `camera_w`). A
    /// name the stage does not have, or a value of another sort, is an
    /// error naming both; nothing is changed then.
    #[doc(alias = "rtPostProcessingStageDeclareVariable")]
    pub fn set_stage_var(&mut self, stage: StageId, name: &str, value: impl Into<StageValue>) -> Result<()> {
        let s = self.stage_mut(stage)?;
        s.set(stage, name, value.into())
    }

    /// The value of `stage`'s variable `name`, if set.
    pub fn stage_var(&self, stage: StageId, name: &str) -> Result<Option<StageValue>> {
        Ok(self.stage(stage)?.vars.get(name).copied())
    }

    /// The kind of `stage`.
    pub fn stage_kind(&self, stage: StageId) -> Result<StageKind> {
        Ok(self.stage(stage)?.kind)
    }

    /// Runs `stage` over `width` x `height` pixels into its
    /// `output_buffer`, as a command list's stage of that launch size
    /// runs (OptiX's `rtCommandListAppendPostprocessingStage`): over
    /// the top-left `width` x `height` of each of its buffers, which must
    /// be at least that large (a renderer whose buffers only grow runs
    /// over the part its picture takes); the output's texels outside that
    /// rectangle stay as they were. On the wgpu backend as compute
    /// passes on the context's device (one submission; the rectangle of
    /// each of the stage's images goes up to the device, or where a launch
    /// left a device-local buffer's newest words on the device is copied
    /// there, and the output's rectangle alone comes back to the host
    /// buffer; a temporal denoiser's history stays on the device), on the
    /// CPU backend natively. The
    /// stage is checked first ([`PostProcessError::BadStage`](crate::PostProcessError::BadStage) naming the variable
    /// at fault); a stage that fails writes nothing.
    pub fn run_stage(&mut self, stage: StageId, width: u32, height: u32) -> Result<()> {
        backend::futures::block(self.run_stage_async(stage, width, height))
    }

    /// [`Context::run_stage`] for a caller that must not block, as
    /// [`Context::launch_async`] is [`Context::launch`]'s: a browser page
    /// awaits the device's read-back of the stage's output. Natively it
    /// is the same run, and awaiting it blocks as `run_stage` does.
    pub async fn run_stage_async(&mut self, stage: StageId, width: u32, height: u32) -> Result<()> {
        let plan = self.plan_stage(stage, Some((width, height)))?;
        self.run_plans(&[plan]).await
    }

    pub(crate) fn stage(&self, stage: StageId) -> Result<&Stage> {
        self.stages.get(stage.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{stage:?}")).into())
    }

    fn stage_mut(&mut self, stage: StageId) -> Result<&mut Stage> {
        self.stages.get_mut(stage.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{stage:?}")).into())
    }

    /// `stage` checked against the context's buffers for a run at `size`.
    pub(crate) fn plan_stage(&self, stage: StageId, size: Option<(u32, u32)>) -> Result<Plan> {
        self.stage(stage)?.plan(stage, &self.scene.buffers, size)
    }

    /// Runs checked stages in order and writes the run's rectangle of
    /// their output buffers: on the CPU backend one by one; on the wgpu
    /// backend all in one submission, a stage reading an earlier one's
    /// output on the device (where one reads beyond the rectangle an
    /// earlier one wrote, it starts a submission of its own, after the
    /// earlier outputs are written). The device's work is awaited.
    pub(crate) async fn run_plans(&mut self, plans: &[Plan]) -> Result<()> {
        if self.backend() != Backend::Wgpu {
            for plan in plans {
                let plan = &self.history_on_host(plan);
                let (out, history) = plan.run_cpu(&Pixels::of(plan).try_map(|b| self.read_rect(b, plan))?);
                self.write_rect(plan.output, plan, &out)?;
                if let Some(history) = history {
                    self.stages[plan.stage.0 as usize].history = Some(Arc::new(history));
                }
            }
            return Ok(());
        }
        let mut rest = plans;
        while !rest.is_empty() {
            let (together, after) = rest.split_at(runs_together(rest));
            let mut stages = Vec::new();
            for (i, plan) in together.iter().enumerate() {
                let ids = Pixels::of(plan);
                let sources = ids.try_map(|b| match together[..i].iter().rposition(|p| p.output == b) {
                    Some(k) => Ok(Source::Earlier(k, together[k].width)),
                    None => self.stage_source(b, plan),
                })?;
                stages.push((plan.clone(), sources));
            }
            let (outputs, histories) = self.run_on_wgpu(&stages).await?;
            self.take_outputs(together, outputs, histories)?;
            rest = after;
        }
        Ok(())
    }

    /// The run's rectangle of `plan` (its top-left `width` x `height`) of
    /// buffer `b`, row by row.
    fn read_rect(&self, b: BufferId, plan: &Plan) -> Result<Vec<Vec4>> {
        let all = self.read_buffer::<Vec4>(b)?;
        Ok(crop(&all, self.buffer_width(b), plan.width, plan.height))
    }

    /// Writes `rect` (row by row) over the run's rectangle of `plan` in
    /// buffer `b`, leaving the rest of it as it was.
    fn write_rect(&mut self, b: BufferId, plan: &Plan, rect: &[Vec4]) -> Result<()> {
        let whole =
            self.scene.buffers.get(b.index() as usize).map(|r| r.width as u64 * r.height as u64 * r.depth as u64);
        if whole == Some(rect.len() as u64) {
            return self.write_buffer(b, rect);
        }
        let mut all = self.read_buffer::<Vec4>(b)?;
        merge(&mut all, self.buffer_width(b), (plan.width, plan.height), rect);
        self.write_buffer(b, &all)
    }

    /// The row length of buffer `b` (its width; 0 for none).
    fn buffer_width(&self, b: BufferId) -> u32 {
        self.scene.buffers.get(b.index() as usize).map_or(0, |r| r.width)
    }

    /// Writes the outputs of `plans`, which ran on the wgpu device and
    /// were read back (counted in `stage_read_back`), to their buffers,
    /// and keeps the next histories of the temporal denoisers among them
    /// (`histories`, in the plans' order) on the device.
    fn take_outputs(&mut self, plans: &[Plan], outputs: Vec<Vec<Vec4>>, histories: Vec<DeviceHistory>) -> Result<()> {
        self.stage_read_back += outputs.iter().map(|o| o.len() as u64 * 16).sum::<u64>();
        for (plan, out) in plans.iter().zip(outputs) {
            self.write_rect(plan.output, plan, &out)?;
        }
        let mut histories = histories.into_iter();
        for (plan, t) in plans.iter().filter_map(|p| Some((p, p.temporal.as_ref()?))) {
            let kept = histories.next().ok_or_else(|| LaunchError::Internal {
                backend: "wgpu",
                problem: "internal: a temporal denoiser left no history on the device".into(),
            })?;
            let texels = Texels::Device(kept);
            let history = History { width: plan.width, height: plan.height, texels, camera: t.camera };
            self.stages[plan.stage.0 as usize].history = Some(Arc::new(history));
        }
        Ok(())
    }

    /// Drops the history of temporal denoiser `stage` (on the wgpu
    /// backend its device buffers): its next run starts again from its
    /// input alone, as its first did.
    pub fn reset_stage_history(&mut self, stage: StageId) -> Result<()> {
        self.stage_mut(stage)?.history = None;
        Ok(())
    }

    /// The history of temporal denoiser `stage`, where it has one: each
    /// pixel's accumulated colour (rgb) and how many frames it holds (w),
    /// row by row, with its size. On the wgpu backend the history lives
    /// on the device and this reads it back (one submission; no run reads
    /// it back); a history on a device the context no longer has (lost
    /// since) is none, and the next run starts again.
    pub fn stage_history(&self, stage: StageId) -> Result<Option<(u32, u32, Vec<Vec4>)>> {
        let Some(h) = &self.stage(stage)?.history else { return Ok(None) };
        let Some(texels) = self.history_texels(h)? else { return Ok(None) };
        let colors = texels.iter().step_by(TEXELS).copied().collect();
        Ok(Some((h.width, h.height, colors)))
    }

    /// The texels of history `h`: the host's, or read back from the wgpu
    /// device that holds it; `None` where that device is gone.
    fn history_texels(&self, h: &History) -> Result<Option<Vec<Vec4>>> {
        match &h.texels {
            Texels::Host(texels) => Ok(Some(texels.clone())),
            Texels::Device(d) => {
                let open = self.wgpu_backend_ref().and_then(|b| b.serial());
                let Some(handles) = self.wgpu_device().filter(|_| open == Some(d.serial)) else { return Ok(None) };
                let texels = (h.width * h.height) as u64 * TEXELS as u64;
                let texels = backend::futures::block(read_history(&handles.queue, d, texels))?;
                if let Some(b) = self.wgpu_backend_ref() {
                    b.count_submission();
                }
                Ok(Some(texels))
            }
        }
    }

    /// `plan` for the CPU backend: its temporal denoiser's history on the
    /// host. One the wgpu device holds (the backend switched since) is
    /// read back once; where that device is gone, or the read fails, the
    /// run starts again, as after a reset.
    fn history_on_host(&self, plan: &Plan) -> Plan {
        let mut plan = plan.clone();
        if let Some(t) = plan.temporal.as_mut()
            && let Some(h) = t.previous.take()
        {
            t.previous = match &h.texels {
                Texels::Host(_) => Some(h),
                Texels::Device(_) => self.history_texels(&h).ok().flatten().map(|texels| {
                    Arc::new(History {
                        width: h.width,
                        height: h.height,
                        texels: Texels::Host(texels),
                        camera: h.camera,
                    })
                }),
            };
        }
        plan
    }

    /// Where `plan` on the wgpu device takes buffer `b` from: the
    /// device's heap, where a launch left newer words than the host's
    /// there (a device-local buffer), else the host's pixels of the run's
    /// rectangle.
    fn stage_source(&self, b: BufferId, plan: &Plan) -> Result<Source> {
        let version = self.scene.buffers.get(b.index() as usize).map(|r| r.host_version);
        let held = version.and_then(|v| self.wgpu_backend_ref()?.held(b.index() as usize, v));
        match held {
            Some(on_device) => Ok(Source::Device(on_device, self.buffer_width(b))),
            None => Ok(Source::Host(self.read_rect(b, plan)?)),
        }
    }

    /// How many stage inputs the wgpu backend has taken from its device
    /// (device-local buffers a launch left there, copied on the device),
    /// not through the host.
    pub fn stage_inputs_read_on_device(&self) -> u64 {
        self.stage_device_inputs
    }

    /// How many queue submissions stages have made of their own on the
    /// wgpu device: one for each [`Context::run_stage`], one for each run
    /// of consecutive stages of a command list that no launch comes
    /// before (the stages after a list's launch ride in its last
    /// submission, [`Context::wgpu_submissions`] counts that).
    pub fn stage_submissions(&self) -> u64 {
        self.stage_submits
    }

    /// Bytes stages' runs on the wgpu backend sent from the host to the
    /// device: their images (the run's rectangle of each) where the
    /// device did not hold them, and a
    /// temporal denoiser's history the CPU backend made (once, after a
    /// switch of backends). A temporal denoiser's own history stays on
    /// the device, frame after frame, and adds nothing.
    pub fn stage_upload_bytes(&self) -> u64 {
        self.stage_uploaded
    }

    /// Bytes stages' runs on the wgpu backend read back from the device:
    /// their outputs (the run's rectangle of each), whether they ran alone or rode in a command list's
    /// launch (whose [`Context::last_read_back_bytes`] counts them too).
    /// No run reads a temporal denoiser's history back
    /// ([`Context::stage_history`] reads it when asked, not counted here).
    pub fn stage_read_back_bytes(&self) -> u64 {
        self.stage_read_back
    }

    /// The stages' pipelines on the wgpu device (opened first if no launch
    /// opened it yet), made once per device; both awaited.
    async fn stage_pipelines(&mut self) -> Result<(Pipelines, super::WgpuDevice)> {
        self.wgpu_backend().open_async().await?;
        let no_device = || LaunchError::Internal { backend: "wgpu", problem: "no device after opening one".into() };
        let handles = self.wgpu_device().ok_or_else(no_device)?;
        let serial = self.wgpu_backend_ref().and_then(|b| b.serial()).ok_or_else(no_device)?;
        if !self.stage_pipelines.as_ref().is_some_and(|p| p.on(serial)) {
            self.stage_pipelines = Some(Pipelines::new(&handles.device, serial).await?);
        }
        Ok((self.stage_pipelines.clone().expect("made above"), handles))
    }

    /// Runs entry point `entry` over `size` (width, height, depth) as
    /// [`Context::launch_3d_with_progress`] does, then the checked stages
    /// `plans` in order. On the wgpu backend the stages are recorded into
    /// the launch's last submission, after its dispatches, reading the
    /// launch's outputs where they lie in its heap; those outputs are not
    /// read back (the device holds them, and a read copies them then),
    /// the stages' outputs are, with the launch's others. A launch that
    /// fails or is cancelled runs no stage. The device's work is awaited.
    pub(crate) async fn launch_then_stages(
        &mut self,
        (entry, width, height, depth): (u32, u32, u32, u32),
        progress: &mut dyn FnMut(LaunchProgress) -> LaunchControl,
        plans: &[Plan],
    ) -> Result<LaunchReport> {
        if self.backend() != Backend::Wgpu || plans.is_empty() {
            let report = self.run_launch_async((entry, width, height, depth), None, Some(progress)).await?;
            self.run_plans(plans).await?;
            return Ok(report);
        }
        // Those that cannot ride with the first (one reads an earlier
        // one's output beyond its rectangle) run after it, on their own.
        let (plans, after) = plans.split_at(runs_together(plans));
        let (pipelines, _) = self.stage_pipelines().await?;
        let tail = StageTail { pipelines, plans: plans.to_vec(), histories: Vec::new(), uploaded: 0 };
        self.wgpu_backend().arm_tail(Box::new(tail));
        let report = self.run_launch_async((entry, width, height, depth), None, Some(progress)).await;
        let ran = self.wgpu_backend().take_tail();
        let report = report?;
        let internal = || LaunchError::Internal {
            backend: "wgpu",
            problem: "internal: the stages after the launch did not run".into(),
        };
        let ran = ran.ok_or_else(internal)?;
        let tail = (ran.tail as Box<dyn Any>).downcast::<StageTail>().map_err(|_| internal())?;
        let outputs: Vec<Vec<Vec4>> = ran.words.iter().map(|words| pixels(words)).collect();
        self.stage_uploaded += tail.uploaded;
        let StageTail { pipelines, histories, .. } = *tail;
        // Made again on the launch's device where it opened a new one.
        self.stage_pipelines = Some(pipelines);
        self.take_outputs(plans, outputs, histories)?;
        self.stage_device_inputs += ran.from_device;
        self.run_plans(after).await?;
        Ok(report)
    }

    /// Runs checked stages' passes on the wgpu device (opened first if no
    /// launch opened it yet), in one submission; their outputs, and the
    /// temporal denoisers' next histories, on the device (awaited).
    async fn run_on_wgpu(&mut self, stages: &[(Plan, Pixels<Source>)]) -> Result<(Vec<Vec<Vec4>>, Vec<DeviceHistory>)> {
        let (pipelines, handles) = self.stage_pipelines().await?;
        let (outputs, recording) = pipelines.run(&handles.queue, stages).await?;
        self.stage_uploaded += recording.uploaded;
        self.stage_submits += 1;
        self.wgpu_backend().count_submission();
        let from_device = stages.iter().flat_map(|(_, s)| s.each()).filter(|s| matches!(s, Source::Device(..)));
        self.stage_device_inputs += from_device.count() as u64;
        Ok((outputs, recording.histories))
    }
}
