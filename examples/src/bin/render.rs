//! Renders a model file the way the `bunny` example shows the bunny: framed
//! from its bounds (or by the glTF file's own camera), on a floor, under a
//! key light with shadows and ambient occlusion, each material in its
//! diffuse or base colour (else grey).
//!
//!     cargo run --release -p examples --bin render -- MODEL.{obj,gltf,glb} --out OUT.{png,exr}
//!
//! Exit status: 0 with the image written; 2 for bad input (the model: one
//! line naming the file, the line or glTF object when known and the
//! problem; or arguments, such as a backend with no adapter), and no
//! image; 1 if rendering or writing failed.

use clap::Parser;
use examples::model::{self, CameraOptions, UpAxis};
use examples::{BackendChoice, Error, Settings, progress_bar};
use std::path::PathBuf;
use std::process::ExitCode;

/// Render an OBJ or glTF model to a PNG or an OpenEXR image.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// The model: OBJ (triangles or polygons; `.mtl` colours are used),
    /// glTF (`.gltf`) or binary glTF (`.glb`).
    mesh: PathBuf,
    /// Where to write the image: `.exr` writes float RGBA (OpenEXR), any
    /// other name a PNG.
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
    /// The model's up axis (glTF's is y; scans are often z).
    #[arg(long, value_enum, default_value_t = UpAxis::Y)]
    up: UpAxis,
    /// Camera azimuth in degrees about the up axis (0: from +Z, 90: from +X).
    #[arg(long, allow_negative_numbers = true)]
    azimuth: Option<f32>,
    /// Camera elevation in degrees above the horizon.
    #[arg(long, allow_negative_numbers = true)]
    elevation: Option<f32>,
    /// Camera distance from the model's centre (default: what frames it).
    #[arg(long)]
    distance: Option<f32>,
    /// Vertical field of view in degrees (default 30, or the file camera's).
    #[arg(long)]
    fov: Option<f32>,
    /// Frame the model even when the glTF file has a camera.
    #[arg(long)]
    no_file_camera: bool,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("render: {e}");
            if e.is_bad_input() { ExitCode::from(2) } else { ExitCode::FAILURE }
        }
    }
}

fn run(args: &Args) -> Result<(), Error> {
    check_camera_args(args)?;
    let (backend, what) = BackendChoice::open_or_choose(args.backend)?;
    let settings = Settings { spp: args.spp, backend, ..Settings::new(args.width, args.height) };
    let options = CameraOptions {
        up: args.up,
        azimuth: args.azimuth,
        elevation: args.elevation,
        distance: args.distance,
        fov: args.fov,
        ignore_file_camera: args.no_file_camera,
    };
    let mut loaded = model::model_scene(&args.mesh, &settings, options)?;
    for warning in &loaded.warnings {
        eprintln!("render: warning: {warning}");
    }
    let bar = progress_bar::spp_bar("render", loaded.scene.frames);
    let rendered = loaded.scene.render(&mut |p| progress_bar::show(&bar, p))?;
    bar.finish_and_clear();
    let exr = args.out.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    if exr {
        rendered.image.save_exr(&args.out)?;
    } else {
        rendered.image.save_png(&args.out)?;
    }
    println!(
        "{}: {} triangles, {}x{}, {} spp with {what}{}: {:.2} s, {:.2} Mrays/s",
        args.out.display(),
        loaded.triangles,
        settings.width,
        settings.height,
        settings.spp,
        if loaded.file_camera { ", the file's camera" } else { "" },
        rendered.seconds,
        rendered.mrays_per_second()
    );
    if !rendered.exceptions.is_empty() {
        eprintln!("render: warning: {} pixels raised exceptions (painted magenta)", rendered.exceptions.len());
    }
    Ok(())
}

/// Camera values a picture cannot be taken with, refused by name.
fn check_camera_args(args: &Args) -> Result<(), Error> {
    if let Some(fov) = args.fov
        && !(fov > 0.0 && fov < 180.0)
    {
        return Err(Error::Settings(format!("--fov {fov} is outside (0, 180) degrees")));
    }
    if let Some(d) = args.distance
        && !(d > 0.0 && d.is_finite())
    {
        return Err(Error::Settings(format!("--distance {d} must be positive")));
    }
    if let Some(e) = args.elevation
        && !(-89.0..=89.0).contains(&e)
    {
        return Err(Error::Settings(format!("--elevation {e} is outside -89..=89 degrees")));
    }
    if args.azimuth.is_some_and(|a| !a.is_finite()) {
        return Err(Error::Settings("--azimuth must be a finite number of degrees".into()));
    }
    Ok(())
}
