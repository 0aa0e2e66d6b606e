//! The host side every example shares: render settings, the camera, a built
//! [`Scene`] and how it renders into an in-memory [`Image`], the errors, and
//! small meshes made in code.

use glam::{UVec2, Vec3, Vec4};
use rt_runtime::{
    Backend, BufferId, BufferType, Context, ExceptionRecord, LaunchControl, LaunchReport, RtError, Scope, Tile,
    Traversal, TriangleMesh,
};
use std::path::{Path, PathBuf};
use web_time::Instant;

/// Which backend renders, as the binaries' `--backend` names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(not(target_arch = "wasm32"), derive(clap::ValueEnum))]
pub enum BackendChoice {
    /// Programs run natively as Rust on every core.
    Cpu,
    /// Programs linked into one WGSL megakernel on a wgpu adapter.
    Wgpu,
}

impl BackendChoice {
    /// The runtime's backend for this choice.
    pub fn backend(self) -> Backend {
        match self {
            BackendChoice::Cpu => Backend::Cpu,
            BackendChoice::Wgpu => Backend::Wgpu,
        }
    }

    /// `choice`, or when there is none the runtime's default
    /// ([`Backend::choose`]: a GPU if wgpu finds one, else the CPU backend),
    /// with a line saying what runs the launches and why.
    pub fn open_or_choose(choice: Option<BackendChoice>) -> Result<(Backend, String), Error> {
        if let Some(c) = choice {
            return c.open();
        }
        let (backend, why) = Backend::choose()?;
        let c = match backend {
            Backend::Wgpu => BackendChoice::Wgpu,
            _ => BackendChoice::Cpu,
        };
        let (backend, what) = c.open()?;
        Ok((backend, format!("{what}, chosen because: {why}")))
    }

    /// The backend and a line saying what will run the launches (threads,
    /// or the adapter), or why it cannot: the wgpu backend needs an adapter.
    pub fn open(self) -> Result<(Backend, String), Error> {
        let backend = self.backend();
        let what = match backend {
            Backend::Wgpu => {
                let info = rt_runtime::backend::wgpu::probe().ok_or(Error::BackendUnavailable {
                    name: "wgpu",
                    why: "wgpu finds no adapter (no GPU, and no Vulkan driver such as Mesa's lavapipe); run with `--backend cpu`".into(),
                })?;
                let (traversal, why) = rt_runtime::Traversal::choose()?;
                let traversal = match traversal {
                    rt_runtime::Traversal::RayQuery => "hardware ray queries",
                    _ => "the compute traversal",
                };
                format!("the wgpu backend on {} ({:?}) with {traversal} ({why})", info.name, info.device_type)
            }
            _ => format!(
                "the {} backend ({} threads)",
                backend.name(),
                std::thread::available_parallelism().map_or(1, |n| n.get())
            ),
        };
        Ok((backend, what))
    }
}

/// How big and how carefully to render.
#[derive(Clone, Copy, Debug)]
pub struct Settings {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel of the stochastic examples (the path-traced Cornell
    /// box, ambient occlusion); the Whitted examples trace one camera ray per
    /// pixel whatever this says.
    pub spp: u32,
    pub backend: Backend,
    /// How the wgpu backend walks the scene (`Auto`: ray queries where the
    /// adapter has them).
    pub traversal: Traversal,
}

impl Settings {
    /// Default image size of the binaries.
    pub const DEFAULT_WIDTH: u32 = 512;
    pub const DEFAULT_HEIGHT: u32 = 384;
    /// Default samples per pixel: the whole tour takes about 29 s in
    /// release on the 2-core CI VM (BENCHMARKS.md).
    pub const DEFAULT_SPP: u32 = 64;
    /// The most pixels a render takes (8K UHD, 7680x4320, fits): each is
    /// 16 bytes in several buffers (output, accumulation, display), so a
    /// 16384x16384 picture would need tens of GiB.
    pub const MAX_PIXELS: u64 = 40 << 20;

    pub fn new(width: u32, height: u32) -> Self {
        Settings { width, height, spp: Self::DEFAULT_SPP, backend: Backend::Cpu, traversal: Traversal::Auto }
    }

    pub fn with_spp(self, spp: u32) -> Self {
        Settings { spp, ..self }
    }

    /// Width over height.
    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height.max(1) as f32
    }

    pub(crate) fn check(&self) -> Result<(), Error> {
        if self.width == 0 || self.height == 0 || self.width > 16384 || self.height > 16384 {
            return Err(Error::Settings(format!("image size {}x{} is outside 1..=16384", self.width, self.height)));
        }
        let pixels = self.width as u64 * self.height as u64;
        if pixels > Self::MAX_PIXELS {
            return Err(Error::Settings(format!(
                "image size {}x{} is {pixels} pixels, over the {} a render holds in memory (16 bytes each, several \
                 buffers)",
                self.width,
                self.height,
                Self::MAX_PIXELS
            )));
        }
        if self.spp == 0 {
            return Err(Error::Settings("--spp must be at least 1".into()));
        }
        Ok(())
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings::new(Self::DEFAULT_WIDTH, Self::DEFAULT_HEIGHT)
    }
}

/// Everything that can go wrong building or rendering an example.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Boxed: the runtime's errors are large, and every builder returns this.
    #[error(transparent)]
    Runtime(Box<RtError>),
    #[error(transparent)]
    Mesh(#[from] crate::mesh::MeshError),
    /// A glTF file (or a file of no known format) that cannot be used.
    #[error(transparent)]
    Scene(#[from] rt_scene::SceneError),
    #[error("the {name} backend is not available: {why}")]
    BackendUnavailable { name: &'static str, why: String },
    #[error("{0}")]
    Settings(String),
    #[error("{path}: {problem}")]
    Io { path: String, problem: String },
    /// A part file of a picture rendered in parts that cannot be used.
    #[error("{path}: {problem}")]
    Part { path: String, problem: String },
}

impl Error {
    /// Whether the input is at fault (a bad file, bad arguments, a backend
    /// that is not there): the binaries exit 2 for these.
    pub fn is_bad_input(&self) -> bool {
        match self {
            Error::Mesh(_) | Error::BackendUnavailable { .. } | Error::Settings(_) | Error::Part { .. } => true,
            Error::Scene(e) => e.is_bad_input(),
            Error::Runtime(_) | Error::Io { .. } => false,
        }
    }
}

impl From<RtError> for Error {
    fn from(e: RtError) -> Error {
        Error::Runtime(Box::new(e))
    }
}

/// A pinhole camera: where it is, what it looks at, which way is up, and
/// its vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub look_at: Vec3,
    pub up: Vec3,
    pub vfov_degrees: f32,
}

impl Camera {
    /// The `u`, `v`, `w` vectors of the seed's camera: a ray through `d` in
    /// `[-1, 1]^2` has direction `d.x * u + d.y * v + w`; `w` is the unit
    /// view direction, `v` points up and `u` right.
    pub fn uvw(&self, aspect: f32) -> (Vec3, Vec3, Vec3) {
        let w = (self.look_at - self.eye).normalize();
        let right = w.cross(self.up).normalize();
        let up = right.cross(w);
        let half = (self.vfov_degrees.to_radians() * 0.5).tan();
        (right * half * aspect, up * half, w)
    }

    /// Where point `p` appears: `d` in `[-1, 1]^2` as the camera programs
    /// use it (`(-1, -1)` the bottom-left corner), or `None` behind the
    /// camera.
    pub fn to_screen(&self, p: Vec3, aspect: f32) -> Option<glam::Vec2> {
        let (u, v, w) = self.uvw(aspect);
        let d = p - self.eye;
        let depth = d.dot(w);
        (depth > 0.0).then(|| glam::Vec2::new(d.dot(u) / u.length_squared(), d.dot(v) / v.length_squared()) / depth)
    }

    /// The launch index (pixel) where point `p` appears in a `width` x
    /// `height` picture, if it is in the frame.
    pub fn pixel_of(&self, p: Vec3, width: u32, height: u32) -> Option<(u32, u32)> {
        let d = self.to_screen(p, width as f32 / height as f32)?;
        let px = (d + 1.0) * 0.5 * glam::Vec2::new(width as f32, height as f32);
        let inside = px.x >= 0.0 && px.y >= 0.0 && px.x < width as f32 && px.y < height as f32;
        inside.then_some((px.x as u32, px.y as u32))
    }

    /// The direction of the ray through the centre of pixel `(x, y)`.
    pub fn ray_direction(&self, x: u32, y: u32, width: u32, height: u32) -> Vec3 {
        let (u, v, w) = self.uvw(width as f32 / height as f32);
        let d = (glam::Vec2::new(x as f32, y as f32) + 0.5) / glam::Vec2::new(width as f32, height as f32) * 2.0 - 1.0;
        (d.x * u + d.y * v + w).normalize()
    }

    /// Sets `eye`, `u`, `v` and `w` on the context.
    pub fn set_vars(&self, ctx: &mut Context, aspect: f32) -> Result<(), Error> {
        let (u, v, w) = self.uvw(aspect);
        ctx.set_var(Scope::Context, "eye", self.eye)?;
        ctx.set_var(Scope::Context, "u", u)?;
        ctx.set_var(Scope::Context, "v", v)?;
        ctx.set_var(Scope::Context, "w", w)?;
        Ok(())
    }

    /// The camera turned about `look_at`: `yaw` radians about `up` (positive
    /// turns the eye to the camera's right), then `pitch` radians towards
    /// `up` (positive raises the eye), stopping short of looking straight
    /// down or up. The distance to `look_at` is kept.
    pub fn orbited(&self, yaw: f32, pitch: f32) -> Camera {
        let up = self.up.normalize();
        let offset = self.eye - self.look_at;
        let distance = offset.length();
        let turned = glam::Quat::from_axis_angle(up, yaw) * offset;
        let elevation = (turned.dot(up) / distance).clamp(-1.0, 1.0).asin();
        let limit = 89f32.to_radians();
        let pitch = (elevation + pitch).clamp(-limit, limit) - elevation;
        let right = up.cross(turned);
        let turned = match right.try_normalize() {
            Some(axis) => glam::Quat::from_axis_angle(axis, -pitch) * turned,
            None => turned,
        };
        Camera { eye: self.look_at + turned.normalize() * distance, ..*self }
    }

    /// The camera moved towards `look_at` by `factor` of its distance
    /// (negative backs away), never reaching it.
    pub fn dollied(&self, factor: f32) -> Camera {
        let offset = self.eye - self.look_at;
        Camera { eye: self.look_at + offset * (1.0 - factor).max(1e-3), ..*self }
    }

    /// The camera and what it looks at moved together by `right`, `up` and
    /// `forward` along its own axes (`forward` level with the ground, `up`
    /// along `self.up`): walking, as in a game.
    pub fn moved(&self, right: f32, up: f32, forward: f32) -> Camera {
        let vertical = self.up.normalize();
        let view = self.look_at - self.eye;
        let level = (view - vertical * view.dot(vertical)).try_normalize().unwrap_or(view.normalize());
        let side = level.cross(vertical);
        let step = side * right + vertical * up + level * forward;
        Camera { eye: self.eye + step, look_at: self.look_at + step, ..*self }
    }

    /// A camera looking along `direction` at the bounding box `[min, max]`,
    /// backed off until all eight corners are in view, with a small margin.
    pub fn framing(min: Vec3, max: Vec3, direction: Vec3, vfov_degrees: f32, aspect: f32) -> Camera {
        let center = (min + max) * 0.5;
        let w = direction.normalize();
        let up = if w.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
        let right = w.cross(up).normalize();
        let true_up = right.cross(w);
        let tan_v = (vfov_degrees.to_radians() * 0.5).tan();
        let tan_h = tan_v * aspect;
        let mut distance = 1e-6f32;
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            );
            let p = corner - center;
            // The corner is in view from `distance` back when |x| <= tan_h
            // * depth and |y| <= tan_v * depth, depth = distance + p.w.
            let depth_needed = (p.dot(right).abs() / tan_h).max(p.dot(true_up).abs() / tan_v);
            distance = distance.max(depth_needed - p.dot(w));
        }
        Camera { eye: center - w * distance * 1.1, look_at: center, up, vfov_degrees }
    }
}

/// A scene ready to launch: the context, the buffer that holds the picture,
/// and how many launches make one picture.
pub struct Scene {
    pub ctx: Context,
    /// A `width` x `height` `Vec4` buffer, launch index (0, 0) bottom-left.
    pub output: BufferId,
    /// The buffer a progressive scene accumulates its samples in, if any.
    pub accumulation: Option<BufferId>,
    pub width: u32,
    pub height: u32,
    /// Launches per picture: progressive scenes accumulate one launch per
    /// frame; before each, the context variable `frame` is set to its number
    /// (from 0).
    pub frames: u32,
    /// A launch of another entry point, at its own size, before entry 0 in
    /// every frame (after `frame` is set): whole, whatever rows are
    /// rendered, so entry 0 sees what a whole render gives it (the
    /// receiver grid's rays, which entry 0 shows).
    pub pre_launch: Option<(u32, UVec2)>,
    /// The guide outputs (AOVs) a denoiser reads, where the scene writes
    /// them.
    pub aovs: Option<Aovs>,
}

/// What a path-traced scene writes beside its picture for a denoiser
/// ([`rt_runtime::postprocess`]): `width` x `height` `Vec4` buffers of the
/// mean linear radiance, the first hit's albedo and its shading normal,
/// each averaged over the samples so far (zero where a path hit nothing),
/// and the luminance's variance entry ([`crate::guides`]: in x the
/// variance of the mean, the denoiser's `input_variance_buffer`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Aovs {
    pub radiance: BufferId,
    pub albedo: BufferId,
    pub normal: BufferId,
    pub variance: BufferId,
    /// The first hit's world position (xyz over w, w the fraction of the
    /// samples that hit something), the temporal denoiser's guide, where
    /// the camera writes it.
    pub position: Option<BufferId>,
}

/// One rendered picture and what it cost.
pub struct Rendered {
    /// What the camera program wrote: for display, gamma corrected.
    pub image: Image,
    /// The mean radiance of every pixel, linear (what an EXR holds), where
    /// the scene accumulates its samples ([`Scene::accumulation`]); alpha
    /// is 1 where the pixel was rendered, 0 where not.
    pub radiance: Option<Image>,
    /// Rays traced, over every launch.
    pub rays: u64,
    /// Wall time of the launches (the scene build is not counted).
    pub seconds: f64,
    pub launches: u32,
    /// Exceptions raised (each painted in the exception program's colour).
    pub exceptions: Vec<ExceptionRecord>,
}

impl Rendered {
    /// Millions of rays per second.
    pub fn mrays_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-9) / 1e6
    }
}

impl Scene {
    /// The usual start of a scene: a context on `settings.backend` with two
    /// ray types (radiance, shadow), entry point 0's exception program, an
    /// output buffer and `scene_epsilon`.
    pub fn start(settings: &Settings, scene_epsilon: f32) -> Result<(Context, BufferId), Error> {
        settings.check()?;
        let mut ctx = Context::new();
        ctx.set_backend(settings.backend);
        ctx.set_traversal(settings.traversal);
        ctx.set_ray_type_count(2);
        let ex = ctx.create_program(&crate::common::exception::PROGRAM);
        ctx.set_exception_program(0, ex)?;
        let output = ctx.create_buffer_2d::<Vec4>(BufferType::Output, settings.width, settings.height)?;
        ctx.set_var(Scope::Context, "output_buffer", output)?;
        ctx.set_var(Scope::Context, "bad_color", Vec3::new(1.0, 0.0, 1.0))?;
        ctx.set_var(Scope::Context, "scene_epsilon", scene_epsilon)?;
        Ok((ctx, output))
    }

    /// A one-launch scene.
    pub fn new(ctx: Context, output: BufferId, settings: &Settings) -> Scene {
        Scene {
            ctx,
            output,
            accumulation: None,
            width: settings.width,
            height: settings.height,
            frames: 1,
            pre_launch: None,
            aovs: None,
        }
    }

    /// Launches entry point 0 `frames` times, calling `progress` after
    /// each tile of each launch (the context cuts launches into tiles,
    /// [`Context::set_tile_budget`]), and reads the output back.
    pub fn render(&mut self, progress: &mut dyn FnMut(Progress)) -> Result<Rendered, Error> {
        self.render_rows(0..self.height, progress)
    }

    /// [`Scene::render`] awaiting each launch
    /// ([`Context::launch_async`]), as a browser page must: the same
    /// launches, whole (no progress between tiles).
    pub async fn render_async(&mut self) -> Result<Rendered, Error> {
        let mut tally = Tally::new();
        for frame in 0..self.frames {
            self.ctx.set_var(Scope::Context, "frame", frame)?;
            if let Some((entry, size)) = self.pre_launch {
                tally.add(self.ctx.launch_async(entry, size.x, size.y).await?);
            }
            tally.add(self.ctx.launch_async(0, self.width, self.height).await?);
        }
        self.finish(tally)
    }

    /// [`Scene::render`] of the rows `rows` only (on the launch's 8-row
    /// grid, [`crate::parts::band`]): every program sees the whole picture,
    /// so these rows are what a whole render gives them; the image's other
    /// rows are not rendered.
    pub fn render_rows(
        &mut self,
        rows: std::ops::Range<u32>,
        progress: &mut dyn FnMut(Progress),
    ) -> Result<Rendered, Error> {
        let part = Tile { origin: UVec2::new(0, rows.start), size: UVec2::new(self.width, rows.len() as u32) };
        let mut tally = Tally::new();
        let frames = self.frames;
        for frame in 0..frames {
            self.ctx.set_var(Scope::Context, "frame", frame)?;
            if let Some((entry, size)) = self.pre_launch {
                tally.add(self.ctx.launch(entry, size.x, size.y)?);
            }
            tally.add(self.ctx.launch_part(0, self.width, self.height, part, |p| {
                progress(Progress { frame, frames, within: p.fraction() });
                LaunchControl::Continue
            })?);
        }
        self.finish(tally)
    }

    /// What a render gives once its launches ran: the output read back, and
    /// the mean radiance where the scene accumulates.
    fn finish(&mut self, tally: Tally) -> Result<Rendered, Error> {
        let seconds = tally.start.elapsed().as_secs_f64();
        let pixels = self.ctx.read_buffer::<Vec4>(self.output)?;
        let image = Image { width: self.width, height: self.height, pixels };
        let radiance = match self.accumulation {
            Some(sums) => {
                let mean = |s: Vec4| if s.w > 0.0 { (s.truncate() / s.w).extend(1.0) } else { Vec4::ZERO };
                let pixels = self.ctx.read_buffer::<Vec4>(sums)?.into_iter().map(mean).collect();
                Some(Image { width: self.width, height: self.height, pixels })
            }
            None => None,
        };
        let Tally { rays, exceptions, .. } = tally;
        Ok(Rendered { image, radiance, rays, seconds, launches: self.frames, exceptions })
    }
}

/// A render's launches so far: rays, exceptions, when it started.
struct Tally {
    rays: u64,
    exceptions: Vec<ExceptionRecord>,
    start: Instant,
}

impl Tally {
    fn new() -> Tally {
        Tally { rays: 0, exceptions: Vec::new(), start: Instant::now() }
    }

    fn add(&mut self, report: LaunchReport) {
        self.rays += report.rays;
        self.exceptions.extend(report.exceptions);
    }
}

/// Where [`Scene::render`] stands: in launch `frame` of `frames`, the
/// fraction `within` of it done.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    pub frame: u32,
    pub frames: u32,
    pub within: f64,
}

impl Progress {
    /// Launches finished.
    pub fn frames_done(&self) -> u32 {
        if self.within >= 1.0 { self.frame + 1 } else { self.frame }
    }

    /// The whole render's fraction done, from 0 to 1.
    pub fn fraction(&self) -> f64 {
        (self.frame as f64 + self.within) / self.frames.max(1) as f64
    }
}

/// An RGBA float image in launch-index order: row 0 is the bottom row.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Vec4>,
}

impl Image {
    /// The picture for display from linear radiance: clamped at 0, gamma
    /// 2.2, alpha 1 (as the progressive cameras write their output, to the
    /// bit on the CPU backend).
    pub fn to_display(&self) -> Image {
        let pixels = self.pixels.iter().map(|p| p.truncate().max(Vec3::ZERO).powf(1.0 / 2.2).extend(1.0)).collect();
        Image { width: self.width, height: self.height, pixels }
    }

    /// The pixel at launch index `(x, y)` (y up from the bottom).
    pub fn at(&self, x: u32, y: u32) -> Vec4 {
        self.pixels[(y * self.width + x) as usize]
    }

    /// The picture as PNG bytes (8 bits, clamped, top row first).
    pub fn encode_png(&self) -> Result<Vec<u8>, Error> {
        let rgba = rt_runtime::image_out::to_rgba8(self.width, self.height, &self.pixels);
        let mut bytes = std::io::Cursor::new(Vec::new());
        rgba.write_to(&mut bytes, image::ImageFormat::Png)
            .map_err(|e| Error::Io { path: "<memory>".into(), problem: e.to_string() })?;
        Ok(bytes.into_inner())
    }

    /// Writes the PNG whole or not at all: encoded in memory, written beside
    /// `path` and renamed over it.
    pub fn save_png(&self, path: &Path) -> Result<(), Error> {
        let bytes = self.encode_png()?;
        write_whole(path, bytes)
    }

    /// Writes the picture as OpenEXR (float RGBA, values as they are), whole
    /// or not at all as [`Image::save_png`] does.
    pub fn save_exr(&self, path: &Path) -> Result<(), Error> {
        let bytes = rt_runtime::image_out::encode_exr(self.width, self.height, &self.pixels)
            .map_err(|e| Error::Io { path: path.display().to_string(), problem: e })?;
        write_whole(path, bytes)
    }
}

/// `bytes` written beside `path` and renamed over it.
pub(crate) fn write_whole(path: &Path, bytes: Vec<u8>) -> Result<(), Error> {
    let io = |e: std::io::Error| Error::Io { path: path.display().to_string(), problem: e.to_string() };
    let mut tmp = PathBuf::from(path);
    tmp.set_file_name(format!(
        ".{}.partial",
        path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default()
    ));
    std::fs::write(&tmp, bytes).map_err(io)?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io(e)
    })
}

/// A quad `corner, corner + a, corner + a + b, corner + b` as two triangles;
/// its geometric normal is `a x b`.
pub fn quad(corner: Vec3, a: Vec3, b: Vec3) -> TriangleMesh {
    TriangleMesh {
        positions: vec![corner, corner + a, corner + a + b, corner + b],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..TriangleMesh::default()
    }
}

/// An axis-aligned box with outward normals, turned `yaw` radians about the
/// vertical through its centre: 12 triangles, 4 vertices per face (flat).
pub fn oriented_box(min: Vec3, max: Vec3, yaw: f32) -> TriangleMesh {
    let center = (min + max) * 0.5;
    let half = (max - min) * 0.5;
    let rot = glam::Quat::from_rotation_y(yaw);
    let mut mesh = TriangleMesh::default();
    // Each face: its normal axis, and two tangents with t1 x t2 = normal.
    let faces = [
        (Vec3::X, Vec3::Y, Vec3::Z),
        (-Vec3::X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z, Vec3::X),
        (-Vec3::Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (-Vec3::Z, Vec3::Y, Vec3::X),
    ];
    for (n, t1, t2) in faces {
        let base = mesh.positions.len() as u32;
        for (s1, s2) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let local = (n + t1 * s1 + t2 * s2) * half;
            mesh.positions.push(center + rot * local);
        }
        mesh.indices.push([base, base + 1, base + 2]);
        mesh.indices.push([base, base + 2, base + 3]);
    }
    mesh
}

/// Where the repository's shared test scenes are (`../shared/scenes` from
/// the project root).
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/scenes")
}

/// One of the shared scenes by file name.
pub fn shared_scene(name: &str) -> PathBuf {
    scenes_dir().join(name)
}
