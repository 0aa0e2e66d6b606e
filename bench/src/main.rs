//! `rt-bench`: the project's backends on a primary + ambient-occlusion
//! workload in the style of tray_racing, over four scenes, against obvhs,
//! Embree and hand-written WGSL kernels measured in the same run.
//!
//! `cargo run --release -p rt-bench -- [--quick] [--json] [--plot DIR]`, or
//! `-- --from FILE.json --plot DIR` to chart an earlier `--json` run
//! without measuring (`plot.rs`).
//!
//! - Scenes: the bunny, the teapot and the Cornell box from
//!   `../shared/scenes`, and a generated wall of 30 bunnies (2,083,530
//!   triangles, one flat mesh), each with a camera framed from its bounds.
//! - Workload: per pixel one primary ray and, at each hit, one
//!   cosine-weighted ambient-occlusion ray (closest hit, unbounded);
//!   Mrays/s counts the rays actually traced.
//! - Peers: obvhs's own CWBVH traversal (rayon, same threads), Embree 3's
//!   `rtcIntersect1` (loaded at run time, see `embree.rs`), a hand-written
//!   WGSL kernel on the same adapter as the megakernel (`handwritten.rs`),
//!   obvhs's direct build against our end-to-end build.
//! - Also: primary rays on the bunny per backend, the tour's megakernel
//!   link and pipeline times (`tour.rs`), lowering time per program
//!   (`lowering.rs`), the denoiser's time per megapixel and against a
//!   1-spp launch (`denoise.rs`).
//!
//! Every ratio compares figures measured in this run, on this machine;
//! higher is better for us.
//!
//! The run, by file: the command line (`cli.rs`); the workload's programs
//! and its context (`programs.rs`); repeated launches and what they
//! measured (`launches.rs`); the bunny's primary rays and build
//! (`bunny.rs`); each scene's CPU side and peers (`measure.rs`), its wgpu
//! side (`gpu.rs`, `rayquery.rs`; `setup.rs` for `--setup-only`); the CPU
//! launches alone for a profiler (`profile.rs`, `--profile-cpu`); the figures and the headline ratios
//! reported from them (`figures.rs`).

// The runtime's errors name programs and scopes; size does not matter here.
#![allow(clippy::result_large_err)]

mod bunny;
mod cli;
mod denoise;
mod embree;
mod figures;
mod gpu;
mod handwritten;
mod handwritten_rayquery;
mod json;
mod launches;
mod lowering;
mod measure;
mod peers;
mod plot;
mod profile;
mod programs;
mod rayquery;
mod scenes;
mod setup;
mod tour;

use clap::Parser;
use cli::Args;
use json::Json;
use std::path::{Path, PathBuf};
use std::time::Instant;

fn main() {
    let args = Args::parse();
    if let (Some(file), Some(dir)) = (&args.from, &args.plot) {
        plot_or_exit(plot::read(file), dir);
        return;
    }
    if let Some(b) = args.backends.iter().find(|b| *b != "cpu" && *b != "wgpu") {
        eprintln!("unknown backend `{b}` (cpu or wgpu)");
        std::process::exit(2);
    }
    // Before any thread exists (rayon and wgpu start later).
    let shader_cache = fresh_shader_cache(&args);
    let (width, height) = args.resolution();
    let reps = args.reps();
    let wgpu_max_triangles = args.wgpu_max_triangles.unwrap_or(usize::MAX);
    let all = load_scenes_or_exit();
    if let Some(launches) = args.profile_cpu {
        let scene = all.iter().find(|s| args.measures_scene(s.name)).unwrap_or(&all[0]);
        if let Err(e) = profile::profile_cpu(scene, (width, height), launches) {
            eprintln!("rt-bench: {e}");
            std::process::exit(1);
        }
        return;
    }
    let start = Instant::now();
    let mut json = Json::obj();
    record_machine(&args, (width, height), reps, &mut json);
    let embree = load_embree(&args, &mut json);

    let only = args.traversal_only || args.setup_only;
    if args.measures_scene("bunny") && !only {
        bunny::bunny_primary(&args, &all[0], width, height, reps, &mut json);
    }
    let mut scene_figures = Vec::new();
    for scene in all.iter().filter(|s| args.measures_scene(s.name)) {
        let j = json.child("scenes").child(scene.name);
        let f = measure::measure_scene(&args, scene, embree.as_ref().ok(), width, height, reps, wgpu_max_triangles, j);
        scene_figures.push((scene.name, f));
    }
    figures::record_ratios(&mut json, &scene_figures);

    if !only {
        let backends: Vec<_> = ["cpu", "wgpu"]
            .into_iter()
            .filter(|b| args.measures(b))
            .filter_map(rt_runtime::Backend::from_name)
            .collect();
        denoise::measure(&backends, (width, height), reps, json.child("denoise"));
        lowering::measure(if args.quick { 5 } else { 20 }, json.child("lowering"));
    }
    // The tour's program sets on the wgpu backend.
    if args.measures("wgpu") && !args.setup_only {
        let names = args.tour_link_names();
        eprintln!();
        tour::measure(&names, json.child("tour_links"));
    }
    if !args.warm_shader_cache {
        let _ = std::fs::remove_dir_all(&shader_cache);
    }
    json.set("seconds", start.elapsed().as_secs_f64());
    eprintln!("\ndone in {:.1} s", start.elapsed().as_secs_f64());
    if args.json {
        println!("{json}");
    }
    if let Some(dir) = &args.plot {
        let run = serde_json::from_str(&json.to_string()).expect("the bench's JSON reads back");
        plot_or_exit(plot::figures(&run), dir);
    }
}

/// The path of a fresh Mesa shader cache for this run, which `main`
/// removes at its end, given to Mesa unless `--warm-shader-cache`: the
/// first compile of each kernel is cold (what the link figures report),
/// and the same kernel over the next scene is not compiled again. To be
/// called before any thread exists.
fn fresh_shader_cache(args: &Args) -> PathBuf {
    let shader_cache = std::env::temp_dir().join(format!("rt-bench-mesa-cache-{}", std::process::id()));
    if !args.warm_shader_cache {
        // SAFETY: set before any thread exists (rayon and wgpu start later).
        unsafe { std::env::set_var("MESA_SHADER_CACHE_DIR", &shader_cache) };
    }
    shader_cache
}

/// The bench's scenes ([`scenes::load_all`]), or says why not and exits
/// with status 2.
fn load_scenes_or_exit() -> Vec<scenes::BenchScene> {
    let dir = scenes::scenes_dir().unwrap_or_else(|e| {
        eprintln!("rt-bench: {e}");
        std::process::exit(2);
    });
    scenes::load_all(&dir).unwrap_or_else(|e| {
        eprintln!("rt-bench: {e}");
        std::process::exit(2);
    })
}

/// The machine and the run's settings into `json`'s `machine`.
fn record_machine(args: &Args, (width, height): (u32, u32), reps: usize, json: &mut Json) {
    let machine = json.child("machine");
    machine.set("threads", rayon::current_num_threads());
    machine.set("resolution", format!("{width}x{height}"));
    machine.set("reps", reps);
    machine.set(
        "mesa_shader_cache",
        if args.warm_shader_cache {
            "the user's (link times may be warm)"
        } else {
            "fresh for this run (first compile of each kernel cold)"
        },
    );
}

/// Embree (unless `--no-embree`), its version and API into `json`'s
/// `embree`, or why it is absent.
fn load_embree(args: &Args, json: &mut Json) -> Result<embree::Embree, String> {
    let embree = if args.no_embree { Err("--no-embree".to_string()) } else { embree::Embree::load(!args.no_install) };
    match &embree {
        Ok(e) => {
            eprintln!(
                "embree {} ({}): rtcIntersect1 and rtcIntersect16, its own BVH (medium build quality)",
                e.version, e.library
            );
            let j = json.child("embree");
            j.set("version", e.version.as_str());
            j.set("library", e.library.as_str());
            j.set(
                "api",
                "the faster of rtcIntersect1 (single rays) and rtcIntersect16 (4x4 tiles: primary rays, then their AO rays), its own BVH (RTC_BUILD_QUALITY_MEDIUM), rayon threads",
            );
        }
        Err(why) => {
            eprintln!("embree: absent: {why}");
            json.set("embree", Json::Null);
            json.set("embree_absent_reason", why.as_str());
        }
    }
    embree
}

/// Writes the charts of `figures` into `dir`, or says why not and exits
/// with status 2.
fn plot_or_exit(figures: Result<plot::Figures, String>, dir: &Path) {
    match figures.and_then(|f| plot::write(&f, dir)) {
        Ok(paths) => paths.iter().for_each(|p| eprintln!("plot: {}", p.display())),
        Err(e) => {
            eprintln!("rt-bench: {e}");
            std::process::exit(2);
        }
    }
}
