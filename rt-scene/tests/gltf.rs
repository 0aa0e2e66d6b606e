//! The glTF loader on files written here: what it reads from `.gltf` (with
//! embedded and external buffers) and `.glb`, how meshes used by several
//! nodes are shared, cameras and lights, generated normals; and every kind
//! of bad input refused with a message naming the file, the object and the
//! problem.

use glam::{Mat4, Vec3, Vec4};
use rt_runtime::{Context, TriangleMesh};
use rt_scene::MaterialInfo;
use rt_scene::glb::{GltfBuilder, base64_encode};
use std::path::{Path, PathBuf};

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("rt-scene-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn triangle() -> TriangleMesh {
    TriangleMesh { positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y], indices: vec![[0, 1, 2]], ..Default::default() }
}

/// Two nodes showing one mesh (one moved by +5 along x), a red material,
/// and a camera.
fn two_instances() -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let red = MaterialInfo {
        name: "red".into(),
        base_color: Vec4::new(1.0, 0.0, 0.0, 1.0),
        base_color_texture: None,
        metallic: 0.0,
        roughness: 0.5,
        emissive: Vec3::ZERO,
    };
    let m = b.material(&red, None);
    let mesh = b.mesh("tri", &triangle(), &[m]);
    b.node(mesh, Mat4::IDENTITY);
    b.node(mesh, Mat4::from_translation(Vec3::new(5.0, 0.0, 0.0)));
    b.camera(Vec3::new(2.5, 0.5, 10.0), Vec3::new(2.5, 0.5, 0.0), Vec3::Y, 40.0);
    b
}

#[test]
fn glb_and_both_kinds_of_gltf_read_the_same() {
    let dir = temp_dir("forms");
    let b = two_instances();
    std::fs::write(dir.join("a.glb"), b.to_glb()).unwrap();
    std::fs::write(dir.join("b.gltf"), b.to_gltf(None)).unwrap();
    std::fs::write(dir.join("c.gltf"), b.to_gltf(Some("c%20data.bin"))).unwrap();
    std::fs::write(dir.join("c data.bin"), b.buffer()).unwrap();
    for name in ["a.glb", "b.gltf", "c.gltf"] {
        let asset = rt_scene::gltf::read(&dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(asset.meshes.len(), 1, "{name}: one mesh, shared");
        assert_eq!(asset.instances.len(), 2, "{name}");
        assert_eq!(asset.instances[1].1.w_axis.x, 5.0, "{name}");
        assert_eq!(asset.meshes[0].mesh.positions, triangle().positions, "{name}");
        // No normals in the file: generated, facing +z.
        assert_eq!(asset.meshes[0].mesh.normals.as_ref().unwrap()[0], Vec3::Z, "{name}");
        assert_eq!(asset.materials[0].base_color, Vec4::new(1.0, 0.0, 0.0, 1.0), "{name}");
        let camera = asset.camera.unwrap_or_else(|| panic!("{name}: camera"));
        assert!((camera.eye - Vec3::new(2.5, 0.5, 10.0)).length() < 1e-5, "{name}: {camera:?}");
        assert!((camera.forward - -Vec3::Z).length() < 1e-5, "{name}: {camera:?}");
        assert!((camera.vfov_degrees - 40.0).abs() < 1e-3, "{name}: {camera:?}");
        assert!(asset.warnings.is_empty(), "{name}: {:?}", asset.warnings);
    }
}

#[test]
fn the_graph_instances_one_geometry_and_reports_what_it_found() {
    let dir = temp_dir("graph");
    std::fs::write(dir.join("two.glb"), two_instances().to_glb()).unwrap();
    let mut ctx = Context::new();
    let loaded = rt_scene::load(&mut ctx, &dir.join("two.glb")).unwrap();
    let info = &loaded.info;
    assert_eq!((info.meshes, info.instances, info.triangles, info.unique_triangles), (1, 2, 2, 1));
    assert_eq!((info.min, info.max), (Vec3::ZERO, Vec3::new(6.0, 1.0, 0.0)));
    assert_eq!(loaded.materials.len(), 1);
    assert_eq!(loaded.materials[0].info.name, "red");
    assert!(info.camera.is_some());
}

/// A one-triangle glTF with its buffer embedded: `positions` (9 floats),
/// then `indices` (u16) if any; `mode` and `extra` JSON spliced into the
/// primitive and the document.
fn gltf_text(positions: [f32; 9], indices: Option<[u16; 3]>, mode: u32, index_count: usize) -> String {
    let mut bin: Vec<u8> = positions.iter().flat_map(|f| f.to_le_bytes()).collect();
    let mut views = vec![r#"{"buffer":0,"byteOffset":0,"byteLength":36}"#.to_string()];
    let mut accessors = vec![
        r#"{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}"#.to_string(),
    ];
    let mut prim_indices = String::new();
    if let Some(ix) = indices {
        bin.extend(ix.iter().flat_map(|i| i.to_le_bytes()));
        views.push(r#"{"buffer":0,"byteOffset":36,"byteLength":6}"#.into());
        accessors.push(format!(r#"{{"bufferView":1,"componentType":5123,"count":{index_count},"type":"SCALAR"}}"#));
        prim_indices = r#","indices":1"#.into();
    }
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}{prim_indices},"mode":{mode}}}]}}],
        "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}],
        "bufferViews":[{}],"accessors":[{}]}}"#,
        bin.len(),
        base64_encode(&bin),
        views.join(","),
        accessors.join(",")
    )
}

const TRI: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

fn refused(bytes: &[u8], file: &str) -> String {
    rt_scene::gltf::parse(bytes, file, None).map(|_| ()).expect_err("must be refused").to_string()
}

#[test]
fn a_good_minimal_file_loads() {
    let asset = rt_scene::gltf::parse(gltf_text(TRI, Some([0, 1, 2]), 4, 3).as_bytes(), "ok.gltf", None).unwrap();
    assert_eq!(asset.meshes[0].mesh.indices.len(), 1);
}

#[test]
fn a_truncated_glb_is_refused_as_truncated() {
    let glb = two_instances().to_glb();
    let short = &glb[..glb.len() - 10];
    assert_eq!(
        refused(short, "cut.glb"),
        format!("cut.glb: truncated GLB: its header says {} bytes, the file has {}", glb.len(), short.len())
    );
    assert_eq!(refused(&glb[..7], "tiny.glb"), "tiny.glb: truncated GLB: 7 bytes, shorter than its 12-byte header");
}

#[test]
fn a_missing_buffer_file_is_named() {
    let dir = temp_dir("missing");
    let b = two_instances();
    std::fs::write(dir.join("m.gltf"), b.to_gltf(Some("gone.bin"))).unwrap();
    let e = rt_scene::gltf::read(&dir.join("m.gltf")).unwrap_err();
    assert_eq!(e.object.as_deref(), Some("buffers[0]"));
    assert_eq!(
        e.to_string(),
        format!(
            "{}: buffers[0]: URI `gone.bin`: cannot read {}: no such file",
            dir.join("m.gltf").display(),
            dir.join("gone.bin").display()
        )
    );
}

#[test]
fn an_accessor_out_of_range_is_named() {
    // Four indices claimed, six bytes (three u16) in the view.
    let text = gltf_text(TRI, Some([0, 1, 2]), 4, 4);
    assert_eq!(
        refused(text.as_bytes(), "r.gltf"),
        "r.gltf: accessors[1]: 4 elements of 2 bytes (stride 2) from offset 0 do not fit bufferViews[1] (6 bytes)"
    );
    // An index past the last vertex.
    let text = gltf_text(TRI, Some([0, 1, 7]), 4, 3);
    assert_eq!(
        refused(text.as_bytes(), "i.gltf"),
        "i.gltf: meshes[0].primitives[0]: index 2 is vertex 7, but there are 3 vertices"
    );
}

#[test]
fn nan_positions_are_refused() {
    let mut p = TRI;
    p[4] = f32::NAN;
    assert_eq!(
        refused(gltf_text(p, None, 4, 0).as_bytes(), "nan.gltf"),
        "nan.gltf: meshes[0].primitives[0]: vertex 1 has a non-finite position [1, NaN, 0]"
    );
}

#[test]
fn non_triangle_modes_are_refused_and_strips_are_read() {
    assert_eq!(
        refused(gltf_text(TRI, None, 1, 0).as_bytes(), "lines.gltf"),
        "lines.gltf: meshes[0].primitives[0]: mode Lines is not supported: only triangles (TRIANGLES, \
         TRIANGLE_STRIP, TRIANGLE_FAN)"
    );
    let strip = rt_scene::gltf::parse(gltf_text(TRI, None, 5, 0).as_bytes(), "strip.gltf", None).unwrap();
    assert_eq!(strip.meshes[0].mesh.indices.len(), 1);
}

#[test]
fn documents_the_gltf_crate_refuses_name_the_object() {
    // A node that names a mesh that is not there.
    let text = gltf_text(TRI, None, 4, 0).replace(r#""nodes":[{"mesh":0}]"#, r#""nodes":[{"mesh":3}]"#);
    assert_eq!(
        refused(text.as_bytes(), "v.gltf"),
        "v.gltf: nodes[0]: mesh names meshes[3], but the file's meshes end at meshes[0]"
    );
    assert!(refused(b"{ not json", "j.gltf").starts_with("j.gltf: not valid glTF JSON: "));
    let e = refused(b"", "empty.obj.gltf");
    assert!(e.starts_with("empty.obj.gltf: not valid glTF JSON"), "{e}");
}

#[test]
fn unknown_extensions_and_unreadable_files_are_named() {
    let mut ctx = Context::new();
    let e = rt_scene::load(&mut ctx, Path::new("scene.fbx")).unwrap_err();
    assert!(e.is_bad_input());
    assert_eq!(e.to_string(), "scene.fbx: not a scene format this build reads (expected .obj, .gltf or .glb)");
    let e = rt_scene::load(&mut ctx, Path::new("/nonexistent/x.glb")).unwrap_err();
    assert_eq!(e.to_string(), "/nonexistent/x.glb: cannot read the file: no such file");
}

#[test]
fn lights_are_read_in_world_space() {
    let text = gltf_text(TRI, None, 4, 0)
        .replace(
            r#""nodes":[{"mesh":0}]"#,
            r#""nodes":[{"mesh":0},{"translation":[1,2,3],"extensions":{"KHR_lights_punctual":{"light":0}}}]"#,
        )
        .replace(r#""scenes":[{"nodes":[0]}]"#, r#""scenes":[{"nodes":[0,1]}]"#)
        .replace(
            r#""asset":{"version":"2.0"}"#,
            r#""asset":{"version":"2.0"},"extensionsUsed":["KHR_lights_punctual"],
            "extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","color":[1,0.5,0.25],"intensity":7}]}}"#,
        );
    let asset = rt_scene::gltf::parse(text.as_bytes(), "light.gltf", None).unwrap();
    assert_eq!(asset.lights.len(), 1);
    let light = &asset.lights[0];
    assert_eq!(
        (light.kind, light.position, light.intensity),
        (rt_scene::LightKind::Point, Vec3::new(1.0, 2.0, 3.0), 7.0)
    );
    assert_eq!(light.color, Vec3::new(1.0, 0.5, 0.25));
}

#[test]
fn a_flattened_scene_bakes_every_instance() {
    let dir = temp_dir("flat");
    std::fs::write(dir.join("two.glb"), two_instances().to_glb()).unwrap();
    let (mesh, camera) = rt_scene::load_flat(&dir.join("two.glb")).unwrap();
    assert!(camera.is_some());
    assert_eq!(mesh.mesh.indices.len(), 2);
    assert_eq!(mesh.mesh.positions[4], Vec3::new(6.0, 0.0, 0.0));
    assert_eq!(mesh.materials.len(), 1);
    assert_eq!((mesh.min, mesh.max), (Vec3::ZERO, Vec3::new(6.0, 1.0, 0.0)));
}
