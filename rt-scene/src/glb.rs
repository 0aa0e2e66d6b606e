//! Writing glTF: a small builder of meshes, materials (with PNG base colour
//! textures), nodes and a camera, written as `.glb` or as `.gltf` with its
//! buffer embedded as a `data:` URI. It is what converts the shared OBJ
//! scenes to glTF for the tests and for `rt-scene`'s `obj2glb` binary; it
//! writes what the loader reads, nothing more (node animations, but no
//! skins, morph targets or extensions).

use crate::MaterialInfo;
use crate::obj::LoadedMesh;
use glam::{Mat4, Quat, Vec3, Vec4};
use rt_runtime::TriangleMesh;
use std::fmt::Write;

/// A glTF document being assembled.
#[derive(Default)]
pub struct GltfBuilder {
    bin: Vec<u8>,
    views: Vec<String>,
    accessors: Vec<String>,
    meshes: Vec<String>,
    materials: Vec<String>,
    images: Vec<String>,
    nodes: Vec<String>,
    cameras: Vec<String>,
    /// Animation channels and their samplers, all in one animation.
    channels: Vec<String>,
    samplers: Vec<String>,
}

impl GltfBuilder {
    /// A document with nothing in it yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// A material; `png` is its base colour texture's encoded PNG, if any.
    /// Returns its index.
    pub fn material(&mut self, m: &MaterialInfo, png: Option<&[u8]>) -> usize {
        let c = m.base_color;
        let mut pbr = format!(
            "\"baseColorFactor\":[{},{},{},{}],\"metallicFactor\":{},\"roughnessFactor\":{}",
            c.x, c.y, c.z, c.w, m.metallic, m.roughness
        );
        if let Some(png) = png {
            let view = self.view(png, None);
            self.images.push(format!("{{\"bufferView\":{view},\"mimeType\":\"image/png\"}}"));
            let _ = write!(pbr, ",\"baseColorTexture\":{{\"index\":{}}}", self.images.len() - 1);
        }
        let e = m.emissive;
        self.materials.push(format!(
            "{{\"name\":{},\"pbrMetallicRoughness\":{{{pbr}}},\"emissiveFactor\":[{},{},{}]}}",
            json_string(&m.name),
            e.x,
            e.y,
            e.z
        ));
        self.materials.len() - 1
    }

    /// A mesh with one primitive per material slot its triangles use;
    /// `materials[slot]` is the glTF material of each slot. Returns its
    /// index.
    pub fn mesh(&mut self, name: &str, mesh: &TriangleMesh, materials: &[usize]) -> usize {
        let positions = self.vec3s(&mesh.positions, true);
        let normals = mesh.normals.as_ref().map(|n| self.vec3s(n, false));
        let texcoords = mesh.texcoords.as_ref().map(|uv| {
            let bytes: Vec<u8> = uv.iter().flat_map(|v| v.to_array()).flat_map(f32::to_le_bytes).collect();
            let view = self.view(&bytes, Some(34962));
            self.accessor(view, 5126, uv.len(), "VEC2", "")
        });
        let slot_count = materials.len().max(1);
        let mut primitives = Vec::new();
        for slot in 0..slot_count {
            let tris: Vec<u32> = mesh
                .indices
                .iter()
                .enumerate()
                .filter(|(t, _)| mesh.material_indices.as_ref().map_or(0, |m| m[*t] as usize) == slot)
                .flat_map(|(_, tri)| *tri)
                .collect();
            if tris.is_empty() {
                continue;
            }
            let bytes: Vec<u8> = tris.iter().flat_map(|i| i.to_le_bytes()).collect();
            let view = self.view(&bytes, Some(34963));
            let indices = self.accessor(view, 5125, tris.len(), "SCALAR", "");
            let mut attributes = format!("\"POSITION\":{positions}");
            if let Some(n) = normals {
                let _ = write!(attributes, ",\"NORMAL\":{n}");
            }
            if let Some(t) = texcoords {
                let _ = write!(attributes, ",\"TEXCOORD_0\":{t}");
            }
            let material = materials.get(slot).map_or(String::new(), |m| format!(",\"material\":{m}"));
            primitives.push(format!("{{\"attributes\":{{{attributes}}},\"indices\":{indices}{material}}}"));
        }
        self.meshes.push(format!("{{\"name\":{},\"primitives\":[{}]}}", json_string(name), primitives.join(",")));
        self.meshes.len() - 1
    }

    /// A root node showing `mesh` under `matrix`. Returns its index.
    pub fn node(&mut self, mesh: usize, matrix: Mat4) -> usize {
        let m: Vec<String> = matrix.to_cols_array().iter().map(|x| x.to_string()).collect();
        self.nodes.push(format!("{{\"mesh\":{mesh},\"matrix\":[{}]}}", m.join(",")));
        self.nodes.len() - 1
    }

    /// A root node showing `mesh` at translation `t`, rotation `r` and
    /// scale `s` (a node animations may move). Returns its index.
    pub fn trs_node(&mut self, mesh: usize, t: Vec3, r: Quat, s: Vec3) -> usize {
        self.nodes.push(format!(
            "{{\"mesh\":{mesh},\"translation\":[{},{},{}],\"rotation\":[{},{},{},{}],\"scale\":[{},{},{}]}}",
            t.x, t.y, t.z, r.x, r.y, r.z, r.w, s.x, s.y, s.z
        ));
        self.nodes.len() - 1
    }

    /// Animates `node`'s `target` (`"translation"`, `"rotation"` or
    /// `"scale"`) through `values` (xyz, or quaternions' xyzw; three per key
    /// for `"CUBICSPLINE"`) at key `times`, interpolated as `interpolation`
    /// says (`"LINEAR"`, `"STEP"`, `"CUBICSPLINE"`). Writes what it is
    /// given, for the loader's checks to judge.
    pub fn animate(&mut self, node: usize, target: &str, interpolation: &str, times: &[f32], values: &[Vec4]) {
        let bytes: Vec<u8> = times.iter().flat_map(|t| t.to_le_bytes()).collect();
        let view = self.view(&bytes, None);
        let (lo, hi) = times.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), t| (a.min(*t), b.max(*t)));
        let input = self.accessor(view, 5126, times.len(), "SCALAR", &format!(",\"min\":[{lo}],\"max\":[{hi}]"));
        let (ty, width) = if target == "rotation" { ("VEC4", 4) } else { ("VEC3", 3) };
        let bytes: Vec<u8> =
            values.iter().flat_map(|v| v.to_array().into_iter().take(width)).flat_map(f32::to_le_bytes).collect();
        let view = self.view(&bytes, None);
        let output = self.accessor(view, 5126, values.len(), ty, "");
        self.samplers.push(format!(
            "{{\"input\":{input},\"output\":{output},\"interpolation\":{}}}",
            json_string(interpolation)
        ));
        self.channels.push(format!(
            "{{\"sampler\":{},\"target\":{{\"node\":{node},\"path\":{}}}}}",
            self.samplers.len() - 1,
            json_string(target)
        ));
    }

    /// A root node with a perspective camera at `eye` looking at `target`
    /// (`up` roughly up), `yfov_degrees` vertical field of view.
    pub fn camera(&mut self, eye: Vec3, target: Vec3, up: Vec3, yfov_degrees: f32) -> usize {
        self.cameras.push(format!(
            "{{\"type\":\"perspective\",\"perspective\":{{\"yfov\":{},\"znear\":0.01}}}}",
            yfov_degrees.to_radians()
        ));
        // The camera looks down its -Z with +Y up.
        let forward = (target - eye).normalize();
        let right = forward.cross(up).normalize();
        let true_up = right.cross(forward);
        let world = Mat4::from_cols(right.extend(0.0), true_up.extend(0.0), (-forward).extend(0.0), eye.extend(1.0));
        let m: Vec<String> = world.to_cols_array().iter().map(|x| x.to_string()).collect();
        self.nodes.push(format!("{{\"camera\":{},\"matrix\":[{}]}}", self.cameras.len() - 1, m.join(",")));
        self.nodes.len() - 1
    }

    /// The document as GLB bytes.
    pub fn to_glb(&self) -> Vec<u8> {
        let mut json = self.json(None).into_bytes();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let mut out = Vec::with_capacity(28 + json.len() + bin.len());
        out.extend(b"glTF");
        out.extend(2u32.to_le_bytes());
        out.extend(((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
        out.extend((json.len() as u32).to_le_bytes());
        out.extend(b"JSON");
        out.extend(&json);
        out.extend((bin.len() as u32).to_le_bytes());
        out.extend(b"BIN\0");
        out.extend(&bin);
        out
    }

    /// The document as `.gltf` JSON, its buffer at `uri` (write
    /// [`GltfBuilder::buffer`] there), or embedded as base64 when `None`.
    pub fn to_gltf(&self, uri: Option<&str>) -> String {
        let uri = uri.map_or_else(
            || format!("data:application/octet-stream;base64,{}", base64_encode(&self.bin)),
            str::to_string,
        );
        self.json(Some(&uri))
    }

    /// The binary buffer's bytes (for a `.gltf` with an external buffer).
    pub fn buffer(&self) -> &[u8] {
        &self.bin
    }

    fn json(&self, uri: Option<&str>) -> String {
        let uri = uri.map_or(String::new(), |u| format!(",\"uri\":{}", json_string(u)));
        let nodes: Vec<String> = (0..self.nodes.len()).map(|i| i.to_string()).collect();
        let mut s = format!(
            "{{\"asset\":{{\"version\":\"2.0\",\"generator\":\"rt-scene\"}},\"scene\":0,\"scenes\":[{{\"nodes\":[{}]}}],\
             \"buffers\":[{{\"byteLength\":{}{uri}}}]",
            nodes.join(","),
            self.bin.len()
        );
        for (key, items) in [
            ("bufferViews", &self.views),
            ("accessors", &self.accessors),
            ("meshes", &self.meshes),
            ("materials", &self.materials),
            ("images", &self.images),
            ("nodes", &self.nodes),
            ("cameras", &self.cameras),
        ] {
            if !items.is_empty() {
                let _ = write!(s, ",\"{key}\":[{}]", items.join(","));
            }
        }
        if !self.channels.is_empty() {
            let _ = write!(
                s,
                ",\"animations\":[{{\"channels\":[{}],\"samplers\":[{}]}}]",
                self.channels.join(","),
                self.samplers.join(",")
            );
        }
        if !self.images.is_empty() {
            let textures: Vec<String> = (0..self.images.len()).map(|i| format!("{{\"source\":{i}}}")).collect();
            let _ = write!(s, ",\"textures\":[{}]", textures.join(","));
        }
        s.push('}');
        s
    }

    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let target = target.map_or(String::new(), |t| format!(",\"target\":{t}"));
        self.views.push(format!(
            "{{\"buffer\":0,\"byteOffset\":{},\"byteLength\":{}{target}}}",
            self.bin.len(),
            bytes.len()
        ));
        self.bin.extend_from_slice(bytes);
        self.views.len() - 1
    }

    fn accessor(&mut self, view: usize, component: u32, count: usize, ty: &str, extra: &str) -> usize {
        self.accessors.push(format!(
            "{{\"bufferView\":{view},\"componentType\":{component},\"count\":{count},\"type\":\"{ty}\"{extra}}}"
        ));
        self.accessors.len() - 1
    }

    /// glTF requires POSITION accessors to have `min` and `max`.
    fn vec3s(&mut self, values: &[Vec3], bounds: bool) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_array()).flat_map(f32::to_le_bytes).collect();
        let view = self.view(&bytes, Some(34962));
        let extra = if bounds && !values.is_empty() {
            let (lo, hi) = values.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), v| (a.min(*v), b.max(*v)));
            format!(",\"min\":[{},{},{}],\"max\":[{},{},{}]", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z)
        } else {
            String::new()
        };
        self.accessor(view, 5126, values.len(), "VEC3", &extra)
    }
}

/// A loaded OBJ as one glTF mesh on one node, its `.mtl` materials as glTF
/// materials (`Kd` as base colour, `Ke` as emissive, not metallic).
pub fn from_obj(loaded: &LoadedMesh, name: &str) -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let materials: Vec<usize> = loaded
        .materials
        .iter()
        .map(|m| {
            let info = MaterialInfo {
                name: m.name.clone(),
                base_color: m.diffuse.extend(1.0),
                base_color_texture: None,
                metallic: 0.0,
                roughness: 1.0,
                emissive: m.emission,
            };
            b.material(&info, None)
        })
        .collect();
    let mesh = b.mesh(name, &loaded.mesh, &materials);
    b.node(mesh, Mat4::IDENTITY);
    b
}

fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Standard base64 with padding.
pub fn base64_encode(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn base64_round_trips() {
        for bytes in [&b""[..], b"h", b"he", b"hel", b"hello world"] {
            let text = super::base64_encode(bytes);
            assert_eq!(text.len() % 4, 0);
            assert_eq!(crate::gltf::buffers::base64(&text).unwrap(), bytes);
        }
    }
}
