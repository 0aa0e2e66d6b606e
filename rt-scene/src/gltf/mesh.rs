//! A glTF mesh as one [`TriangleMesh`]: its primitives' triangles
//! (strips and fans unrolled, non-indexed ones indexed), positions checked
//! finite, indices checked in range, normals where the file has them and
//! generated ([`with_crease_normals`]) where it does not, texture
//! coordinates set 0, and a material index per triangle into the mesh's own
//! material slots (one per distinct glTF material, in order of first use).

use super::Reader;
use super::buffers::check_accessor;
use crate::error::GltfError;
use crate::obj::{CREASE_DEGREES, with_crease_normals};
use glam::{Vec2, Vec3};
use gltf::mesh::{Mode, Semantic};
use rt_runtime::TriangleMesh;

/// One mesh, ready for `create_triangles`.
#[derive(Clone, Debug)]
pub struct MeshData {
    /// The glTF mesh's index.
    pub index: usize,
    /// The glTF mesh's name, else its JSON path (`meshes[2]`).
    pub name: String,
    /// Its primitives' triangles, as one mesh.
    pub mesh: TriangleMesh,
    /// The glTF material of each slot `mesh.material_indices` uses; `None`
    /// is glTF's default material (primitives without one).
    pub materials: Vec<Option<usize>>,
}

/// Reads every primitive of `mesh`.
pub(super) fn read_mesh(r: &Reader, mesh: &gltf::Mesh, buffers: &[Vec<u8>]) -> Result<MeshData, GltfError> {
    let mut out = TriangleMesh { normals: Some(Vec::new()), texcoords: Some(Vec::new()), ..Default::default() };
    let mut slots: Vec<Option<usize>> = Vec::new();
    let mut material_indices = Vec::new();
    let mut any_texcoords = false;
    for primitive in mesh.primitives() {
        let object = format!("meshes[{}].primitives[{}]", mesh.index(), primitive.index());
        let part = read_primitive(r, &object, &primitive, buffers)?;
        any_texcoords |= part.texcoords.is_some();
        let material = primitive.material().index();
        let slot = match slots.iter().position(|&m| m == material) {
            Some(s) => s,
            None => {
                slots.push(material);
                slots.len() - 1
            }
        } as u32;
        let base = out.positions.len() as u32;
        let count = part.positions.len();
        out.positions.extend(&part.positions);
        out.normals.as_mut().expect("set above").extend(part.normals.expect("read_primitive fills normals"));
        out.texcoords.as_mut().expect("set above").extend(part.texcoords.unwrap_or_else(|| vec![Vec2::ZERO; count]));
        out.indices.extend(part.indices.iter().map(|t| t.map(|i| i + base)));
        material_indices.extend(std::iter::repeat_n(slot, part.indices.len()));
    }
    if out.indices.is_empty() {
        return Err(r.error(&format!("meshes[{}]", mesh.index()), "has no triangles".into()));
    }
    if !any_texcoords {
        out.texcoords = None;
    }
    out.material_indices = Some(material_indices);
    let name = mesh.name().map_or_else(|| format!("meshes[{}]", mesh.index()), str::to_string);
    Ok(MeshData { index: mesh.index(), name, mesh: out, materials: slots })
}

fn read_primitive(
    r: &Reader,
    object: &str,
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
) -> Result<TriangleMesh, GltfError> {
    let mode = primitive.mode();
    if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
        return Err(r.error(
            object,
            format!("mode {mode:?} is not supported: only triangles (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN)"),
        ));
    }
    for (semantic, accessor) in primitive.attributes() {
        if matches!(semantic, Semantic::Positions | Semantic::Normals | Semantic::TexCoords(0)) {
            check_accessor(r, &format!("{object}.attributes.{}", semantic.to_string()), &accessor, buffers)?;
        }
    }
    if let Some(indices) = primitive.indices() {
        check_accessor(r, &format!("{object}.indices"), &indices, buffers)?;
    }
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    let unreadable = |what: &str| r.error(object, format!("its {what} cannot be read (a wrong component type?)"));
    let positions: Vec<Vec3> = reader
        .read_positions()
        .ok_or_else(|| r.error(object, "has no POSITION attribute".into()))?
        .map(Vec3::from_array)
        .collect();
    if positions.is_empty() {
        return Err(unreadable("POSITION"));
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(r.error(object, format!("vertex {i} has a non-finite position {}", positions[i])));
    }
    let n = positions.len();
    let corners: Vec<u32> = match reader.read_indices() {
        Some(indices) => indices.into_u32().collect(),
        None => (0..n as u32).collect(),
    };
    if let Some((k, &i)) = corners.iter().enumerate().find(|&(_, &i)| i as usize >= n) {
        return Err(r.error(object, format!("index {k} is vertex {i}, but there are {n} vertices")));
    }
    let indices = triangles(mode, &corners);
    let normals = reader.read_normals().map(|it| it.map(Vec3::from_array).collect::<Vec<_>>());
    let texcoords = reader.read_tex_coords(0).map(|it| it.into_f32().map(Vec2::from_array).collect::<Vec<_>>());
    for (what, len) in [("NORMAL", normals.as_ref().map(Vec::len)), ("TEXCOORD_0", texcoords.as_ref().map(Vec::len))] {
        if let Some(len) = len
            && len != n
        {
            return Err(r.error(object, format!("{what} has {len} elements for {n} positions")));
        }
    }
    let mut mesh = TriangleMesh { positions, indices, normals: None, texcoords, material_indices: None };
    match normals {
        Some(normals) if normals.iter().all(|v| v.is_finite()) => {
            mesh.normals = Some(normals.into_iter().map(|v| v.normalize_or(Vec3::Y)).collect());
        }
        _ => mesh = with_crease_normals(mesh, CREASE_DEGREES),
    }
    Ok(mesh)
}

/// Triangles from a primitive's corner list, by mode; strips keep every
/// triangle's winding as the first one's.
fn triangles(mode: Mode, corners: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (0..corners.len().saturating_sub(2))
            .map(|i| {
                let (a, b, c) = (corners[i], corners[i + 1], corners[i + 2]);
                if i % 2 == 0 { [a, b, c] } else { [b, a, c] }
            })
            .collect(),
        Mode::TriangleFan => {
            (1..corners.len().saturating_sub(1)).map(|i| [corners[0], corners[i], corners[i + 1]]).collect()
        }
        _ => corners.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_unroll_with_consistent_winding() {
        assert_eq!(triangles(Mode::TriangleStrip, &[0, 1, 2, 3]), [[0, 1, 2], [2, 1, 3]]);
        assert_eq!(triangles(Mode::TriangleFan, &[0, 1, 2, 3]), [[0, 1, 2], [0, 2, 3]]);
        assert_eq!(triangles(Mode::Triangles, &[0, 1, 2, 3, 4]), [[0, 1, 2]]);
    }
}
