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
//! A glTF file's node animation: `--time T` renders the scene posed at T
//! seconds (default 0), and `--frames A..B --fps F` renders frames A to B-1
//! at T = frame / F, each to `--out` with its `#`s replaced by the frame
//! number (`frame_####.png` → `frame_0007.png`), so a job array can give
//! each machine its range (with `--tile`, each frame's part).
//!
//! `--denoise` writes the picture through the runtime's denoiser (guided
//! by the first hit's albedo and normal and by each pixel's luminance
//! variance, which the camera writes beside the radiance), and `--aov
//! DIR` writes those guides as OpenEXR: `DIR/<stem>_albedo.exr`,
//! `DIR/<stem>_normal.exr` and `DIR/<stem>_variance.exr` (grey: the
//! variance of the mean's luminance, -1 below 2 spp), `<stem>` the name
//! of `--out` without its extension. Both need the whole picture, so
//! neither goes with `--tile` or `--merge`.
//!
//! Exit status: 0 with the image written; 2 for bad input (the model: one
//! line naming the file, the line or glTF object when known and the
//! problem; or arguments, such as a backend with no adapter, a camera or
//! time that is not finite or out of range, a picture too large to hold),
//! and no image; 1 if rendering or writing failed. Every image is written
//! whole or not at all (to a name beside it, then renamed); a `--frames`
//! run that fails removes the frames it had written.
//!
//! The model is loaded within [`rt_scene::LoadLimits`] (flags
//! `--max-file-mib`, `--max-texture-pixels`, `--max-triangles`, ...): its
//! URIs and `mtllib`s may name files only inside its folder, unless
//! `--allow-path DIR` allows another.

use clap::Parser;
use examples::denoised::{self, Denoiser};
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
    #[command(flatten)]
    limits: examples::limits::LimitArgs,
    /// Seconds into the file's animation to pose the scene at.
    #[arg(long, allow_negative_numbers = true, conflicts_with = "frames")]
    time: Option<f32>,
    /// Frames A to B-1 of the file's animation (`A..B`), one image each:
    /// `--out` names them with its `#`s replaced by the frame number.
    #[arg(long, value_name = "A..B")]
    frames: Option<String>,
    /// Frames per second of `--frames`.
    #[arg(long, default_value_t = 24.0)]
    fps: f32,
    /// Write the picture denoised: the runtime's denoiser over the mean
    /// radiance, guided by the first hit's albedo and normal and each
    /// pixel's luminance variance.
    #[arg(long)]
    denoise: bool,
    /// Also write the denoiser's guides as OpenEXR into DIR (created if
    /// missing): `<stem>_albedo.exr`, `<stem>_normal.exr` and
    /// `<stem>_variance.exr`, `<stem>` being `--out`'s file name without
    /// its extension.
    #[arg(long, value_name = "DIR")]
    aov: Option<PathBuf>,
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

/// Refuses flags that do not go together (clap's own conflicts aside):
/// the denoiser and the guides need the whole picture.
fn check_flags(args: &Args) -> Result<(), Error> {
    let whole = [
        ("--denoise", args.denoise, "the denoiser reads each pixel's neighbours, which other parts render"),
        ("--aov", args.aov.is_some(), "it writes the whole picture's guides"),
    ];
    for (flag, _, why) in whole.iter().filter(|(_, on, _)| *on) {
        if args.tile.is_some() {
            let why =
                if *flag == "--denoise" { format!("it needs the whole picture ({why})") } else { why.to_string() };
            return Err(Error::Settings(format!("{flag} cannot go with --tile: {why}; render without --tile")));
        }
        if !args.merge.is_empty() {
            return Err(Error::Settings(format!(
                "{flag} cannot go with --merge: part files hold the radiance only; render the whole picture \
                 with {flag} instead"
            )));
        }
    }
    Ok(())
}

fn run(args: &Args) -> Result<(), Error> {
    check_flags(args)?;
    if !args.merge.is_empty() {
        return merge(args);
    }
    let mesh = args.mesh.as_deref().expect("clap requires a model without --merge");
    let options = args.camera.options()?;
    if let Some(time) = args.time.filter(|t| !t.is_finite()) {
        return Err(Error::Settings(format!("--time {time} is not a finite number of seconds")));
    }
    let tile = args.tile.as_deref().map(parts::parse_tile).transpose()?;
    let rows = match tile {
        Some((k, n)) => parts::band(args.height, k, n)?,
        None => 0..args.height,
    };
    let (backend, what) = BackendChoice::open_or_choose(args.backend)?;
    let settings = Settings { spp: args.spp, backend, ..Settings::new(args.width, args.height) };
    let frames = args.frames.as_deref().map(|f| parse_frames(f, args.fps, &args.out)).transpose()?;
    let mut loaded = model::model_scene_with(mesh, &settings, options, &args.limits.limits())?;
    for warning in &loaded.warnings {
        eprintln!("render: warning: {warning}");
    }
    let denoiser = match args.denoise {
        true => Some(Denoiser::new(&mut loaded.scene)?.ok_or_else(|| no_guides(mesh))?),
        false => None,
    };
    let denoiser = denoiser.as_ref();
    let no_animation =
        || Error::Settings(format!("{}: has no node animation to pose (--time and --frames need one)", mesh.display()));
    match (frames, loaded.animation.take()) {
        (None, animation) => {
            let time = match (args.time, animation) {
                (Some(time), Some(animation)) => {
                    animation.pose(&mut loaded.scene.ctx, time)?;
                    Some(time)
                }
                (Some(_), None) => return Err(no_animation()),
                (None, _) => None,
            };
            render_one(args, (mesh, &what, time), &mut loaded, (tile, rows), (&args.out, denoiser)).map(|_| ())
        }
        (Some(frames), Some(animation)) => {
            // Each frame is written whole (beside its name, then renamed);
            // a run that fails removes the frames it wrote, so no frame of
            // a failing run is left.
            let mut written = Vec::new();
            for frame in frames {
                let time = frame as f32 / args.fps;
                let out = frame_path(&args.out, frame);
                let done = animation.pose(&mut loaded.scene.ctx, time).map_err(Error::from).and_then(|()| {
                    render_one(args, (mesh, &what, Some(time)), &mut loaded, (tile, rows.clone()), (&out, denoiser))
                });
                match done {
                    Ok(paths) => written.extend(paths),
                    Err(e) => {
                        for path in &written {
                            let _ = std::fs::remove_file(path);
                        }
                        return Err(e);
                    }
                }
            }
            Ok(())
        }
        (Some(_), None) => Err(no_animation()),
    }
}

/// `A..B` as the frames A to B-1 (`--out` must say where their numbers go).
fn parse_frames(text: &str, fps: f32, out: &Path) -> Result<std::ops::Range<u32>, Error> {
    let bad = || Error::Settings(format!("--frames {text}: expected A..B, frames A to B-1 (e.g. 0..48)"));
    let (a, b) = text.split_once("..").ok_or_else(bad)?;
    let (a, b) = (a.trim().parse::<u32>().map_err(|_| bad())?, b.trim().parse::<u32>().map_err(|_| bad())?);
    if a >= b {
        return Err(Error::Settings(format!("--frames {text} holds no frame (B must exceed A)")));
    }
    if !(fps > 0.0 && fps.is_finite()) {
        return Err(Error::Settings(format!("--fps {fps} must be positive")));
    }
    if !out.to_string_lossy().contains('#') {
        return Err(Error::Settings(format!(
            "--out {} has no `#` for the frame number (with --frames, e.g. frame_####.png)",
            out.display()
        )));
    }
    Ok(a..b)
}

/// `out` with its last run of `#`s replaced by `frame`, zero-padded to the
/// run's length.
fn frame_path(out: &Path, frame: u32) -> PathBuf {
    let text = out.to_string_lossy();
    let Some(last) = text.rfind('#') else { return out.to_path_buf() };
    let end = last + 1;
    let start = text[..end].trim_end_matches('#').len();
    PathBuf::from(format!("{}{frame:0width$}{}", &text[..start], &text[end..], width = end - start))
}

/// A model scene that writes no guides to denoise with.
fn no_guides(mesh: &Path) -> Error {
    Error::Settings(format!("{}: the scene writes no guides for the denoiser", mesh.display()))
}

/// `--aov`: the last render's guides into `dir`, named after `out`, each
/// path added to `written` once written.
fn write_guides(
    loaded: &model::Model,
    (mesh, out): (&Path, &Path),
    dir: &Path,
    written: &mut Vec<PathBuf>,
) -> Result<(), Error> {
    let guides = denoised::guides(&loaded.scene)?.ok_or_else(|| no_guides(mesh))?;
    std::fs::create_dir_all(dir).map_err(|e| Error::Io { path: dir.display().to_string(), problem: e.to_string() })?;
    let stem = out.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "render".into());
    for (name, image) in [("albedo", guides.albedo), ("normal", guides.normal), ("variance", guides.variance)] {
        let path = dir.join(format!("{stem}_{name}.exr"));
        image.save_exr(&path)?;
        println!("{}", path.display());
        written.push(path);
    }
    Ok(())
}

/// Renders the scene as it is posed to `out` (the whole picture, or the
/// part `tile` of it: its `rows`), denoised by `denoiser` if given, with
/// the guides beside it for `--aov`; the paths written.
fn render_one(
    args: &Args,
    (mesh, what, time): (&Path, &str, Option<f32>),
    loaded: &mut model::Model,
    (tile, rows): (Option<(u32, u32)>, std::ops::Range<u32>),
    (out, denoiser): (&Path, Option<&Denoiser>),
) -> Result<Vec<PathBuf>, Error> {
    let settings = &loaded.scene;
    let (width, height, spp) = (settings.width, settings.height, settings.frames);
    let bar = progress_bar::spp_bar("render", loaded.scene.frames);
    let rendered = loaded.scene.render_rows(rows.clone(), &mut |p| progress_bar::show(&bar, p))?;
    bar.finish_and_clear();
    // Every model scene accumulates its samples (the radiance the files
    // hold); a display picture is only what a scene without would give.
    let radiance = rendered
        .radiance
        .as_ref()
        .ok_or_else(|| Error::Settings(format!("{}: the scene keeps no radiance to write", mesh.display())))?;
    let denoised = denoiser.map(|d| d.run(&mut loaded.scene)).transpose()?;
    let radiance = denoised.as_ref().unwrap_or(radiance);
    // The picture, then its guides: a failure removes what this call wrote.
    let mut written = Vec::new();
    let mut write = || -> Result<(), Error> {
        match tile {
            Some(tile) => {
                let mut line = settings_line(args, mesh, loaded.scene.ctx.backend().name())?;
                if let Some(time) = time {
                    line.push_str(&format!(" time {time}"));
                }
                parts::Part::of(radiance, tile, &line)?.save(out)?;
            }
            None => save(radiance, out)?,
        }
        written.push(out.to_path_buf());
        if let Some(dir) = &args.aov {
            write_guides(loaded, (mesh, out), dir, &mut written)?;
        }
        Ok(())
    };
    if let Err(e) = write() {
        for path in &written {
            let _ = std::fs::remove_file(path);
        }
        return Err(e);
    }
    let part = tile.map_or(String::new(), |(k, n)| format!(" (part {k} of {n}: rows {}..{})", rows.start, rows.end));
    println!(
        "{}{part}: {} triangles, {}x{}, {} spp{}{} with {what}{}: {:.2} s, {:.2} Mrays/s",
        out.display(),
        loaded.triangles,
        width,
        height,
        spp,
        if denoised.is_some() { " denoised" } else { "" },
        time.map_or(String::new(), |t| format!(" at {t} s of the animation")),
        if loaded.file_camera { ", the file's camera" } else { "" },
        rendered.seconds,
        rendered.mrays_per_second()
    );
    if !rendered.exceptions.is_empty() {
        eprintln!("render: warning: {} pixels raised exceptions (painted magenta)", rendered.exceptions.len());
    }
    Ok(written)
}
