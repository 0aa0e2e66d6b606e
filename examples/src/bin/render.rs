//! Renders any OBJ file the way the `bunny` example shows the bunny: framed
//! from its bounds, on a floor, under a key light with shadows and ambient
//! occlusion, each `.mtl` material in its diffuse colour (else grey).
//!
//!     cargo run --release -p examples --bin render -- MESH.obj --out OUT.png
//!
//! Exit status: 0 with the PNG written; 2 for bad input (the mesh: one line
//! naming the file, the line when known and the problem; or arguments, such
//! as a backend with no adapter), and no PNG; 1 if rendering or writing
//! failed.

use clap::Parser;
use examples::bunny::{self, MeshView};
use examples::{BackendChoice, Error, Settings, mesh};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::process::ExitCode;

/// Render an OBJ mesh to a PNG.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// The OBJ file (triangles or polygons; `.mtl` colours are used).
    mesh: PathBuf,
    /// Where to write the PNG.
    #[arg(long)]
    out: PathBuf,
    #[arg(long, default_value_t = Settings::DEFAULT_WIDTH)]
    width: u32,
    #[arg(long, default_value_t = Settings::DEFAULT_HEIGHT)]
    height: u32,
    /// Which backend renders (default: a GPU if there is one, else the CPU).
    #[arg(long, value_enum)]
    backend: Option<BackendChoice>,
    /// Samples per pixel (one launch each).
    #[arg(long, default_value_t = Settings::DEFAULT_SPP)]
    spp: u32,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("render: {e}");
            match e {
                Error::Mesh(_) | Error::BackendUnavailable { .. } | Error::Settings(_) => ExitCode::from(2),
                _ => ExitCode::FAILURE,
            }
        }
    }
}

fn run(args: &Args) -> Result<(), Error> {
    let (backend, what) = BackendChoice::open_or_choose(args.backend)?;
    let settings = Settings { spp: args.spp, backend, ..Settings::new(args.width, args.height) };
    let loaded = mesh::load_obj(&args.mesh)?;
    for warning in &loaded.warnings {
        eprintln!("render: warning: {warning}");
    }
    let mut scene = bunny::mesh_scene(&loaded, &settings, MeshView::default())?;
    let bar = ProgressBar::new(scene.frames as u64);
    bar.set_style(
        ProgressStyle::with_template("render [{bar:30}] {pos}/{len} spp, {elapsed} (eta {eta})")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    let rendered = scene.render(&mut |done, _| bar.set_position(done as u64))?;
    bar.finish_and_clear();
    rendered.image.save_png(&args.out)?;
    println!(
        "{}: {} triangles, {}x{}, {} spp with {what}: {:.2} s, {:.2} Mrays/s",
        args.out.display(),
        loaded.mesh.indices.len(),
        settings.width,
        settings.height,
        settings.spp,
        rendered.seconds,
        rendered.mrays_per_second()
    );
    if !rendered.exceptions.is_empty() {
        eprintln!("render: warning: {} pixels raised exceptions (painted magenta)", rendered.exceptions.len());
    }
    Ok(())
}
