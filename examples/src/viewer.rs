//! The `viewer` binary's rendering, without the window: a mesh shown as
//! [`bunny::mesh_scene`] shows it, refined progressively while the camera
//! is still.
//!
//! [`Progressive`] launches the scene once per [`refine`](Progressive::refine)
//! with the context variable `frame` set to the number of samples so far:
//! [`bunny::accumulating_camera`] restarts its running mean at `frame` 0
//! (one ray through each pixel's centre) and jitters the camera ray and the
//! occlusion rays of every later sample. Moving the camera or resizing
//! starts again from sample 0, so a still view after `n` refinements is
//! exactly what `render --spp n` draws of it.
//!
//! With [`Progressive::set_denoise`] at [`Denoise::Spatial`],
//! [`Progressive::picture`] is the running mean through the runtime's
//! denoiser stage ([`rt_runtime::postprocess`], its spatial filter
//! [`rt_runtime::postprocess::denoise`]) over the guides the camera
//! writes, gamma corrected as the camera corrects its own; the samples go
//! on accumulating as before, so turning it off shows the raw mean of the
//! same samples. At [`Denoise::Temporal`] the stage runs in its temporal
//! mode ([`rt_runtime::postprocess::temporal`]): each picture is blended
//! into the last one's history reprojected through the last camera, so
//! that a moved camera, which starts the samples again, keeps what it saw
//! of the points still in view (those it did not see, or that a closer
//! surface hid, start again); a resize, or turning the mode on, starts
//! with no history.
//!
//! While denoising, each refinement is one command list, the launch then
//! the stage: on the wgpu backend one submission, the stage reading the
//! mean radiance and the guides where the launch left them on the device
//! and keeping its history there, so nothing but the denoised picture
//! comes back to the host (the output and accumulation buffers stay on
//! the device too). On the CPU backend the stage runs natively, as the
//! same filter.
//!
//! The runtime cannot free or resize a buffer, so the output,
//! accumulation, guide and denoised buffers only grow: a smaller picture
//! is launched, and the stage run, over the top-left part of them (launch
//! indices and stages address buffers by their own width) and cropped on
//! the way out.
//!
//! ```no_run
//! use examples::{Settings, mesh, viewer::Progressive};
//! let loaded = mesh::load_obj(&examples::scene::shared_scene("teapot.obj"))?;
//! let mut view = Progressive::new(&loaded, &Settings::new(320, 240))?;
//! for _ in 0..16 {
//!     view.refine()?;
//! }
//! view.set_camera(view.camera().orbited(0.3, 0.0)); // back to sample 0
//! let frame = view.refine()?;
//! assert_eq!(view.samples(), 1);
//! frame.image.save_png(std::path::Path::new("teapot.png"))?;
//! # Ok::<(), examples::Error>(())
//! ```

use crate::bunny;
use crate::mesh::LoadedMesh;
use crate::model::CameraOptions;
use crate::scene::{Camera, Error, Image, Scene, Settings};
use glam::{Vec3, Vec4};
use rt_runtime::{BufferId, BufferType, CommandList, LaunchReport, Scope, StageId, StageKind};
use rt_scene::SceneCamera;
use std::time::Instant;

/// One refinement: the picture so far and what the launch cost.
pub struct Frame {
    /// The running mean over [`Progressive::samples`] samples, gamma
    /// corrected, launch-index order (row 0 at the bottom).
    pub image: Image,
    pub sample: Sample,
}

/// What one sample's launch cost.
#[derive(Clone, Copy, Debug, Default)]
pub struct Sample {
    /// Rays this launch traced.
    pub rays: u64,
    /// Wall time of the launch and the read-back.
    pub seconds: f64,
    /// Pixels that raised an exception (painted magenta).
    pub exceptions: usize,
}

/// The buffer a window shows: the output buffer, its rows' length, and
/// the part of it the picture takes.
#[derive(Clone, Copy, Debug)]
pub struct Output {
    pub buffer: rt_runtime::BufferId,
    pub stride: u32,
    pub size: (u32, u32),
}

/// What [`Progressive::picture`] shows: the raw mean, or it denoised.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Denoise {
    /// The running mean as it is.
    #[default]
    Off,
    /// Through the denoiser's spatial filter.
    Spatial,
    /// Through its temporal pass, then its spatial filter.
    Temporal,
}

impl Denoise {
    /// The mode after this one, as the viewer's N key steps: off,
    /// spatial, temporal, off.
    pub fn next(self) -> Denoise {
        match self {
            Denoise::Off => Denoise::Spatial,
            Denoise::Spatial => Denoise::Temporal,
            Denoise::Temporal => Denoise::Off,
        }
    }

    /// How the viewer's title says it.
    pub fn name(self) -> &'static str {
        match self {
            Denoise::Off => "off",
            Denoise::Spatial => "spatial",
            Denoise::Temporal => "temporal",
        }
    }
}

/// The runtime's denoiser stage over the scene's guides, the buffer it
/// writes (of `capacity`), and what that holds.
struct Denoiser {
    stage: StageId,
    output: BufferId,
    capacity: (u32, u32),
    /// The launch and the size of the picture in `output`, where it is
    /// the current mode's.
    done: Option<(u64, (u32, u32))>,
    /// Whether the next run starts with no history.
    fresh: bool,
}

/// The temporal mode's `alpha_min`: a still view's picture follows its
/// running mean (which gains a sample each frame) within a few frames.
const TEMPORAL_ALPHA_MIN: f32 = 0.2;

/// A mesh scene refined one sample per launch while nothing changes.
pub struct Progressive {
    scene: Scene,
    /// The size of the output and accumulation buffers.
    capacity: (u32, u32),
    camera: Camera,
    samples: u32,
    /// How the camera was asked for, and the file's own.
    options: CameraOptions,
    file_camera: Option<SceneCamera>,
    bounds: (Vec3, Vec3),
    /// Whether the output and accumulation buffers stay on the device.
    device_local: bool,
    /// How [`Progressive::picture`] is denoised.
    denoise: Denoise,
    /// Launches so far, of any camera.
    launches: u64,
    /// The denoiser stage, once a picture was denoised.
    denoiser: Option<Denoiser>,
}

impl Progressive {
    /// `loaded` on a floor, framed as [`bunny::mesh_scene`] frames it, at
    /// `settings`' size on `settings.backend` (`settings.spp` is unused).
    pub fn new(loaded: &LoadedMesh, settings: &Settings) -> Result<Progressive, Error> {
        Progressive::framed(loaded, settings, CameraOptions::default(), None)
    }

    /// [`Progressive::new`] seen as `options` ask (`render`'s camera
    /// flags), or by the file's `file_camera` (`loaded` is already turned
    /// by `options.up`; the file's camera is turned here).
    pub fn framed(
        loaded: &LoadedMesh,
        settings: &Settings,
        options: CameraOptions,
        file_camera: Option<SceneCamera>,
    ) -> Result<Progressive, Error> {
        let view = options.view();
        let bounds = (loaded.min, loaded.max);
        let camera = options.camera(bounds, file_camera, options.up.to_y_up(), settings.aspect());
        let scene = bunny::mesh_scene_from(loaded, settings, view, camera)?;
        Ok(Progressive {
            capacity: (scene.width, scene.height),
            camera,
            samples: 0,
            options,
            file_camera,
            bounds,
            scene,
            device_local: false,
            denoise: Denoise::Off,
            launches: 0,
            denoiser: None,
        })
    }

    /// The camera the scene starts with, framing the mesh at the current
    /// size (what the viewer's reset key returns to).
    pub fn home_camera(&self) -> Camera {
        let aspect = self.width() as f32 / self.height() as f32;
        self.options.camera(self.bounds, self.file_camera, self.options.up.to_y_up(), aspect)
    }

    /// Half the diagonal of the mesh's bounds: how big it is.
    pub fn radius(&self) -> f32 {
        ((self.bounds.1 - self.bounds.0).length() * 0.5).max(1e-6)
    }

    pub fn camera(&self) -> Camera {
        self.camera
    }

    pub fn width(&self) -> u32 {
        self.scene.width
    }

    pub fn height(&self) -> u32 {
        self.scene.height
    }

    /// Samples in the current picture.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// The runtime context (its backend, counters).
    pub fn context(&self) -> &rt_runtime::Context {
        &self.scene.ctx
    }

    /// The runtime context, to open its device for a window
    /// ([`crate::present::GpuPresenter::open`]).
    pub fn context_mut(&mut self) -> &mut rt_runtime::Context {
        &mut self.scene.ctx
    }

    /// Keeps the output and accumulation buffers on the wgpu device
    /// (`Context::set_buffer_device_local`): launches read nothing back,
    /// and [`Progressive::output`] says where a window finds the picture.
    /// While denoising they stay there whatever this says: the picture
    /// shown is the denoiser's.
    pub fn keep_on_device(&mut self, on: bool) -> Result<(), Error> {
        self.device_local = on;
        self.place_buffers()
    }

    /// The output and accumulation buffers on the device where
    /// [`Progressive::keep_on_device`] asks, or while denoising.
    fn place_buffers(&mut self) -> Result<(), Error> {
        let on = self.device_local || self.denoise != Denoise::Off;
        let ctx = &mut self.scene.ctx;
        ctx.set_buffer_device_local(self.scene.output, on)?;
        let accumulation = self.scene.accumulation.expect("mesh_scene accumulates");
        ctx.set_buffer_device_local(accumulation, on)?;
        Ok(())
    }

    /// The buffer the picture is in.
    pub fn output(&self) -> Output {
        Output { buffer: self.scene.output, stride: self.capacity.0, size: (self.scene.width, self.scene.height) }
    }

    /// Looks through `camera` from the next refinement on; a different
    /// camera starts the picture again.
    pub fn set_camera(&mut self, camera: Camera) {
        if camera != self.camera {
            self.camera = camera;
            self.samples = 0;
        }
    }

    /// Renders `width` x `height` pictures from the next refinement on; a
    /// different size starts the picture again. The camera keeps its
    /// vertical field of view.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<(), Error> {
        if (width, height) == (self.scene.width, self.scene.height) {
            return Ok(());
        }
        Settings::new(width, height).check()?;
        let (cap_w, cap_h) = self.capacity;
        if width > cap_w || height > cap_h {
            // Grow by at least a quarter, so that dragging a window's corner
            // leaves few buffers behind.
            let grow = |need: u32, have: u32| if need > have { need.max(have + have / 4).min(16384) } else { have };
            let capacity = (grow(width, cap_w), grow(height, cap_h));
            let ctx = &mut self.scene.ctx;
            let output = ctx.create_buffer_2d::<Vec4>(BufferType::Output, capacity.0, capacity.1)?;
            let accum = ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, capacity.0, capacity.1)?;
            ctx.set_var(Scope::Context, "output_buffer", output)?;
            ctx.set_var(Scope::Context, "accum_buffer", accum)?;
            self.scene.output = output;
            self.scene.accumulation = Some(accum);
            self.scene.aovs = Some(bunny::guide_buffers(ctx, capacity)?);
            self.capacity = capacity;
            self.place_buffers()?;
        }
        self.scene.width = width;
        self.scene.height = height;
        self.samples = 0;
        Ok(())
    }

    /// Adds one sample to every pixel (or starts again after a change) and
    /// returns the picture so far.
    pub fn refine(&mut self) -> Result<Frame, Error> {
        let start = Instant::now();
        let mut sample = self.sample()?;
        let image = self.picture()?;
        sample.seconds = start.elapsed().as_secs_f64();
        Ok(Frame { image, sample })
    }

    /// [`Progressive::refine`] without reading the picture back: it stays
    /// in [`Progressive::output`] (on the device, with
    /// [`Progressive::keep_on_device`]). While denoising, the launch and
    /// the denoiser are one command list, and the denoised picture is
    /// read back ([`Progressive::picture`] then shows it).
    pub fn sample(&mut self) -> Result<Sample, Error> {
        let (width, height) = (self.scene.width, self.scene.height);
        let start = Instant::now();
        self.place_buffers()?;
        if self.samples == 0 {
            self.camera.set_vars(&mut self.scene.ctx, width as f32 / height as f32)?;
        }
        self.scene.ctx.set_var(Scope::Context, "frame", self.samples)?;
        let report = match self.denoise {
            Denoise::Off => self.scene.ctx.launch(0, width, height)?,
            _ => self.launch_and_denoise()?,
        };
        self.samples += 1;
        self.launches += 1;
        if let Some(d) = self.denoiser.as_mut().filter(|_| self.denoise != Denoise::Off) {
            d.done = Some((self.launches, (width, height)));
        }
        Ok(Sample { rays: report.rays, seconds: start.elapsed().as_secs_f64(), exceptions: report.exceptions.len() })
    }

    /// The launch then the denoiser, as one command list; the launch's
    /// report.
    fn launch_and_denoise(&mut self) -> Result<LaunchReport, Error> {
        let (width, height) = (self.scene.width, self.scene.height);
        let stage = self.denoiser_stage()?;
        let ctx = &mut self.scene.ctx;
        let mut list = CommandList::new();
        list.append_launch_2d(0, width, height)?;
        list.append_stage(stage, width, height)?;
        list.finalize(ctx)?;
        let report = list.execute(ctx)?.into_iter().next();
        report.ok_or_else(|| Error::Settings("the command list's launch gave no report".into()))
    }

    /// The denoiser stage, set up for the current mode, camera and
    /// buffers (made the first time; its output grown with the others).
    fn denoiser_stage(&mut self) -> Result<StageId, Error> {
        let aovs = self.scene.aovs.ok_or_else(|| Error::Settings("the scene writes no guides to denoise".into()))?;
        let ctx = &mut self.scene.ctx;
        let capacity = self.capacity;
        if self.denoiser.as_ref().is_none_or(|d| d.capacity != capacity) {
            let output = ctx.create_buffer_2d::<Vec4>(BufferType::Output, capacity.0, capacity.1)?;
            let stage = match &self.denoiser {
                Some(d) => d.stage,
                None => ctx.create_postprocessing_stage(StageKind::Denoiser),
            };
            let fresh = self.denoiser.as_ref().is_none_or(|d| d.fresh);
            self.denoiser = Some(Denoiser { stage, output, capacity, done: None, fresh });
        }
        let d = self.denoiser.as_mut().expect("made above");
        let stage = d.stage;
        if std::mem::take(&mut d.fresh) {
            ctx.reset_stage_history(stage)?;
        }
        let temporal = self.denoise == Denoise::Temporal;
        let buffers = [
            ("input_buffer", Some(aovs.radiance)),
            ("input_albedo_buffer", Some(aovs.albedo)),
            ("input_normal_buffer", Some(aovs.normal)),
            ("input_variance_buffer", Some(aovs.variance)),
            ("input_position_buffer", aovs.position),
            ("output_buffer", Some(d.output)),
        ];
        for (name, b) in buffers {
            if let Some(b) = b {
                ctx.set_stage_var(stage, name, b)?;
            }
        }
        ctx.set_stage_var(stage, "temporal", if temporal { 1.0f32 } else { 0.0 })?;
        ctx.set_stage_var(stage, "alpha_min", TEMPORAL_ALPHA_MIN)?;
        if temporal {
            let (u, v, w) = self.camera.uvw(self.scene.width as f32 / self.scene.height as f32);
            let camera = [("camera_eye", self.camera.eye), ("camera_u", u), ("camera_v", v), ("camera_w", w)];
            for (name, x) in camera {
                ctx.set_stage_var(stage, name, x)?;
            }
        }
        Ok(stage)
    }

    /// Denoises [`Progressive::picture`] as `mode` says from now on; the
    /// samples so far are kept either way. Temporal starts with no
    /// history.
    pub fn set_denoise(&mut self, mode: Denoise) {
        if mode != self.denoise
            && let Some(d) = &mut self.denoiser
        {
            (d.done, d.fresh) = (None, true);
        }
        self.denoise = mode;
    }

    /// How [`Progressive::picture`] is denoised.
    pub fn denoising(&self) -> Denoise {
        self.denoise
    }

    /// Frames the temporal mode's history holds at each pixel, launch
    /// index order (row by row, of the size it was made at); none without
    /// a history. On the wgpu backend the history is read from the
    /// device.
    pub fn history_frames(&self) -> Result<Vec<u32>, Error> {
        let Some(d) = self.denoiser.as_ref().filter(|d| !d.fresh) else { return Ok(Vec::new()) };
        let history = self.scene.ctx.stage_history(d.stage)?;
        Ok(history.map_or(Vec::new(), |(_, _, colors)| colors.iter().map(|c| c.w as u32).collect()))
    }

    /// The picture so far, read from the output buffer, or from the
    /// denoiser's ([`Progressive::set_denoise`]), which runs here where
    /// the last launch's picture has not been denoised in this mode yet.
    /// In temporal mode a run blends the picture into the history; a
    /// second call shows the same picture.
    pub fn picture(&mut self) -> Result<Image, Error> {
        let (width, height) = (self.scene.width, self.scene.height);
        if self.denoise == Denoise::Off {
            return Ok(Image { width, height, pixels: self.read_cropped(self.scene.output)? });
        }
        let now = Some((self.launches, (width, height)));
        if self.denoiser.as_ref().is_none_or(|d| d.done != now || d.capacity != self.capacity) {
            let stage = self.denoiser_stage()?;
            self.scene.ctx.run_stage(stage, width, height)?;
        }
        let d = self.denoiser.as_mut().expect("set up above");
        d.done = now;
        let output = d.output;
        Ok(Image { width, height, pixels: self.read_cropped(output)? }.to_display())
    }

    /// The picture's part of buffer `b` (of the capacity's size), row by
    /// row.
    fn read_cropped(&self, b: BufferId) -> Result<Vec<Vec4>, Error> {
        let (width, height) = (self.scene.width as usize, self.scene.height as usize);
        let all = self.scene.ctx.read_buffer::<Vec4>(b)?;
        let stride = self.capacity.0 as usize;
        Ok((0..height).flat_map(|y| &all[y * stride..y * stride + width]).copied().collect())
    }
}

/// Packs a picture as `0x00RRGGBB` words, top row first, for a window: the
/// same 8-bit colours as [`Image::save_png`] writes.
pub fn to_xrgb(image: &Image) -> Vec<u32> {
    let rgba = rt_runtime::image_out::to_rgba8(image.width, image.height, &image.pixels);
    rgba.pixels().map(|p| (p[0] as u32) << 16 | (p[1] as u32) << 8 | p[2] as u32).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bunny::MeshView;
    use crate::mesh;
    use rt_runtime::postprocess::denoise::{self, Guided};
    use rt_runtime::postprocess::temporal::{self, Pinhole};

    fn teapot(width: u32, height: u32) -> (LoadedMesh, Progressive) {
        let loaded = mesh::load_obj(&crate::scene::shared_scene("teapot.obj")).unwrap();
        let view = Progressive::new(&loaded, &Settings::new(width, height)).unwrap();
        (loaded, view)
    }

    #[test]
    fn refining_a_still_view_is_rendering_with_that_many_samples() {
        let (loaded, mut view) = teapot(24, 18);
        let mut last = None;
        for _ in 0..3 {
            last = Some(view.refine().unwrap());
        }
        assert_eq!(view.samples(), 3);
        let settings = Settings::new(24, 18).with_spp(3);
        let rendered = bunny::mesh_scene(&loaded, &settings, MeshView::default()).unwrap().render(&mut |_| {}).unwrap();
        assert_eq!(last.unwrap().image, rendered.image);
    }

    #[test]
    fn moving_or_resizing_starts_again() {
        let (_, mut view) = teapot(24, 18);
        view.refine().unwrap();
        view.refine().unwrap();
        view.set_camera(view.camera());
        assert_eq!(view.samples(), 2, "the same camera is no change");
        view.set_camera(view.camera().orbited(0.2, 0.1));
        assert_eq!(view.samples(), 0);
        view.refine().unwrap();
        view.resize(24, 18).unwrap();
        assert_eq!(view.samples(), 1, "the same size is no change");
        view.resize(30, 20).unwrap();
        assert_eq!(view.samples(), 0);
    }

    /// A grown picture is the one a scene of that size renders; a shrunk one
    /// is launched over part of the grown buffers and matches too.
    #[test]
    fn resized_pictures_match_fresh_scenes() {
        let (loaded, mut view) = teapot(16, 12);
        for (w, h) in [(26, 20), (10, 14)] {
            view.resize(w, h).unwrap();
            view.set_camera(view.home_camera());
            view.refine().unwrap();
            let frame = view.refine().unwrap();
            let settings = Settings::new(w, h).with_spp(2);
            let fresh =
                bunny::mesh_scene(&loaded, &settings, MeshView::default()).unwrap().render(&mut |_| {}).unwrap();
            assert_eq!(frame.image, fresh.image, "{w}x{h}");
            assert!(frame.sample.rays >= (w * h) as u64);
        }
    }

    /// The denoised picture is the raw one's samples through the denoiser:
    /// nearer a picture of many more samples, kept across the toggle, and
    /// (as the camera corrects its own) gamma corrected.
    #[test]
    fn denoising_shows_the_same_samples_nearer_a_converged_picture() {
        let loaded = mesh::load_obj(&crate::scene::shared_scene("teapot.obj")).unwrap();
        let options = CameraOptions { elevation: Some(3.0), ..CameraOptions::default() };
        let mut view = Progressive::framed(&loaded, &Settings::new(128, 96), options, None).unwrap();
        view.resize(120, 90).unwrap(); // launched over part of the buffers
        view.set_camera(view.home_camera());
        view.refine().unwrap();
        let raw = view.refine().unwrap().image;
        view.set_denoise(Denoise::Spatial);
        assert_eq!(view.denoising(), Denoise::Spatial);
        let denoised = view.picture().unwrap();
        assert_eq!(view.samples(), 2, "the toggle keeps the samples");
        view.set_denoise(Denoise::Off);
        assert_eq!(view.picture().unwrap(), raw);
        let settings = Settings::new(120, 90).with_spp(32);
        let camera = options.camera((loaded.min, loaded.max), None, options.up.to_y_up(), settings.aspect());
        let mut scene = bunny::mesh_scene_from(&loaded, &settings, options.view(), camera).unwrap();
        let converged = scene.render(&mut |_| {}).unwrap().image;
        let error = |image: &Image| -> f32 {
            image.pixels.iter().zip(&converged.pixels).map(|(a, b)| (*a - *b).truncate().length_squared()).sum()
        };
        let (raw_error, denoised_error) = (error(&raw), error(&denoised));
        eprintln!("squared error against 32 spp: raw {raw_error}, denoised {denoised_error}");
        assert_ne!(raw, denoised);
        assert!(denoised_error < raw_error * 0.8, "raw {raw_error}, denoised {denoised_error}");
    }

    #[test]
    fn the_denoise_key_steps_off_spatial_temporal() {
        let modes: Vec<_> = std::iter::successors(Some(Denoise::Off), |m| Some(m.next())).take(4).collect();
        assert_eq!(modes, [Denoise::Off, Denoise::Spatial, Denoise::Temporal, Denoise::Off]);
        assert_eq!(modes.iter().map(|m| m.name()).collect::<Vec<_>>(), ["off", "spatial", "temporal", "off"]);
    }

    /// The temporal mode after a camera move: the samples start again (one
    /// a pixel), but the history seen before, reprojected, keeps the
    /// picture nearer a converged one than the spatial filter alone gets
    /// from that one sample; points it did not see start again; a resize
    /// or turning the mode off and on drops the history.
    #[test]
    fn temporal_mode_keeps_the_history_through_a_camera_move() {
        let loaded = mesh::load_obj(&crate::scene::shared_scene("teapot.obj")).unwrap();
        let options = CameraOptions { elevation: Some(3.0), ..CameraOptions::default() };
        let (w, h) = (96, 72);
        let mut view = Progressive::framed(&loaded, &Settings::new(w, h), options, None).unwrap();
        view.set_denoise(Denoise::Temporal);
        for _ in 0..8 {
            view.refine().unwrap();
        }
        let centre = |frames: Vec<u32>| frames.get((h / 2 * w + w / 2) as usize).copied().unwrap_or(0);
        assert_eq!(centre(view.history_frames().unwrap()), 8, "a still view blends every picture");
        assert_eq!(view.refine().unwrap().image, view.picture().unwrap(), "a second call shows the same picture");
        let moved = view.camera().orbited(0.03, 0.0);
        view.set_camera(moved);
        let temporal = view.refine().unwrap().image;
        assert_eq!(view.samples(), 1);
        let frames = view.history_frames().unwrap();
        assert_eq!(frames.len(), (w * h) as usize);
        let kept = frames.iter().filter(|&&f| f == 10).count();
        let restarted = frames.iter().filter(|&&f| f == 1).count();
        eprintln!("after the move: {kept} pixels kept their history, {restarted} started again");
        assert!(kept > frames.len() / 2 && restarted > 0, "kept {kept}, restarted {restarted}");
        view.set_denoise(Denoise::Spatial);
        let spatial = view.picture().unwrap();
        let settings = Settings::new(w, h).with_spp(32);
        let mut scene = bunny::mesh_scene_from(&loaded, &settings, options.view(), moved).unwrap();
        let converged = scene.render(&mut |_| {}).unwrap().image;
        let error = |image: &Image| -> f32 {
            image.pixels.iter().zip(&converged.pixels).map(|(a, b)| (*a - *b).truncate().length_squared()).sum()
        };
        let (temporal_error, spatial_error) = (error(&temporal), error(&spatial));
        eprintln!("squared error against 32 spp after the move: temporal {temporal_error}, spatial {spatial_error}");
        assert!(temporal_error < spatial_error * 0.7, "temporal {temporal_error}, spatial {spatial_error}");
        view.set_denoise(Denoise::Temporal);
        assert_eq!(centre(view.history_frames().unwrap()), 0, "turning the mode on starts with no history");
        view.refine().unwrap();
        view.resize(w - 8, h).unwrap();
        view.refine().unwrap();
        let frames = view.history_frames().unwrap();
        assert_eq!(frames.get(((h / 2) * (w - 8) + w / 2) as usize), Some(&1), "a resize starts again");
    }

    /// What the viewer showed before its denoiser ran as the runtime's
    /// stage: the guides read back cropped, filtered on the host (and in
    /// temporal mode first blended into a history kept here).
    struct HostDenoiser {
        history: Option<(Vec<Vec4>, Pinhole)>,
    }

    impl HostDenoiser {
        fn picture(&mut self, view: &Progressive) -> Image {
            let (width, height) = (view.width(), view.height());
            let aovs = view.scene.aovs.unwrap();
            let read = |b| view.read_cropped(b).unwrap();
            let [color, albedo, normal, variance] = [aovs.radiance, aovs.albedo, aovs.normal, aovs.variance].map(read);
            let (w, h) = (width as usize, height as usize);
            let pixels = if view.denoising() == Denoise::Spatial {
                let variance = Some(&variance[..]);
                denoise::denoise(
                    &Guided { width: w, height: h, color: &color, albedo: &albedo, normal: &normal, variance },
                    0.0,
                )
            } else {
                let position = read(aovs.position.unwrap());
                let (u, v, w_axis) = view.camera().uvw(width as f32 / height as f32);
                let camera = Pinhole { eye: view.camera().eye, u, v, w: w_axis };
                let frame = temporal::Frame {
                    width: w,
                    height: h,
                    color: &color,
                    albedo: &albedo,
                    normal: &normal,
                    position: &position,
                    camera,
                };
                let previous = self.history.as_ref().map(|(texels, camera)| (&texels[..], camera));
                let acc = temporal::accumulate(&frame, previous, TEMPORAL_ALPHA_MIN);
                let variance = Some(&acc.variance[..]);
                let guided =
                    Guided { width: w, height: h, color: &acc.color, albedo: &albedo, normal: &normal, variance };
                self.history = Some((acc.history, camera));
                denoise::denoise(&guided, 0.0)
            };
            Image { width, height, pixels }.to_display()
        }
    }

    /// The viewer's denoised pictures, spatial and temporal (through a
    /// camera move), launched and denoised over part of its buffers, are
    /// the host filter's over the same samples: bit for bit on the CPU
    /// backend, within 1e-4 on wgpu, where the denoiser rides in the
    /// launch's submission and only the denoised picture comes back.
    #[test]
    fn the_denoiser_stage_shows_what_the_host_filter_showed() {
        for backend in [rt_runtime::Backend::Cpu, rt_runtime::Backend::Wgpu] {
            let loaded = mesh::load_obj(&crate::scene::shared_scene("teapot.obj")).unwrap();
            let mut settings = Settings::new(48, 40);
            settings.backend = backend;
            let mut view = Progressive::new(&loaded, &settings).unwrap();
            view.resize(44, 33).unwrap(); // over part of the buffers
            view.set_camera(view.home_camera());
            let mut host = HostDenoiser { history: None };
            let mut frames = 0;
            for (mode, moves) in [(Denoise::Spatial, [false, false, false]), (Denoise::Temporal, [false, false, true])]
            {
                view.set_denoise(mode);
                for moved in moves {
                    if moved {
                        view.set_camera(view.camera().orbited(0.03, 0.0));
                    }
                    let ctx = view.context();
                    let before = (ctx.stage_read_back_bytes(), ctx.stage_upload_bytes(), ctx.stage_submissions());
                    let shown = view.refine().unwrap().image;
                    let ctx = view.context();
                    let after = (ctx.stage_read_back_bytes(), ctx.stage_upload_bytes(), ctx.stage_submissions());
                    let want = host.picture(&view);
                    frames += 1;
                    assert_eq!(view.picture().unwrap(), shown, "{backend:?}: a second call shows the same picture");
                    if backend == rt_runtime::Backend::Cpu {
                        assert_eq!(shown, want, "{mode:?} frame {frames}");
                        continue;
                    }
                    let picture = (44 * 33 * 16) as u64;
                    assert_eq!(after.0 - before.0, picture, "{mode:?}: the denoised picture alone comes back");
                    assert_eq!(after.1 - before.1, 0, "{mode:?}: the stage reads the guides on the device");
                    assert_eq!(after.2, before.2, "{mode:?}: the stage rides in the launch's submission");
                    // Besides the denoised picture, the launch reads back its
                    // log's header and counters alone: not the raw picture,
                    // the accumulation or the guides.
                    let launch_read = view.context().last_read_back_bytes();
                    assert!(launch_read >= picture && launch_read - picture < 64, "{mode:?}: {launch_read} bytes");
                    for (i, (x, y)) in want.pixels.iter().zip(&shown.pixels).enumerate() {
                        let tolerance = 1e-4 * x.abs().max_element().max(1.0);
                        assert!(
                            (*x - *y).abs().max_element() <= tolerance,
                            "{mode:?} frame {frames} pixel {i}: host {x}, wgpu {y}"
                        );
                    }
                }
            }
            assert!(
                view.history_frames().unwrap().contains(&3),
                "{backend:?}: the history kept pixels through the move"
            );
        }
    }

    #[test]
    fn orbiting_keeps_the_distance_and_stops_short_of_the_pole() {
        let (_, view) = teapot(16, 12);
        let home = view.home_camera();
        let distance = (home.eye - home.look_at).length();
        let turned = home.orbited(1.0, 0.3);
        assert_eq!(turned.look_at, home.look_at);
        assert!(((turned.eye - turned.look_at).length() - distance).abs() < distance * 1e-5);
        let top = home.orbited(0.0, 10.0);
        let elevation = ((top.eye - top.look_at).normalize().dot(Vec3::Y)).asin().to_degrees();
        assert!((elevation - 89.0).abs() < 0.01, "{elevation}");
        // Yaw turns the eye towards the camera's right.
        let (right, _, _) = home.uvw(1.0);
        assert!((home.orbited(0.1, 0.0).eye - home.eye).dot(right) > 0.0);
    }

    #[test]
    fn walking_moves_the_camera_and_its_target_together() {
        let (_, view) = teapot(16, 12);
        let home = view.home_camera();
        let walked = home.moved(1.0, 2.0, 3.0);
        assert!(((walked.eye - home.eye) - (walked.look_at - home.look_at)).length() < 1e-5);
        assert!(((walked.eye - home.eye).length() - 14f32.sqrt()).abs() < 1e-4);
        assert!((walked.eye.y - home.eye.y - 2.0).abs() < 1e-5, "Q/E move along up only");
        let closer = home.dollied(0.5);
        assert!(((closer.eye - closer.look_at).length() * 2.0 - (home.eye - home.look_at).length()).abs() < 1e-4);
    }

    #[test]
    fn xrgb_is_the_png_colours_top_row_first() {
        let image =
            Image { width: 1, height: 2, pixels: vec![Vec4::new(1.0, 0.0, 0.0, 1.0), Vec4::new(0.0, 0.5, 1.0, 1.0)] };
        assert_eq!(to_xrgb(&image), vec![0x0000_80ff, 0x00ff_0000]);
    }
}
