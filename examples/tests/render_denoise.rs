//! `render --denoise` and `render --aov DIR` as a user runs them: the
//! denoised picture differs from the raw one and is nearer a render of
//! many more samples (its relative MSE at least a fifth lower: about a
//! third lower measured, the reference's own noise included); the guides are written as OpenEXR beside it (the
//! floor's albedo and normal where the floor is seen); flags that need
//! the whole picture refuse `--tile` and `--merge` with exit status 2, one
//! line, and nothing written.

use examples::bunny::{BACKGROUND, FLOOR_KD};
use examples::scene::shared_scene;
use glam::{Vec3, Vec4, Vec4Swizzles};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A small picture, seen from low enough that the sky shows above the
/// floor's far edge.
/// (Much smaller, the teapot's contact shadow, a few pixels, is most of
/// the picture's error, and the denoiser's widest taps blur it.)
const VIEW: [&str; 6] = ["--width", "128", "--height", "96", "--elevation", "3"];

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("render-denoise-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn render(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render")).args(args).output().expect("render runs")
}

/// Renders the teapot at `spp` on the CPU backend to `out`, with `extra`
/// flags, and checks that it succeeded; its stdout.
fn teapot(out: &Path, spp: u32, extra: &[&str]) -> String {
    let model = shared_scene("teapot.obj");
    let spp = spp.to_string();
    let mut args = vec![model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--spp", &spp, "--backend", "cpu"];
    args.extend(VIEW);
    args.extend(extra);
    let result = render(&args);
    let stdout = String::from_utf8_lossy(&result.stdout).into_owned();
    assert!(result.status.success(), "{args:?}: {stdout}{}", String::from_utf8_lossy(&result.stderr));
    stdout
}

/// An OpenEXR file's pixels, top row first.
fn read_exr(path: &Path) -> (u32, u32, Vec<Vec4>) {
    let image = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).into_rgba32f();
    let (w, h) = image.dimensions();
    (w, h, image.pixels().map(|p| Vec4::from(p.0)).collect())
}

/// Relative MSE: the mean over pixels and channels of `(x - r)^2 / (r^2 +
/// 0.01)`.
fn rel_mse(img: &[Vec4], reference: &[Vec4]) -> f64 {
    let sum: f64 = img
        .iter()
        .zip(reference)
        .map(|(x, r)| ((x.xyz() - r.xyz()).powf(2.0) / (r.xyz() * r.xyz() + Vec3::splat(0.01))).element_sum() as f64)
        .sum();
    sum / (img.len() * 3) as f64
}

#[test]
fn denoise_brings_a_few_samples_nearer_many_and_aov_writes_the_guides() {
    let dir = temp_dir("quality");
    let (raw, denoised, reference) = (dir.join("raw.exr"), dir.join("denoised.exr"), dir.join("reference.exr"));
    let aov = dir.join("aov");
    teapot(&raw, 2, &[]);
    let said = teapot(&denoised, 2, &["--denoise", "--aov", aov.to_str().unwrap()]);
    teapot(&reference, 32, &[]);
    assert!(said.contains("2 spp denoised"), "{said}");
    let (_, _, raw) = read_exr(&raw);
    let (_, _, denoised) = read_exr(&denoised);
    let (_, _, reference) = read_exr(&reference);
    let (raw_error, denoised_error) = (rel_mse(&raw, &reference), rel_mse(&denoised, &reference));
    eprintln!("relative MSE against 32 spp: raw {raw_error:.5}, denoised {denoised_error:.5}");
    assert_ne!(raw, denoised, "the denoiser changed nothing");
    assert!(denoised_error < raw_error * 0.8, "raw {raw_error}, denoised {denoised_error}");

    // The guides, named after `--out`, at the picture's size.
    let mut files: Vec<_> =
        std::fs::read_dir(&aov).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    files.sort();
    assert_eq!(files, ["denoised_albedo.exr", "denoised_normal.exr"]);
    let (w, h, albedo) = read_exr(&aov.join("denoised_albedo.exr"));
    let (nw, nh, normal) = read_exr(&aov.join("denoised_normal.exr"));
    assert_eq!(((w, h), (nw, nh)), ((128, 96), (128, 96)));
    let near = |a: Vec3, b: Vec3| (a - b).abs().max_element() < 1e-5;
    // Where both samples saw the floor: its colour and its normal, +Y.
    let floor = albedo.iter().zip(&normal).filter(|(a, n)| near(a.xyz(), FLOOR_KD) && near(n.xyz(), Vec3::Y));
    assert!(floor.count() > 48, "the floor is seen in the guides");
    // Where both saw the sky: its colour, and no normal.
    let sky = albedo.iter().zip(&normal).filter(|(a, n)| near(a.xyz(), BACKGROUND) && n.xyz() == Vec3::ZERO);
    assert!(sky.count() > 0, "the sky is seen in the guides");
    for n in &normal {
        assert!(n.xyz().length() <= 1.0 + 1e-4 && n.w == 1.0, "{n}");
    }
}

/// `render ARGS` is refused: exit status 2, the one line `message`, and
/// nothing in `dir`.
fn refused(dir: &Path, args: &[&str], message: &str) {
    let result = render(args);
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "one line expected:\n{err}");
    assert_eq!(err.trim_end(), message);
    assert_eq!(std::fs::read_dir(dir).unwrap().count(), 0, "{args:?} wrote something");
}

#[test]
fn denoise_and_aov_refuse_parts() {
    let dir = temp_dir("refused");
    let model = shared_scene("teapot.obj");
    let (model, out) = (model.to_str().unwrap(), dir.join("out.png"));
    let (out, aov) = (out.to_str().unwrap(), dir.join("aov"));
    let aov = aov.to_str().unwrap();
    refused(
        &dir,
        &[model, "--out", out, "--tile", "0/2", "--denoise"],
        "render: --denoise cannot go with --tile: it needs the whole picture (the denoiser reads each pixel's \
         neighbours, which other parts render); render without --tile",
    );
    refused(
        &dir,
        &[model, "--out", out, "--tile", "1/2", "--aov", aov],
        "render: --aov cannot go with --tile: it writes the whole picture's guides; render without --tile",
    );
    refused(
        &dir,
        &["--merge", "a.part", "b.part", "--out", out, "--aov", aov],
        "render: --aov cannot go with --merge: part files hold the radiance only; render the whole picture with \
         --aov instead",
    );
    refused(
        &dir,
        &["--merge", "a.part", "--out", out, "--denoise"],
        "render: --denoise cannot go with --merge: part files hold the radiance only; render the whole picture \
         with --denoise instead",
    );
}
