//! The valid files every mutation starts from: a glTF scene that uses
//! most of what the loader reads (two instances of a textured mesh, TRS
//! and matrix nodes, a child node, a camera, a punctual light, a skin, a
//! morph target, a sparse accessor, translation, rotation and scale
//! animations with every interpolation), an OBJ with its MTL, and a part
//! file.

use glam::{Mat4, Quat, Vec3, Vec4};
use rt_runtime::TriangleMesh;
use rt_scene::MaterialInfo;
use rt_scene::glb::GltfBuilder;
use serde_json::{Value, json};

/// A 2x2 RGBA PNG.
pub fn png() -> Vec<u8> {
    let pixels = [255u8, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128];
    let mut out = std::io::Cursor::new(Vec::new());
    image::write_buffer_with_format(&mut out, &pixels, 2, 2, image::ExtendedColorType::Rgba8, image::ImageFormat::Png)
        .expect("a 2x2 PNG encodes");
    out.into_inner()
}

/// The glTF scene: its JSON (without a buffer URI) and its binary buffer.
pub fn gltf() -> (Value, Vec<u8>) {
    let mut b = GltfBuilder::new();
    let info = MaterialInfo {
        name: "tex".into(),
        base_color: Vec4::new(1.0, 0.5, 0.25, 1.0),
        base_color_texture: None,
        metallic: 0.0,
        roughness: 0.5,
        emissive: Vec3::ZERO,
    };
    let m = b.material(&info, Some(&png()));
    let quad = TriangleMesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        texcoords: Some(vec![glam::Vec2::ZERO, glam::Vec2::X, glam::Vec2::ONE, glam::Vec2::Y]),
        normals: Some(vec![Vec3::Z; 4]),
        ..Default::default()
    };
    let mesh = b.mesh("quad", &quad, &[m]);
    b.node(mesh, Mat4::IDENTITY);
    let moving = b.trs_node(mesh, Vec3::new(2.0, 0.0, 0.0), Quat::IDENTITY, Vec3::ONE);
    b.animate(moving, "translation", "LINEAR", &[0.0, 1.0], &[Vec4::ZERO, Vec4::X]);
    let q = |a: f32| Quat::from_rotation_y(a).into();
    b.animate(
        moving,
        "rotation",
        "CUBICSPLINE",
        &[0.0, 1.0],
        &[Vec4::ZERO, q(0.0), Vec4::ZERO, Vec4::ZERO, q(1.0), Vec4::ZERO],
    );
    b.animate(moving, "scale", "STEP", &[0.0, 0.5], &[Vec4::ONE, Vec4::splat(2.0)]);
    b.camera(Vec3::new(0.5, 0.5, 5.0), Vec3::new(0.5, 0.5, 0.0), Vec3::Y, 40.0);
    let mut doc: Value = serde_json::from_str(&b.to_gltf(Some("seed.bin"))).expect("the builder writes JSON");
    let bin = b.buffer().to_vec();
    add_extras(&mut doc);
    if let Some(buffer) = doc["buffers"][0].as_object_mut() {
        buffer.remove("uri");
    }
    (doc, bin)
}

/// What the builder does not write: a child node with a light, a skin, a
/// morph target and a sparse accessor (neither used for drawing).
fn add_extras(doc: &mut Value) {
    doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1, 1, 1], "intensity": 3, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}
    ]}});
    let nodes = doc["nodes"].as_array_mut().expect("nodes");
    nodes.push(json!({"translation": [0, 3, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}));
    let child = nodes.len() - 1;
    nodes[0]["children"] = json!([child]);
    nodes[0]["skin"] = json!(0);
    doc["skins"] = json!([{"joints": [0]}]);
    doc["meshes"][0]["primitives"][0]["targets"] = json!([{"POSITION": 0}]);
    let accessors = doc["accessors"].as_array_mut().expect("accessors");
    accessors.push(json!({"componentType": 5126, "count": 4, "type": "VEC3", "sparse": {
        "count": 1, "indices": {"bufferView": 0, "componentType": 5121}, "values": {"bufferView": 0}}}));
}

pub const OBJ: &str = "# a cube's corner, with texture coordinates and normals\n\
mtllib seed.mtl\n\
o corner\n\
v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n\
vt 0 0\nvt 1 0\nvt 1 1\nvt 0.5\n\
vn 0 0 1\nvn 0 1 0\n\
g front\n\
usemtl red\n\
f 1/1/1 2/2/1 3/3/1 4/4/1\n\
s 1\n\
usemtl\tlight\n\
f 1//2 5//2 6//2 2//2\n\
f -1 -2 -3\n";

pub const MTL: &str = "newmtl red\nKd 1 0 0\nKa 0 0 0\nNs 10\nd 1\nillum 2\n\
newmtl light\nKd 1\nKe 20 20 20\nmap_Kd none.png\n";

/// FNV-1a, 64 bits (the part file's pixel check).
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ *b as u64).wrapping_mul(0x0000_0100_0000_01b3))
}

/// The one part of a 4x16 picture (part 0 of 1, rows 0..16): a part file
/// that merges alone.
pub fn part() -> Vec<u8> {
    let pixels: Vec<u8> = (0..4 * 16 * 4).flat_map(|i| (i as f32 / 256.0).to_le_bytes()).collect();
    let mut out = format!(
        "rt-part 1\nsize 4 16\ntile 0 1\nrows 0 16\nsettings model seed.obj 4x16 spp 1\npixels {:016x}\n\n",
        fnv1a(&pixels)
    )
    .into_bytes();
    out.extend(pixels);
    out
}
