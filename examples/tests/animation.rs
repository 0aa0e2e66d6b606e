//! `render` over a glTF file's node animation: `--frames A..B --fps F`
//! writes one image per frame (its number in place of `--out`'s `#`s), each
//! the scene posed at frame / F seconds: frame k is `--time k/F` to the
//! bit, the frames differ where the model moved, and a frame rendered in
//! parts merges to the frame. What cannot be rendered is refused by name
//! with exit status 2 and no image.

use glam::{Quat, Vec3, Vec4};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("animation-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn render(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render")).args(args).output().expect("render runs")
}

fn ok(out: Output) -> String {
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn refused(out: Output, text: &str) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end(), format!("render: {text}"));
}

/// The teapot sliding a third of its size along x over two seconds and
/// half-turning about y at one second (step), as `.glb`.
fn sliding_teapot(dir: &Path) -> PathBuf {
    let teapot = examples::mesh::load_obj(&examples::scene::shared_scene("teapot.obj")).unwrap();
    let size = (teapot.max - teapot.min).length();
    let mut b = rt_scene::glb::GltfBuilder::new();
    let mesh = b.mesh("teapot", &teapot.mesh, &[]);
    let node = b.trs_node(mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
    let to = Vec4::new(size / 3.0, 0.0, 0.0, 0.0);
    b.animate(node, "translation", "LINEAR", &[0.0, 2.0], &[Vec4::ZERO, to]);
    let half = Quat::from_rotation_y(std::f32::consts::PI);
    b.animate(node, "rotation", "STEP", &[0.0, 1.0], &[Quat::IDENTITY.into(), half.into()]);
    let path = dir.join("sliding.glb");
    std::fs::write(&path, b.to_glb()).unwrap();
    path
}

fn png(path: &Path) -> image::RgbaImage {
    image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgba8()
}

const SIZE: [&str; 6] = ["--width", "48", "--height", "40", "--spp", "2"];

#[test]
fn frames_are_the_scene_posed_at_their_times() {
    let dir = temp_dir("frames");
    let model = sliding_teapot(&dir);
    let model = model.to_str().unwrap();
    let out = dir.join("frame_##.png");
    let stdout = ok(render(
        &[&[model, "--backend", "cpu", "--frames", "0..3", "--fps", "1", "--out", out.to_str().unwrap()], &SIZE[..]]
            .concat(),
    ));
    assert_eq!(stdout.lines().count(), 3, "{stdout}");
    assert!(stdout.contains("at 2 s of the animation"), "{stdout}");
    let frames: Vec<_> = (0..3).map(|k| png(&dir.join(format!("frame_{k:02}.png")))).collect();
    assert_ne!(frames[0], frames[1], "the model moved between frames 0 and 1");
    assert_ne!(frames[1], frames[2]);
    // Frame 1 is the scene at 1 s, rendered alone.
    let at_one = dir.join("at_one.png");
    ok(render(&[&[model, "--backend", "cpu", "--time", "1", "--out", at_one.to_str().unwrap()], &SIZE[..]].concat()));
    assert_eq!(png(&at_one), frames[1], "frame 1 is --time 1");
    // Without --time the rest pose: frame 0.
    let rest = dir.join("rest.png");
    ok(render(&[&[model, "--backend", "cpu", "--out", rest.to_str().unwrap()], &SIZE[..]].concat()));
    assert_eq!(png(&rest), frames[0]);

    // Frame 2 in two parts, merged.
    let mut parts = Vec::new();
    for k in 0..2 {
        let part = dir.join(format!("part{k}_#.rtpart"));
        let tile = format!("{k}/2");
        ok(render(
            &[
                &[model, "--backend", "cpu", "--frames", "2..3", "--fps", "1", "--tile", &tile][..],
                &["--out", part.to_str().unwrap()][..],
                &SIZE[..],
            ]
            .concat(),
        ));
        parts.push(dir.join(format!("part{k}_2.rtpart")).to_str().unwrap().to_string());
    }
    let merged = dir.join("merged.png");
    ok(render(&["--merge", &parts[0], &parts[1], "--out", merged.to_str().unwrap()]));
    assert_eq!(png(&merged), frames[2], "frame 2's parts merge to frame 2");
}

#[test]
fn what_cannot_be_animated_is_refused() {
    let dir = temp_dir("refused");
    let model = sliding_teapot(&dir);
    let model = model.to_str().unwrap();
    let teapot = examples::scene::shared_scene("teapot.obj");
    let out = dir.join("f_#.png");
    let out = out.to_str().unwrap();
    refused(
        render(&[teapot.to_str().unwrap(), "--backend", "cpu", "--time", "1", "--out", out]),
        &format!("{}: has no node animation to pose (--time and --frames need one)", teapot.display()),
    );
    let flat = dir.join("flat.png");
    refused(
        render(&[model, "--backend", "cpu", "--frames", "0..2", "--out", flat.to_str().unwrap()]),
        &format!("--out {} has no `#` for the frame number (with --frames, e.g. frame_####.png)", flat.display()),
    );
    refused(render(&[model, "--frames", "3..3", "--out", out]), "--frames 3..3 holds no frame (B must exceed A)");
    refused(
        render(&[model, "--frames", "0-3", "--out", out]),
        "--frames 0-3: expected A..B, frames A to B-1 (e.g. 0..48)",
    );
    refused(render(&[model, "--frames", "0..3", "--fps", "0", "--out", out]), "--fps 0 must be positive");
    assert!(std::fs::read_dir(&dir).unwrap().all(|e| !e.unwrap().file_name().to_string_lossy().ends_with(".png")));
}

/// `--frames` with `--denoise` and `--aov`: each frame denoised as a
/// render of that time alone is, its guides named after it.
#[test]
fn frames_are_denoised_each_with_its_guides() {
    let dir = temp_dir("denoised-frames");
    let model = sliding_teapot(&dir);
    let model = model.to_str().unwrap();
    let (out, aov) = (dir.join("frame_##.png"), dir.join("aov"));
    let denoise = ["--denoise", "--aov", aov.to_str().unwrap()];
    let frames = [model, "--backend", "cpu", "--frames", "0..2", "--fps", "1", "--out", out.to_str().unwrap()];
    ok(render(&[&frames[..], &denoise[..], &SIZE[..]].concat()));
    let mut guides: Vec<_> =
        std::fs::read_dir(&aov).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    guides.sort();
    let want: Vec<_> = ["frame_00", "frame_01"]
        .iter()
        .flat_map(|f| ["albedo", "normal", "variance"].map(|g| format!("{f}_{g}.exr")))
        .collect();
    assert_eq!(guides, want);
    let at_one = dir.join("at_one.png");
    let alone = [model, "--backend", "cpu", "--time", "1", "--out", at_one.to_str().unwrap()];
    ok(render(&[&alone[..], &["--denoise"][..], &SIZE[..]].concat()));
    assert_eq!(png(&at_one), png(&dir.join("frame_01.png")), "frame 1 is --time 1 --denoise");
    let raw = dir.join("raw.png");
    ok(render(&[&[model, "--backend", "cpu", "--time", "1", "--out", raw.to_str().unwrap()][..], &SIZE[..]].concat()));
    assert_ne!(png(&raw), png(&at_one), "the denoiser changed nothing");
}
