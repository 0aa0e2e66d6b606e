//! Renders every example to `DIR/<name>.png`, one line per image with its
//! time and ray rate.
//!
//!     cargo run --release -p examples --bin tour -- --out out
//!
//! `--denoise` adds the denoiser's before and after where an example
//! writes its guides (cornell, bunny): the example rendered again at
//! `--denoise-spp` samples a pixel, through the runtime's tonemapper
//! without and with its denoiser (`cornell_noisy.png`,
//! `cornell_denoised.png`), beside the `--spp` render through the same
//! tonemapper (`cornell_converged.png`).

use clap::Parser;
use examples::{BackendChoice, EXAMPLES, Settings, progress_bar};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Render the worked examples.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Directory the PNGs are written to (created if missing).
    #[arg(long)]
    out: PathBuf,
    #[arg(long, default_value_t = Settings::DEFAULT_WIDTH)]
    width: u32,
    #[arg(long, default_value_t = Settings::DEFAULT_HEIGHT)]
    height: u32,
    /// Which backend renders. Without it: a GPU through wgpu when there is
    /// one, else the CPU backend (faster than Mesa's lavapipe; see
    /// BENCHMARKS.md); `RT_BACKEND=cpu|wgpu` also chooses.
    #[arg(long, value_enum)]
    backend: Option<BackendChoice>,
    /// Samples per pixel of the progressive examples (cornell, bunny).
    #[arg(long, default_value_t = Settings::DEFAULT_SPP)]
    spp: u32,
    /// Render only these examples (by name; repeatable).
    #[arg(long = "only")]
    only: Vec<String>,
    /// Also write, for the examples that write a denoiser's guides
    /// (cornell, bunny), `<name>_noisy.png` and `<name>_denoised.png`:
    /// the example at `--denoise-spp` through the runtime's tonemapper,
    /// without and with its denoiser (`examples::denoised`), and
    /// `<name>_converged.png`: the `--spp` render through the same
    /// tonemapper.
    #[arg(long)]
    denoise: bool,
    /// Samples per pixel of the `--denoise` pair.
    #[arg(long, default_value_t = 16)]
    denoise_spp: u32,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("tour: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> Result<(), String> {
    let (backend, what) = BackendChoice::open_or_choose(args.backend).map_err(|e| e.to_string())?;
    if let Some(unknown) = args.only.iter().find(|n| examples::example(n).is_none()) {
        let names: Vec<&str> = EXAMPLES.iter().map(|e| e.name).collect();
        return Err(format!("no example is called `{unknown}`; the examples are {}", names.join(", ")));
    }
    let settings = Settings { spp: args.spp, backend, ..Settings::new(args.width, args.height) };
    std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
    eprintln!(
        "tour: rendering {}x{} with {what}, {} spp for progressive examples",
        settings.width, settings.height, settings.spp
    );
    let start = Instant::now();
    let (mut total_rays, mut total_seconds) = (0u64, 0.0f64);
    for example in EXAMPLES.iter().filter(|e| args.only.is_empty() || args.only.iter().any(|n| n == e.name)) {
        let built = Instant::now();
        let mut scene = (example.build)(&settings).map_err(|e| format!("{}: {e}", example.name))?;
        let build_seconds = built.elapsed().as_secs_f64();
        let bar = (example.progressive && scene.frames > 1).then(|| progress_bar::spp_bar(example.name, scene.frames));
        let rendered = scene
            .render(&mut |p| {
                if let Some(bar) = &bar {
                    progress_bar::show(bar, p);
                }
            })
            .map_err(|e| format!("{}: {e}", example.name))?;
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
        let path = args.out.join(format!("{}.png", example.name));
        rendered.image.save_png(&path).map_err(|e| e.to_string())?;
        total_rays += rendered.rays;
        total_seconds += rendered.seconds;
        println!(
            "{:<12} {:>7.2} s {:>7.2} Mrays/s {:>11} rays  (scene {:.2} s)  {}",
            example.name,
            rendered.seconds,
            rendered.mrays_per_second(),
            rendered.rays,
            build_seconds,
            path.display()
        );
        if args.denoise {
            denoise(args, example, &settings, &mut scene).map_err(|e| format!("{}: {e}", example.name))?;
        }
        if !rendered.exceptions.is_empty() {
            let first = rendered.exceptions[0];
            eprintln!(
                "tour: {}: {} launch indices raised exceptions (first at {}: code {:#x}); they are painted magenta",
                example.name,
                rendered.exceptions.len(),
                first.launch_index,
                first.code
            );
        }
    }
    println!(
        "{:<12} {:>7.2} s {:>7.2} Mrays/s {:>11} rays  (wall {:.2} s)",
        "total",
        total_seconds,
        total_rays as f64 / total_seconds.max(1e-9) / 1e6,
        total_rays,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// `--denoise`: where `scene` (rendered at `--spp`) writes guides, its
/// picture through the tonemapper, and the example rendered again at
/// `--denoise-spp`, without and with the denoiser.
fn denoise(
    args: &Args,
    example: &examples::Example,
    settings: &Settings,
    scene: &mut examples::Scene,
) -> Result<(), examples::Error> {
    let Some(converged) = examples::denoised::tonemapped(scene)? else {
        return Ok(());
    };
    let low = Settings { spp: args.denoise_spp, ..*settings };
    let mut noisy_scene = (example.build)(&low)?;
    noisy_scene.render(&mut |_| {})?;
    let Some((noisy, denoised)) = examples::denoised::noisy_and_denoised(&mut noisy_scene)? else {
        return Ok(());
    };
    for (suffix, image) in [("noisy", noisy), ("denoised", denoised), ("converged", converged)] {
        let path = args.out.join(format!("{}_{suffix}.png", example.name));
        image.save_png(&path)?;
        println!("{:<12} {}", "", path.display());
    }
    Ok(())
}
