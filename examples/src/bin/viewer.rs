//! Shows an OBJ or glTF model (the Stanford bunny by default) in a window,
//! the way `render` draws it, refined sample by sample while the camera is
//! still.
//!
//!     cargo run --release -p examples --bin viewer -- [MODEL.{obj,gltf,glb}] [--up z]
//!         [--azimuth D] [--elevation D] [--distance L] [--fov D] [--no-file-camera]
//!
//! The camera flags are `render`'s (a glTF file's own camera is used when
//! it has one and no position is asked for). Left-drag orbits, the wheel
//! zooms, W/A/S/D walk, Q/E go down and up, R resets the camera, N steps
//! the denoiser from off to spatial to temporal and off again
//! (`--denoise` starts spatial, `--temporal` temporal: the picture kept
//! through camera motion, [`examples::viewer::Denoise`]), Esc quits. The
//! title says the frame rate, the rays per second, the samples so far,
//! the denoiser's mode and the backend.
//!
//! On the wgpu backend frames go from the GPU to the window: the picture
//! stays on the device (`Context::set_buffer_device_local`) and is drawn
//! through a wgpu surface on the launch's own device
//! ([`examples::present`]); nothing is read back but the launch's log
//! (and, while denoising, the denoised picture, which goes up again). On
//! the CPU backend, or with `--present host`, each frame is copied into the
//! window through softbuffer.
//!
//! For automation, `--frames N --screenshot OUT.png` closes the window
//! after N frames and writes the last one shown (after reading the window
//! back from the X server: a warning says when it shows something else);
//! `--size WxH` sets the window's size and `--spin K` turns the camera on
//! each of the first K frames, as a drag would.
//!
//! Exit status: 0; 2 for bad input (the mesh: one line naming the file, the
//! line when known and the problem; or arguments, such as a backend with no
//! adapter); 1 if the window could not be opened or rendering failed.

use clap::Parser;
use examples::present::GpuPresenter;
use examples::viewer::{self, Denoise, Progressive};
use examples::{BackendChoice, Camera, Error, Image, Settings, scene};
use std::collections::HashSet;
use std::num::NonZeroU32;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

/// Show an OBJ or glTF model in a window, refined progressively.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// The OBJ, glTF or GLB file (default: the Stanford bunny of the shared
    /// scenes); a glTF scene is shown as one mesh, its instances baked.
    mesh: Option<PathBuf>,
    #[command(flatten)]
    camera: examples::model::CameraArgs,
    #[command(flatten)]
    limits: examples::limits::LimitArgs,
    /// The window's inner size in pixels.
    #[arg(long, value_parser = parse_size, default_value = "512x384")]
    size: (u32, u32),
    /// Which backend renders (default: a GPU if there is one, else the CPU).
    #[arg(long, value_enum)]
    backend: Option<BackendChoice>,
    /// Close after this many frames (for automation).
    #[arg(long)]
    frames: Option<u32>,
    /// Write the last frame shown to this PNG on closing (with `--frames`,
    /// the window is read back first and checked against it).
    #[arg(long)]
    screenshot: Option<PathBuf>,
    /// Turn the camera 10 degrees on each of the first K frames, as a
    /// left-drag would (for automation: each turn starts the refinement
    /// again).
    #[arg(long, default_value_t = 0)]
    spin: u32,
    /// How frames reach the window: from the GPU (the wgpu backend's
    /// frames drawn on its device), through the host (read back, copied by
    /// softbuffer), or the first that works (auto: from the GPU on the
    /// wgpu backend).
    #[arg(long, value_enum, default_value_t = Present::Auto)]
    present: Present,
    /// Show a glTF file's node animation posed at this time, in seconds
    /// (as `render --time` poses it).
    #[arg(long, allow_negative_numbers = true)]
    time: Option<f32>,
    /// Stop refining at this many samples per pixel.
    #[arg(long, default_value_t = 4096, value_parser = clap::value_parser!(u32).range(1..))]
    max_spp: u32,
    /// Start with the denoiser on (the N key steps it off, spatial,
    /// temporal): the picture shown is the samples so far through the
    /// runtime's denoiser.
    #[arg(long)]
    denoise: bool,
    /// Start with the denoiser in its temporal mode: each picture blended
    /// into the last ones reprojected through the camera, so that moving
    /// keeps what was seen.
    #[arg(long, conflicts_with = "denoise")]
    temporal: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Present {
    Auto,
    Gpu,
    Host,
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("`{s}` is not WIDTHxHEIGHT"))?;
    let dim = |d: &str| d.trim().parse::<u32>().ok().filter(|n| (1..=16384).contains(n));
    match (dim(w), dim(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("`{s}` is not WIDTHxHEIGHT with each in 1..=16384")),
    }
}

/// Radians of orbit per pixel dragged.
const ORBIT_PER_PIXEL: f32 = 0.006;
/// Fraction of the distance to the target one wheel notch zooms.
const ZOOM_PER_NOTCH: f32 = 0.1;
/// Walking speed, in mesh radii per second.
const WALK_SPEED: f32 = 1.0;
/// How often the title's figures are brought up to date.
const READOUT_PERIOD: Duration = Duration::from_millis(500);

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Input(e)) => {
            eprintln!("viewer: {e}");
            ExitCode::from(2)
        }
        Err(Failure::Other(message)) => {
            eprintln!("viewer: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Why the viewer stopped: bad input (exit status 2) or anything else (1).
enum Failure {
    Input(Error),
    Other(String),
}

impl From<Error> for Failure {
    fn from(e: Error) -> Failure {
        if e.is_bad_input() { Failure::Input(e) } else { Failure::Other(e.to_string()) }
    }
}

fn run(args: &Args) -> Result<(), Failure> {
    let path = args.mesh.clone().unwrap_or_else(|| scene::shared_scene("stanford-bunny.obj"));
    // glTF scenes are shown flattened into one world-space mesh (the
    // viewer's scene is `bunny::mesh_scene`'s).
    let options = args.camera.options()?;
    let limits = args.limits.limits();
    let flat = match args.time {
        Some(time) => rt_scene::load_flat_at(&path, &limits, time),
        None => rt_scene::load_flat_with(&path, &limits),
    };
    let (mut loaded, file_camera) = flat.map_err(|e| match e {
        rt_scene::SceneError::Obj(e) => Error::Mesh(e),
        e => Error::Scene(e),
    })?;
    examples::model::turn(&mut loaded, options.up.to_y_up());
    for warning in &loaded.warnings {
        eprintln!("viewer: warning: {warning}");
    }
    let (backend, what) = BackendChoice::open_or_choose(args.backend)?;
    if args.present == Present::Gpu && backend != rt_runtime::Backend::Wgpu {
        return Err(Failure::Input(Error::Settings(format!(
            "`--present gpu` needs the wgpu backend; the {} backend renders on the host",
            backend.name()
        ))));
    }
    let (width, height) = args.size;
    let settings = Settings { spp: 1, backend, ..Settings::new(width, height) };
    let bounds = (loaded.min, loaded.max);
    let camera = options.camera(bounds, file_camera, options.up.to_y_up(), settings.aspect());
    options.check_camera(&path, &camera, bounds)?;
    let mut view = Progressive::framed(&loaded, &settings, options, file_camera)?;
    view.set_denoise(match (args.denoise, args.temporal) {
        (_, true) => Denoise::Temporal,
        (true, false) => Denoise::Spatial,
        (false, false) => Denoise::Off,
    });
    let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    let event_loop =
        EventLoop::new().map_err(|e| Failure::Other(format!("cannot open a window: {}", without_location(&e))))?;
    let mut app = App::new(args, view, name, backend.name());
    event_loop.run_app(&mut app).map_err(|e| Failure::Other(format!("the window's event loop failed: {e}")))?;
    if let Some(e) = app.failure.take() {
        return Err(e);
    }
    if let (Some(path), Some(image)) = (&args.screenshot, app.shown.as_ref()) {
        image.save_png(path)?;
    }
    if args.frames.is_some() {
        let totals = &app.totals;
        println!(
            "viewer: {} frames of {}x{} in {:.2} s with {what}, {}: {:.1} FPS, {:.2} Mrays/s, {} samples accumulated, {} bytes read back from the device by the last launch",
            totals.frames,
            app.view.width(),
            app.view.height(),
            totals.wall.as_secs_f64(),
            app.shown_window.as_ref().map_or("never shown", |s| s.screen.how()),
            totals.fps(),
            totals.mrays_per_second(),
            app.view.samples(),
            app.view.context().last_read_back_bytes()
        );
    }
    Ok(())
}

/// winit's message without the source location it starts with ("os error
/// at …/linux/mod.rs:765: neither … nor DISPLAY is set").
fn without_location(e: &dyn std::fmt::Display) -> String {
    let message = e.to_string();
    match message.strip_prefix("os error at ").and_then(|rest| rest.split_once(".rs:")) {
        Some((_, after)) => after.split_once(": ").map_or(message.clone(), |(_, m)| m.to_string()),
        None => message,
    }
}

/// Frames, rays and times added up over a stretch.
#[derive(Clone, Copy, Default)]
struct Tally {
    frames: u32,
    rays: u64,
    /// Time spent launching and reading back.
    launch_seconds: f64,
    /// Wall time the stretch covers.
    wall: Duration,
}

impl Tally {
    fn fps(&self) -> f64 {
        self.frames as f64 / self.wall.as_secs_f64().max(1e-9)
    }

    fn mrays_per_second(&self) -> f64 {
        self.rays as f64 / self.launch_seconds.max(1e-9) / 1e6
    }
}

/// The window and how it is filled.
struct Shown {
    window: Arc<Window>,
    screen: Screen,
}

/// How frames reach the window.
enum Screen {
    /// Through the host: each frame read back and copied into the window
    /// (softbuffer), as the CPU backend renders it.
    Host(softbuffer::Surface<Arc<Window>, Arc<Window>>),
    /// From the GPU: the launch's output, left on the device, drawn through
    /// a wgpu surface on the same device.
    Gpu(Box<GpuPresenter>),
}

impl Screen {
    /// How it shows frames, for the summary line.
    fn how(&self) -> &'static str {
        match self {
            Screen::Host(_) => "shown through the host (softbuffer)",
            Screen::Gpu(_) => "shown from the GPU (a wgpu surface on the launch's device)",
        }
    }
}

struct App {
    view: Progressive,
    name: String,
    backend: &'static str,
    shown_window: Option<Shown>,
    present: Present,
    /// The last picture presented, and its `0x00RRGGBB` words (shown again
    /// when the window needs it but the picture is as refined as it gets).
    shown: Option<Image>,
    shown_words: Vec<u32>,
    want_screenshot: bool,
    size: (u32, u32),
    frames_to_run: Option<u32>,
    spin: u32,
    max_spp: u32,
    /// Where the camera goes on the next frame.
    camera: Camera,
    dragging: bool,
    cursor: Option<PhysicalPosition<f64>>,
    keys_held: HashSet<KeyCode>,
    last_frame: Option<Instant>,
    started: Instant,
    totals: Tally,
    /// Since the title last changed.
    readout: Tally,
    readout_since: Instant,
    failure: Option<Failure>,
    /// The picture must be shown again as it is (the denoiser was turned
    /// on or off), even when no sample is to be added.
    restyle: bool,
}

/// The window's title: the model, the figures, the denoiser's mode.
fn title(name: &str, readout: &Tally, spp: u32, denoise: Denoise, backend: &str, exceptions: usize) -> String {
    format!(
        "{name} - {:.1} FPS, {:.2} Mrays/s, {spp} spp, denoiser {}, {backend} backend{}",
        readout.fps(),
        readout.mrays_per_second(),
        denoise.name(),
        if exceptions > 0 { format!(", {exceptions} exceptions") } else { String::new() }
    )
}

impl App {
    fn new(args: &Args, view: Progressive, name: String, backend: &'static str) -> App {
        App {
            camera: view.camera(),
            view,
            name,
            backend,
            shown_window: None,
            present: args.present,
            shown: None,
            shown_words: Vec::new(),
            want_screenshot: args.screenshot.is_some(),
            size: args.size,
            frames_to_run: args.frames,
            spin: args.spin,
            max_spp: args.max_spp,
            dragging: false,
            cursor: None,
            keys_held: HashSet::new(),
            last_frame: None,
            started: Instant::now(),
            totals: Tally::default(),
            readout: Tally::default(),
            readout_since: Instant::now(),
            failure: None,
            restyle: false,
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, failure: Failure) {
        self.failure.get_or_insert(failure);
        event_loop.exit();
    }

    /// Whether the picture is as refined as it gets. With `--frames`,
    /// never: the frames all refine.
    fn converged(&self) -> bool {
        self.frames_to_run.is_none() && self.view.samples() >= self.max_spp
    }

    /// Whether there is more to draw without new input.
    fn busy(&self) -> bool {
        !self.converged()
            || self.restyle
            || self.size != (self.view.width(), self.view.height())
            || self.keys_held.iter().any(|k| walk_direction(*k).is_some())
            || self.camera != self.view.camera()
    }

    /// Walks for the time since the last frame, refines, presents.
    fn redraw(&mut self) -> Result<(), Failure> {
        if self.shown_window.is_none() {
            return Ok(());
        }
        let now = Instant::now();
        let dt = self.last_frame.map_or(0.0, |t| (now - t).as_secs_f32().min(0.1));
        self.last_frame = Some(now);
        let step = self.keys_held.iter().filter_map(|k| walk_direction(*k)).fold(glam::Vec3::ZERO, |a, b| a + b);
        if step != glam::Vec3::ZERO {
            let d = step * WALK_SPEED * self.view.radius() * dt;
            self.camera = self.camera.moved(d.x, d.y, d.z);
        }
        if self.totals.frames < self.spin {
            self.camera = self.camera.orbited(10f32.to_radians(), 0.0);
        }
        let (width, height) = self.size;
        let (Some(w), Some(h)) = (NonZeroU32::new(width), NonZeroU32::new(height)) else {
            return Ok(()); // minimised
        };
        self.view.resize(width, height)?;
        self.view.set_camera(self.camera);
        let last = self.frames_to_run.is_some_and(|n| self.totals.frames + 1 >= n);
        let again = self.converged() && self.totals.frames > 0;
        let want_screenshot = last && self.want_screenshot;
        let shown = self.shown_window.as_mut().expect("checked above");
        let sample = match &mut shown.screen {
            Screen::Host(surface) => {
                if again && !self.restyle {
                    // Nothing new to draw: show the last picture again
                    // (the window may have been uncovered).
                    return show_words(surface, &self.shown_words);
                }
                let sample = if again { viewer::Sample::default() } else { self.view.sample()? };
                let image = self.view.picture()?;
                self.shown_words = viewer::to_xrgb(&image);
                surface.resize(w, h).map_err(window_failure)?;
                show_words(surface, &self.shown_words)?;
                self.shown = Some(image);
                if want_screenshot {
                    // The screenshot is the picture sent; reading the
                    // window back checks the whole way to the screen (a
                    // covered or off-screen window reads back wrong, or
                    // not at all).
                    check_window(|| surface.fetch().map_err(|e| e.to_string()), &self.shown_words, 1);
                }
                sample
            }
            Screen::Gpu(presenter) => {
                if again && !self.restyle {
                    return presenter.redraw((width, height)).map_err(Failure::Other);
                }
                let sample = if again { viewer::Sample::default() } else { self.view.sample()? };
                if self.view.denoising() != Denoise::Off {
                    // Denoised by the runtime's stage, which reads the
                    // guides on the device; its picture alone came back,
                    // and goes up from the host.
                    let image = self.view.picture()?;
                    presenter.present_image(&image).map_err(Failure::Other)?;
                    if want_screenshot {
                        check_window(fetch_window(&shown.window, (w, h)), &viewer::to_xrgb(&image), 50);
                    }
                    self.shown = Some(image);
                } else {
                    let out = self.view.output();
                    presenter.present(self.view.context(), out.buffer, out.stride, out.size).map_err(Failure::Other)?;
                }
                if want_screenshot && self.view.denoising() == Denoise::Off {
                    // The picture the device holds, read back once, and
                    // the window as the X server has it (the presentation
                    // may reach it a little later).
                    let image = self.view.picture()?;
                    let words = viewer::to_xrgb(&image);
                    check_window(fetch_window(&shown.window, (w, h)), &words, 50);
                    self.shown = Some(image);
                }
                sample
            }
        };
        for tally in [&mut self.totals, &mut self.readout] {
            tally.frames += 1;
            tally.rays += sample.rays;
            tally.launch_seconds += sample.seconds;
        }
        self.totals.wall = self.started.elapsed();
        self.readout.wall = self.readout_since.elapsed();
        if self.totals.frames == 1 || self.readout.wall >= READOUT_PERIOD || self.restyle {
            let spp = self.view.samples();
            let denoise = self.view.denoising();
            shown.window.set_title(&title(&self.name, &self.readout, spp, denoise, self.backend, sample.exceptions));
            self.readout = Tally::default();
            self.readout_since = Instant::now();
        }
        self.restyle = false;
        Ok(())
    }

    /// Opens the window, and on the wgpu backend a surface on the
    /// context's device (the device opened for it), falling back to the
    /// host's way with a warning when there is none.
    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<(), String> {
        let attributes = Window::default_attributes()
            .with_title(format!("{} - {} backend", self.name, self.backend))
            .with_inner_size(PhysicalSize::new(self.size.0, self.size.1));
        let window = Arc::new(event_loop.create_window(attributes).map_err(|e| e.to_string())?);
        let size = window.inner_size();
        self.size = (size.width, size.height);
        let mut screen = None;
        if self.view.context().backend() == rt_runtime::Backend::Wgpu && self.present != Present::Host {
            match GpuPresenter::open(self.view.context_mut(), window.clone(), self.size) {
                Ok(presenter) => {
                    self.view.keep_on_device(true).map_err(|e| e.to_string())?;
                    screen = Some(Screen::Gpu(Box::new(presenter)));
                }
                Err(e) if self.present == Present::Gpu => return Err(format!("cannot show frames from the GPU: {e}")),
                Err(e) => eprintln!("viewer: warning: cannot show frames from the GPU ({e}); they go through the host"),
            }
        }
        let screen = match screen {
            Some(screen) => screen,
            None => {
                let context = softbuffer::Context::new(window.clone()).map_err(|e| e.to_string())?;
                Screen::Host(softbuffer::Surface::new(&context, window.clone()).map_err(|e| e.to_string())?)
            }
        };
        window.request_redraw();
        self.shown_window = Some(Shown { window, screen });
        Ok(())
    }
}

fn window_failure(e: softbuffer::SoftBufferError) -> Failure {
    Failure::Other(format!("cannot draw in the window: {e}"))
}

/// Copies `words` into the window and presents them (unless the window's
/// size changed since they were made).
fn show_words(surface: &mut softbuffer::Surface<Arc<Window>, Arc<Window>>, words: &[u32]) -> Result<(), Failure> {
    let mut buffer = surface.buffer_mut().map_err(window_failure)?;
    if buffer.len() == words.len() {
        buffer.copy_from_slice(words);
        buffer.present().map_err(window_failure)?;
    }
    Ok(())
}

/// The window's pixels as the X server has them, read through softbuffer
/// (whatever drew them).
fn fetch_window(window: &Arc<Window>, (w, h): (NonZeroU32, NonZeroU32)) -> impl FnMut() -> Result<Vec<u32>, String> {
    let surface = softbuffer::Context::new(window.clone())
        .and_then(|context| softbuffer::Surface::new(&context, window.clone()))
        .and_then(|mut surface| surface.resize(w, h).map(|()| surface));
    let mut surface = surface.map_err(|e| e.to_string());
    move || match &mut surface {
        Ok(surface) => surface.fetch().map_err(|e| e.to_string()),
        Err(e) => Err(e.clone()),
    }
}

/// Warns unless the window reads back as `sent` (`0x00RRGGBB` words),
/// asking `fetch` up to `tries` times, 20 ms apart.
fn check_window(mut fetch: impl FnMut() -> Result<Vec<u32>, String>, sent: &[u32], tries: u32) {
    for attempt in 1..=tries {
        match fetch() {
            Ok(words) if words.len() == sent.len() && words.iter().zip(sent).all(|(a, b)| a & 0x00ff_ffff == *b) => {
                return;
            }
            Ok(_) if attempt < tries => std::thread::sleep(Duration::from_millis(20)),
            Ok(_) => eprintln!(
                "viewer: warning: the window reads back different from the picture sent to it (covered?); the screenshot is the picture sent"
            ),
            Err(e) => {
                eprintln!(
                    "viewer: warning: cannot read the window back ({e}); the screenshot is the picture sent to it"
                );
                return;
            }
        }
    }
}

/// Where a walking key goes: (right, up, forward).
fn walk_direction(key: KeyCode) -> Option<glam::Vec3> {
    Some(match key {
        KeyCode::KeyW => glam::Vec3::Z,
        KeyCode::KeyS => -glam::Vec3::Z,
        KeyCode::KeyD => glam::Vec3::X,
        KeyCode::KeyA => -glam::Vec3::X,
        KeyCode::KeyE => glam::Vec3::Y,
        KeyCode::KeyQ => -glam::Vec3::Y,
        _ => return None,
    })
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.shown_window.is_none()
            && let Err(e) = self.open(event_loop)
        {
            self.fail(event_loop, Failure::Other(format!("cannot open a window: {e}")));
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => self.size = (size.width, size.height),
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.redraw() {
                    return self.fail(event_loop, e);
                }
                if self.frames_to_run.is_some_and(|n| self.totals.frames >= n) {
                    event_loop.exit();
                }
            }
            WindowEvent::MouseInput { state, button: MouseButton::Left, .. } => {
                self.dragging = state == ElementState::Pressed;
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let (true, Some(last)) = (self.dragging, self.cursor) {
                    let (dx, dy) = ((position.x - last.x) as f32, (position.y - last.y) as f32);
                    self.camera = self.camera.orbited(-dx * ORBIT_PER_PIXEL, dy * ORBIT_PER_PIXEL);
                }
                self.cursor = Some(position);
            }
            WindowEvent::CursorLeft { .. } => self.cursor = None,
            WindowEvent::MouseWheel { delta, .. } => {
                let notches = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                self.camera = self.camera.dollied(1.0 - (1.0 - ZOOM_PER_NOTCH).powf(notches));
            }
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(key) = event.physical_key else { return };
                if event.state == ElementState::Released {
                    self.keys_held.remove(&key);
                    return;
                }
                self.keys_held.insert(key);
                match key {
                    KeyCode::KeyR => self.camera = self.view.home_camera(),
                    KeyCode::KeyN => {
                        self.view.set_denoise(self.view.denoising().next());
                        self.restyle = true;
                    }
                    KeyCode::Escape => event_loop.exit(),
                    _ => {}
                }
            }
            WindowEvent::Focused(false) => self.keys_held.clear(),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(shown) = &self.shown_window
            && (self.busy() || self.totals.frames == 0)
        {
            shown.window.request_redraw();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_title_says_the_denoisers_mode() {
        let readout = Tally { frames: 10, rays: 2_000_000, launch_seconds: 2.0, wall: Duration::from_secs(2) };
        let on = title("bunny.obj", &readout, 12, Denoise::Spatial, "cpu", 0);
        assert_eq!(on, "bunny.obj - 5.0 FPS, 1.00 Mrays/s, 12 spp, denoiser spatial, cpu backend");
        let temporal = title("bunny.obj", &readout, 12, Denoise::Temporal, "cpu", 0);
        assert_eq!(temporal, "bunny.obj - 5.0 FPS, 1.00 Mrays/s, 12 spp, denoiser temporal, cpu backend");
        let off = title("bunny.obj", &readout, 12, Denoise::Off, "wgpu", 3);
        assert_eq!(off, "bunny.obj - 5.0 FPS, 1.00 Mrays/s, 12 spp, denoiser off, wgpu backend, 3 exceptions");
    }
}
