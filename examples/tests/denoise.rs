//! The denoiser's quality on the path-traced Cornell box at 128x128 on
//! the CPU backend, against a reference of [`REFERENCE_SPP`] samples a
//! pixel checked in as `tests/reference/cornell_reference_128.exr` (its
//! linear radiance; rendering it takes minutes in a release build, too
//! long for a debug test). To make it again (after a change meant to
//! change the Cornell box's picture) run, in release:
//!
//!     RT_BLESS=1 cargo test --release -p examples --test denoise
//!
//! At 4 and at 16 samples a pixel the denoised image's relative MSE must
//! be at least 6 times lower than the raw image's, with the per-pixel
//! variance the camera writes and with the denoiser's spatial estimate
//! alone, and the gradients
//! across the picture's geometric edges (where the first hit's normal
//! turns) and across its sharpest shadow edges (on the floor, one
//! surface) must stay within 20% of the reference's. Each test prints its
//! figures (`--nocapture`).

use examples::{Aovs, Settings, cornell};
use glam::{Vec3, Vec4, Vec4Swizzles};
use rt_runtime::postprocess::denoise::luminance;
use rt_runtime::{Backend, BufferType, Context, StageKind};
use std::path::PathBuf;

const W: u32 = 128;
const H: u32 = 128;
/// Samples a pixel of the reference.
const REFERENCE_SPP: u32 = 4096;
/// Pixels either side of an edge its gradient is taken over.
const D: u32 = 2;

fn reference_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference/cornell_reference_128.exr")
}

/// The Cornell box at `spp` on the CPU backend: its context (for the
/// denoiser to run in), the guides it wrote and the mean radiance.
fn render(spp: u32) -> (Context, Aovs, Vec<Vec4>) {
    let settings = Settings { backend: Backend::Cpu, ..Settings::new(W, H).with_spp(spp) };
    let mut scene = cornell::scene(&settings).unwrap();
    scene.render(&mut |_| {}).unwrap();
    let aovs = scene.aovs.expect("the Cornell box writes its guides");
    let radiance = scene.ctx.read_buffer::<Vec4>(aovs.radiance).unwrap();
    (scene.ctx, aovs, radiance)
}

/// The reference's linear radiance, rendered and written first when
/// `RT_BLESS=1`.
fn reference() -> Vec<Vec4> {
    let path = reference_path();
    if std::env::var("RT_BLESS").as_deref() == Ok("1") {
        let (_, _, radiance) = render(REFERENCE_SPP);
        std::fs::write(&path, rt_runtime::image_out::encode_exr(W, H, &radiance).unwrap()).unwrap();
    }
    let img = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).into_rgba32f();
    assert_eq!(img.dimensions(), (W, H), "{}", path.display());
    // The file's row 0 is the top; launch row 0 is the bottom.
    (0..H).flat_map(|y| (0..W).map(move |x| (x, y))).map(|(x, y)| Vec4::from(img.get_pixel(x, H - 1 - y).0)).collect()
}

/// The denoiser run on the render's context over its guides, and over
/// its per-pixel variance when `with_variance` (else the denoiser
/// estimates the variance from the neighbouring pixels).
fn denoise(ctx: &mut Context, aovs: Aovs, with_variance: bool) -> Vec<Vec4> {
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, W, H).unwrap();
    let stage = ctx.create_postprocessing_stage(StageKind::Denoiser);
    ctx.set_stage_var(stage, "input_buffer", aovs.radiance).unwrap();
    ctx.set_stage_var(stage, "input_albedo_buffer", aovs.albedo).unwrap();
    ctx.set_stage_var(stage, "input_normal_buffer", aovs.normal).unwrap();
    ctx.set_stage_var(stage, "output_buffer", out).unwrap();
    if with_variance {
        ctx.set_stage_var(stage, "input_variance_buffer", aovs.variance).unwrap();
    }
    ctx.run_stage(stage, W, H).unwrap();
    ctx.read_buffer::<Vec4>(out).unwrap()
}

/// Relative MSE: the mean over pixels and channels of `(x - r)^2 / (r^2 +
/// 0.01)`.
fn rel_mse(img: &[Vec4], reference: &[Vec4]) -> f64 {
    let mut sum = 0.0f64;
    for (x, r) in img.iter().zip(reference) {
        let (x, r) = (x.xyz(), r.xyz());
        sum += ((x - r) * (x - r) / (r * r + Vec3::splat(0.01))).element_sum() as f64;
    }
    sum / (img.len() * 3) as f64
}

/// The edges to keep sharp: pixels `(x, y)` whose neighbours `D` to the
/// left and right see different surfaces (normals apart), and floor pixels
/// between floor pixels where the reference's luminance changes most
/// across (shadow edges: the 24 strongest).
fn edges(reference: &[Vec4], normal: &[Vec4]) -> (Vec<usize>, Vec<usize>) {
    let (mut geometric, mut shadow) = (Vec::new(), Vec::new());
    for y in 0..H {
        for x in D..W - D {
            let p = (y * W + x) as usize;
            let (l, r) = (p - D as usize, p + D as usize);
            let (nl, nr) = (normal[l].xyz().normalize_or_zero(), normal[r].xyz().normalize_or_zero());
            if nl != Vec3::ZERO && nr != Vec3::ZERO && nl.dot(nr) < 0.5 {
                geometric.push(p);
            }
            if (l..=r).all(|q| normal[q].y > 0.99) {
                shadow.push(p);
            }
        }
    }
    shadow.sort_by(|&a, &b| gradient(reference, b).total_cmp(&gradient(reference, a)));
    shadow.truncate(24);
    (geometric, shadow)
}

/// The luminance gradient across pixel `p`, left to right.
fn gradient(img: &[Vec4], p: usize) -> f32 {
    (luminance(img[p + D as usize].xyz()) - luminance(img[p - D as usize].xyz())).abs() / (2 * D) as f32
}

fn mean_gradient(img: &[Vec4], pixels: &[usize]) -> f32 {
    pixels.iter().map(|&p| gradient(img, p)).sum::<f32>() / pixels.len() as f32
}

fn check(spp: u32) {
    let reference = reference();
    let (mut ctx, aovs, raw) = render(spp);
    let normal = ctx.read_buffer::<Vec4>(aovs.normal).unwrap();
    let (geometric, shadow) = edges(&reference, &normal);
    assert!(geometric.len() > 100, "{} geometric edge pixels", geometric.len());
    let raw_error = rel_mse(&raw, &reference);
    for (with_variance, variance) in [(true, "per-pixel variance"), (false, "spatial variance estimate")] {
        let denoised = denoise(&mut ctx, aovs, with_variance);
        let denoised_error = rel_mse(&denoised, &reference);
        let report = format!(
            "{spp} spp, {variance}: relative MSE raw {raw_error:.5}, denoised {denoised_error:.5} ({:.1}x lower); geometric edges' gradient {:.4} vs reference {:.4}; shadow edges' {:.4} vs {:.4}",
            raw_error / denoised_error,
            mean_gradient(&denoised, &geometric),
            mean_gradient(&reference, &geometric),
            mean_gradient(&denoised, &shadow),
            mean_gradient(&reference, &shadow),
        );
        println!("{report}");
        assert!(denoised_error * 6.0 <= raw_error, "{report}");
        for pixels in [&geometric, &shadow] {
            let (got, want) = (mean_gradient(&denoised, pixels), mean_gradient(&reference, pixels));
            assert!((got - want).abs() <= 0.2 * want, "{report}");
        }
    }
}

#[test]
fn at_4_spp_the_denoised_error_is_6x_lower_and_edges_stay_sharp() {
    check(4);
}

#[test]
fn at_16_spp_the_denoised_error_is_6x_lower_and_edges_stay_sharp() {
    check(16);
}

/// The same stage on the wgpu backend (its WGSL passes on the device)
/// gives the CPU's denoised Cornell box within 1e-3 relative, guided by
/// the per-pixel variance.
#[test]
fn the_wgpu_denoiser_agrees_with_the_cpu_on_the_cornell_box() {
    let (mut ctx, aovs, _) = render(4);
    let cpu = denoise(&mut ctx, aovs, true);
    ctx.set_backend(Backend::Wgpu);
    let gpu = denoise(&mut ctx, aovs, true);
    let mut worst = 0.0f32;
    for (c, g) in cpu.iter().zip(&gpu) {
        worst = worst.max(((*c - *g).abs() / c.abs().max(Vec4::splat(0.01))).max_element());
    }
    println!("largest relative difference, cpu against wgpu: {worst:e}");
    assert!(worst <= 1e-3, "{worst}");
}

/// The tour's `--denoise` pair (`examples::denoised`, a command list of
/// the denoiser and two tonemappers): the denoised picture is nearer the
/// tonemapped reference than the noisy one; a scene without guides gives
/// no pair.
#[test]
fn the_tours_denoised_pair_is_nearer_the_reference_than_the_noisy_picture() {
    use rt_runtime::postprocess::tonemap::tonemap_pixel;
    let reference: Vec<Vec4> =
        reference().iter().map(|&p| tonemap_pixel(p, examples::denoised::EXPOSURE, 2.2)).collect();
    let settings = Settings { backend: Backend::Cpu, ..Settings::new(W, H).with_spp(4) };
    let mut scene = cornell::scene(&settings).unwrap();
    scene.render(&mut |_| {}).unwrap();
    let (noisy, denoised) = examples::denoised::noisy_and_denoised(&mut scene).unwrap().expect("cornell has guides");
    let mse = |img: &[Vec4]| img.iter().zip(&reference).map(|(a, b)| (*a - *b).xyz().length_squared()).sum::<f32>();
    let (noisy_error, denoised_error) = (mse(&noisy.pixels), mse(&denoised.pixels));
    println!("display MSE: noisy {noisy_error:.3}, denoised {denoised_error:.3}");
    assert!(denoised_error * 4.0 < noisy_error, "noisy {noisy_error}, denoised {denoised_error}");
    let mut plain = examples::normal::scene(&settings).unwrap();
    assert!(examples::denoised::noisy_and_denoised(&mut plain).unwrap().is_none());
}
