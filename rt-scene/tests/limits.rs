//! `LoadLimits`: what a file may make the loader read and allocate, each
//! refusal naming the file, the object and the limit; files read only
//! when regular and inside the model's folder (or an allowed one).

mod common;

use common::{edited, load_text, refused, refused_with, temp_dir};
use rt_runtime::Context;
use rt_scene::LoadLimits;
use rt_scene::glb::base64_encode;

/// A PNG of only its signature, header chunk, an empty data chunk and
/// end: enough for its size to be read, nothing to decode.
fn png_header(width: u32, height: u32) -> Vec<u8> {
    fn crc(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= b as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xedb8_8320 ^ (c >> 1) } else { c >> 1 };
            }
        }
        !c
    }
    let chunk = |kind: &[u8], data: &[u8]| {
        let mut body = kind.to_vec();
        body.extend(data);
        let mut out = (data.len() as u32).to_be_bytes().to_vec();
        out.extend(&body);
        out.extend(crc(&body).to_be_bytes());
        out
    };
    let mut ihdr = width.to_be_bytes().to_vec();
    ihdr.extend(height.to_be_bytes());
    ihdr.extend([1, 0, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(chunk(b"IHDR", &ihdr));
    // An empty zlib stream: the size is read before any pixel data.
    png.extend(chunk(b"IDAT", &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]));
    png.extend(chunk(b"IEND", &[]));
    png
}

/// The base file with a material whose base colour texture is `png`.
fn textured(png: &[u8]) -> String {
    let images = format!(
        r#""materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}],"textures":[{{"source":0}}],
        "images":[{{"uri":"data:image/png;base64,{}"}}],"buffers":["#,
        base64_encode(png)
    );
    edited(&[(r#""indices":1}"#, r#""indices":1,"material":0}"#), (r#""buffers":["#, &images)])
}

#[test]
fn a_decompression_bomb_is_refused_from_its_header() {
    assert_eq!(
        refused("bomb.gltf", &textured(&png_header(16384, 16384))),
        "images[0]: a 16384x16384 image: the count of texture pixels is 268435456, over the limit of 33554432 \
         (LoadLimits::max_texture_pixels)"
    );
    let limits = LoadLimits { max_texture_bytes: 1000, ..Default::default() };
    assert_eq!(
        refused_with("bytes.gltf", &textured(&png_header(64, 64)), &limits),
        "images[0]: a 64x64 image: the count of texture bytes (16 a pixel) is 65536, over the limit of 1000 \
         (LoadLimits::max_texture_bytes)"
    );
}

#[test]
fn counts_are_bounded_and_named() {
    let cases = [
        (
            LoadLimits { max_triangles: 2, ..Default::default() },
            "nodes[2]: the count of triangles shown is 3, over the limit of 2 (LoadLimits::max_triangles)",
        ),
        (
            LoadLimits { max_instances: 1, ..Default::default() },
            "nodes[1]: the count of instances is 2, over the limit of 1 (LoadLimits::max_instances)",
        ),
        (
            LoadLimits { max_nodes: 2, ..Default::default() },
            "the count of nodes is 3, over the limit of 2 (LoadLimits::max_nodes)",
        ),
        (
            LoadLimits { max_buffer_bytes: 100, ..Default::default() },
            "buffers[0]: the count of buffer bytes is 132, over the limit of 100 (LoadLimits::max_buffer_bytes)",
        ),
        (
            LoadLimits { max_data_uri_bytes: 64, ..Default::default() },
            "buffers[0]: the `data:` URI's count of bytes is 132, over the limit of 64 (LoadLimits::max_data_uri_bytes)",
        ),
    ];
    for (limits, problem) in cases {
        assert_eq!(refused_with("counts.gltf", &common::base(), &limits), problem);
    }
    let size = common::base().len();
    assert_eq!(
        refused_with("file.gltf", &common::base(), &LoadLimits { max_file_bytes: 100, ..Default::default() }),
        format!(
            "cannot read the file: its size in bytes is {size}, over the limit of 100 (LoadLimits::max_file_bytes)"
        )
    );
}

/// A buffer URI naming `uri`, in the model's folder `dir`.
fn buffer_uri(uri: &str) -> String {
    let text = common::base();
    let start = text.find("data:application").unwrap();
    let end = start + text[start..].find('"').unwrap();
    format!("{}{uri}{}", &text[..start], &text[end..])
}

#[test]
fn uris_resolve_only_inside_the_models_folder_and_name_regular_files() {
    let dir = temp_dir("outside");
    let outside = |uri: &str, path: &str| {
        let mut ctx = Context::new();
        let model = dir.join("m.gltf");
        std::fs::write(&model, buffer_uri(uri)).unwrap();
        let e = rt_scene::load(&mut ctx, &model).map(|_| ()).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "{}: buffers[0]: URI `{uri}`: cannot read {path} is outside the model's folder {} (allow its folder \
                 with LoadLimits::allowed_dirs, `--allow-path DIR`)",
                model.display(),
                dir.display()
            )
        );
    };
    std::fs::write(dir.join("../rt-scene-secret.bin"), [0u8; 200]).unwrap();
    outside("../rt-scene-secret.bin", &dir.join("../rt-scene-secret.bin").display().to_string());
    outside("/dev/zero", "/dev/zero");
    outside("%2Fdev%2Fzero", "/dev/zero");
    // Allowed, but not a regular file: never read.
    let limits = LoadLimits { allowed_dirs: vec!["/dev".into()], ..Default::default() };
    assert_eq!(
        refused_with("zero.gltf", &buffer_uri("/dev/zero"), &limits),
        "buffers[0]: URI `/dev/zero`: cannot read /dev/zero: not a regular file"
    );
    // A FIFO inside the folder: refused at once rather than waited on.
    let fifo_dir = temp_dir("fifo");
    let made = std::process::Command::new("mkfifo").arg(fifo_dir.join("pipe.bin")).status();
    if made.is_ok_and(|s| s.success()) {
        let model = fifo_dir.join("m.gltf");
        std::fs::write(&model, buffer_uri("pipe.bin")).unwrap();
        let e = rt_scene::load(&mut Context::new(), &model).map(|_| ()).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "{}: buffers[0]: URI `pipe.bin`: cannot read {}: not a regular file",
                model.display(),
                fifo_dir.join("pipe.bin").display()
            )
        );
    }
}

#[test]
fn obj_files_read_what_the_format_allows_and_refuse_bad_materials() {
    let dir = temp_dir("obj");
    std::fs::write(dir.join("m.mtl"), "newmtl\tred one\nKd 1\nKa 0.5\nNs 10\n").unwrap();
    let obj = "mtllib\tm.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nvt 0.25 0.75\nvt 1\nusemtl\tred one\nf 1/1 2/2 3/3\n";
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    let loaded = rt_scene::obj::load_obj(&dir.join("m.obj")).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    assert_eq!(loaded.materials[0].name, "red one");
    assert_eq!(loaded.materials[0].diffuse, glam::Vec3::ONE);
    assert_eq!(loaded.mesh.material_indices.as_ref().unwrap(), &[0]);
    std::fs::write(dir.join("bad.mtl"), "newmtl m\nKd 0.5\nKe inf 0 0\n").unwrap();
    std::fs::write(dir.join("bad.obj"), obj.replace("m.mtl", "bad.mtl")).unwrap();
    let e = rt_scene::obj::load_obj(&dir.join("bad.obj")).unwrap_err();
    assert_eq!(e.to_string(), "bad.mtl:3: `Ke` has inf, which is not finite");
    // An `mtllib` outside the folder is not read (a warning, as for a
    // missing one).
    std::fs::write(dir.join("../rt-scene-outside.mtl"), "newmtl red one\nKd 1 0 0\n").unwrap();
    std::fs::write(dir.join("out.obj"), obj.replace("m.mtl", "../rt-scene-outside.mtl")).unwrap();
    let loaded = rt_scene::obj::load_obj(&dir.join("out.obj")).unwrap();
    assert_eq!(loaded.warnings.len(), 1, "{:?}", loaded.warnings);
    assert!(loaded.warnings[0].contains("is outside the model's folder"), "{:?}", loaded.warnings);
}

#[test]
fn the_limits_default_as_documented() {
    let l = LoadLimits::default();
    assert_eq!(
        (l.max_file_bytes, l.max_buffer_bytes, l.max_data_uri_bytes, l.max_texture_pixels, l.max_texture_bytes),
        (1 << 30, 1 << 30, 256 << 20, 2 * 4096 * 4096, 512 << 20)
    );
    assert_eq!((l.max_triangles, l.max_instances, l.max_nodes), (100_000_000, 1_000_000, 1_000_000));
    assert!(l.allowed_dirs.is_empty());
    let (_, loaded) = load_text("unlimited.gltf", &common::base(), &LoadLimits::unlimited());
    assert!(loaded.is_ok());
}
