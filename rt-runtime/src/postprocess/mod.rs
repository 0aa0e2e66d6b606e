//! Post-processing stages: OptiX 6's `RTpostprocessingstage`, the built-in
//! image passes a renderer runs after its launches (a denoiser and a
//! tonemapper), configured by named variables as OptiX configures them.
//!
//! A stage is created by kind ([`StageKind`]) or by OptiX's built-in
//! name (`DLDenoiser`, `TonemapperSimple`) and set up with
//! [`Context::set_stage_var`](crate::Context::set_stage_var): buffers
//! (`input_buffer`, `input_albedo_buffer`, `input_normal_buffer`, the
//! optional `input_variance_buffer`, `output_buffer`) and settings
//! (`blend`, `exposure`, `gamma`). Every image buffer holds one `Vec4` a
//! pixel, RGBA (a normal's xyz, an albedo's rgb, a variance in x), 2D and
//! of the stage's size. `Stage::plan` checks all
//! of it before anything runs, naming the stage and the variable at
//! fault; a command list's finalize runs the same check
//! ([`crate::command_list`]).
//!
//! The passes: [`denoise`] (an edge-avoiding à-trous wavelet filter
//! guided by albedo, normal and a luminance variance, the renderer's
//! per-pixel one or its own spatial estimate: the spatial part of SVGF) and [`tonemap`] (exposure, ACES-fitted filmic
//! curve, gamma), each a CPU reference here and a WGSL compute pass in
//! `gpu.rs` that the wgpu backend runs on its device.

pub mod denoise;
pub(crate) mod gpu;
pub mod tonemap;

use crate::buffer::{BufferRec, Typed};
use crate::error::{PostProcessError, Result};
use crate::scene::BufferId;
use glam::Vec4;
use std::collections::BTreeMap;

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

    /// The variables a stage of this kind takes: name, whether it is a
    /// buffer, and a setting's default (`None` for buffers). Every buffer
    /// must be set but the denoiser's `input_variance_buffer`.
    pub fn variables(self) -> &'static [(&'static str, Option<f32>)] {
        match self {
            StageKind::Denoiser => {
                &[(INPUT, None), (ALBEDO, None), (NORMAL, None), (VARIANCE, None), (OUTPUT, None), ("blend", Some(0.0))]
            }
            StageKind::Tonemapper => &[(INPUT, None), (OUTPUT, None), ("exposure", Some(1.0)), ("gamma", Some(2.2))],
        }
    }
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

/// A stage variable's value: a buffer or a number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StageValue {
    /// A buffer (`input_buffer`, `output_buffer`, ...).
    Buffer(BufferId),
    /// A setting (`blend`, `exposure`, `gamma`).
    Float(f32),
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

/// A stage: its kind and the variables set on it.
#[derive(Clone, Debug)]
pub(crate) struct Stage {
    pub kind: StageKind,
    pub vars: BTreeMap<&'static str, StageValue>,
}

/// A stage checked against the context's buffers, ready to run at
/// `width` x `height`: its buffers (input, guides, output) and settings.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Plan {
    pub kind: StageKind,
    pub width: u32,
    pub height: u32,
    pub input: BufferId,
    /// The denoiser's albedo and normal guides.
    pub guides: Option<(BufferId, BufferId)>,
    /// The denoiser's per-pixel variance, where set.
    pub variance: Option<BufferId>,
    pub output: BufferId,
    /// `blend` for the denoiser; `exposure` and `gamma` for the tonemapper.
    pub settings: Vec<f32>,
}

impl Stage {
    pub fn new(kind: StageKind) -> Stage {
        Stage { kind, vars: BTreeMap::new() }
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
        let Some(&(known, default)) = self.kind.variables().iter().find(|(n, _)| *n == name) else {
            let names: Vec<_> = self.kind.variables().iter().map(|(n, _)| *n).collect();
            return Err(bad(format!("is not a variable of the {}; it has {}", self.kind.name(), names.join(", "))));
        };
        match (default, value) {
            (None, StageValue::Float(x)) => return Err(bad(format!("is a buffer, but was given the number {x}"))),
            (Some(_), StageValue::Buffer(b)) => {
                return Err(bad(format!("is a number, but was given buffer {}", b.0)));
            }
            (Some(_), StageValue::Float(x)) if !x.is_finite() => return Err(bad(format!("must be finite, not {x}"))),
            _ => {}
        }
        self.vars.insert(known, value);
        Ok(())
    }

    /// Checks the stage against `buffers` for a run at `size` (the size
    /// of its input buffer when `None`): every buffer set (the variance
    /// where given), existing, 2D of `Vec4`, of that size, the output
    /// apart from the inputs.
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
        let names: &[&'static str] = match self.kind {
            StageKind::Denoiser if has_variance => &[INPUT, ALBEDO, NORMAL, VARIANCE, OUTPUT],
            StageKind::Denoiser => &[INPUT, ALBEDO, NORMAL, OUTPUT],
            StageKind::Tonemapper => &[INPUT, OUTPUT],
        };
        let mut ids = Vec::new();
        for &name in names {
            let (b, rec) = buffer(name)?;
            if (rec.width, rec.height * rec.depth) != (width, height) {
                let (w, h) = (rec.width, rec.height * rec.depth);
                return Err(bad(
                    name,
                    format!("is buffer {} of {w}x{h} elements, but the stage runs at {width}x{height}", b.0),
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
        let settings = self.kind.variables().iter().filter_map(|(n, d)| d.map(|d| self.setting(n, d))).collect();
        let guides = (self.kind == StageKind::Denoiser).then(|| (ids[1], ids[2]));
        let variance = (self.kind == StageKind::Denoiser && has_variance).then(|| ids[3]);
        Ok(Plan { kind: self.kind, width, height, input, guides, variance, output, settings })
    }

    fn setting(&self, name: &str, default: f32) -> f32 {
        match self.vars.get(name) {
            Some(StageValue::Float(x)) => *x,
            _ => default,
        }
    }
}

/// A planned stage's images: the input and, for the denoiser, its guides
/// and the variance where given; each the pixels on the host, or on the
/// wgpu backend where they are (`gpu::Source`).
pub(crate) struct Pixels<T = Vec<Vec4>> {
    pub input: T,
    pub guides: Option<(T, T)>,
    pub variance: Option<T>,
}

impl<T> Pixels<T> {
    /// Every image: the input, the guides, the variance.
    pub fn each(&self) -> impl Iterator<Item = &T> {
        std::iter::once(&self.input).chain(self.guides.iter().flat_map(|(a, n)| [a, n])).chain(&self.variance)
    }

    /// Each image through `f`, the first error stopping.
    pub fn try_map<U, E>(self, mut f: impl FnMut(T) -> std::result::Result<U, E>) -> std::result::Result<Pixels<U>, E> {
        let guides = match self.guides {
            Some((a, n)) => Some((f(a)?, f(n)?)),
            None => None,
        };
        Ok(Pixels { input: f(self.input)?, guides, variance: self.variance.map(&mut f).transpose()? })
    }
}

impl Plan {
    /// The stage's output, computed on the CPU.
    pub fn run_cpu(&self, pixels: &Pixels) -> Vec<Vec4> {
        let (w, h) = (self.width as usize, self.height as usize);
        match (&self.kind, &pixels.guides) {
            (StageKind::Denoiser, Some((albedo, normal))) => {
                let variance = pixels.variance.as_deref();
                let images = denoise::Guided { width: w, height: h, color: &pixels.input, albedo, normal, variance };
                denoise::denoise(&images, self.settings[0])
            }
            _ => tonemap::tonemap(&pixels.input, self.settings[0], self.settings[1]),
        }
    }
}
