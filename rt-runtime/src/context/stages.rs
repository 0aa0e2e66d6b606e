//! Post-processing stages ([`crate::postprocess`]): creating them, setting
//! their variables, running one.

use super::Context;
use crate::backend::tiles::{LaunchControl, LaunchProgress};
use crate::backend::{Backend, LaunchReport};
use crate::error::{ConfigError, LaunchError, Result, SceneError};
use crate::postprocess::gpu::{Pipelines, Source, StageTail, pixels};
use crate::postprocess::{History, Pixels, Plan, Stage, StageId, StageKind, StageValue};
use crate::scene::BufferId;
use glam::Vec4;
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

    /// Runs `stage` over `width` x `height` pixels, the size its buffers
    /// must have, into its `output_buffer`: on the wgpu backend as compute
    /// passes on the context's device (one submission; the stage's images
    /// go up to the device, or where a launch left a device-local buffer's
    /// newest words on the device are copied there, and its output comes
    /// back to the host buffer), on the CPU backend natively. The
    /// stage is checked first ([`PostProcessError::BadStage`](crate::PostProcessError::BadStage) naming the variable
    /// at fault); a stage that fails writes nothing.
    pub fn run_stage(&mut self, stage: StageId, width: u32, height: u32) -> Result<()> {
        let plan = self.plan_stage(stage, Some((width, height)))?;
        self.run_plans(&[plan])
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

    /// Runs checked stages in order and writes their output buffers: on
    /// the CPU backend one by one; on the wgpu backend all in one
    /// submission, a stage reading an earlier one's output on the device.
    pub(crate) fn run_plans(&mut self, plans: &[Plan]) -> Result<()> {
        if self.backend() != Backend::Wgpu {
            for plan in plans {
                let (out, history) = plan.run_cpu(&Pixels::of(plan).try_map(|b| self.read_buffer::<Vec4>(b))?);
                self.write_buffer(plan.output, &out)?;
                if let Some(history) = history {
                    self.stages[plan.stage.0 as usize].history = Some(Arc::new(history));
                }
            }
            return Ok(());
        }
        let mut stages = Vec::new();
        for (i, plan) in plans.iter().enumerate() {
            let ids = Pixels::of(plan);
            let sources = ids.try_map(|b| match plans[..i].iter().rposition(|p| p.output == b) {
                Some(k) => Ok(Source::Earlier(k)),
                None => self.stage_source(b),
            })?;
            stages.push((plan.clone(), sources));
        }
        let outputs = self.run_on_wgpu(&stages)?;
        self.take_outputs(plans, outputs)
    }

    /// Writes the outputs of `plans`, which ran on the wgpu device, to
    /// their buffers, and keeps the next histories of the temporal
    /// denoisers among them (`images`: the outputs, then the histories in
    /// the plans' order).
    fn take_outputs(&mut self, plans: &[Plan], images: Vec<Vec<Vec4>>) -> Result<()> {
        let mut images = images.into_iter();
        for (plan, out) in plans.iter().zip(images.by_ref()) {
            self.write_buffer(plan.output, &out)?;
        }
        for (plan, t) in plans.iter().filter_map(|p| Some((p, p.temporal.as_ref()?))) {
            let texels = images.next().ok_or_else(|| LaunchError::Internal {
                backend: "wgpu",
                problem: "internal: a temporal denoiser's history did not come back".into(),
            })?;
            let history = History { width: plan.width, height: plan.height, texels, camera: t.camera };
            self.stages[plan.stage.0 as usize].history = Some(Arc::new(history));
        }
        Ok(())
    }

    /// Drops the history of temporal denoiser `stage`: its next run
    /// starts again from its input alone, as its first did.
    pub fn reset_stage_history(&mut self, stage: StageId) -> Result<()> {
        self.stage_mut(stage)?.history = None;
        Ok(())
    }

    /// The history of temporal denoiser `stage`, where it has one: each
    /// pixel's accumulated colour (rgb) and how many frames it holds (w),
    /// row by row, with its size.
    pub fn stage_history(&self, stage: StageId) -> Result<Option<(u32, u32, Vec<Vec4>)>> {
        let Some(h) = &self.stage(stage)?.history else { return Ok(None) };
        let colors = h.texels.iter().step_by(crate::postprocess::temporal::TEXELS).copied().collect();
        Ok(Some((h.width, h.height, colors)))
    }

    /// Where a stage on the wgpu device takes buffer `b` from: the
    /// device's heap, where a launch left newer words than the host's
    /// there (a device-local buffer), else the host's pixels.
    fn stage_source(&self, b: BufferId) -> Result<Source> {
        let version = self.scene.buffers.get(b.index() as usize).map(|r| r.host_version);
        let held = version.and_then(|v| self.wgpu_backend_ref()?.held(b.index() as usize, v));
        match held {
            Some(on_device) => Ok(Source::Device(on_device)),
            None => Ok(Source::Host(self.read_buffer::<Vec4>(b)?)),
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

    /// The stages' pipelines on the wgpu device (opened first if no launch
    /// opened it yet), made once per device.
    fn stage_pipelines(&mut self) -> Result<(Pipelines, super::WgpuDevice)> {
        self.open_wgpu()?;
        let handles = self
            .wgpu_device()
            .ok_or_else(|| LaunchError::Internal { backend: "wgpu", problem: "no device after opening one".into() })?;
        if !self.stage_pipelines.as_ref().is_some_and(|p| p.on(&handles.device)) {
            self.stage_pipelines = Some(Pipelines::new(&handles.device)?);
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
    /// fails or is cancelled runs no stage.
    pub(crate) fn launch_then_stages(
        &mut self,
        (entry, width, height, depth): (u32, u32, u32, u32),
        progress: &mut dyn FnMut(LaunchProgress) -> LaunchControl,
        plans: &[Plan],
    ) -> Result<LaunchReport> {
        if self.backend() != Backend::Wgpu || plans.is_empty() {
            let report = self.launch_3d_with_progress(entry, width, height, depth, progress)?;
            self.run_plans(plans)?;
            return Ok(report);
        }
        let (pipelines, _) = self.stage_pipelines()?;
        let tail = StageTail { pipelines, plans: plans.to_vec() };
        self.wgpu_backend().arm_tail(Box::new(tail));
        let report = self.launch_3d_with_progress(entry, width, height, depth, progress);
        let ran = self.wgpu_backend().take_tail();
        let report = report?;
        let (outputs, from_device) = ran.ok_or_else(|| LaunchError::Internal {
            backend: "wgpu",
            problem: "internal: the stages after the launch did not run".into(),
        })?;
        self.take_outputs(plans, outputs.iter().map(|words| pixels(words)).collect())?;
        self.stage_device_inputs += from_device;
        Ok(report)
    }

    /// Runs checked stages' passes on the wgpu device (opened first if no
    /// launch opened it yet), in one submission; their outputs.
    fn run_on_wgpu(&mut self, stages: &[(Plan, Pixels<Source>)]) -> Result<Vec<Vec<Vec4>>> {
        let (pipelines, handles) = self.stage_pipelines()?;
        let outputs = pipelines.run(&handles.queue, stages)?;
        self.stage_submits += 1;
        self.wgpu_backend().count_submission();
        let from_device = stages.iter().flat_map(|(_, s)| s.each()).filter(|s| matches!(s, Source::Device(_)));
        self.stage_device_inputs += from_device.count() as u64;
        Ok(outputs)
    }
}
