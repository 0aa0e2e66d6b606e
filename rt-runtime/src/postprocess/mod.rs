//! Post-processing stages: OptiX 6's `RTpostprocessingstage`, the built-in
//! image passes a renderer runs after its launches (a denoiser and a
//! tonemapper), configured by named variables as OptiX configures them.
//!
//! A stage is created by kind ([`StageKind`]) or by OptiX's built-in
//! name (`DLDenoiser`, `TonemapperSimple`) and set up with
//! [`Context::set_stage_var`](crate::Context::set_stage_var): buffers
//! (`input_buffer`, `input_albedo_buffer`, `input_normal_buffer`, the
//! optional `input_variance_buffer`, `output_buffer`) and settings
//! (`blend`, `exposure`, `gamma`), and for the denoiser's temporal mode
//! ([`temporal`]: `temporal` 1) `alpha_min`, the camera (`camera_eye`,
//! `camera_u`, `camera_v`, `camera_w`, vectors) and the position guide
//! (`input_position_buffer`). Every image buffer holds one `Vec4` a
//! pixel, RGBA (a normal's xyz, an albedo's rgb, a variance in x), 2D and
//! at least of the stage's run size: as with OptiX's
//! `rtCommandListAppendPostprocessingStage`, a run over `width` x `height` covers
//! the top-left `width` x `height` of each buffer (rows of the buffer's
//! own width), and leaves the output's texels outside it as they were,
//! so a renderer whose buffers only grow runs over the part its picture
//! takes. `Stage::plan` checks all
//! of it before anything runs, naming the stage and the variable at
//! fault; a command list's finalize runs the same check
//! ([`crate::command_list`]).
//!
//! The passes: [`denoise`] (an edge-avoiding à-trous wavelet filter
//! guided by albedo, normal and a luminance variance, the renderer's
//! per-pixel one or its own spatial estimate: the spatial part of SVGF),
//! run after [`temporal`] (SVGF's temporal part: a history the stage
//! keeps, reprojected through the camera; on the wgpu backend it stays on
//! the device, and no run reads it back) in temporal mode, and [`tonemap`] (exposure, ACES-fitted filmic
//! curve, gamma), each a CPU reference here and a WGSL compute pass in
//! `gpu.rs` that the wgpu backend runs on its device.

pub mod denoise;
pub(crate) mod gpu;
pub mod temporal;
pub mod tonemap;

use crate::buffer::{BufferRec, Typed};
use crate::error::{PostProcessError, Result};
use crate::scene::BufferId;
use glam::{Vec3, Vec4};
use std::collections::BTreeMap;
use std::sync::Arc;
use temporal::Pinhole;

/// A post-processing stage of a context (OptiX's `RTpostprocessingstage`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct StageId(pub(crate) u32);

impl StageId {
    /// Its index among the context's stages, in creation order.
    pub fn index(self) -> u32 {
        self.0
    }
}

/// The built-in stages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StageKind {
    /// The denoiser ([`denoise`]), OptiX's `DLDenoiser`.
    Denoiser,
    /// The tonemapper ([`tonemap`]), OptiX's `TonemapperSimple`.
    Tonemapper,
}

impl StageKind {
    /// The kind OptiX's name (`DLDenoiser`, `TonemapperSimple`) or this
    /// crate's (`denoiser`, `tonemapper`) names.
    pub fn from_name(name: &str) -> Option<StageKind> {
        match name {
            "DLDenoiser" | "denoiser" => Some(StageKind::Denoiser),
            "TonemapperSimple" | "tonemapper" => Some(StageKind::Tonemapper),
            _ => None,
        }
    }

    /// This crate's name of the kind.
    pub fn name(self) -> &'static str {
        match self {
            StageKind::Denoiser => "denoiser",
            StageKind::Tonemapper => "tonemapper",
        }
    }

    /// The variables a stage of this kind takes: name and sort (a
    /// buffer, a number and its default, or a vector). Every buffer must
    /// be set but the denoiser's `input_variance_buffer`, and its
    /// `input_position_buffer` and camera but in temporal mode.
    pub fn variables(self) -> &'static [(&'static str, Sort)] {
        match self {
            StageKind::Denoiser => &[
                (INPUT, Sort::Buffer),
                (ALBEDO, Sort::Buffer),
                (NORMAL, Sort::Buffer),
                (VARIANCE, Sort::Buffer),
                (POSITION, Sort::Buffer),
                (OUTPUT, Sort::Buffer),
                ("blend", Sort::Number(0.0)),
                (TEMPORAL, Sort::Number(0.0)),
                ("alpha_min", Sort::Number(0.2)),
                (CAMERA[0], Sort::Vector),
                (CAMERA[1], Sort::Vector),
                (CAMERA[2], Sort::Vector),
                (CAMERA[3], Sort::Vector),
            ],
            StageKind::Tonemapper => &[
                (INPUT, Sort::Buffer),
                (OUTPUT, Sort::Buffer),
                ("exposure", Sort::Number(1.0)),
                ("gamma", Sort::Number(2.2)),
            ],
        }
    }
}

/// The sort of a stage variable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sort {
    /// An image buffer.
    Buffer,
    /// A number, with its default.
    Number(f32),
    /// A 3-vector (the temporal denoiser's camera), no default.
    Vector,
}

const INPUT: &str = "input_buffer";
const ALBEDO: &str = "input_albedo_buffer";
const NORMAL: &str = "input_normal_buffer";
/// The denoiser's optional per-pixel variance: in x, the variance of the
/// pixel's mean luminance (of its colour divided by its albedo, as
/// [`denoise`] filters it), negative where unknown (fewer than two
/// samples).
const VARIANCE: &str = "input_variance_buffer";
const OUTPUT: &str = "output_buffer";
/// The temporal denoiser's world position guide: xyz over w, w 0 where
/// the camera ray hit nothing ([`temporal`]).
const POSITION: &str = "input_position_buffer";
/// 1 turns the denoiser's temporal mode on ([`temporal`]), 0 off.
const TEMPORAL: &str = "temporal";
/// The temporal denoiser's camera (eye, u, v, w), as the examples'
/// cameras name theirs ([`temporal::Pinhole`]).
const CAMERA: [&str; 4] = ["camera_eye", "camera_u", "camera_v", "camera_w"];

/// A stage variable's value: a buffer, a number or a vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StageValue {
    /// A buffer (`input_buffer`, `output_buffer`, ...).
    Buffer(BufferId),
    /// A setting (`blend`, `exposure`, `gamma`, `temporal`, `alpha_min`).
    Float(f32),
    /// A vector (the temporal denoiser's `camera_eye`, `camera_u`, ...).
    Vector(Vec3),
}

impl From<Vec3> for StageValue {
    fn from(v: Vec3) -> StageValue {
        StageValue::Vector(v)
    }
}

impl From<BufferId> for StageValue {
    fn from(b: BufferId) -> StageValue {
        StageValue::Buffer(b)
    }
}

impl From<f32> for StageValue {
    fn from(x: f32) -> StageValue {
        StageValue::Float(x)
    }
}

/// A stage: its kind, the variables set on it, and the temporal
/// denoiser's history of its last run.
#[derive(Clone, Debug)]
pub(crate) struct Stage {
    pub kind: StageKind,
    pub vars: BTreeMap<&'static str, StageValue>,
    pub history: Option<Arc<History>>,
}

/// The temporal denoiser's history ([`temporal`]): the texels of its last
/// run ([`temporal::TEXELS`] a pixel), where the backend that ran it
/// keeps them, its size and its camera.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct History {
    pub width: u32,
    pub height: u32,
    pub texels: Texels,
    pub camera: Pinhole,
}

/// Where a history's texels lie: on the host (the CPU backend's), or on
/// the wgpu device that ran the stage, in buffers the stage owns, which
/// no run reads back ([`gpu::DeviceHistory`]). A run on the other backend
/// moves them: an upload at a wgpu run, one read at a CPU run
/// (`context/stages.rs`).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Texels {
    Host(Vec<Vec4>),
    Device(gpu::DeviceHistory),
}

/// A temporal denoiser's run: its position guide, the frame's camera,
/// `alpha_min`, and the history to blend into (of the run's size).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Temporal {
    pub camera: Pinhole,
    pub alpha_min: f32,
    pub previous: Option<Arc<History>>,
}

/// A stage checked against the context's buffers, ready to run at
/// `width` x `height` (over the top-left of its buffers, each at least
/// that large): its buffers (input, guides, output) and settings.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Plan {
    pub stage: StageId,
    pub kind: StageKind,
    pub width: u32,
    pub height: u32,
    pub input: BufferId,
    /// The denoiser's albedo and normal guides.
    pub guides: Option<(BufferId, BufferId)>,
    /// The denoiser's per-pixel variance, where set.
    pub variance: Option<BufferId>,
    /// The temporal denoiser's position guide.
    pub position: Option<BufferId>,
    pub output: BufferId,
    /// `blend` (and `temporal`, `alpha_min`) for the denoiser; `exposure`
    /// and `gamma` for the tonemapper.
    pub settings: Vec<f32>,
    /// The temporal denoiser's camera and history.
    pub temporal: Option<Temporal>,
}

impl Stage {
    pub fn new(kind: StageKind) -> Stage {
        Stage { kind, vars: BTreeMap::new(), history: None }
    }

    /// How errors name stage `id` of this kind.
    pub fn label(&self, id: StageId) -> String {
        format!("{} (`{}`)", id.0, self.kind.name())
    }

    /// Sets variable `name`, which must be one of the kind's, to a value
    /// of its sort (a buffer for buffers, a finite number for settings).
    pub fn set(&mut self, id: StageId, name: &str, value: StageValue) -> Result<()> {
        let label = self.label(id);
        let bad = |problem: String| {
            PostProcessError::BadStage { stage: label.clone(), variable: name.into(), problem }.into()
        };
        let Some(&(known, sort)) = self.kind.variables().iter().find(|(n, _)| *n == name) else {
            let names: Vec<_> = self.kind.variables().iter().map(|(n, _)| *n).collect();
            return Err(bad(format!("is not a variable of the {}; it has {}", self.kind.name(), names.join(", "))));
        };
        let given = match value {
            StageValue::Buffer(b) => format!("buffer {}", b.0),
            StageValue::Float(x) => format!("the number {x}"),
            StageValue::Vector(v) => format!("the vector {v}"),
        };
        match (sort, value) {
            (Sort::Buffer, StageValue::Buffer(_)) => {}
            (Sort::Number(_), StageValue::Float(x)) if !x.is_finite() => {
                return Err(bad(format!("must be finite, not {x}")));
            }
            (Sort::Vector, StageValue::Vector(v)) if !v.is_finite() => {
                return Err(bad(format!("must be finite, not {v}")));
            }
            (Sort::Number(_), StageValue::Float(_)) | (Sort::Vector, StageValue::Vector(_)) => {}
            (Sort::Buffer, _) => return Err(bad(format!("is a buffer, but was given {given}"))),
            (Sort::Number(_), _) => return Err(bad(format!("is a number, but was given {given}"))),
            (Sort::Vector, _) => return Err(bad(format!("is a vector, but was given {given}"))),
        }
        match (known, value) {
            (TEMPORAL, StageValue::Float(x)) if x != 0.0 && x != 1.0 => {
                return Err(bad(format!("is 1 (on) or 0 (off), not {x}")));
            }
            ("alpha_min", StageValue::Float(x)) if !(x > 0.0 && x <= 1.0) => {
                return Err(bad(format!("is a blend weight in (0, 1], not {x}")));
            }
            _ => {}
        }
        // Turning the temporal mode on or off starts it again.
        if known == TEMPORAL && self.vars.get(TEMPORAL) != Some(&value) {
            self.history = None;
        }
        self.vars.insert(known, value);
        Ok(())
    }

    /// Checks the stage against `buffers` for a run at `size` (the size
    /// of its input buffer when `None`): every buffer set (the variance
    /// where given), existing, 2D of `Vec4`, at least of that size (the
    /// run covers the top-left of each), the output apart from the
    /// inputs.
    pub fn plan(&self, id: StageId, buffers: &[BufferRec], size: Option<(u32, u32)>) -> Result<Plan> {
        let label = self.label(id);
        let bad = |variable: &str, problem: String| {
            PostProcessError::BadStage { stage: label.clone(), variable: variable.into(), problem }.into()
        };
        let buffer = |name: &'static str| -> Result<(BufferId, &BufferRec)> {
            let b = match self.vars.get(name) {
                Some(StageValue::Buffer(b)) => *b,
                _ => {
                    let why = match name {
                        ALBEDO | NORMAL => "; the denoiser is guided by an albedo and a normal buffer",
                        POSITION => "; the temporal denoiser reprojects each pixel by its world position",
                        _ => "",
                    };
                    return Err(bad(name, format!("is not set{why}")));
                }
            };
            let rec = buffers
                .get(b.0 as usize)
                .ok_or_else(|| bad(name, format!("is buffer {}, which does not exist", b.0)))?;
            if rec.storage.as_any().downcast_ref::<Typed<Vec4>>().is_none() {
                let holds = rec.storage.layout().rust;
                return Err(bad(
                    name,
                    format!("is buffer {}, which holds `{holds}`; stages take float RGBA (`Vec4`) buffers", b.0),
                ));
            }
            Ok((b, rec))
        };
        let (input, input_rec) = buffer(INPUT)?;
        let (width, height) = size.unwrap_or((input_rec.width, input_rec.height * input_rec.depth));
        if width == 0 || height == 0 {
            return Err(bad(INPUT, format!("a stage runs over at least 1x1 pixels, not {width}x{height}")));
        }
        let has_variance = self.vars.contains_key(VARIANCE);
        let temporal = self.kind == StageKind::Denoiser && self.setting(TEMPORAL) == 1.0;
        let mut names: Vec<&'static str> = match self.kind {
            StageKind::Denoiser => vec![INPUT, ALBEDO, NORMAL],
            StageKind::Tonemapper => vec![INPUT],
        };
        names.extend(has_variance.then_some(VARIANCE));
        names.extend(temporal.then_some(POSITION));
        names.push(OUTPUT);
        let mut ids = Vec::new();
        for &name in &names {
            let (b, rec) = buffer(name)?;
            let (w, h) = (rec.width, rec.height * rec.depth);
            if w < width || h < height {
                return Err(bad(
                    name,
                    format!(
                        "is buffer {} of {w}x{h} elements, but the stage runs at {width}x{height}: its buffers must be at least that large",
                        b.0
                    ),
                ));
            }
            ids.push(b);
        }
        let output = *ids.last().expect("every stage has an output");
        if let Some(i) = ids[..ids.len() - 1].iter().position(|&b| b == output) {
            let problem = format!(
                "is buffer {}, which is also its `{}`: the output must be a buffer of its own",
                output.0, names[i]
            );
            return Err(bad(OUTPUT, problem));
        }
        let id_of = |name| names.iter().position(|n| *n == name).map(|i| ids[i]);
        let settings = self
            .kind
            .variables()
            .iter()
            .filter(|(_, sort)| matches!(sort, Sort::Number(_)))
            .map(|(n, _)| self.setting(n))
            .collect();
        let temporal = match temporal {
            true => Some(self.temporal(width, height).map_err(|(variable, problem)| bad(variable, problem))?),
            false => None,
        };
        let guides = (self.kind == StageKind::Denoiser).then(|| (ids[1], ids[2]));
        let (variance, position) = (id_of(VARIANCE), id_of(POSITION));
        Ok(Plan {
            stage: id,
            kind: self.kind,
            width,
            height,
            input,
            guides,
            variance,
            position,
            output,
            settings,
            temporal,
        })
    }

    /// The temporal denoiser's camera (every vector set) and its history
    /// where it is of the run's size; else the variable at fault.
    fn temporal(&self, width: u32, height: u32) -> std::result::Result<Temporal, (&'static str, String)> {
        let mut v = [Vec3::ZERO; 4];
        for (slot, name) in v.iter_mut().zip(CAMERA) {
            match self.vars.get(name) {
                Some(StageValue::Vector(x)) => *slot = *x,
                _ => {
                    let why = "; the temporal denoiser reprojects its history through the camera (`camera_eye`, `camera_u`, `camera_v`, `camera_w`)";
                    return Err((name, format!("is not set{why}")));
                }
            }
        }
        let [eye, u, v, w] = v;
        if u.cross(v).length_squared() == 0.0 || w.length_squared() == 0.0 {
            return Err((CAMERA[1], format!("spans no picture: u {u}, v {v}, w {w}")));
        }
        let previous = self.history.clone().filter(|h| (h.width, h.height) == (width, height));
        Ok(Temporal { camera: Pinhole { eye, u, v, w }, alpha_min: self.setting("alpha_min"), previous })
    }

    /// Number `name` as set, else its default (the kind's
    /// [`StageKind::variables`]; 0 for a name that is not a number).
    fn setting(&self, name: &str) -> f32 {
        match self.vars.get(name) {
            Some(StageValue::Float(x)) => *x,
            _ => self
                .kind
                .variables()
                .iter()
                .find_map(|(n, sort)| match sort {
                    Sort::Number(d) if *n == name => Some(*d),
                    _ => None,
                })
                .unwrap_or(0.0),
        }
    }
}

/// A planned stage's images: the input and, for the denoiser, its guides,
/// the variance and the position where given; each the pixels on the
/// host (the run's rectangle, row by row), or on the wgpu backend where
/// they are (`gpu::Source`).
pub(crate) struct Pixels<T = Vec<Vec4>> {
    pub input: T,
    pub guides: Option<(T, T)>,
    pub variance: Option<T>,
    pub position: Option<T>,
}

impl Pixels<BufferId> {
    /// The buffers `plan` reads.
    pub fn of(plan: &Plan) -> Pixels<BufferId> {
        Pixels { input: plan.input, guides: plan.guides, variance: plan.variance, position: plan.position }
    }
}

impl<T> Pixels<T> {
    /// Every image: the input, the guides, the variance, the position.
    pub fn each(&self) -> impl Iterator<Item = &T> {
        std::iter::once(&self.input)
            .chain(self.guides.iter().flat_map(|(a, n)| [a, n]))
            .chain(&self.variance)
            .chain(&self.position)
    }

    /// Each image through `f`, the first error stopping.
    pub fn try_map<U, E>(self, mut f: impl FnMut(T) -> std::result::Result<U, E>) -> std::result::Result<Pixels<U>, E> {
        let guides = match self.guides {
            Some((a, n)) => Some((f(a)?, f(n)?)),
            None => None,
        };
        let input = f(self.input)?;
        let variance = self.variance.map(&mut f).transpose()?;
        Ok(Pixels { input, guides, variance, position: self.position.map(&mut f).transpose()? })
    }
}

impl Plan {
    /// The stage's output, computed on the CPU, and the temporal
    /// denoiser's next history.
    pub fn run_cpu(&self, pixels: &Pixels) -> (Vec<Vec4>, Option<History>) {
        let (w, h) = (self.width as usize, self.height as usize);
        let Some((albedo, normal)) = &pixels.guides else {
            return (tonemap::tonemap(&pixels.input, self.settings[0], self.settings[1]), None);
        };
        let (Some(t), Some(position)) = (&self.temporal, &pixels.position) else {
            let variance = pixels.variance.as_deref();
            let images = denoise::Guided { width: w, height: h, color: &pixels.input, albedo, normal, variance };
            return (denoise::denoise(&images, self.settings[0]), None);
        };
        let frame =
            temporal::Frame { width: w, height: h, color: &pixels.input, albedo, normal, position, camera: t.camera };
        // A history still on a device is no history here: the context
        // brings it to the host first, where it can.
        let previous = t.previous.as_deref().and_then(|h| match &h.texels {
            Texels::Host(texels) => Some((&texels[..], &h.camera)),
            Texels::Device(_) => None,
        });
        let acc = temporal::accumulate(&frame, previous, t.alpha_min);
        let variance = Some(&acc.variance[..]);
        let images = denoise::Guided { width: w, height: h, color: &acc.color, albedo, normal, variance };
        let texels = Texels::Host(acc.history);
        let history = History { width: self.width, height: self.height, texels, camera: t.camera };
        (denoise::denoise(&images, self.settings[0]), Some(history))
    }
}

/// The top-left `width` x `height` of `all`, an image of rows of `stride`
/// pixels, row by row.
pub(crate) fn crop(all: &[Vec4], stride: u32, width: u32, height: u32) -> Vec<Vec4> {
    let (stride, width) = (stride as usize, width as usize);
    (0..height as usize).flat_map(|y| &all[y * stride..y * stride + width]).copied().collect()
}

/// `all`, an image of rows of `stride` pixels, with its top-left
/// `width` x `height` replaced by `rect` (row by row); the rest as it was.
pub(crate) fn merge(all: &mut [Vec4], stride: u32, (width, height): (u32, u32), rect: &[Vec4]) {
    let (stride, width) = (stride as usize, width as usize);
    for (y, row) in rect.chunks_exact(width).take(height as usize).enumerate() {
        all[y * stride..y * stride + width].copy_from_slice(row);
    }
}

/// How many of `plans` (at least one) run together on a device, each
/// reading an earlier one's output where that output lies on the device:
/// all, up to the first that reads an earlier one's output beyond the
/// earlier run's rectangle (which only the buffer on the host has, once
/// the earlier ones' outputs are merged into it).
pub(crate) fn runs_together(plans: &[Plan]) -> usize {
    let beyond = |i: usize| {
        Pixels::of(&plans[i]).each().any(|&b| {
            plans[..i]
                .iter()
                .rfind(|p| p.output == b)
                .is_some_and(|p| p.width < plans[i].width || p.height < plans[i].height)
        })
    };
    (1..plans.len()).find(|&i| beyond(i)).unwrap_or(plans.len())
}
