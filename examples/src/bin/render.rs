//! Renders a model file the way the `bunny` example shows the bunny: framed
//! from its bounds (or by the glTF file's own camera), on a floor, under a
//! key light with shadows and ambient occlusion, each material in its
//! diffuse or base colour (else grey).
//!
//!     cargo run --release -p examples --bin render -- MODEL.{obj,gltf,glb} --out OUT.{png,exr}
//!
//! In parts, on several machines (`examples::parts`): `--tile K/N` renders
//! band K (from 0) of N bands of rows into a part file, and `render
//! --merge PART... --out OUT.png` puts the parts together bit for bit.
//!
//! Exit status: 0 with the image written; 2 for bad input (the model: one
//! line naming the file, the line or glTF object when known and the
//! problem; or arguments, such as a backend with no adapter), and no
//! image; 1 if rendering or writing failed.

use clap::Parser;
use examples::model::{self, CameraArgs};
use examples::scene::Image;
use examples::{BackendChoice, Error, Settings, parts, progress_bar};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Render an OBJ or glTF model to a PNG or an OpenEXR image.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// The model: OBJ (triangles or polygons; `.mtl` colours are used),
    /// glTF (`.gltf`) or binary glTF (`.glb`).
    #[arg(required_unless_present = "merge")]
    mesh: Option<PathBuf>,
    /// Where to write the image: `.exr` writes float RGBA (OpenEXR), any
    /// other name a PNG; with `--tile`, the part file.
    #[arg(long)]
    out: PathBuf,
    /// Render only part K (from 0) of N: a band of the picture's rows,
    /// written to `--out` as a part file for `--merge`. Every part sees the
    /// whole picture (its seeds and rays), so the parts put together are
    /// the whole render's image, bit for bit, on one backend.
    #[arg(long, value_name = "K/N", conflicts_with = "merge")]
    tile: Option<String>,
    /// Put part files (from `--tile`) together into `--out`, checking that
    /// they are every part of one render once.
    #[arg(long, value_name = "PART", num_args = 1.., conflicts_with = "mesh")]
    merge: Vec<PathBuf>,
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
    #[command(flatten)]
    camera: CameraArgs,
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

/// Writes `image` to `out`: OpenEXR for `.exr`, else PNG.
/// Writes the mean radiance: as it is to an EXR, gamma corrected to a PNG.
fn save(radiance: &Image, out: &Path) -> Result<(), Error> {
    if out.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
        radiance.save_exr(out)
    } else {
        radiance.to_display().save_png(out)
    }
}

/// `--merge`: the parts, checked and put together, into `--out`.
fn merge(args: &Args) -> Result<(), Error> {
    let parts = args.merge.iter().map(|p| Ok((p.clone(), parts::Part::load(p)?))).collect::<Result<Vec<_>, Error>>()?;
    let image = parts::merge(&parts)?;
    save(&image, &args.out)?;
    println!("{}: {} parts, {}x{}", args.out.display(), parts.len(), image.width, image.height);
    Ok(())
}

/// What decides a render's pixels, for a part file: parts merge only with
/// parts of the same settings (the model file by its length and hash).
fn settings_line(args: &Args, model: &Path, backend: &str) -> Result<String, Error> {
    let bytes =
        std::fs::read(model).map_err(|e| Error::Io { path: model.display().to_string(), problem: e.to_string() })?;
    Ok(format!(
        "model {} ({} bytes, fnv1a {:016x}) {}x{} spp {} backend {backend} up {:?} azimuth {:?} elevation {:?} distance {:?} fov {:?} file-camera {}",
        model.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default(),
        bytes.len(),
        parts::fnv1a(&bytes),
        args.width,
        args.height,
        args.spp,
        args.camera.up,
        args.camera.azimuth,
        args.camera.elevation,
        args.camera.distance,
        args.camera.fov,
        !args.camera.no_file_camera,
    ))
}

fn run(args: &Args) -> Result<(), Error> {
    if !args.merge.is_empty() {
        return merge(args);
    }
    let mesh = args.mesh.as_deref().expect("clap requires a model without --merge");
    let options = args.camera.options()?;
    let tile = args.tile.as_deref().map(parts::parse_tile).transpose()?;
    let rows = match tile {
        Some((k, n)) => parts::band(args.height, k, n)?,
        None => 0..args.height,
    };
    let (backend, what) = BackendChoice::open_or_choose(args.backend)?;
    let settings = Settings { spp: args.spp, backend, ..Settings::new(args.width, args.height) };
    let mut loaded = model::model_scene(mesh, &settings, options)?;
    for warning in &loaded.warnings {
        eprintln!("render: warning: {warning}");
    }
    let bar = progress_bar::spp_bar("render", loaded.scene.frames);
    let rendered = loaded.scene.render_rows(rows.clone(), &mut |p| progress_bar::show(&bar, p))?;
    bar.finish_and_clear();
    // Every model scene accumulates its samples (the radiance the files
    // hold); a display picture is only what a scene without would give.
    let radiance = rendered
        .radiance
        .as_ref()
        .ok_or_else(|| Error::Settings(format!("{}: the scene keeps no radiance to write", mesh.display())))?;
    match tile {
        Some(tile) => {
            let line = settings_line(args, mesh, settings.backend.name())?;
            parts::Part::of(radiance, tile, &line)?.save(&args.out)?;
        }
        None => save(radiance, &args.out)?,
    }
    let part = tile.map_or(String::new(), |(k, n)| format!(" (part {k} of {n}: rows {}..{})", rows.start, rows.end));
    println!(
        "{}{part}: {} triangles, {}x{}, {} spp with {what}{}: {:.2} s, {:.2} Mrays/s",
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
