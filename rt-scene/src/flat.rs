//! A scene as one world-space mesh: every instance's triangles
//! transformed and concatenated, for code that takes an OBJ-style
//! [`obj::LoadedMesh`] (the viewer, `obj2glb`), posed at a time of the
//! file's node animation if asked.

use crate::{Format, GltfError, LoadLimits, MaterialInfo, SceneCamera, SceneError, gltf, guard, obj};
use glam::Vec3;
use std::path::Path;

/// Loads the scene at `path` as one mesh in world space (every instance's
/// triangles transformed and concatenated, material indices into one
/// list): for code that takes an OBJ-style [`obj::LoadedMesh`].
pub fn load_flat(path: &Path) -> Result<(obj::LoadedMesh, Option<SceneCamera>), SceneError> {
    load_flat_with(path, &LoadLimits::default())
}

/// [`load_flat`] within `limits`.
pub fn load_flat_with(path: &Path, limits: &LoadLimits) -> Result<(obj::LoadedMesh, Option<SceneCamera>), SceneError> {
    load_flat_posed(path, limits, None)
}

/// [`load_flat_with`] with the file's node animation posed at `time`
/// (seconds; before the first key and after the last the poses hold), as
/// [`crate::Animation::pose`] poses a loaded scene. A time that is not
/// finite, a file without a node animation (an OBJ, a glTF file whose
/// animations move no node a mesh hangs from), and a pose whose matrix
/// cannot be inverted or moves a vertex out of f32's range are errors
/// naming the file.
pub fn load_flat_at(
    path: &Path,
    limits: &LoadLimits,
    time: f32,
) -> Result<(obj::LoadedMesh, Option<SceneCamera>), SceneError> {
    load_flat_posed(path, limits, Some(time))
}

fn load_flat_posed(
    path: &Path,
    limits: &LoadLimits,
    time: Option<f32>,
) -> Result<(obj::LoadedMesh, Option<SceneCamera>), SceneError> {
    let file = path.display().to_string();
    let bad =
        |object: Option<String>, problem: String| SceneError::Gltf(GltfError { file: file.clone(), object, problem });
    // A time that is not finite is refused before the file is read (an
    // OBJ's too), as `Animation::pose` refuses it.
    if let Some(problem) = time.and_then(gltf::animation::time_problem) {
        return Err(bad(None, problem));
    }
    let no_animation = || bad(None, "has no node animation to pose".into());
    guard::guarded(path, || match Format::of(path) {
        Some(Format::Obj) if time.is_some() => Err(no_animation()),
        Some(Format::Obj) => Ok((obj::load_obj_with(path, limits)?, None)),
        Some(Format::Gltf) => {
            let mut asset = gltf::read_with(path, limits)?;
            if let Some(time) = time {
                if !asset.rig.is_animated() {
                    return Err(no_animation());
                }
                let matrices = asset.rig.checked_matrices(time).map_err(|(object, problem)| bad(object, problem))?;
                pose(&mut asset, matrices, time).map_err(|(object, problem)| bad(Some(object), problem))?;
            }
            let camera = asset.camera;
            Ok((flatten(asset), camera))
        }
        None => Err(SceneError::UnknownFormat { file: file.clone() }),
    })
}

/// Every instance of `asset` moved to its world matrix at `time`
/// (`matrices`, checked), or the node whose pose moves a vertex out of
/// f32's range.
fn pose(asset: &mut gltf::Asset, matrices: Vec<glam::Mat4>, time: f32) -> Result<(), (String, String)> {
    for (i, (instance, matrix)) in asset.instances.iter_mut().zip(matrices).enumerate() {
        let positions = &asset.meshes[instance.0].mesh.positions;
        if let Some(p) = positions.iter().find(|p| !matrix.transform_point3(**p).is_finite()) {
            let node = asset.rig.paths[i].last().copied().unwrap_or_default();
            return Err((
                format!("nodes[{node}]"),
                format!("at {time} s, its transform moves vertex {p} out of f32's range"),
            ));
        }
        instance.1 = matrix;
    }
    Ok(())
}

/// `asset`'s instances baked into one world-space mesh.
pub fn flatten(asset: gltf::Asset) -> obj::LoadedMesh {
    use rt_runtime::TriangleMesh;
    let mut mesh = TriangleMesh { normals: Some(Vec::new()), material_indices: Some(Vec::new()), ..Default::default() };
    let mut materials: Vec<obj::MeshMaterial> = Vec::new();
    let mut slot_of: Vec<Option<usize>> = Vec::new();
    let mut default_slot = None;
    let (mut min, mut max) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for &(m, world) in &asset.instances {
        let data = &asset.meshes[m];
        let normal_matrix = world.inverse().transpose();
        let base = mesh.positions.len() as u32;
        for p in &data.mesh.positions {
            let q = world.transform_point3(*p);
            min = min.min(q);
            max = max.max(q);
            mesh.positions.push(q);
        }
        let normals = data.mesh.normals.as_deref().unwrap_or(&[]);
        mesh.normals
            .as_mut()
            .expect("set above")
            .extend(normals.iter().map(|n| normal_matrix.transform_vector3(*n).normalize_or(Vec3::Y)));
        let flip = world.determinant() < 0.0;
        for t in &data.mesh.indices {
            let [a, b, c] = t.map(|i| i + base);
            mesh.indices.push(if flip { [a, c, b] } else { [a, b, c] });
        }
        let slots: Vec<u32> = data
            .materials
            .iter()
            .map(|gm| {
                let slot = match gm {
                    Some(i) => {
                        if slot_of.len() <= *i {
                            slot_of.resize(*i + 1, None);
                        }
                        *slot_of[*i].get_or_insert_with(|| {
                            materials.push(mesh_material(&asset.materials[*i]));
                            materials.len() - 1
                        })
                    }
                    None => *default_slot.get_or_insert_with(|| {
                        materials.push(mesh_material(&MaterialInfo::default()));
                        materials.len() - 1
                    }),
                };
                slot as u32
            })
            .collect();
        let local = data.mesh.material_indices.as_deref().unwrap_or(&[]);
        mesh.material_indices
            .as_mut()
            .expect("set above")
            .extend((0..data.mesh.indices.len()).map(|t| slots[local.get(t).copied().unwrap_or(0) as usize]));
    }
    obj::LoadedMesh { mesh, materials, min, max, warnings: asset.warnings }
}

fn mesh_material(m: &MaterialInfo) -> obj::MeshMaterial {
    obj::MeshMaterial { name: m.name.clone(), diffuse: m.base_color.truncate(), emission: m.emissive }
}
