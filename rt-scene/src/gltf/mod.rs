//! glTF 2.0 (`.gltf` with external or embedded buffers, and `.glb`) read
//! into an [`Asset`]: plain data, no context yet ([`crate::build`] makes
//! the graph of it).
//!
//! What is read: the default scene's node hierarchy (or the first scene's,
//! or every root node's when there are no scenes), each node's world matrix
//! (parent times local, TRS or matrix); every mesh a node uses, once, with
//! its primitives (`mesh`); materials' base colour factor and texture,
//! metallic and roughness factors and emissive factor; the first
//! perspective camera met in the hierarchy; `KHR_lights_punctual` lights.
//! Node animations ([`animation`]) are read into [`Asset::rig`], so a
//! loaded scene can be posed at any time.
//! What is ignored is listed in [`Asset::warnings`]: skins, morph targets
//! (and their weights' animation), animated cameras and lights,
//! orthographic cameras, texture sets other than 0, textures in formats
//! this build does not decode (only PNG is enabled).
//!
//! Problems are [`GltfError`]s naming the file and the object, never
//! panics: the GLB header and every accessor's byte range are checked
//! (`buffers`) before the `gltf` crate reads anything.

pub mod animation;
pub(crate) mod buffers;
mod mesh;
mod texture;
mod validate;

pub use animation::Rig;
pub use mesh::MeshData;

use crate::clip::clip_quoted;
use crate::error::GltfError;
use crate::limits::LoadLimits;
use crate::{Light, LightKind, MaterialInfo, SceneCamera};
use glam::{Mat4, Vec3, Vec4};
use std::path::Path;

/// What a glTF file holds, read and checked.
#[derive(Clone, Debug)]
pub struct Asset {
    /// Each mesh some node uses, once.
    pub meshes: Vec<MeshData>,
    /// Each node that shows a mesh: the index into `meshes` and the node's
    /// world matrix.
    pub instances: Vec<(usize, Mat4)>,
    /// The document's materials, by glTF index.
    pub materials: Vec<MaterialInfo>,
    /// The first node with a perspective camera, in world space.
    pub camera: Option<SceneCamera>,
    /// The `KHR_lights_punctual` lights nodes hold, in world space.
    pub lights: Vec<Light>,
    /// The nodes the instances hang from and the animations that move
    /// them.
    pub rig: Rig,
    /// What was in the file but is not used, one line each.
    pub warnings: Vec<String>,
}

/// Names the file in errors, and keeps the limits and what counts
/// against them.
pub(crate) struct Reader {
    file: String,
    pub(crate) limits: LoadLimits,
    /// Texture pixels decoded so far.
    texture_pixels: std::cell::Cell<u64>,
}

impl Reader {
    pub(crate) fn error(&self, object: &str, problem: String) -> GltfError {
        GltfError { file: self.file.clone(), object: Some(object.to_string()), problem }
    }

    pub(crate) fn file_error(&self, problem: String) -> GltfError {
        GltfError { file: self.file.clone(), object: None, problem }
    }

    fn new(file: String, limits: &LoadLimits) -> Reader {
        Reader { file, limits: limits.clone(), texture_pixels: Default::default() }
    }

    /// `count` of `what` within limit `name`, or an error naming `object`.
    pub(crate) fn within(
        &self,
        object: Option<&str>,
        what: &str,
        count: u64,
        limit: u64,
        name: &str,
    ) -> Result<(), GltfError> {
        match (crate::limits::over(what, count, limit, name), object) {
            (None, _) => Ok(()),
            (Some(problem), Some(object)) => Err(self.error(object, problem)),
            (Some(problem), None) => Err(self.file_error(problem)),
        }
    }
}

/// Deeper node hierarchies are refused (the `gltf` crate does not check
/// for cycles).
const MAX_DEPTH: usize = 256;

/// Reads the glTF or GLB file at `path` (buffers and images relative to
/// it) within the default [`LoadLimits`].
pub fn read(path: &Path) -> Result<Asset, GltfError> {
    read_with(path, &LoadLimits::default())
}

/// [`read`] within `limits`.
pub fn read_with(path: &Path, limits: &LoadLimits) -> Result<Asset, GltfError> {
    let r = Reader::new(path.display().to_string(), limits);
    let bytes =
        crate::limits::read_file(path, limits).map_err(|why| r.file_error(format!("cannot read the file: {why}")))?;
    read_bytes(&r, &bytes, path.parent())
}

/// Reads glTF or GLB bytes; `file` names them in errors, relative URIs are
/// looked up in `dir` (within the default [`LoadLimits`]).
pub fn parse(bytes: &[u8], file: &str, dir: Option<&Path>) -> Result<Asset, GltfError> {
    parse_with(bytes, file, dir, &LoadLimits::default())
}

/// [`parse`] within `limits`.
pub fn parse_with(bytes: &[u8], file: &str, dir: Option<&Path>, limits: &LoadLimits) -> Result<Asset, GltfError> {
    read_bytes(&Reader::new(file.to_string(), limits), bytes, dir)
}

fn read_bytes(r: &Reader, bytes: &[u8], dir: Option<&Path>) -> Result<Asset, GltfError> {
    if bytes.starts_with(b"glTF") {
        buffers::check_glb_header(r, bytes)?;
    }
    let gltf = gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| document_error(r, e))?;
    let json = gltf.document.into_json();
    validate::check(r, &json)?;
    r.within(None, "the count of nodes", json.nodes.len() as u64, r.limits.max_nodes, "max_nodes")?;
    let doc = gltf::Document::from_json(json).map_err(|e| document_error(r, e))?;
    let buffers = buffers::load_buffers(r, &doc, gltf.blob, dir)?;
    let doc = &doc;
    let mut asset = Asset {
        meshes: Vec::new(),
        instances: Vec::new(),
        materials: Vec::new(),
        camera: None,
        lights: Vec::new(),
        rig: Rig { locals: doc.nodes().map(|n| animation::Local::of(&n)).collect(), ..Rig::default() },
        warnings: Vec::new(),
    };
    for material in doc.materials() {
        asset.materials.push(read_material(r, &material, &buffers, dir, &mut asset.warnings)?);
    }
    let roots: Vec<gltf::Node> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let children: std::collections::HashSet<usize> =
                doc.nodes().flat_map(|n| n.children().map(|c| c.index()).collect::<Vec<_>>()).collect();
            doc.nodes().filter(|n| !children.contains(&n.index())).collect()
        }
    };
    let mut mesh_slot = vec![None; doc.meshes().len()];
    let mut stack: Vec<(gltf::Node, Mat4, Vec<usize>)> =
        roots.into_iter().rev().map(|n| (n, Mat4::IDENTITY, Vec::new())).collect();
    let (mut visited, mut triangles) = (0u64, 0u64);
    while let Some((node, parent, mut path)) = stack.pop() {
        visited += 1;
        r.within(None, "the count of nodes visited", visited, r.limits.max_nodes, "max_nodes")?;
        let depth = path.len();
        path.push(node.index());
        let object = format!("nodes[{}]", node.index());
        if depth > MAX_DEPTH {
            return Err(r.error(&object, format!("the node hierarchy is deeper than {MAX_DEPTH} (a cycle?)")));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if !world.is_finite() {
            return Err(r.error(&object, "its transform is not finite".into()));
        }
        if let Some(mesh) = node.mesh() {
            let slot = match mesh_slot[mesh.index()] {
                Some(s) => s,
                None => {
                    asset.meshes.push(mesh::read_mesh(r, &mesh, &buffers)?);
                    if mesh.primitives().any(|p| p.morph_targets().next().is_some()) {
                        asset.warnings.push(format!("meshes[{}]: morph targets ignored", mesh.index()));
                    }
                    mesh_slot[mesh.index()] = Some(asset.meshes.len() - 1);
                    asset.meshes.len() - 1
                }
            };
            if let Some(problem) = transform_problem(&world) {
                return Err(r.error(&object, format!("its world transform {problem}")));
            }
            let positions = &asset.meshes[slot].mesh.positions;
            if let Some(p) = positions.iter().find(|p| !world.transform_point3(**p).is_finite()) {
                return Err(r.error(
                    &object,
                    format!("meshes[{}] has vertex {p}, which its transform moves out of f32's range", mesh.index()),
                ));
            }
            asset.instances.push((slot, world));
            let limits = &r.limits;
            r.within(
                Some(&object),
                "the count of instances",
                asset.instances.len() as u64,
                limits.max_instances,
                "max_instances",
            )?;
            triangles += asset.meshes[slot].mesh.indices.len() as u64;
            r.within(Some(&object), "the count of triangles shown", triangles, limits.max_triangles, "max_triangles")?;
            asset.rig.paths.push(path.clone());
        }
        if node.skin().is_some() {
            asset.warnings.push(format!("{object}: skin ignored (the mesh is shown in its bind pose)"));
        }
        if let Some(camera) = node.camera() {
            read_camera(&object, &camera, world, &mut asset);
        }
        if let Some(light) = node.light() {
            asset.lights.push(read_light(&light, world));
        }
        for child in node.children().collect::<Vec<_>>().into_iter().rev() {
            stack.push((child, world, path.clone()));
        }
    }
    asset.rig.channels = animation::read_channels(r, doc, &buffers, &mut asset.warnings)?;
    let unshown: std::collections::BTreeSet<usize> = (asset.rig.channels.iter())
        .map(|c| c.node)
        .filter(|n| !asset.rig.paths.iter().any(|p| p.contains(n)))
        .collect();
    for node in unshown {
        asset.warnings.push(format!(
            "nodes[{node}]: animated, but no shown mesh hangs from it (cameras and lights are not animated)"
        ));
    }
    if asset.instances.is_empty() {
        return Err(r.file_error("the scene shows no meshes".into()));
    }
    Ok(asset)
}

/// Why `m` cannot place an instance (the runtime inverts it to trace
/// rays), or `None`.
pub(crate) fn transform_problem(m: &Mat4) -> Option<String> {
    let det = m.determinant();
    if !m.is_finite() || !det.is_finite() {
        return Some("is not finite".into());
    }
    if det.abs() < 1e-12 || !m.inverse().is_finite() {
        return Some(format!("is singular (determinant {det:e}): a scale of zero?"));
    }
    None
}

/// The `gltf` crate's refusal, as one line naming the object when it can.
fn document_error(r: &Reader, e: gltf::Error) -> GltfError {
    match e {
        gltf::Error::Validation(errors) => {
            let (path, why) = &errors[0];
            let more =
                if errors.len() > 1 { format!(" (and {} more problems)", errors.len() - 1) } else { String::new() };
            r.error(&path.to_string(), format!("{why}{more}"))
        }
        gltf::Error::Binary(e) => r.file_error(format!("not a valid GLB file: {e}")),
        gltf::Error::Deserialize(e) => r.file_error(format!("not valid glTF JSON: {}", clip_quoted(&e.to_string()))),
        other => r.file_error(other.to_string()),
    }
}

fn read_material(
    r: &Reader,
    material: &gltf::Material,
    buffers: &[Vec<u8>],
    dir: Option<&Path>,
    warnings: &mut Vec<String>,
) -> Result<MaterialInfo, GltfError> {
    let index = material.index().expect("document materials have indices");
    let pbr = material.pbr_metallic_roughness();
    let object = format!("materials[{index}]");
    let base_color_texture = match pbr.base_color_texture() {
        None => None,
        Some(info) => {
            if info.tex_coord() != 0 {
                warnings.push(format!("{object}: base colour texture uses TEXCOORD_{}; ignored", info.tex_coord()));
                None
            } else {
                texture::read_texture(r, &object, &info.texture(), buffers, dir, warnings)?
            }
        }
    };
    Ok(MaterialInfo {
        name: material.name().map_or_else(|| object.clone(), str::to_string),
        base_color: Vec4::from_array(pbr.base_color_factor()),
        base_color_texture,
        metallic: pbr.metallic_factor(),
        roughness: pbr.roughness_factor(),
        emissive: Vec3::from_array(material.emissive_factor()),
    })
}

fn read_camera(object: &str, camera: &gltf::Camera, world: Mat4, asset: &mut Asset) {
    let gltf::camera::Projection::Perspective(p) = camera.projection() else {
        asset.warnings.push(format!("{object}: orthographic cameras[{}] ignored", camera.index()));
        return;
    };
    if asset.camera.is_some() {
        asset.warnings.push(format!("{object}: cameras[{}] ignored (the first camera is used)", camera.index()));
        return;
    }
    let eye = world.transform_point3(Vec3::ZERO);
    let forward = world.transform_vector3(-Vec3::Z).normalize_or(-Vec3::Z);
    let up = world.transform_vector3(Vec3::Y).normalize_or(Vec3::Y);
    asset.camera =
        Some(SceneCamera { eye, forward, up, vfov_degrees: p.yfov().to_degrees(), aspect: p.aspect_ratio() });
}

fn read_light(light: &gltf::khr_lights_punctual::Light, world: Mat4) -> Light {
    use gltf::khr_lights_punctual::Kind;
    let kind = match light.kind() {
        Kind::Directional => LightKind::Directional,
        Kind::Point => LightKind::Point,
        Kind::Spot { inner_cone_angle, outer_cone_angle } => LightKind::Spot { inner_cone_angle, outer_cone_angle },
    };
    Light {
        name: light.name().map_or_else(|| format!("lights[{}]", light.index()), str::to_string),
        kind,
        color: Vec3::from_array(light.color()),
        intensity: light.intensity(),
        range: light.range(),
        position: world.transform_point3(Vec3::ZERO),
        direction: world.transform_vector3(-Vec3::Z).normalize_or(-Vec3::Z),
    }
}
