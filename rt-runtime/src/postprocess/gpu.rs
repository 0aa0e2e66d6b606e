//! The stages on a wgpu device: the passes of `gpu/stages.wgsl` (the
//! same arithmetic as [`super::denoise`] and [`super::tonemap`]) as plain
//! compute passes, all of a run of stages (a command list's stages one
//! after another, or one stage) in one submission: the run's rectangle
//! of each stage's images (the top-left `width` x `height`) is uploaded
//! to storage buffers (or, where a launch left a device-local buffer's
//! newest words in its heap, the span of the heap holding it is copied
//! on the device, and the passes read it in rows of the buffer's width;
//! or, where an earlier stage of the run wrote them, read where it did),
//! every pass runs (the denoiser's prepare, its à-trous passes
//! ping-ponging between two buffers, finish; or the tonemapper's one),
//! and every stage's output, of the run's size, is read back (the context
//! merges it into the rectangle of the output buffer). In temporal mode the
//! denoiser's `gpu/temporal.wgsl` pass runs first, over its history where
//! the device keeps it ([`DeviceHistory`]: two buffers the stage owns,
//! one read and the other written, swapped each run), and nothing of it
//! is read back: a progressive renderer's launch, denoiser and
//! tonemapper run frame after frame with no history crossing to the
//! host ([`read_history`] reads one when asked). The pipelines are made
//! once per device ([`Pipelines`]).
//!
//! After a command list's launch, the run rides in the launch's last
//! submission instead ([`StageTail`], a `backend::wgpu::tail::Tail`):
//! recorded after the launch's dispatches, reading what the launch wrote
//! where it lies in the heap.

use super::denoise::Tuning;
use super::temporal::TEXELS;
use super::{Pixels, Plan, StageKind, Temporal, Texels};
use crate::backend::wgpu::DeviceBuffer;
use crate::backend::wgpu::readback;
use crate::backend::wgpu::tail::{Recorded, Tail};
use crate::error::{DeviceError, Result, RtError};
use crate::scene::{BufferId, Scene};
use glam::Vec4;
use wgpu::util::DeviceExt;

const WGSL: &str = include_str!("gpu/stages.wgsl");
const TEMPORAL_WGSL: &str = include_str!("gpu/temporal.wgsl");

/// The stages' pipelines on one device.
#[derive(Clone)]
pub(crate) struct Pipelines {
    device: wgpu::Device,
    /// The device's serial (`backend::wgpu::WgpuBackend::serial`).
    serial: u64,
    layout: wgpu::BindGroupLayout,
    prepare: wgpu::ComputePipeline,
    atrous: wgpu::ComputePipeline,
    finish: wgpu::ComputePipeline,
    tonemap: wgpu::ComputePipeline,
    /// The temporal denoiser's pass (`gpu/temporal.wgsl`) and its layout.
    temporal_layout: wgpu::BindGroupLayout,
    temporal: wgpu::ComputePipeline,
}

impl Pipelines {
    /// Whether these were made on the device of serial `serial`.
    pub fn on(&self, serial: u64) -> bool {
        self.serial == serial
    }

    /// The stages' pipelines on `device`, of serial `serial`, once the
    /// device has checked their WGSL (awaited: a browser page cannot
    /// block on it).
    pub async fn new(device: &wgpu::Device, serial: u64) -> Result<Pipelines> {
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("rt post-processing stages"),
            source: wgpu::ShaderSource::Wgsl(WGSL.into()),
        });
        let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let uniform = wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let entries = [
            uniform,
            storage(1, true),
            storage(2, true),
            storage(3, true),
            storage(4, true),
            storage(5, false),
            storage(6, true),
        ];
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rt post-processing stages"),
            entries: &entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("rt post-processing stages"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let temporal_entries: Vec<_> =
            std::iter::once(uniform).chain((1..=5).map(|b| storage(b, true))).chain([storage(6, false)]).collect();
        let (temporal_layout, temporal) = Self::temporal_pipeline(device, &temporal_entries);
        let made = Pipelines {
            device: device.clone(),
            serial,
            prepare: pipeline("prepare"),
            atrous: pipeline("atrous"),
            finish: pipeline("finish"),
            tonemap: pipeline("tonemap"),
            layout,
            temporal_layout,
            temporal,
        };
        match scope.pop().await {
            Some(e) => Err(DeviceError::Gpu(format!("the post-processing stages' WGSL does not compile: {e}")).into()),
            None => Ok(made),
        }
    }

    /// The temporal pass's layout (of `entries`) and pipeline.
    fn temporal_pipeline(
        device: &wgpu::Device,
        entries: &[wgpu::BindGroupLayoutEntry],
    ) -> (wgpu::BindGroupLayout, wgpu::ComputePipeline) {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("rt temporal denoiser"),
            source: wgpu::ShaderSource::Wgsl(TEMPORAL_WGSL.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rt temporal denoiser"),
            entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("rt temporal denoiser"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("temporal"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("temporal"),
            compilation_options: Default::default(),
            cache: None,
        });
        (layout, pipeline)
    }

    /// Runs `stages` (each a plan over its images) in order on `queue`,
    /// all in one submission: each one's output, read back, and what was
    /// recorded (the temporal denoisers' next histories stay on the
    /// device). An image that an earlier stage of the run wrote
    /// ([`Source::Earlier`]) is that stage's output as it lies on the
    /// device. The read-back is awaited (a browser page cannot block on
    /// it).
    pub async fn run(
        &self,
        queue: &wgpu::Queue,
        stages: &[(Plan, Pixels<Source>)],
    ) -> Result<(Vec<Vec<Vec4>>, Recording)> {
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let recording = self.record(&mut encoder, stages);
        let whole: Vec<_> = recording.outputs.iter().map(|b| (b, b.size())).collect();
        let words = read_back(&self.device, queue, encoder, &whole, "running a post-processing stage").await?;
        Ok((words.iter().map(|w| pixels(w)).collect(), recording))
    }

    /// Records `stages`' passes into `encoder`, in order.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, stages: &[(Plan, Pixels<Source>)]) -> Recording {
        let mut r = Recording { outputs: Vec::new(), histories: Vec::new(), uploaded: 0 };
        for (plan, images) in stages {
            let (out, history) = self.encode(encoder, plan, images, &r.outputs, &mut r.uploaded);
            r.outputs.push(out);
            r.histories.extend(history);
        }
        r
    }

    /// Records `plan`'s passes over `images` into `encoder` (`earlier`:
    /// the outputs of the run's stages before it; `uploaded` counts the
    /// bytes of images and histories sent from the host), returning the
    /// buffer its output will be in, and the temporal denoiser's next
    /// history.
    fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        plan: &Plan,
        images: &Pixels<Source>,
        earlier: &[wgpu::Buffer],
        uploaded: &mut u64,
    ) -> (wgpu::Buffer, Option<DeviceHistory>) {
        let device = &self.device;
        let n = (plan.width * plan.height) as usize;
        let bytes = (n * 16) as u64;
        let upload = |label, px: &[Vec4]| upload(device, label, px);
        let scratch = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        // Each image with its row length: the host's rectangle is uploaded
        // (rows of the run's width); on the device, the span of the heap
        // that holds the rectangle (rows of the buffer's width) is copied
        // in this submission, before the passes read it; an earlier
        // stage's output is read where that stage wrote it.
        let mut image = |label, source: &Source| match source {
            Source::Host(px) => {
                *uploaded += px.len() as u64 * 16;
                (upload(label, px), plan.width)
            }
            Source::Device(d, stride) => {
                let span = ((plan.height as u64 - 1) * *stride as u64 + plan.width as u64) * 16;
                let size = span.min(d.size).max(16);
                let b = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                encoder.copy_buffer_to_buffer(&d.buffer, d.offset, &b, 0, span.min(d.size));
                (b, *stride)
            }
            Source::Earlier(k, stride) => (earlier[*k].clone(), *stride),
        };
        let unused = || (upload("rt stage: unused", &[Vec4::ZERO]), 0);
        let empty = upload("rt stage: unused", &[Vec4::ZERO]);
        let color = image("rt stage: input", &images.input);
        let (albedo, normal) = match &images.guides {
            Some((a, n)) => (image("rt stage: albedo", a), image("rt stage: normal", n)),
            None => (unused(), unused()),
        };
        let variance = match &images.variance {
            Some(v) => image("rt stage: variance", v),
            None => unused(),
        };
        let position = images.position.as_ref().map(|p| image("rt stage: position", p));
        // The temporal denoiser's accumulated colour and variance (rows of
        // the run's width) take the place of its input's for the spatial
        // passes.
        let (color, variance, history) = match (&plan.temporal, position) {
            (Some(t), Some(position)) => {
                let frame = [&color, &albedo, &normal, &position];
                let (acc, acc_variance, history) = self.encode_temporal(encoder, plan, t, frame, uploaded);
                ((acc, plan.width), (acc_variance, plan.width), Some(history))
            }
            _ => (color, variance, None),
        };
        let strides = [color.1, albedo.1, normal.1, variance.1];
        let [(color, _), (albedo, _), (normal, _), (variance, _)] = [color, albedo, normal, variance];
        let has_variance = plan.variance.is_some() || history.is_some();
        let (a, b) = (scratch("rt stage: ping"), scratch("rt stage: pong"));
        let t = Tuning::default();
        let mut pass = |pipeline: &wgpu::ComputePipeline, step: i32, src: &wgpu::Buffer, dst: &wgpu::Buffer| {
            let settings = [plan.settings[0], plan.settings.get(1).copied().unwrap_or(0.0)];
            let params = params(plan, step, &t, settings, has_variance, strides);
            let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("rt stage: params"),
                contents: &params,
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let buffers = [&uniform, &color, &albedo, &normal, src, dst, &variance];
            dispatch(device, encoder, (&self.layout, pipeline), &buffers, plan);
        };
        match plan.kind {
            StageKind::Denoiser => {
                pass(&self.prepare, 0, &empty, &a);
                let (mut src, mut dst) = (&a, &b);
                for i in 0..t.iterations {
                    pass(&self.atrous, 1 << i, src, dst);
                    std::mem::swap(&mut src, &mut dst);
                }
                pass(&self.finish, 0, src, dst);
                (dst.clone(), history)
            }
            StageKind::Tonemapper => {
                pass(&self.tonemap, 0, &empty, &a);
                (a, None)
            }
        }
    }

    /// Records the temporal pass of `plan` over its `frame` (colour,
    /// albedo, normal, position, each with its row length): the buffers of the accumulated colour,
    /// its variance, and the next history. The last run's history is
    /// read where this device keeps it; one the CPU backend made is
    /// uploaded (counted in `uploaded`), one on another device (lost
    /// since) is none. The next is written into the buffer the run before
    /// wrote, where the history has one of this size, else a new one.
    fn encode_temporal(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        plan: &Plan,
        t: &Temporal,
        frame: [&(wgpu::Buffer, u32); 4],
        uploaded: &mut u64,
    ) -> (wgpu::Buffer, wgpu::Buffer, DeviceHistory) {
        let device = &self.device;
        let n = (plan.width * plan.height) as u64;
        let storage = |label, size| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let upload = |label, px: &[Vec4]| upload(device, label, px);
        let texels = n * TEXELS as u64;
        let size = (texels + 2 * n) * 16;
        let (previous, spare) = match t.previous.as_ref().map(|h| &h.texels) {
            Some(Texels::Device(d)) if d.serial == self.serial => (Some(d.held.clone()), d.spare.clone()),
            Some(Texels::Host(px)) => {
                *uploaded += px.len() as u64 * 16;
                (Some(upload("rt stage: previous history", px)), None)
            }
            _ => (None, None),
        };
        let next = spare.filter(|b| b.size() == size).unwrap_or_else(|| storage("rt stage: history", size));
        let bound = previous.clone().unwrap_or_else(|| upload("rt stage: no history", &[Vec4::ZERO]));
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("rt stage: temporal params"),
            contents: &temporal_params(plan, t, previous.is_some(), frame.map(|(_, stride)| *stride)),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let [color, albedo, normal, position] = frame.map(|(b, _)| b);
        let buffers = [&uniform, color, albedo, normal, position, &bound, &next];
        dispatch(device, encoder, (&self.temporal_layout, &self.temporal), &buffers, plan);
        let (acc, acc_variance) =
            (storage("rt stage: accumulated", n * 16), storage("rt stage: temporal variance", n * 16));
        encoder.copy_buffer_to_buffer(&next, texels * 16, &acc, 0, n * 16);
        encoder.copy_buffer_to_buffer(&next, (texels + n) * 16, &acc_variance, 0, n * 16);
        // The buffer read this run is written by the next, where it is
        // this device's (an uploaded one is of another size).
        let spare = previous.filter(|b| b.size() == size);
        (acc, acc_variance, DeviceHistory { device: device.clone(), serial: self.serial, held: next, spare })
    }
}

/// A temporal denoiser's history on a wgpu device, in buffers the stage
/// owns: `held`, written by its last run (`gpu/temporal.wgsl`'s `next`:
/// [`TEXELS`] texels a pixel of history, then that run's accumulated
/// colour and variance), and `spare`, the one the run before wrote,
/// which the next run writes (none until two runs). A run reads one and
/// writes the other, so a run that fails leaves the history as it was.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct DeviceHistory {
    pub device: wgpu::Device,
    /// The device's serial (`backend::wgpu::WgpuBackend::serial`).
    pub serial: u64,
    pub held: wgpu::Buffer,
    pub spare: Option<wgpu::Buffer>,
}

/// What [`Pipelines::record`] recorded: the buffers each stage's output
/// will be in, each temporal denoiser's next history (in the stages'
/// order), and the bytes of images and histories it uploaded from the
/// host.
pub(crate) struct Recording {
    pub outputs: Vec<wgpu::Buffer>,
    pub histories: Vec<DeviceHistory>,
    pub uploaded: u64,
}

/// The first `texels` texels of history `h`, read back from its device
/// through `queue` (one submission, awaited).
pub(crate) async fn read_history(queue: &wgpu::Queue, h: &DeviceHistory, texels: u64) -> Result<Vec<Vec4>> {
    let encoder = h.device.create_command_encoder(&Default::default());
    let what = "reading a denoiser's history";
    let words = read_back(&h.device, queue, encoder, &[(&h.held, texels * 16)], what).await?;
    Ok(words.first().map(|w| pixels(w)).unwrap_or_default())
}

/// Submits `encoder` with copies of the first `size` bytes of each of
/// `buffers` after its work, and reads them back through the backend's
/// read-back (`backend::wgpu::readback::read_back`, awaited: in a browser
/// the page's event loop delivers the mapping), inside a validation error
/// scope of its own; `what` names the work in an error.
async fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    encoder: wgpu::CommandEncoder,
    buffers: &[(&wgpu::Buffer, u64)],
    what: &str,
) -> Result<Vec<Vec<u32>>> {
    let copies: Vec<_> = buffers.iter().map(|&(b, size)| (b, 0, size)).collect();
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let mut staging = None;
    let read = readback::read_back(device, queue, &mut staging, encoder, &copies, false).await;
    // Popped whatever the read gave: where wgpu refused a pass, that is
    // the error to report.
    let gpu_err = |step: &str, e: String| DeviceError::Gpu(format!("{what}: {step}: {e}")).into();
    if let Some(e) = scope.pop().await {
        return Err(gpu_err("validation", e.to_string()));
    }
    let mut words = read.map_err(|e| gpu_err("reading back", e))?;
    let mut each = Vec::new();
    for &(_, size) in buffers.iter().rev() {
        each.push(words.split_off(words.len() - (size / 4) as usize));
    }
    each.reverse();
    Ok(each)
}

/// One pass of `pipeline` over `plan`'s pixels (8 x 8 a workgroup), its
/// `buffers` bound in order from binding 0 of `layout`.
fn dispatch(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    (layout, pipeline): (&wgpu::BindGroupLayout, &wgpu::ComputePipeline),
    buffers: &[&wgpu::Buffer],
    plan: &Plan,
) {
    let entries: Vec<_> = buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32, resource: b.as_entire_binding() })
        .collect();
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor { label: None, layout, entries: &entries });
    let mut cpass = encoder.begin_compute_pass(&Default::default());
    cpass.set_pipeline(pipeline);
    cpass.set_bind_group(0, &group, &[]);
    cpass.dispatch_workgroups(plan.width.div_ceil(8), plan.height.div_ceil(8), 1);
}

/// The little-endian bytes of `pixels`.
fn words(pixels: &[Vec4]) -> Vec<u8> {
    pixels.iter().flat_map(|p| p.to_array()).flat_map(f32::to_le_bytes).collect()
}

/// A storage buffer on `device` holding `pixels`.
fn upload(device: &wgpu::Device, label: &str, pixels: &[Vec4]) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: &words(pixels),
        usage: wgpu::BufferUsages::STORAGE,
    })
}

/// The `Params` uniform of `temporal.wgsl`, over the last run's history
/// where `has_history`, the frame's images in rows of `strides` pixels
/// (colour, albedo, normal, position).
fn temporal_params(plan: &Plan, t: &Temporal, has_history: bool, strides: [u32; 4]) -> Vec<u8> {
    let has_history = has_history as u32;
    let head = [plan.width, plan.height, has_history, t.alpha_min.to_bits()];
    let mut bytes: Vec<u8> = head.iter().chain(&strides).flat_map(|w| w.to_le_bytes()).collect();
    let before = t.previous.as_ref().map_or(t.camera, |h| h.camera);
    for v in [t.camera.eye, before.eye, before.u, before.v, before.w] {
        bytes.extend(words(&[v.extend(0.0)]));
    }
    bytes
}

/// Where a stage's image is for the device: the host's pixels of the
/// run's rectangle (uploaded), a range of the launch heap holding a
/// buffer's newest words (copied on the device, never through the host)
/// in rows of the buffer's width, or the output of the `k`th stage of the
/// same run (read where it lies) in rows of that run's width.
pub(crate) enum Source {
    Host(Vec<Vec4>),
    Device(DeviceBuffer, u32),
    Earlier(usize, u32),
}

/// Pixels from their words, four a pixel.
pub(crate) fn pixels(words: &[u32]) -> Vec<Vec4> {
    let f = f32::from_bits;
    words.chunks_exact(4).map(|c| Vec4::new(f(c[0]), f(c[1]), f(c[2]), f(c[3]))).collect()
}

/// A run of stages after a command list's launch, in its last submission
/// (`backend::wgpu::tail`): each image is an earlier stage's output of
/// the run, where it lies; else where the device has the buffer's newest
/// words (the launch wrote it, or holds it); else the host's pixels,
/// uploaded. Once recorded it holds the temporal denoisers' next
/// histories, on the device, and the bytes it uploaded; the backend hands
/// it back to the context after the launch
/// (`backend::wgpu::WgpuBackend::take_tail`).
pub(crate) struct StageTail {
    pub pipelines: Pipelines,
    pub plans: Vec<Plan>,
    pub histories: Vec<DeviceHistory>,
    pub uploaded: u64,
}

impl StageTail {
    /// Where `plans[i]` takes image `b` from.
    fn source(
        &self,
        i: usize,
        b: BufferId,
        scene: &Scene,
        on_device: &dyn Fn(usize) -> Option<DeviceBuffer>,
    ) -> Source {
        if let Some(k) = self.plans[..i].iter().rposition(|p| p.output == b) {
            return Source::Earlier(k, self.plans[k].width);
        }
        let rec = &scene.buffers[b.index() as usize];
        if let Some(d) = on_device(b.index() as usize) {
            return Source::Device(d, rec.width);
        }
        let mut words = Vec::new();
        rec.storage.to_words(&mut words);
        Source::Host(super::crop(&pixels(&words), rec.width, self.plans[i].width, self.plans[i].height))
    }
}

impl Tail for StageTail {
    /// Every buffer of the stages: what the launch left in those they read
    /// stays on the device for them, and those they write take the
    /// stages' outputs (which the context writes to the host, newer than
    /// what the device holds), so the launch reads none of them back.
    fn keeps(&self, buffer: usize) -> bool {
        let touches = |p: &Plan| {
            let ids = Pixels::of(p);
            p.output.index() as usize == buffer || ids.each().any(|b| b.index() as usize == buffer)
        };
        self.plans.iter().any(touches)
    }

    fn record(
        &mut self,
        (device, serial): (&wgpu::Device, u64),
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        on_device: &dyn Fn(usize) -> Option<DeviceBuffer>,
    ) -> Result<Recorded> {
        // The launch opened a new device (the last was lost): the
        // pipelines again, blocking on the WGSL's check (in a browser,
        // which cannot block, that fails saying so).
        if !self.pipelines.on(serial) {
            self.pipelines = crate::backend::futures::block(Pipelines::new(device, serial))?;
        }
        let mut stages = Vec::new();
        let mut from_device = 0;
        for (i, plan) in self.plans.iter().enumerate() {
            let ids = Pixels::of(plan);
            let sources = ids.try_map(|b| Ok::<_, RtError>(self.source(i, b, scene, on_device)))?;
            from_device += sources.each().filter(|s| matches!(s, Source::Device(..))).count() as u64;
            stages.push((plan.clone(), sources));
        }
        let recording = self.pipelines.record(encoder, &stages);
        (self.histories, self.uploaded) = (recording.histories, recording.uploaded);
        Ok(Recorded { read_back: recording.outputs, from_device })
    }
}

/// The `Params` uniform of `stages.wgsl` for one pass, its images in
/// rows of `strides` pixels (colour, albedo, normal, variance).
fn params(
    plan: &Plan,
    step: i32,
    t: &Tuning,
    [first, second]: [f32; 2],
    has_variance: bool,
    strides: [u32; 4],
) -> Vec<u8> {
    let [color, albedo, normal, variance] = strides;
    let words: [u32; 16] = [
        plan.width,
        plan.height,
        step as u32,
        t.variance_radius as u32,
        t.sigma_luminance.to_bits(),
        t.sigma_normal.to_bits(),
        t.sigma_albedo.to_bits(),
        first.to_bits(),
        second.to_bits(),
        has_variance as u32,
        0,
        0,
        color,
        albedo,
        normal,
        variance,
    ];
    words.iter().flat_map(|w| w.to_le_bytes()).collect()
}
