//! The `viewer` binary as automation drives it: on a virtual X display
//! (Xvfb) it opens its window, refines a few frames, screenshots the window
//! and exits, on the CPU backend and on the wgpu backend (Mesa's lavapipe
//! where there is no GPU); and it refuses bad input in one line without
//! opening a window.
//!
//! Xvfb is installed here when it is missing and the tests run as root (CI
//! installs it in scripts/test.sh); otherwise the window tests are skipped
//! with a message.

use examples::scene::shared_scene;
use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// A fresh directory under cargo's per-target temporary directory.
fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("examples-viewer-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A running Xvfb, killed when dropped (also when a test fails).
struct Xvfb {
    child: Child,
    display: String,
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn is_root() -> bool {
    Command::new("id").arg("-u").output().is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
}

fn xvfb_installed() -> bool {
    Command::new("Xvfb").arg("-help").stdout(Stdio::null()).stderr(Stdio::null()).status().is_ok()
}

/// Installs Xvfb once per test run when it is missing and we are root
/// (as scripts/test.sh installs lavapipe); `false` when it is missing and
/// cannot be installed here.
fn ensure_xvfb() -> bool {
    static INSTALL: Mutex<()> = Mutex::new(());
    let _one_at_a_time = INSTALL.lock().unwrap_or_else(|e| e.into_inner());
    if xvfb_installed() {
        return true;
    }
    if !is_root() {
        return false;
    }
    eprintln!("viewer test: installing xvfb");
    let apt = |args: &[&str]| {
        let status = Command::new("apt-get").args(args).env("DEBIAN_FRONTEND", "noninteractive").status();
        assert!(status.as_ref().is_ok_and(|s| s.success()), "apt-get {args:?} failed: {status:?}");
    };
    apt(&["update", "-qq"]);
    // And what the viewer loads at run time (scripts/test.sh installs the same).
    apt(&[
        "install",
        "-y",
        "-qq",
        "xvfb",
        "libx11-6",
        "libx11-xcb1",
        "libxcursor1",
        "libxi6",
        "libxkbcommon0",
        "libxkbcommon-x11-0",
    ]);
    assert!(xvfb_installed(), "xvfb was installed but `Xvfb` does not run");
    true
}

/// Starts Xvfb on a display of its own choosing (`-displayfd` writes the
/// number it took, so parallel tests never race for one), or `None`, with a
/// message, when Xvfb is missing and cannot be installed.
fn start_xvfb(test: &str) -> Option<Xvfb> {
    if !ensure_xvfb() {
        eprintln!(
            "SKIPPED {test}: Xvfb is not installed and the tests do not run as root to install it (apt-get install xvfb)"
        );
        return None;
    }
    let child = Command::new("Xvfb")
        .args(["-displayfd", "1", "-screen", "0", "640x480x24", "-nolisten", "tcp"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("Xvfb starts");
    let mut xvfb = Xvfb { child, display: String::new() };
    let mut line = String::new();
    BufReader::new(xvfb.child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    let number = line.trim();
    assert!(!number.is_empty() && number.chars().all(|c| c.is_ascii_digit()), "Xvfb did not say its display: {line:?}");
    xvfb.display = format!(":{number}");
    Some(xvfb)
}

/// What a run of the viewer left.
struct Run {
    status: ExitStatus,
    stdout: String,
    stderr: String,
}

/// Runs the viewer on `display` (none: no `DISPLAY`), killing it after
/// two minutes.
fn viewer(display: Option<&str>, args: &[&str], dir: &Path) -> Run {
    let (out, err) = (dir.join("stdout.txt"), dir.join("stderr.txt"));
    let mut command = Command::new(env!("CARGO_BIN_EXE_viewer"));
    command.args(args).stdout(File::create(&out).unwrap()).stderr(File::create(&err).unwrap());
    command.env_remove("WAYLAND_DISPLAY").env_remove("RT_BACKEND");
    match display {
        Some(d) => command.env("DISPLAY", d),
        None => command.env_remove("DISPLAY"),
    };
    let mut child = command.spawn().expect("the viewer starts");
    let deadline = Instant::now() + Duration::from_secs(120);
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("the viewer ran past two minutes: {}", std::fs::read_to_string(&err).unwrap_or_default());
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let read = |p: &Path| std::fs::read_to_string(p).unwrap();
    Run { status, stdout: read(&out), stderr: read(&err) }
}

/// `viewer --frames N --screenshot` on `display`, checked: exit 0, nothing
/// on stderr, the summary line, and the screenshot at `width` x `height`.
fn screenshot(display: &str, dir: &Path, name: &str, size: (u32, u32), frames: u32, extra: &[&str]) -> image::RgbImage {
    let png = dir.join(format!("{name}.png"));
    let size_arg = format!("{}x{}", size.0, size.1);
    let frames_arg = frames.to_string();
    let mut args = vec!["--size", &size_arg, "--frames", &frames_arg, "--screenshot", png.to_str().unwrap()];
    args.extend(extra);
    let run = viewer(Some(display), &args, dir);
    assert!(run.status.success(), "{name}: {:?}\n{}", run.status, run.stderr);
    assert!(run.stderr.is_empty(), "{name}: {}", run.stderr);
    let summary = format!("viewer: {frames} frames of {size_arg} in ");
    assert!(run.stdout.starts_with(&summary) && run.stdout.contains(" Mrays/s, "), "{name}: {}", run.stdout);
    let image = image::open(&png).unwrap_or_else(|e| panic!("{name}: {}: {e}", png.display())).to_rgb8();
    assert_eq!(image.dimensions(), size, "{name}");
    image
}

/// `render`'s picture of the same mesh at the same size and samples.
fn rendered(dir: &Path, mesh: &Path, size: (u32, u32), spp: u32) -> image::RgbImage {
    rendered_with(dir, mesh, size, spp, &[])
}

/// [`rendered`] with more of `render`'s flags.
fn rendered_with(dir: &Path, mesh: &Path, size: (u32, u32), spp: u32, extra: &[&str]) -> image::RgbImage {
    let png = dir.join("render.png");
    let (w, h, spp) = (size.0.to_string(), size.1.to_string(), spp.to_string());
    let args = [mesh.to_str().unwrap(), "--out", png.to_str().unwrap(), "--width", &w, "--height", &h];
    let out = Command::new(env!("CARGO_BIN_EXE_render"))
        .args(args)
        .args(["--spp", &spp, "--backend", "cpu"])
        .args(extra)
        .output()
        .unwrap();
    assert!(out.status.success(), "render: {}", String::from_utf8_lossy(&out.stderr));
    image::open(&png).unwrap().to_rgb8()
}

/// The largest difference of any channel of any pixel, and the mean.
fn difference(a: &image::RgbImage, b: &image::RgbImage) -> (u8, f64) {
    assert_eq!(a.dimensions(), b.dimensions());
    let diffs: Vec<u8> = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| x.abs_diff(*y)).collect();
    (*diffs.iter().max().unwrap(), diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64)
}

/// The background as the viewer shows it (the miss colour, gamma corrected).
fn background() -> image::Rgb<u8> {
    let c = examples::bunny::BACKGROUND.powf(1.0 / 2.2);
    image::Rgb([c.x, c.y, c.z].map(|v| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8))
}

/// A picture with the mesh in the middle: many colours, and the centre
/// ninth mostly not the background.
fn assert_shows_a_mesh(image: &image::RgbImage, name: &str) {
    let colours: std::collections::HashSet<_> = image.pixels().collect();
    assert!(colours.len() > 50, "{name}: only {} colours", colours.len());
    let (w, h) = image.dimensions();
    let centre: Vec<_> = (h / 3..2 * h / 3).flat_map(|y| (w / 3..2 * w / 3).map(move |x| (x, y))).collect();
    let bg = background();
    let near_bg = |p: &image::Rgb<u8>| p.0.iter().zip(bg.0).all(|(a, b)| a.abs_diff(b) <= 4);
    let mesh = centre.iter().filter(|&&(x, y)| !near_bg(image.get_pixel(x, y))).count();
    assert!(mesh * 4 > centre.len() * 3, "{name}: {mesh} of {} centre pixels show the mesh", centre.len());
}

const SIZE: (u32, u32) = (96, 72);

/// On the CPU backend, eight still frames are `render --spp 8` to the byte,
/// and the window reads back the same (else a warning on stderr); turning the camera starts the refinement
/// again and shows the mesh from elsewhere.
#[test]
fn viewer_under_xvfb_shows_what_render_draws() {
    let Some(xvfb) = start_xvfb("viewer_under_xvfb_shows_what_render_draws") else { return };
    let dir = temp_dir("cpu");
    let bunny = screenshot(&xvfb.display, &dir, "bunny", SIZE, 8, &["--backend", "cpu"]);
    assert_shows_a_mesh(&bunny, "bunny");
    let reference = rendered(&dir, &shared_scene("stanford-bunny.obj"), SIZE, 8);
    assert_eq!(difference(&bunny, &reference), (0, 0.0), "the viewer's bunny is not render's");

    let turned = screenshot(&xvfb.display, &dir, "turned", SIZE, 5, &["--backend", "cpu", "--spin", "3"]);
    assert_shows_a_mesh(&turned, "turned");
    let (_, mean) = difference(&bunny, &turned);
    assert!(mean > 2.0, "turning the camera changed little: mean difference {mean}");
    let summary = std::fs::read_to_string(dir.join("stdout.txt")).unwrap();
    // The third turn's frame is the first sample of the still view.
    assert!(summary.contains(", 3 samples accumulated"), "{summary}");
    assert!(summary.contains("shown through the host (softbuffer)"), "{summary}");
}

/// `--denoise` (the N key's state at the start): the window shows the
/// samples through the denoiser, what `render --denoise` draws, to the
/// byte on the CPU backend.
#[test]
fn viewer_denoised_is_what_render_denoise_draws() {
    let Some(xvfb) = start_xvfb("viewer_denoised_is_what_render_denoise_draws") else { return };
    let dir = temp_dir("denoise");
    let shot = screenshot(&xvfb.display, &dir, "denoised", SIZE, 4, &["--backend", "cpu", "--denoise"]);
    assert_shows_a_mesh(&shot, "denoised");
    let bunny = shared_scene("stanford-bunny.obj");
    assert_eq!(difference(&shot, &rendered_with(&dir, &bunny, SIZE, 4, &["--denoise"])), (0, 0.0));
    assert!(difference(&shot, &rendered(&dir, &bunny, SIZE, 4)).1 > 0.5, "the denoiser changed little");
}

/// The camera flags are `render`'s, with its meaning: the same picture to
/// the byte.
#[test]
fn viewer_takes_renders_camera_flags() {
    let Some(xvfb) = start_xvfb("viewer_takes_renders_camera_flags") else { return };
    let dir = temp_dir("camera");
    let teapot = shared_scene("teapot.obj");
    let flags = ["--up", "z", "--azimuth", "90", "--elevation", "30", "--distance", "9", "--fov", "50"];
    let mut args = vec![teapot.to_str().unwrap(), "--backend", "cpu"];
    args.extend(flags);
    let shot = screenshot(&xvfb.display, &dir, "side", SIZE, 3, &args);
    assert_shows_a_mesh(&shot, "side");
    assert_eq!(difference(&shot, &rendered_with(&dir, &teapot, SIZE, 3, &flags)), (0, 0.0));
    let default = rendered(&dir, &teapot, SIZE, 3);
    assert!(difference(&shot, &default).1 > 2.0, "the flags changed little");
    let run = viewer(None, &["--elevation", "95", "--frames", "1"], &dir);
    assert_eq!(run.status.code(), Some(2), "{}", run.stderr);
    assert_eq!(run.stderr.trim_end(), "viewer: --elevation 95 is outside -89..=89 degrees");
}

/// The bytes the summary says the last launch read back from the device.
fn read_back(summary: &str) -> u64 {
    let (before, _) = summary.rsplit_once(" bytes read back from the device by the last launch").expect(summary);
    before.rsplit(' ').next().unwrap().parse().unwrap()
}

/// On the wgpu backend (lavapipe without a GPU) frames go from the
/// launch's buffer to the window on the device: the launches read back
/// only their log, the window (read back from the X server; any other
/// picture is a warning on stderr, which `screenshot` refuses) holds
/// exactly the device's picture in `render`'s 8-bit colours, and that
/// picture is the CPU backend's within the backends' rounding. Turning the
/// camera starts the refinement again there too.
#[test]
fn viewer_under_xvfb_shows_frames_from_the_gpu() {
    let Some(xvfb) = start_xvfb("viewer_under_xvfb_shows_frames_from_the_gpu") else { return };
    let dir = temp_dir("wgpu");
    let teapot = shared_scene("teapot.obj");
    let shot = screenshot(&xvfb.display, &dir, "teapot", SIZE, 4, &[teapot.to_str().unwrap(), "--backend", "wgpu"]);
    let summary = std::fs::read_to_string(dir.join("stdout.txt")).unwrap();
    assert!(summary.contains("with the wgpu backend on "), "{summary}");
    assert!(summary.contains("shown from the GPU (a wgpu surface on the launch's device)"), "{summary}");
    // The log's header and the timestamps; a picture would be 96 x 72 x 16 bytes.
    assert!(read_back(&summary) <= 64, "{summary}");
    assert_shows_a_mesh(&shot, "teapot");
    let (max, mean) = difference(&shot, &rendered(&dir, &teapot, SIZE, 4));
    assert!(max <= 16 && mean < 0.5, "wgpu differs from the CPU backend: max {max}, mean {mean}");

    let turned = screenshot(
        &xvfb.display,
        &dir,
        "turned",
        SIZE,
        5,
        &[teapot.to_str().unwrap(), "--backend", "wgpu", "--spin", "3"],
    );
    assert_shows_a_mesh(&turned, "turned");
    assert!(difference(&shot, &turned).1 > 2.0, "turning the camera changed little");
    let summary = std::fs::read_to_string(dir.join("stdout.txt")).unwrap();
    assert!(summary.contains(", 3 samples accumulated"), "{summary}");
}

/// `--present host` on the wgpu backend: every frame is read back (the
/// output and accumulation buffers) and copied into the window, which
/// shows what `--present gpu` shows. `--present gpu` on the CPU backend is
/// refused in one line.
#[test]
fn viewer_can_show_wgpu_frames_through_the_host() {
    let Some(xvfb) = start_xvfb("viewer_can_show_wgpu_frames_through_the_host") else { return };
    let dir = temp_dir("wgpu-host");
    let teapot = shared_scene("teapot.obj");
    let mesh = teapot.to_str().unwrap();
    let host = screenshot(&xvfb.display, &dir, "host", SIZE, 2, &[mesh, "--backend", "wgpu", "--present", "host"]);
    let summary = std::fs::read_to_string(dir.join("stdout.txt")).unwrap();
    assert!(summary.contains("shown through the host (softbuffer)"), "{summary}");
    let picture = (SIZE.0 * SIZE.1 * 16) as u64;
    assert!(read_back(&summary) >= 2 * picture, "{summary}");
    let gpu = screenshot(&xvfb.display, &dir, "gpu", SIZE, 2, &[mesh, "--backend", "wgpu", "--present", "gpu"]);
    assert_eq!(difference(&host, &gpu), (0, 0.0), "the two ways to the window differ");

    let run = viewer(Some(&xvfb.display), &[mesh, "--backend", "cpu", "--present", "gpu", "--frames", "1"], &dir);
    assert_eq!(run.status.code(), Some(2), "{}", run.stderr);
    assert_eq!(
        run.stderr.trim_end(),
        "viewer: `--present gpu` needs the wgpu backend; the cpu backend renders on the host"
    );
}

/// Bad input is one line and exit status 2, before any window opens (so
/// no display is needed), and no screenshot.
#[test]
fn viewer_refuses_bad_input_in_one_line() {
    let dir = temp_dir("refuse");
    let png = dir.join("shot.png");
    let missing = dir.join("no-such-mesh.obj");
    let malformed = dir.join("malformed.obj");
    std::fs::write(&malformed, "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    for (mesh, location, problem) in [
        (&missing, "", "cannot read the file: no such file"),
        (&malformed, ":2", "a vertex has `zero`, which is not a number"),
    ] {
        let run = viewer(None, &[mesh.to_str().unwrap(), "--frames", "1", "--screenshot", png.to_str().unwrap()], &dir);
        assert_eq!(run.status.code(), Some(2), "{}", run.stderr);
        assert_eq!(run.stderr.trim_end(), format!("viewer: {}{location}: {problem}", mesh.display()));
        assert_eq!(run.stderr.lines().count(), 1);
        assert!(run.stdout.is_empty());
        assert!(!png.exists());
    }
    let run = viewer(None, &["--size", "96by72"], &dir);
    assert_eq!(run.status.code(), Some(2), "{}", run.stderr);
    assert!(run.stderr.contains("`96by72` is not WIDTHxHEIGHT"), "{}", run.stderr);
    // The loader's limits and the camera's range, as `render` has them.
    let teapot = shared_scene("teapot.obj");
    for (flags, text) in [
        (["--max-triangles", "10"], "over the limit of 10 (LoadLimits::max_triangles)"),
        (["--distance", "1e-30"], "--distance 1e-30 is outside "),
        (["--time", "1"], "teapot.obj: has no node animation to pose"),
        (["--time", "NaN"], "cannot pose the animation at time NaN: not a finite number of seconds"),
    ] {
        let mut args = vec![teapot.to_str().unwrap(), "--frames", "1", "--backend", "cpu"];
        args.extend(flags);
        let run = viewer(None, &args, &dir);
        assert_eq!(run.status.code(), Some(2), "{}", run.stderr);
        assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
        assert!(run.stderr.contains(text), "{}", run.stderr);
    }
}

/// Without a display the viewer says so and fails (status 1), no panic.
#[test]
fn viewer_without_a_display_says_so() {
    let dir = temp_dir("no-display");
    let teapot = shared_scene("teapot.obj");
    let run = viewer(None, &[teapot.to_str().unwrap(), "--size", "8x6", "--backend", "cpu", "--frames", "1"], &dir);
    assert_eq!(run.status.code(), Some(1), "{}", run.stderr);
    assert!(run.stderr.starts_with("viewer: cannot open a window: "), "{}", run.stderr);
    assert!(run.stderr.contains("DISPLAY"), "{}", run.stderr);
    assert!(!run.stderr.contains(".rs:"), "no source locations: {}", run.stderr);
    assert!(!run.stderr.contains("panicked"), "{}", run.stderr);
}
