//! # Scenes users already have
//!
//! [`load`] reads a glTF 2.0 file (`.gltf`, with external or embedded
//! buffers, or `.glb`) or an OBJ with its `.mtl` files into a context's
//! scene graph and returns the graph's top node, its materials and what it
//! found ([`SceneInfo`]: counts, world bounds, the file's camera and
//! lights, warnings for what it ignored). Add your own programs to the
//! materials and launch (README.md, packaged with this crate, opens with
//! such programs; [rt-runtime's first program](rt_runtime#a-first-program)
//! renders them on the CPU backend):
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let mut ctx = rt_runtime::Context::new();
//! let scene = rt_scene::load(&mut ctx, std::path::Path::new("model.glb"))?;
//! for m in &scene.materials {
//!     // ctx.set_closest_hit_program(m.id, 0, my_shader)?;
//!     println!("{}: base colour {}", m.info.name, m.info.base_color);
//! }
//! ctx.set_var(rt_runtime::Scope::Context, "top_object", scene.top)?;
//! println!("{} triangles in {:?}..{:?}", scene.info.triangles, scene.info.min, scene.info.max);
//! # Ok(()) }
//! ```
//!
//! ## The graph
//! Each mesh is one geometry and one BVH, instanced by a `Transform` per
//! node that shows it, all under one top `Group` ([`build`]): two levels,
//! whatever the file's hierarchy.
//!
//! ## Materials as variables
//! Every material carries the same variables, so one set of programs reads
//! any loaded scene (OBJ materials fill them from `Kd` and `Ke`):
//!
//! | variable | type | glTF |
//! | --- | --- | --- |
//! | `base_color` | `Vec3` | `pbrMetallicRoughness.baseColorFactor` (rgb) |
//! | `base_color_texture` | `Sampler2d` | `baseColorTexture` in linear RGB, or 1x1 white |
//! | `metallic` | `f32` | `metallicFactor` |
//! | `roughness` | `f32` | `roughnessFactor` |
//! | `emissive` | `Vec3` | `emissiveFactor` |
//!
//! Triangles report `texcoord` (set 0) to hit programs that declare it.
//!
//! ## Errors
//! Bad input is a [`SceneError`] naming the file and, for glTF, the object
//! (`meshes[2].primitives[0]`) and the problem; nothing here panics on a
//! file's contents. glTF documents are checked whole before the `gltf`
//! crate reads them (`gltf/validate/`). Should a panic escape anyway, [`load`]
//! catches it at its boundary as [`SceneError::Internal`] naming the file,
//! and the panic hook stays silent for it (`guard.rs`), so the error is the
//! one line a user sees.
//!
//! ## Limits
//! Files come from strangers: [`LoadLimits`] bounds what loading may read
//! and allocate (file, buffer and texture bytes, texture pixels from the
//! image header before decoding, triangles, instances, nodes) and which
//! folders URIs and `mtllib`s may name ([`load_with`]; [`load`] uses the
//! defaults).
//!
//! ## Why a crate of its own
//! Loading pulls in file-format crates (`gltf`, `tobj`) that the runtime
//! does not need to trace rays; keeping them out of `rt-runtime` keeps its
//! build, its API and its review surface about ray tracing. The binaries,
//! examples and benchmarks depend on this crate; a user who builds scenes
//! by hand never compiles it.

#![warn(missing_docs)]

pub mod build;
pub mod clip;
pub mod error;
pub mod flat;
pub mod glb;
pub mod gltf;
mod guard;
pub mod limits;
pub mod mtl;
pub mod obj;

pub use error::{GltfError, SceneError};
pub use flat::{flatten, load_flat, load_flat_at, load_flat_with};
pub use limits::LoadLimits;

use glam::{Vec3, Vec4};
use rt_runtime::{Context, MaterialId, NodeId};
use std::path::Path;

/// A scene added to a context.
#[derive(Debug)]
pub struct Loaded {
    /// The graph's top node (set it as `top_object`).
    pub top: NodeId,
    /// The materials made, each with the variables of the table above.
    pub materials: Vec<Material>,
    /// What the file holds: counts, bounds, camera, lights, warnings.
    pub info: SceneInfo,
    /// The file's node animation, bound to the transforms it moves (glTF
    /// files with animations of the nodes meshes hang from).
    pub animation: Option<Animation>,
}

/// A loaded scene's node animation: every instance under an animated node
/// has a `Transform` of its own, which [`Animation::pose`] sets for a time.
#[derive(Clone, Debug)]
pub struct Animation {
    rig: gltf::Rig,
    /// Per instance, the transform the animation moves (`None`: it does not
    /// move).
    transforms: Vec<Option<NodeId>>,
    /// The first key time, seconds.
    pub start: f32,
    /// The last key time, seconds.
    pub end: f32,
    file: String,
}

impl Animation {
    /// Sets every moved instance's transform to its pose at `time`
    /// (seconds; before the first key and after the last the poses hold).
    /// A pose the context refuses (a key that scales to zero: a singular
    /// matrix) is an error naming the file.
    /// A time that is not finite, or a pose whose matrix cannot be
    /// inverted, is a [`SceneError::Gltf`] naming the file and the node.
    pub fn pose(&self, ctx: &mut Context, time: f32) -> Result<(), SceneError> {
        let matrices = self
            .rig
            .checked_matrices(time)
            .map_err(|(object, problem)| SceneError::Gltf(GltfError { file: self.file.clone(), object, problem }))?;
        for (matrix, node) in matrices.into_iter().zip(&self.transforms) {
            if let Some(node) = node {
                ctx.set_transform(*node, matrix).map_err(|e| SceneError::Runtime {
                    file: format!("{} at {time} s", self.file),
                    error: Box::new(e),
                })?;
            }
        }
        Ok(())
    }

    /// The world matrix of every instance at `time`, as [`Animation::pose`]
    /// sets them (for tests and other uses of the poses).
    pub fn instance_matrices(&self, time: f32) -> Vec<glam::Mat4> {
        self.rig.instance_matrices(time)
    }
}

/// One material of a loaded scene: its context handle and what it was made
/// from.
#[derive(Clone, Debug)]
pub struct Material {
    /// The context's material, carrying the variables of the table above.
    pub id: MaterialId,
    /// What the file says the material is.
    pub info: MaterialInfo,
}

/// A material as a file describes it.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialInfo {
    /// The file's name for it (a glTF material without one: its JSON path,
    /// `materials[3]`).
    pub name: String,
    /// Linear RGBA.
    pub base_color: Vec4,
    /// The base colour's texture, decoded, if the material has one.
    pub base_color_texture: Option<Texture>,
    /// Metalness, 0 to 1 (glTF's `metallicFactor`).
    pub metallic: f32,
    /// Perceptual roughness, 0 to 1 (glTF's `roughnessFactor`).
    pub roughness: f32,
    /// Emitted linear RGB (glTF's `emissiveFactor`, OBJ's `Ke`).
    pub emissive: Vec3,
}

/// A decoded texture: linear RGBA texels, row 0 the image's top row (glTF's
/// texture coordinate (0, 0)).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Texels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// `width * height` texels, row by row from the top.
    pub texels: Vec<Vec4>,
}

/// What a loaded file holds.
#[derive(Clone, Debug)]
pub struct SceneInfo {
    /// Distinct meshes (geometries and BVHs built).
    pub meshes: usize,
    /// Nodes that show a mesh.
    pub instances: usize,
    /// Triangles as seen, counting each instance.
    pub triangles: usize,
    /// Triangles stored, counting each mesh once.
    pub unique_triangles: usize,
    /// World-space bounds of everything shown: the lowest corner.
    pub min: Vec3,
    /// World-space bounds of everything shown: the highest corner.
    pub max: Vec3,
    /// The file's first perspective camera.
    pub camera: Option<SceneCamera>,
    /// `KHR_lights_punctual` lights, in world space.
    pub lights: Vec<Light>,
    /// What the file has that was ignored, one line each.
    pub warnings: Vec<String>,
}

/// A file's perspective camera, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneCamera {
    /// Where the camera is.
    pub eye: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// Unit up direction, perpendicular to `forward`.
    pub up: Vec3,
    /// Vertical field of view, degrees.
    pub vfov_degrees: f32,
    /// The aspect ratio the file asks for, if any.
    pub aspect: Option<f32>,
}

/// A punctual light, in world space.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// The file's name for it, else its JSON path (`lights[0]`).
    pub name: String,
    /// Directional, point or spot.
    pub kind: LightKind,
    /// Linear RGB.
    pub color: Vec3,
    /// Candela (point, spot) or lux (directional).
    pub intensity: f32,
    /// The distance beyond which the light is meant to be ignored, if the
    /// file sets one.
    pub range: Option<f32>,
    /// Where the light is (point, spot).
    pub position: Vec3,
    /// Unit direction the light shines (directional, spot).
    pub direction: Vec3,
}

/// The kinds of `KHR_lights_punctual` light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Parallel light from infinitely far, along [`Light::direction`].
    Directional,
    /// Light from [`Light::position`] in every direction.
    Point,
    /// A cone of light from [`Light::position`] along [`Light::direction`].
    Spot {
        /// Full intensity inside this angle from the axis, radians.
        inner_cone_angle: f32,
        /// No light outside this angle from the axis, radians.
        outer_cone_angle: f32,
    },
}

/// Which loader a file needs, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ (`.obj`), with its `.mtl` files.
    Obj,
    /// glTF 2.0: `.gltf` (JSON) or `.glb` (binary).
    Gltf,
}

impl Format {
    /// `.obj`, `.gltf` or `.glb` (any case).
    pub fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Some(Format::Obj),
            "gltf" | "glb" => Some(Format::Gltf),
            _ => None,
        }
    }
}

/// Loads the scene at `path` into `ctx`, by its extension, within the
/// default [`LoadLimits`].
pub fn load(ctx: &mut Context, path: &Path) -> Result<Loaded, SceneError> {
    load_with(ctx, path, &LoadLimits::default())
}

/// [`load`] within `limits`. A panic while loading (a bug, here or in a
/// format crate) is caught and returned as [`SceneError::Internal`]; what
/// it had added to `ctx` stays there, unreferenced.
pub fn load_with(ctx: &mut Context, path: &Path, limits: &LoadLimits) -> Result<Loaded, SceneError> {
    let file = path.display().to_string();
    guard::guarded(path, || match Format::of(path) {
        Some(Format::Obj) => build::build_obj(ctx, obj::load_obj_with(path, limits)?, &file),
        Some(Format::Gltf) => build::build_gltf(ctx, gltf::read_with(path, limits)?, &file),
        None => Err(SceneError::UnknownFormat { file: file.clone() }),
    })
}
