//! The binaries as a user runs them: `render` refuses bad meshes with one
//! line and exit status 2, writing nothing, and renders a real one, on
//! either backend; `tour` renders what it is asked to and says which backend
//! did.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh directory under cargo's per-target temporary directory.
fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("examples-cli-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn render(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render")).args(args).output().expect("render runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Renders `obj` and checks the refusal: exit status 2, one line on stderr
/// naming the file, `line` and `problem`, nothing on stdout, no PNG.
fn refused(dir: &Path, obj: &Path, line: Option<usize>, problem: &str) {
    let png = dir.join("out.png");
    let out = render(&[
        obj.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--width",
        "32",
        "--height",
        "24",
        "--spp",
        "1",
    ]);
    let err = stderr(&out);
    let name = obj.display();
    assert_eq!(out.status.code(), Some(2), "{name}: {err}");
    assert_eq!(err.lines().count(), 1, "{name}: one line expected, got:\n{err}");
    let location = match line {
        Some(l) => format!("{name}:{l}: "),
        None => format!("{name}: "),
    };
    assert_eq!(err.trim_end(), format!("render: {location}{problem}"));
    assert!(out.stdout.is_empty(), "{name}: {}", String::from_utf8_lossy(&out.stdout));
    let pngs: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("png"))
        .collect();
    assert!(pngs.is_empty(), "{name}: wrote {pngs:?}");
}

/// Writes `text` as `name` in `dir` and checks that `render` refuses it.
fn refused_text(dir: &Path, name: &str, text: &str, line: Option<usize>, problem: &str) {
    let obj = dir.join(name);
    std::fs::write(&obj, text).unwrap();
    refused(dir, &obj, line, problem);
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn render_refuses_a_missing_file() {
    let dir = temp_dir("missing");
    refused(&dir, &dir.join("no-such-mesh.obj"), None, "cannot read the file: no such file");
}

#[test]
fn render_refuses_malformed_obj() {
    let dir = temp_dir("malformed");
    refused_text(
        &dir,
        "word.obj",
        "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n",
        Some(2),
        "a vertex has `zero`, which is not a number",
    );
    refused_text(&dir, "short.obj", "# two numbers\nv 0 0\n", Some(2), "a vertex needs 3 numbers, found 2");
    refused_text(
        &dir,
        "face.obj",
        &format!("{TRIANGLE}f 1 2\n"),
        Some(4),
        "a face needs at least 3 vertices, this one has 2",
    );
    refused_text(
        &dir,
        "index.obj",
        &format!("{TRIANGLE}f 1 2 x\n"),
        Some(4),
        "face vertex index `x` is not an integer",
    );
    refused_text(
        &dir,
        "zero.obj",
        &format!("{TRIANGLE}f 0 1 2\n"),
        Some(4),
        "face vertex index 0 is invalid (OBJ indices start at 1)",
    );
}

#[test]
fn render_refuses_non_finite_coordinates() {
    let dir = temp_dir("nan");
    refused_text(
        &dir,
        "nan.obj",
        "v 0 0 0\nv 1 0 0\nv 0 NaN 0\nf 1 2 3\n",
        Some(3),
        "vertex 3 has a non-finite coordinate (NaN)",
    );
    refused_text(
        &dir,
        "inf.obj",
        "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n",
        Some(2),
        "vertex 2 has a non-finite coordinate (inf)",
    );
}

#[test]
fn render_refuses_indices_out_of_range() {
    let dir = temp_dir("range");
    refused_text(
        &dir,
        "high.obj",
        &format!("{TRIANGLE}f 1 2 4\n"),
        Some(4),
        "face vertex index 4 is out of range: there are 3 vertices",
    );
    refused_text(
        &dir,
        "relative.obj",
        &format!("{TRIANGLE}f -1 -2 -4\n"),
        Some(4),
        "face vertex index -4 is out of range: there are 3 vertices so far",
    );
    refused_text(
        &dir,
        "normal.obj",
        &format!("{TRIANGLE}vn 0 0 1\nf 1//1 2//1 3//2\n"),
        Some(5),
        "face normal index 2 is out of range: there is 1 normal",
    );
}

#[test]
fn render_refuses_empty_meshes() {
    let dir = temp_dir("empty");
    refused_text(&dir, "empty.obj", "", None, "the mesh is empty: it has no faces");
    refused_text(&dir, "points.obj", TRIANGLE, None, "the mesh is empty: it has no faces");
}

#[test]
fn render_renders_the_teapot() {
    let dir = temp_dir("teapot");
    let png = dir.join("teapot.png");
    let teapot = examples::scene::shared_scene("teapot.obj");
    let out = render(&[
        teapot.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--width",
        "48",
        "--height",
        "36",
        "--spp",
        "2",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let image = image::open(&png).unwrap().to_rgba8();
    assert_eq!(image.dimensions(), (48, 36));
    // The teapot, framed in the middle, is not the background.
    let (centre, corner) = (image.get_pixel(24, 18), image.get_pixel(0, 0));
    assert_ne!(centre, corner);
}

#[test]
fn an_unknown_backend_is_a_usage_error() {
    let dir = temp_dir("backend");
    let teapot = examples::scene::shared_scene("teapot.obj");
    let png = dir.join("teapot.png");
    let out = render(&[teapot.to_str().unwrap(), "--out", png.to_str().unwrap(), "--backend", "metal"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("possible values: cpu, wgpu"), "{}", stderr(&out));
    assert!(!png.exists());
}

/// The wgpu backend renders where wgpu finds an adapter (Mesa's lavapipe
/// counts), and is refused in one clear line where it finds none.
#[test]
fn render_runs_on_the_wgpu_backend_or_says_why_not() {
    let dir = temp_dir("wgpu");
    let obj = dir.join("triangle.obj");
    std::fs::write(&obj, format!("{TRIANGLE}f 1 2 3\n")).unwrap();
    let png = dir.join("triangle.png");
    let out = render(&[
        obj.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--width",
        "8",
        "--height",
        "6",
        "--spp",
        "1",
        "--backend",
        "wgpu",
    ]);
    let err = stderr(&out);
    match out.status.code() {
        Some(0) => {
            let stdout = String::from_utf8_lossy(&out.stdout);
            assert!(stdout.contains("with the wgpu backend on "), "{stdout}");
            assert_eq!(image::open(&png).unwrap().width(), 8);
        }
        Some(2) => {
            assert!(err.contains("render: the wgpu backend is not available: wgpu finds no adapter"), "{err}");
            assert!(!png.exists());
        }
        code => panic!("exit status {code:?}: {err}"),
    }
}

/// Headless as it comes: without `XDG_RUNTIME_DIR` (a container, a CI
/// runner) a wgpu render prints nothing on stderr; Mesa's device-selection
/// layer used to print "error: XDG_RUNTIME_DIR is invalid or not set".
#[test]
fn a_wgpu_render_without_xdg_runtime_dir_prints_nothing_on_stderr() {
    let dir = temp_dir("headless");
    let obj = dir.join("triangle.obj");
    std::fs::write(&obj, format!("{TRIANGLE}f 1 2 3\n")).unwrap();
    let png = dir.join("triangle.png");
    let out = Command::new(env!("CARGO_BIN_EXE_render"))
        .args([obj.to_str().unwrap(), "--out", png.to_str().unwrap(), "--width", "8", "--height", "6"])
        .args(["--spp", "1", "--backend", "wgpu"])
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("NODEVICE_SELECT")
        .output()
        .expect("render runs");
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(stderr(&out), "");
}

#[test]
fn tour_renders_the_named_examples_and_says_which_backend() {
    let dir = temp_dir("tour");
    let out = Command::new(env!("CARGO_BIN_EXE_tour"))
        .args([
            "--out",
            dir.to_str().unwrap(),
            "--width",
            "32",
            "--height",
            "24",
            "--spp",
            "1",
            "--only",
            "normal",
            "--only",
            "cornell",
        ])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("with the cpu backend ("), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.lines().any(|l| l.starts_with("normal") && l.contains("Mrays/s")), "{stdout}");
    for name in ["normal", "cornell"] {
        let image = image::open(dir.join(format!("{name}.png"))).unwrap();
        assert_eq!((image.width(), image.height()), (32, 24));
    }
    assert!(!dir.join("bunny.png").exists());
}

/// `tour --denoise`: for an example that writes guides (bunny), the pair
/// at `--denoise-spp` and the `--spp` picture through the same tonemapper;
/// nothing more for one that writes none (normal).
#[test]
fn tour_denoise_writes_the_pair_beside_the_converged_picture() {
    let dir = temp_dir("tour-denoise");
    let out = Command::new(env!("CARGO_BIN_EXE_tour"))
        .args(["--out", dir.to_str().unwrap(), "--width", "32", "--height", "24", "--spp", "3"])
        .args(["--denoise-spp", "1", "--backend", "cpu", "--denoise", "--only", "normal", "--only", "bunny"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let mut written: Vec<_> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    written.sort();
    assert_eq!(written, ["bunny.png", "bunny_converged.png", "bunny_denoised.png", "bunny_noisy.png", "normal.png"]);
    let read = |name: &str| image::open(dir.join(name)).unwrap().to_rgb8();
    let (noisy, denoised, converged) =
        (read("bunny_noisy.png"), read("bunny_denoised.png"), read("bunny_converged.png"));
    assert_eq!(noisy.dimensions(), (32, 24));
    assert_ne!(noisy, denoised);
    assert_ne!(noisy, converged, "the pair is rendered at --denoise-spp, not --spp");
}
