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
//! With [`Progressive::set_denoise`] on, [`Progressive::picture`] is the
//! running mean through the runtime's denoiser
//! ([`rt_runtime::postprocess::denoise`], on the host) over the guides the
//! camera writes, gamma corrected as the camera corrects its own; the
//! samples go on accumulating as before, so turning it off shows the raw
//! mean of the same samples.
//!
//! The runtime cannot free or resize a buffer, so the output, accumulation
//! and guide buffers only grow: a smaller picture is launched over the
//! top-left part of them (launch indices address buffers by their own
//! width) and cropped on the way out.
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
use rt_runtime::postprocess::denoise::{self, Guided};
use rt_runtime::{BufferType, Scope};
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
    /// Whether [`Progressive::picture`] is denoised.
    denoise: bool,
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
            denoise: false,
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
    pub fn keep_on_device(&mut self, on: bool) -> Result<(), Error> {
        self.device_local = on;
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
            self.keep_on_device(self.device_local)?;
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
    /// [`Progressive::keep_on_device`]).
    pub fn sample(&mut self) -> Result<Sample, Error> {
        let (width, height) = (self.scene.width, self.scene.height);
        let start = Instant::now();
        let ctx = &mut self.scene.ctx;
        if self.samples == 0 {
            self.camera.set_vars(ctx, width as f32 / height as f32)?;
        }
        ctx.set_var(Scope::Context, "frame", self.samples)?;
        let report = ctx.launch(0, width, height)?;
        self.samples += 1;
        Ok(Sample { rays: report.rays, seconds: start.elapsed().as_secs_f64(), exceptions: report.exceptions.len() })
    }

    /// Denoises [`Progressive::picture`] from now on (or not); the
    /// samples so far are kept either way.
    pub fn set_denoise(&mut self, on: bool) {
        self.denoise = on;
    }

    /// Whether [`Progressive::picture`] is denoised.
    pub fn denoising(&self) -> bool {
        self.denoise
    }

    /// The picture so far, read from the output buffer, or denoised from
    /// the guides ([`Progressive::set_denoise`]).
    pub fn picture(&self) -> Result<Image, Error> {
        let (width, height) = (self.scene.width, self.scene.height);
        if self.denoise {
            let aovs =
                self.scene.aovs.ok_or_else(|| Error::Settings("the scene writes no guides to denoise".into()))?;
            let [color, albedo, normal, variance] =
                [aovs.radiance, aovs.albedo, aovs.normal, aovs.variance].map(|b| self.read_cropped(b));
            let (color, albedo, normal, variance) = (color?, albedo?, normal?, variance?);
            let (w, h) = (width as usize, height as usize);
            let variance = Some(&variance[..]);
            let guided = Guided { width: w, height: h, color: &color, albedo: &albedo, normal: &normal, variance };
            let pixels = denoise::denoise(&guided, 0.0);
            return Ok(Image { width, height, pixels }.to_display());
        }
        Ok(Image { width, height, pixels: self.read_cropped(self.scene.output)? })
    }

    /// The picture's part of buffer `b` (of the capacity's size), row by
    /// row.
    fn read_cropped(&self, b: rt_runtime::BufferId) -> Result<Vec<Vec4>, Error> {
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
        view.set_denoise(true);
        assert!(view.denoising());
        let denoised = view.picture().unwrap();
        assert_eq!(view.samples(), 2, "the toggle keeps the samples");
        view.set_denoise(false);
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
