//! Models users already have, through `render`'s path ([`model_scene`]):
//! the Cornell box and the Stanford bunny converted to `.glb` by
//! `rt_scene::glb` render the same pictures as their OBJ files (by the
//! golden images' rule: 99.9% of the 8-bit channels within 2/255, none
//! beyond 16/255); `--up` turns a model, and the `render` binary reads
//! glTF, writes EXR and refuses a bad `.glb` with exit status 2.

use examples::model::{CameraOptions, UpAxis, model_scene};
use examples::{Image, Settings, scene::shared_scene};
use rt_runtime::Backend;
use std::path::{Path, PathBuf};
use std::process::Command;

const W: u32 = 64;
const H: u32 = 48;

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("gltf-render-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `obj` written as `.glb` into `dir` by the loader's own writer.
fn convert(obj: &Path, dir: &Path) -> PathBuf {
    let loaded = examples::mesh::load_obj(obj).unwrap();
    let glb = dir.join(obj.with_extension("glb").file_name().unwrap());
    std::fs::write(&glb, rt_scene::glb::from_obj(&loaded, "model").to_glb()).unwrap();
    glb
}

fn render(path: &Path, options: CameraOptions) -> Image {
    let settings = Settings { spp: 2, backend: Backend::Cpu, ..Settings::new(W, H) };
    let mut model = model_scene(path, &settings, options).unwrap_or_else(|e| panic!("{e}"));
    let rendered = model.scene.render(&mut |_| {}).unwrap();
    assert!(rendered.exceptions.is_empty(), "{}: {:?}", path.display(), rendered.exceptions);
    rendered.image
}

/// The golden images' rule, on the 8-bit picture.
fn assert_same_picture(a: &Image, b: &Image, what: &str) {
    let (a, b) = (a.encode_png().unwrap(), b.encode_png().unwrap());
    let (a, b) = (image::load_from_memory(&a).unwrap().to_rgb8(), image::load_from_memory(&b).unwrap().to_rgb8());
    let diffs: Vec<i32> = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| (*x as i32 - *y as i32).abs()).collect();
    let near = diffs.iter().filter(|&&d| d <= 2).count();
    let worst = diffs.iter().copied().max().unwrap_or(0);
    eprintln!("{what}: {near} of {} channels within 2/255, worst {worst}/255", diffs.len());
    assert!(near as f64 >= 0.999 * diffs.len() as f64, "{what}: only {near} of {} channels within 2/255", diffs.len());
    assert!(worst <= 16, "{what}: a channel differs by {worst}/255");
}

#[test]
fn the_cornell_box_and_the_bunny_as_glb_render_as_their_obj_files() {
    let dir = temp_dir("convert");
    for name in ["cornell_box.obj", "stanford-bunny.obj"] {
        let obj = shared_scene(name);
        let glb = convert(&obj, &dir);
        let from_obj = render(&obj, CameraOptions::default());
        let from_glb = render(&glb, CameraOptions::default());
        assert_same_picture(&from_obj, &from_glb, name);
        // Not a blank picture: the model covers the middle of it.
        assert_ne!(from_obj.at(W / 2, H / 2), from_obj.at(0, H - 1), "{name}");
    }
}

#[test]
fn up_z_turns_a_model_as_a_z_up_file_needs() {
    // The bunny turned to Z-up by hand and told `--up z` is the bunny.
    let dir = temp_dir("up");
    let mut loaded = examples::mesh::load_obj(&shared_scene("stanford-bunny.obj")).unwrap();
    examples::model::turn(&mut loaded, UpAxis::Z.to_y_up().inverse());
    let glb = dir.join("z-up.glb");
    std::fs::write(&glb, rt_scene::glb::from_obj(&loaded, "bunny").to_glb()).unwrap();
    let upright = render(&shared_scene("stanford-bunny.obj"), CameraOptions::default());
    let turned = render(&glb, CameraOptions { up: UpAxis::Z, ..Default::default() });
    assert_same_picture(&upright, &turned, "z-up bunny");
    let lying = render(&glb, CameraOptions::default());
    assert_ne!(lying, upright, "without --up z it lies on its side");
}

#[test]
fn render_reads_glb_writes_exr_and_refuses_a_truncated_glb() {
    let dir = temp_dir("cli");
    let glb = convert(&shared_scene("cornell_box.obj"), &dir);
    let exr = dir.join("cornell.exr");
    let run = |args: &[&str]| Command::new(env!("CARGO_BIN_EXE_render")).args(args).output().unwrap();
    let size = ["--width", "32", "--height", "24", "--spp", "1", "--backend", "cpu"];
    let out = run(&[&[glb.to_str().unwrap(), "--out", exr.to_str().unwrap()][..], &size[..]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let back = image::open(&exr).unwrap().to_rgba32f();
    assert_eq!(back.dimensions(), (32, 24));
    assert!(back.pixels().any(|p| p[0] > 0.1), "an image, not black");

    let cut = dir.join("cut.glb");
    let bytes = std::fs::read(&glb).unwrap();
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let png = dir.join("cut.png");
    let out = run(&[&[cut.to_str().unwrap(), "--out", png.to_str().unwrap()][..], &size[..]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(
        err.trim_end(),
        format!(
            "render: {}: truncated GLB: its header says {} bytes, the file has {}",
            cut.display(),
            bytes.len(),
            bytes.len() / 2
        )
    );
    assert!(!png.exists());
    let out = run(&[&[glb.to_str().unwrap(), "--out", png.to_str().unwrap(), "--fov", "0"][..], &size[..]].concat());
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(String::from_utf8_lossy(&out.stderr).trim_end(), "render: --fov 0 is outside (0, 180) degrees");
}
