//! Golden images: every tour example rendered at 64x48 (4 samples per pixel
//! for the progressive ones) and compared with the PNG checked in under
//! `tests/golden/`, by the project's differential rule: at least 99.9% of
//! the 8-bit channels within 2/255 of the golden, none beyond 16/255.
//!
//! The goldens come from the CPU backend; to make them again (after a
//! change that is meant to change a picture) run
//!
//!     RT_BLESS=1 cargo test -p examples --test golden
//!
//! and look at every changed PNG before checking it in. While blessing, the
//! wgpu tests compare with a fresh CPU render instead of the files.
//!
//! Every example runs on the CPU backend. Random numbers come from a hash of
//! the launch index and the frame (`tea4`), so even the progressive
//! examples (cornell, bunny) are deterministic and the same on both
//! backends: no example needs a denoised statistic, each is compared pixel
//! by pixel.
//!
//! Every example is checked on the wgpu backend too, with each traversal:
//! the compute traversal (`wgpu::*`) and hardware ray queries
//! (`rayquery::*`, where the adapter has them: lavapipe from Mesa 25). The first launch of a
//! process compiles the megakernel; where per-depth clones would be many,
//! programs that trace run from one loop in their resumable form
//! (rt-compiler's `func/resume.rs`), so the kernel holds each program and
//! the traversal once, whatever the trace depth.
//! Before, per-depth clones of every program that traces were inlined by
//! Mesa into each other (reflections took 217 s to link, instances 267 s,
//! convex_hull ran out of 24 GiB of memory). Each test below on the 2-core
//! CI-class VM with `MESA_SHADER_CACHE_DISABLE=true`, other builds running
//! (load average 4-5), 2026-11-23, build and render included:
//!
//! | example | wgpu test |
//! | --- | --- |
//! | normal | 8.6 s |
//! | shadows | 11.7 s |
//! | reflections | 35.8 s |
//! | envmap | 49.1 s |
//! | convex_hull | 83.0 s |
//! | cornell | 22.0 s |
//! | bunny | 20.4 s |
//! | instances | 20.6 s |
//!
//! An example that cannot run on wgpu goes in the `skipped` list with its
//! reason (an `#[ignore]`d test); none does now.

use examples::{EXAMPLES, Image, Settings};
use image::RgbaImage;
use rt_runtime::{Backend, Traversal};
use std::path::PathBuf;
use std::time::Instant;

const W: u32 = 64;
const H: u32 = 48;
/// Launches of the progressive examples: enough to show the picture, few
/// enough to stay cheap in a debug build.
const SPP: u32 = 4;

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden").join(format!("{name}.png"))
}

/// A backend and, on wgpu, its traversal.
#[derive(Clone, Copy)]
struct Target(Backend, Traversal);

const CPU: Target = Target(Backend::Cpu, Traversal::Auto);
const COMPUTE: Target = Target(Backend::Wgpu, Traversal::Compute);
const RAY_QUERY: Target = Target(Backend::Wgpu, Traversal::RayQuery);

impl Target {
    fn name(self) -> &'static str {
        match self {
            Target(Backend::Cpu, _) => "cpu",
            Target(_, Traversal::RayQuery) => "rayquery",
            _ => "compute",
        }
    }

    /// Whether it runs here: ray queries need an adapter with them (without
    /// one the test passes with a note, or fails when
    /// `RT_REQUIRE_RAY_QUERY=1`, as scripts/test.sh sets with Mesa 25).
    fn available(self) -> bool {
        if self.1 != Traversal::RayQuery || rt_runtime::backend::wgpu::probe_ray_queries() {
            return true;
        }
        assert!(
            std::env::var("RT_REQUIRE_RAY_QUERY").as_deref() != Ok("1"),
            "RT_REQUIRE_RAY_QUERY=1 but the adapter has no ray queries"
        );
        eprintln!("skipped: the adapter has no ray queries");
        false
    }
}

fn blessing() -> bool {
    std::env::var("RT_BLESS").is_ok_and(|v| !v.is_empty() && v != "0")
}

/// `name` rendered on `backend`, without exceptions.
fn render(name: &str, backend: Target) -> Image {
    let example = examples::example(name).unwrap_or_else(|| panic!("no example {name}"));
    let settings = Settings { spp: SPP, backend: backend.0, traversal: backend.1, ..Settings::new(W, H) };
    let start = Instant::now();
    let mut scene = (example.build)(&settings).unwrap_or_else(|e| panic!("{name}: {e}"));
    let rendered = scene.render(&mut |_| {}).unwrap_or_else(|e| panic!("{name} on {}: {e}", backend.name()));
    eprintln!(
        "golden: {name} on {}: {} launches in {:.2} s ({:.2} s with the scene build)",
        backend.name(),
        rendered.launches,
        rendered.seconds,
        start.elapsed().as_secs_f64()
    );
    assert!(
        rendered.exceptions.is_empty(),
        "{name} on {} raised {} exceptions, the first {:?}",
        backend.name(),
        rendered.exceptions.len(),
        &rendered.exceptions[..rendered.exceptions.len().min(3)]
    );
    rendered.image
}

/// The picture as the PNG holds it: 8 bits a channel, top row first.
fn rgba8(image: &Image) -> RgbaImage {
    rt_runtime::image_out::to_rgba8(image.width, image.height, &image.pixels)
}

/// The golden of `name`; while blessing, a fresh CPU render instead (the
/// CPU test may be rewriting the file).
fn golden(name: &str) -> RgbaImage {
    if blessing() {
        return rgba8(&render(name, CPU));
    }
    let path = golden_path(name);
    image::open(&path)
        .unwrap_or_else(|e| {
            panic!("{}: {e}; make the goldens with `RT_BLESS=1 cargo test -p examples --test golden`", path.display())
        })
        .to_rgba8()
}

/// The differential rule, or what breaks it: the worst pixels with their
/// PNG position (top-left origin), launch index and both values. The
/// rendered picture is saved for a look.
fn compare(name: &str, backend: Target, want: &RgbaImage, got: &RgbaImage) -> Result<(), String> {
    let what = format!("{name} on {}", backend.name());
    if want.dimensions() != got.dimensions() {
        return Err(format!("{what}: rendered {:?}, golden {:?}", got.dimensions(), want.dimensions()));
    }
    let diffs: Vec<u8> = want.as_raw().iter().zip(got.as_raw()).map(|(a, b)| a.abs_diff(*b)).collect();
    let beyond_2 = diffs.iter().filter(|d| **d > 2).count();
    let max = diffs.iter().copied().max().unwrap_or(0);
    eprintln!("golden: {what}: max difference {max}/255, {beyond_2} of {} channels beyond 2/255", diffs.len());
    if beyond_2 * 1000 <= diffs.len() && max <= 16 {
        return Ok(());
    }
    let mut worst: Vec<(u8, u32, u32)> = got
        .enumerate_pixels()
        .map(|(x, y, p)| {
            let d = (0..4).map(|c| p.0[c].abs_diff(want.get_pixel(x, y).0[c])).max().unwrap_or(0);
            (d, x, y)
        })
        .filter(|(d, ..)| *d > 2)
        .collect();
    worst.sort_by(|a, b| b.0.cmp(&a.0).then((a.2, a.1).cmp(&(b.2, b.1))));
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("golden");
    let saved = std::fs::create_dir_all(&dir)
        .and_then(|()| got.save(dir.join(format!("{name}-{}.png", backend.name()))).map_err(std::io::Error::other))
        .map_or_else(
            |e| format!("(could not save the render: {e})"),
            |()| format!("render saved in {}", dir.display()),
        );
    let mut message = format!(
        "{what} differs from {}: {beyond_2} of {} channels beyond 2/255 (at most {} allowed), max {max}/255 \
         (16 allowed); {} pixels differ by more than 2/255, the worst:",
        golden_path(name).display(),
        diffs.len(),
        diffs.len() / 1000,
        worst.len()
    );
    for &(d, x, y) in worst.iter().take(12) {
        message += &format!(
            "\n  png ({x}, {y}) = launch index ({x}, {}): golden {:?}, rendered {:?} (off by {d})",
            H - 1 - y,
            want.get_pixel(x, y).0,
            got.get_pixel(x, y).0
        );
    }
    Err(format!("{message}\n{saved}"))
}

/// Renders `name` on `backend` and compares it with its golden.
fn check(name: &str, backend: Target) {
    if !backend.available() {
        return;
    }
    let got = rgba8(&render(name, backend));
    if let Err(e) = compare(name, backend, &golden(name), &got) {
        panic!("{e}");
    }
}

/// Every example on the CPU backend (and, with `RT_BLESS`, writes the
/// goldens). All failures are reported together.
#[test]
fn cpu_renders_match_the_goldens() {
    let mut failures = Vec::new();
    for example in &EXAMPLES {
        let image = render(example.name, CPU);
        if blessing() {
            let path = golden_path(example.name);
            std::fs::create_dir_all(path.parent().expect("a parent")).expect("the golden directory");
            image.save_png(&path).unwrap_or_else(|e| panic!("{e}"));
            eprintln!("golden: wrote {}", path.display());
            continue;
        }
        if let Err(e) = compare(example.name, CPU, &golden(example.name), &rgba8(&image)) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// Every golden belongs to an example (no stale files), and every example
/// is either checked on wgpu or skipped there with a reason.
#[test]
fn goldens_and_wgpu_lists_cover_exactly_the_examples() {
    let names: Vec<&str> = EXAMPLES.iter().map(|e| e.name).collect();
    let mut listed: Vec<&str> = WGPU_CHECKED.iter().copied().chain(WGPU_SKIPPED.iter().map(|(n, _)| *n)).collect();
    listed.sort_unstable();
    let mut sorted = names.clone();
    sorted.sort_unstable();
    assert_eq!(listed, sorted, "each example is in exactly one of the wgpu lists");
    if blessing() {
        return;
    }
    let dir = golden_path("x").parent().expect("a parent").to_path_buf();
    for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let file = entry.expect("a directory entry").file_name().to_string_lossy().into_owned();
        let stem = file.strip_suffix(".png").unwrap_or_else(|| panic!("{file} in {} is not a PNG", dir.display()));
        assert!(names.contains(&stem), "{file} in {} is no example's golden", dir.display());
    }
}

/// The wgpu tests: `checked` run with every `cargo test`, `skipped` are
/// ignored with their reason (see the module documentation).
macro_rules! wgpu_goldens {
    (checked: [$($checked:ident),* $(,)?], skipped: [$($skipped:ident: $why:literal),* $(,)?] $(,)?) => {
        const WGPU_CHECKED: &[&str] = &[$(stringify!($checked)),*];
        const WGPU_SKIPPED: &[(&str, &str)] = &[$((stringify!($skipped), $why)),*];
        mod wgpu {
            use super::*;
            $(
                #[test]
                fn $checked() {
                    check(stringify!($checked), COMPUTE);
                }
            )*
            $(
                #[test]
                #[ignore = $why]
                fn $skipped() {
                    check(stringify!($skipped), COMPUTE);
                }
            )*
        }
        mod rayquery {
            use super::*;
            $(
                #[test]
                fn $checked() {
                    check(stringify!($checked), RAY_QUERY);
                }
            )*
            $(
                #[test]
                #[ignore = $why]
                fn $skipped() {
                    check(stringify!($skipped), RAY_QUERY);
                }
            )*
        }
    };
}

wgpu_goldens! {
    checked: [
        normal, diffuse, phong, shadows, reflections, envmap, convex_hull, cornell, bunny, instances, receiver_grid,
        callable_brdfs, motion_blur,
    ],
    skipped: [],
}
