//! glTF node animation: the channels that move nodes (translation, rotation,
//! scale; step, linear or cubic-spline keys), read and checked, and the
//! pose they give every instance at a time ([`Rig::instance_matrices`]).
//!
//! Every animation of the file plays at once, from its own keys' times (a
//! file's animations are independent; a viewer that picks one would take
//! its channels alone). Before the first key a channel holds its first
//! value, after the last its last, as the glTF specification says. Morph
//! target weights are not played (the loader warns of morph targets).

use super::Reader;
use super::buffers::check_accessor;
use crate::error::GltfError;
use glam::{Mat4, Quat, Vec3, Vec4};
use gltf::animation::util::ReadOutputs;
use gltf::animation::{Interpolation, Property};

/// What a channel moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// The node's translation (xyz).
    Translation,
    /// The node's rotation (a unit quaternion, xyzw).
    Rotation,
    /// The node's scale (xyz).
    Scale,
}

/// One animated property of one node.
#[derive(Clone, Debug)]
pub struct Channel {
    /// The node moved, by glTF index.
    pub node: usize,
    /// Which of its properties.
    pub target: Target,
    /// Step, linear or cubic spline between keys.
    pub interpolation: Interpolation,
    /// Key times, seconds, increasing.
    pub times: Vec<f32>,
    /// One value per key (xyz, or a quaternion's xyzw); with cubic-spline
    /// keys three per key: in-tangent, value, out-tangent.
    pub values: Vec<Vec4>,
}

/// A node's local transform as the file gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Local {
    /// A matrix (no channel may move it).
    Matrix(Mat4),
    /// Translation, rotation, scale: what channels move.
    Trs(Vec3, Quat, Vec3),
}

impl Local {
    pub(super) fn of(node: &gltf::Node) -> Local {
        match node.transform() {
            gltf::scene::Transform::Matrix { matrix } => Local::Matrix(Mat4::from_cols_array_2d(&matrix)),
            gltf::scene::Transform::Decomposed { translation, rotation, scale } => {
                Local::Trs(Vec3::from_array(translation), Quat::from_array(rotation), Vec3::from_array(scale))
            }
        }
    }

    fn matrix(&self) -> Mat4 {
        match *self {
            Local::Matrix(m) => m,
            Local::Trs(t, r, s) => Mat4::from_scale_rotation_translation(s, r, t),
        }
    }
}

/// The node tree's part that instances hang from, and the channels that
/// move it: what posing a loaded file at a time needs.
#[derive(Clone, Debug, Default)]
pub struct Rig {
    /// Every node's local transform.
    pub locals: Vec<Local>,
    /// For each instance (as `Asset::instances`), its node chain from the
    /// root down to the node that shows the mesh.
    pub paths: Vec<Vec<usize>>,
    /// The animation's channels, each moving one property of one node.
    pub channels: Vec<Channel>,
}

impl Rig {
    /// Whether any channel moves a node an instance hangs from.
    pub fn is_animated(&self) -> bool {
        self.channels.iter().any(|c| self.paths.iter().any(|p| p.contains(&c.node)))
    }

    /// The first and last key times over every channel (`None` without
    /// channels).
    pub fn time_range(&self) -> Option<(f32, f32)> {
        let first = self.channels.iter().filter_map(|c| c.times.first()).copied().reduce(f32::min)?;
        let last = self.channels.iter().filter_map(|c| c.times.last()).copied().reduce(f32::max)?;
        Some((first, last))
    }

    /// Every instance's world matrix at `time` (seconds), checked: a time
    /// that is not finite (no object), or the node of an instance whose
    /// world matrix is not finite or cannot be inverted, with the problem
    /// as `GltfError` words.
    pub fn checked_matrices(&self, time: f32) -> Result<Vec<Mat4>, (Option<String>, String)> {
        if let Some(problem) = time_problem(time) {
            return Err((None, problem));
        }
        let matrices = self.instance_matrices(time);
        for (path, matrix) in self.paths.iter().zip(&matrices) {
            if let Some(problem) = super::transform_problem(matrix) {
                let node = path.last().copied().unwrap_or_default();
                return Err((Some(format!("nodes[{node}]")), format!("at {time} s, its world transform {problem}")));
            }
        }
        Ok(matrices)
    }

    /// Every instance's world matrix at `time` (seconds).
    pub fn instance_matrices(&self, time: f32) -> Vec<Mat4> {
        let mut locals = self.locals.clone();
        for c in &self.channels {
            let v = c.sample(time);
            // Channels target TRS nodes only (checked when read).
            if let Local::Trs(t, r, s) = &mut locals[c.node] {
                match c.target {
                    Target::Translation => *t = v.truncate(),
                    Target::Rotation => *r = Quat::from_vec4(v).normalize(),
                    Target::Scale => *s = v.truncate(),
                }
            }
        }
        self.paths.iter().map(|path| path.iter().fold(Mat4::IDENTITY, |world, &n| world * locals[n].matrix())).collect()
    }
}

/// Why an animation cannot be posed at `time`, if it cannot: a time that
/// is not finite.
pub fn time_problem(time: f32) -> Option<String> {
    (!time.is_finite()).then(|| format!("cannot pose the animation at time {time}: not a finite number of seconds"))
}

impl Channel {
    /// The channel's value at `time`.
    fn sample(&self, time: f32) -> Vec4 {
        let cubic = self.interpolation == Interpolation::CubicSpline;
        let value = |k: usize| if cubic { self.values[3 * k + 1] } else { self.values[k] };
        let last = self.times.len() - 1;
        // A time that is not a number poses the first key
        // (`Animation::pose` refuses it before).
        if time.is_nan() || time <= self.times[0] {
            return value(0);
        }
        if time >= self.times[last] {
            return value(last);
        }
        // The key at or before `time`: times increase (checked when read).
        let k = self.times.partition_point(|&t| t <= time) - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        let dt = t1 - t0;
        let u = (time - t0) / dt;
        match self.interpolation {
            Interpolation::Step => value(k),
            Interpolation::Linear if self.target == Target::Rotation => {
                Quat::from_vec4(value(k)).slerp(Quat::from_vec4(value(k + 1)), u).into()
            }
            Interpolation::Linear => value(k).lerp(value(k + 1), u),
            Interpolation::CubicSpline => {
                // glTF's Hermite spline: the value, then the out-tangent of
                // key k and the in-tangent of key k + 1, scaled by dt.
                let (p0, m0) = (self.values[3 * k + 1], self.values[3 * k + 2] * dt);
                let (p1, m1) = (self.values[3 * (k + 1) + 1], self.values[3 * (k + 1)] * dt);
                let (u2, u3) = (u * u, u * u * u);
                p0 * (2.0 * u3 - 3.0 * u2 + 1.0)
                    + m0 * (u3 - 2.0 * u2 + u)
                    + p1 * (-2.0 * u3 + 3.0 * u2)
                    + m1 * (u3 - u2)
            }
        }
    }
}

/// Reads every channel of every animation that moves a node (morph target
/// weights are skipped, with a warning); each accessor's range is checked
/// first, the key times must be finite and increasing, and there must be
/// as many values as the interpolation needs.
pub(super) fn read_channels(
    r: &Reader,
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    warnings: &mut Vec<String>,
) -> Result<Vec<Channel>, GltfError> {
    let mut channels = Vec::new();
    for animation in doc.animations() {
        for channel in animation.channels() {
            let object = format!("animations[{}].channels[{}]", animation.index(), channel.index());
            let target = match channel.target().property() {
                Property::Translation => Target::Translation,
                Property::Rotation => Target::Rotation,
                Property::Scale => Target::Scale,
                Property::MorphTargetWeights => {
                    warnings.push(format!("{object}: morph target weights not played"));
                    continue;
                }
            };
            let node = channel.target().node();
            if let gltf::scene::Transform::Matrix { .. } = node.transform() {
                return Err(r.error(
                    &object,
                    format!(
                        "it moves nodes[{}], which has a matrix (animated nodes take translation, rotation and scale)",
                        node.index()
                    ),
                ));
            }
            let sampler = channel.sampler();
            check_accessor(r, &format!("{object} input"), &sampler.input(), buffers)?;
            check_accessor(r, &format!("{object} output"), &sampler.output(), buffers)?;
            let reader = channel.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
            let times: Vec<f32> = reader
                .read_inputs()
                .ok_or_else(|| r.error(&object, "its sampler's input has no data".into()))?
                .collect();
            if times.is_empty() {
                return Err(r.error(&object, "its sampler has no keys".into()));
            }
            if let Some(bad) = times.iter().position(|t| !t.is_finite()) {
                return Err(r.error(&object, format!("key {bad} has time {}, which is not finite", times[bad])));
            }
            if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
                return Err(r.error(
                    &object,
                    format!("key times must increase: key {} at {} follows {}", k + 1, times[k + 1], times[k]),
                ));
            }
            let values: Vec<Vec4> = match reader.read_outputs() {
                Some(ReadOutputs::Translations(v)) | Some(ReadOutputs::Scales(v)) => {
                    v.map(|v| Vec3::from_array(v).extend(0.0)).collect()
                }
                Some(ReadOutputs::Rotations(v)) => v.into_f32().map(Vec4::from_array).collect(),
                _ => return Err(r.error(&object, "its sampler's output does not match its target".into())),
            };
            let interpolation = sampler.interpolation();
            let per_key = if interpolation == Interpolation::CubicSpline { 3 } else { 1 };
            if values.len() != times.len() * per_key {
                return Err(r.error(
                    &object,
                    format!(
                        "{} output values for {} keys; {:?} interpolation needs {}",
                        values.len(),
                        times.len(),
                        interpolation,
                        times.len() * per_key
                    ),
                ));
            }
            if let Some(bad) = values.iter().position(|v| !v.is_finite()) {
                return Err(r.error(&object, format!("output value {bad} is not finite: {:?}", values[bad])));
            }
            channels.push(Channel { node: node.index(), target, interpolation, times, values });
        }
    }
    Ok(channels)
}
