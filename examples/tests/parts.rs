//! A render in parts (`render --tile K/N`, then `render --merge`) gives the
//! whole render's image bit for bit, on the CPU backend and on wgpu; parts
//! that do not belong together, a missing or repeated part and a damaged
//! part file are refused by name with exit status 2 and no image.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("examples-parts-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn render(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render")).args(args).output().expect("render runs")
}

fn ok(out: Output) {
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
}

/// Refused by name: exit status 2, `text` on stderr, no `image`.
fn refused(out: Output, text: &str, image: &Path) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(text), "{err}");
    assert!(!image.exists());
}

fn floats(path: &Path) -> Vec<u32> {
    image::open(path).unwrap().to_rgba32f().into_raw().into_iter().map(f32::to_bits).collect()
}

/// The teapot at 40 x 44 (bands of 8 rows: 0..8, 8..24, 24..44 for three
/// parts), `spp` samples per pixel, on `backend`.
fn teapot_args<'a>(teapot: &'a str, backend: &'a str, spp: &'a str) -> Vec<&'a str> {
    vec![teapot, "--width", "40", "--height", "44", "--spp", spp, "--backend", backend]
}

fn parts_merge_to_the_whole_render(backend: &str) {
    let dir = temp_dir(backend);
    let teapot = examples::scene::shared_scene("teapot.obj");
    let teapot = teapot.to_str().unwrap();
    let whole = dir.join("whole.exr");
    ok(render(&[&teapot_args(teapot, backend, "3")[..], &["--out", whole.to_str().unwrap()]].concat()));
    let parts: Vec<PathBuf> = (0..3).map(|k| dir.join(format!("teapot.{k}.part"))).collect();
    for (k, part) in parts.iter().enumerate() {
        let tile = format!("{k}/3");
        let out = render(
            &[&teapot_args(teapot, backend, "3")[..], &["--tile", &tile, "--out", part.to_str().unwrap()]].concat(),
        );
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        ok(out);
        assert!(stdout.contains(&format!("(part {k} of 3: rows ")), "{stdout}");
    }
    let merged = dir.join("merged.exr");
    let paths: Vec<&str> = parts.iter().rev().map(|p| p.to_str().unwrap()).collect();
    ok(render(&[&["--merge"][..], &paths, &["--out", merged.to_str().unwrap()]].concat()));
    let (a, b) = (floats(&whole), floats(&merged));
    assert_eq!(a.len(), 40 * 44 * 4);
    assert!(a == b, "{backend}: the merged image differs from the whole render");
    // The teapot is in the picture, across the bands.
    assert!(a.chunks(4).map(|p| p[0]).collect::<std::collections::HashSet<_>>().len() > 20);

    // A missing part, a part twice, a part of another render, a damaged part.
    let png = dir.join("bad.png");
    refused(render(&["--merge", paths[0], paths[1], "--out", png.to_str().unwrap()]), "part 0 of 3 missing", &png);
    refused(
        render(&["--merge", paths[0], paths[1], paths[2], paths[0], "--out", png.to_str().unwrap()]),
        &format!("{}: it is part 2 of 3, as {} is", paths[0], paths[0]),
        &png,
    );
    let other = dir.join("other.part");
    ok(render(
        &[&teapot_args(teapot, backend, "1")[..], &["--tile", "1/3", "--out", other.to_str().unwrap()]].concat(),
    ));
    refused(
        render(&["--merge", paths[2], other.to_str().unwrap(), paths[0], "--out", png.to_str().unwrap()]),
        "its settings (",
        &png,
    );
    let mut bytes = std::fs::read(&parts[1]).unwrap();
    let last = bytes.len() - 1;
    bytes[last] ^= 1;
    let damaged = dir.join("damaged.part");
    std::fs::write(&damaged, &bytes).unwrap();
    refused(
        render(&["--merge", paths[2], damaged.to_str().unwrap(), paths[0], "--out", png.to_str().unwrap()]),
        "damaged.part: its pixels do not match their hash (the file is damaged)",
        &png,
    );
    std::fs::write(&damaged, &bytes[..bytes.len() - 16]).unwrap();
    refused(
        render(&["--merge", paths[2], damaged.to_str().unwrap(), paths[0], "--out", png.to_str().unwrap()]),
        "10224 bytes of pixels where rows 8..24 of 40 need 10240",
        &png,
    );
}

#[test]
fn parts_merge_to_the_whole_render_on_the_cpu_backend() {
    parts_merge_to_the_whole_render("cpu");
}

#[test]
fn parts_merge_to_the_whole_render_on_wgpu() {
    parts_merge_to_the_whole_render("wgpu");
}

#[test]
fn a_tile_that_does_not_fit_is_refused() {
    let dir = temp_dir("bad-tile");
    let teapot = examples::scene::shared_scene("teapot.obj");
    let part = dir.join("x.part");
    let args = |tile: &'static str| {
        vec![teapot.to_str().unwrap().to_string(), "--height".into(), "16".into(), "--tile".into(), tile.into()]
    };
    for (tile, text) in [
        ("3/3", "--tile 3/3: K must be below N (parts are numbered from 0)"),
        ("0/3", "--tile 0/3: 16 rows make at most 2 parts"),
        ("a/b", "--tile `a/b`: expected K/N"),
    ] {
        let mut a = args(tile);
        a.extend(["--out".into(), part.to_str().unwrap().into()]);
        let out = Command::new(env!("CARGO_BIN_EXE_render")).args(&a).output().unwrap();
        refused(out, text, &part);
    }
}

/// An EXR holds the mean radiance, linear; the PNG of the same render is
/// it gamma corrected, the 8-bit colours `to_rgba8` gives (to the bit on
/// the CPU backend); and parts merged to a PNG are the whole PNG.
#[test]
fn an_exr_holds_linear_radiance_and_the_png_its_display_colours() {
    let dir = temp_dir("linear");
    let teapot = examples::scene::shared_scene("teapot.obj");
    let args = teapot_args(teapot.to_str().unwrap(), "cpu", "2");
    let (exr, png) = (dir.join("whole.exr"), dir.join("whole.png"));
    ok(render(&[&args[..], &["--out", exr.to_str().unwrap()]].concat()));
    ok(render(&[&args[..], &["--out", png.to_str().unwrap()]].concat()));
    let linear = image::open(&exr).unwrap().to_rgba32f();
    let display = image::open(&png).unwrap().to_rgba8();
    let mut darker = 0;
    for (l, d) in linear.pixels().zip(display.pixels()) {
        assert_eq!(l[3], 1.0);
        for c in 0..3 {
            let q = (l[c].max(0.0).powf(1.0 / 2.2).clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
            assert_eq!(q, d[c], "the PNG is the EXR gamma corrected");
            darker += (l[c] > 0.01 && l[c] < 0.99 && l[c] * 255.0 + 1.0 < d[c] as f32) as usize;
        }
    }
    assert!(darker > 1000, "only {darker} channels are darker in linear than on display: not linear");

    let mut parts = Vec::new();
    for k in 0..3 {
        let part = dir.join(format!("p{k}.rtpart"));
        let tile = format!("{k}/3");
        ok(render(&[&args[..], &["--tile", &tile, "--out", part.to_str().unwrap()]].concat()));
        parts.push(part.to_str().unwrap().to_string());
    }
    let merged = dir.join("merged.png");
    let mut merge = vec!["--merge"];
    merge.extend(parts.iter().map(String::as_str));
    merge.extend(["--out", merged.to_str().unwrap()]);
    ok(render(&merge));
    assert_eq!(image::open(&merged).unwrap().to_rgba8(), display, "merged parts are the whole PNG");
}
