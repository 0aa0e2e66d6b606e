//! A user's model file (OBJ, glTF or GLB) lit as [`bunny::mesh_scene`]
//! lights a mesh, seen by the camera a user asks for: which axis is up
//! (OBJ has no convention; glTF's is +Y), azimuth, elevation, distance and
//! field of view, or the glTF file's own camera.
//!
//! OBJ files go through [`bunny::mesh_scene_from`] as before (the mesh
//! turned so its up axis is +Y); glTF files are loaded by
//! [`rt_scene::load`] as a graph (each mesh one BVH, instanced per node)
//! under a `Transform` that turns them the same way, beside the floor.

use crate::bunny::{self, MeshView};
use crate::mesh::LoadedMesh;
use crate::scene::{Camera, Error, Scene, Settings};
use glam::{Mat3, Mat4, Vec3};
use rt_runtime::{Acceleration, Builder, Scope};
use rt_scene::{Format, LoadLimits, SceneCamera};
use std::path::Path;

/// Which axis of the file points up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum UpAxis {
    X,
    #[default]
    Y,
    Z,
}

impl UpAxis {
    /// The rotation that turns this axis into +Y (a quarter turn, exact in
    /// floating point).
    pub fn to_y_up(self) -> Mat3 {
        match self {
            UpAxis::Y => Mat3::IDENTITY,
            // (x, y, z) -> (x, z, -y)
            UpAxis::Z => Mat3::from_cols(Vec3::X, -Vec3::Z, Vec3::Y),
            // (x, y, z) -> (-y, x, z)
            UpAxis::X => Mat3::from_cols(Vec3::Y, -Vec3::X, Vec3::Z),
        }
    }
}

/// How the camera is placed. Angles in degrees; unset values keep
/// [`MeshView::default`]'s view (azimuth about -24.2, elevation about 19.1)
/// and the distance that frames the whole model.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CameraOptions {
    pub up: UpAxis,
    /// Degrees about the up axis; 0 looks along -Z (from +Z), 90 from +X.
    pub azimuth: Option<f32>,
    /// Degrees above the horizon.
    pub elevation: Option<f32>,
    /// From the model's centre, in its units.
    pub distance: Option<f32>,
    /// Vertical field of view, degrees.
    pub fov: Option<f32>,
    /// Ignore a glTF file's camera.
    pub ignore_file_camera: bool,
}

/// The camera flags `render` and `viewer` take, as one clap group.
#[derive(Clone, Copy, Debug, Default, PartialEq, clap::Args)]
pub struct CameraArgs {
    /// The model's up axis (glTF's is y; scans are often z).
    #[arg(long, value_enum, default_value_t = UpAxis::Y)]
    pub up: UpAxis,
    /// Camera azimuth in degrees about the up axis (0: from +Z, 90: from +X).
    #[arg(long, allow_negative_numbers = true)]
    pub azimuth: Option<f32>,
    /// Camera elevation in degrees above the horizon.
    #[arg(long, allow_negative_numbers = true)]
    pub elevation: Option<f32>,
    /// Camera distance from the model's centre (default: what frames it).
    #[arg(long)]
    pub distance: Option<f32>,
    /// Vertical field of view in degrees (default 30, or the file camera's).
    #[arg(long)]
    pub fov: Option<f32>,
    /// Frame the model even when the glTF file has a camera.
    #[arg(long)]
    pub no_file_camera: bool,
}

impl CameraArgs {
    /// The options, or the first flag no picture can be taken with, by
    /// name ([`Error::Settings`]: exit status 2).
    pub fn options(&self) -> Result<CameraOptions, Error> {
        if let Some(fov) = self.fov
            && !(fov > 0.0 && fov < 180.0)
        {
            return Err(Error::Settings(format!("--fov {fov} is outside (0, 180) degrees")));
        }
        if let Some(d) = self.distance
            && !(d > 0.0 && d.is_finite())
        {
            return Err(Error::Settings(format!("--distance {d} must be positive")));
        }
        if let Some(e) = self.elevation
            && !(-89.0..=89.0).contains(&e)
        {
            return Err(Error::Settings(format!("--elevation {e} is outside -89..=89 degrees")));
        }
        if self.azimuth.is_some_and(|a| !a.is_finite()) {
            return Err(Error::Settings("--azimuth must be a finite number of degrees".into()));
        }
        Ok(CameraOptions {
            up: self.up,
            azimuth: self.azimuth,
            elevation: self.elevation,
            distance: self.distance,
            fov: self.fov,
            ignore_file_camera: self.no_file_camera,
        })
    }
}

impl CameraOptions {
    /// Whether a position was asked for (which overrides a file's camera).
    pub fn places_camera(&self) -> bool {
        self.azimuth.is_some() || self.elevation.is_some() || self.distance.is_some()
    }

    /// The view as [`MeshView`] (its direction from azimuth and elevation).
    pub fn view(&self) -> MeshView {
        let mut view = MeshView::default();
        if self.azimuth.is_some() || self.elevation.is_some() {
            let eye = -view.view_direction.normalize();
            let azimuth = self.azimuth.map_or(eye.x.atan2(eye.z), f32::to_radians);
            let elevation = self.elevation.map_or(eye.y.asin(), f32::to_radians);
            let from = Vec3::new(elevation.cos() * azimuth.sin(), elevation.sin(), elevation.cos() * azimuth.cos());
            view.view_direction = -from;
        }
        if let Some(fov) = self.fov {
            view.vfov_degrees = fov;
        }
        view
    }

    /// The camera for a model spanning `bounds` (already Y-up), or the
    /// file's `camera` (turned by `to_y_up`) when it has one and no
    /// position was asked for.
    pub fn camera(&self, bounds: (Vec3, Vec3), file: Option<SceneCamera>, to_y_up: Mat3, aspect: f32) -> Camera {
        let view = self.view();
        if let Some(c) = file.filter(|_| !self.places_camera() && !self.ignore_file_camera) {
            let (eye, forward) = (to_y_up * c.eye, to_y_up * c.forward);
            let center = (bounds.0 + bounds.1) * 0.5;
            let depth = (center - eye).dot(forward).max(1e-3);
            return Camera {
                eye,
                look_at: eye + forward * depth,
                up: to_y_up * c.up,
                vfov_degrees: self.fov.unwrap_or(c.vfov_degrees),
            };
        }
        let mut camera = Camera::framing(bounds.0, bounds.1, view.view_direction, view.vfov_degrees, aspect);
        if let Some(d) = self.distance {
            camera.eye = camera.look_at - view.view_direction.normalize() * d;
        }
        camera
    }
}

/// How far from the model's centre, in model sizes, a camera may be: far
/// enough that rays are not lost in rounding, near enough that the model
/// is not lost in it.
pub const DISTANCE_RANGE: (f32, f32) = (1e-6, 1e6);

impl CameraOptions {
    /// Refuses a camera no picture of the model at `path` can be taken
    /// with: a `--distance` out of [`DISTANCE_RANGE`] of the model's size,
    /// or any camera (the file's too) whose position, view direction or up
    /// vector is not finite or degenerate.
    pub fn check_camera(&self, path: &Path, camera: &Camera, bounds: (Vec3, Vec3)) -> Result<(), Error> {
        let size = (bounds.1 - bounds.0).length();
        let size = if size > 0.0 && size.is_finite() { size } else { 1.0 };
        if let Some(d) = self.distance {
            let (lo, hi) = (DISTANCE_RANGE.0 * size, DISTANCE_RANGE.1 * size);
            if !(lo..=hi).contains(&d) {
                return Err(Error::Settings(format!(
                    "--distance {d:e} is outside {lo:e}..={hi:e} ({:e} to {:e} times the size of {})",
                    DISTANCE_RANGE.0,
                    DISTANCE_RANGE.1,
                    path.display()
                )));
            }
        }
        let forward = camera.look_at - camera.eye;
        let sound = camera.eye.is_finite()
            && forward.is_finite()
            && forward.length() > 0.0
            && forward.normalize().cross(camera.up).length() > 1e-6
            && camera.vfov_degrees > 0.0
            && camera.vfov_degrees < 180.0;
        if !sound {
            return Err(Error::Settings(format!(
                "{}: no picture can be taken with the camera at {} looking at {} (up {}, {} degrees)",
                path.display(),
                camera.eye,
                camera.look_at,
                camera.up,
                camera.vfov_degrees
            )));
        }
        Ok(())
    }
}

/// What [`model_scene`] loaded.
pub struct Model {
    pub scene: Scene,
    pub triangles: usize,
    pub warnings: Vec<String>,
    /// Whether the file's own camera is the one used.
    pub file_camera: bool,
    /// The glTF file's node animation, if it has one (pose the scene with
    /// it before rendering a time).
    pub animation: Option<rt_scene::Animation>,
}

/// The file at `path` lit and framed as the `render` binary shows it,
/// loaded within the default [`LoadLimits`].
pub fn model_scene(path: &Path, settings: &Settings, options: CameraOptions) -> Result<Model, Error> {
    model_scene_with(path, settings, options, &LoadLimits::default())
}

/// [`model_scene`] within `limits`.
pub fn model_scene_with(
    path: &Path,
    settings: &Settings,
    options: CameraOptions,
    limits: &LoadLimits,
) -> Result<Model, Error> {
    let to_y_up = options.up.to_y_up();
    match Format::of(path) {
        Some(Format::Obj) => {
            let mut loaded = crate::mesh::load_obj_with(path, limits)?;
            turn(&mut loaded, to_y_up);
            let camera = options.camera((loaded.min, loaded.max), None, to_y_up, settings.aspect());
            options.check_camera(path, &camera, (loaded.min, loaded.max))?;
            let scene = bunny::mesh_scene_from(&loaded, settings, options.view(), camera)?;
            Ok(Model {
                scene,
                triangles: loaded.mesh.indices.len(),
                warnings: loaded.warnings,
                file_camera: false,
                animation: None,
            })
        }
        Some(Format::Gltf) => gltf_scene(path, settings, options, limits),
        None => Err(rt_scene::SceneError::UnknownFormat { file: path.display().to_string() }.into()),
    }
}

fn gltf_scene(path: &Path, settings: &Settings, options: CameraOptions, limits: &LoadLimits) -> Result<Model, Error> {
    let to_y_up = options.up.to_y_up();
    let (mut ctx, output) = Scene::start(settings, 1.0)?;
    let loaded = rt_scene::load_with(&mut ctx, path, limits)?;
    let info = &loaded.info;
    let bounds = turned_bounds(info.min, info.max, to_y_up);
    let camera = options.camera(bounds, info.camera, to_y_up, settings.aspect());
    options.check_camera(path, &camera, bounds)?;
    let file_camera = info.camera.is_some() && !options.places_camera() && !options.ignore_file_camera;
    let lit = bunny::light_and_frame(&mut ctx, settings, bounds, options.view(), camera)?;
    for m in &loaded.materials {
        lit.attach(&mut ctx, m.id, m.info.base_color.truncate())?;
    }
    let model = if to_y_up == Mat3::IDENTITY {
        loaded.top
    } else {
        ctx.create_transform(Mat4::from_mat3(to_y_up), loaded.top)?
    };
    let floor_material = lit.material(&mut ctx, bunny::FLOOR_KD)?;
    let floor = ctx.create_triangles(bunny::floor_quad(bounds.0, bounds.1))?;
    let floor = ctx.create_geometry_instance(floor, &[floor_material])?;
    let floor = ctx.create_geometry_group(&[floor], Acceleration::new(Builder::Bvh))?;
    let top = ctx.create_group(&[model, floor], Acceleration::new(Builder::Bvh))?;
    ctx.set_var(Scope::Context, "top_object", top)?;
    ctx.set_var(Scope::Context, "top_shadower", top)?;
    let mut scene = Scene::new(ctx, output, settings);
    scene.frames = settings.spp;
    scene.accumulation = Some(lit.accumulation);
    scene.aovs = Some(lit.aovs);
    Ok(Model {
        scene,
        triangles: info.triangles,
        warnings: info.warnings.clone(),
        file_camera,
        animation: loaded.animation,
    })
}

/// Turns a loaded mesh by a quarter-turn rotation (positions, normals and
/// bounds).
pub fn turn(loaded: &mut LoadedMesh, rotation: Mat3) {
    if rotation == Mat3::IDENTITY {
        return;
    }
    for p in &mut loaded.mesh.positions {
        *p = rotation * *p;
    }
    if let Some(normals) = &mut loaded.mesh.normals {
        for n in normals {
            *n = rotation * *n;
        }
    }
    (loaded.min, loaded.max) = turned_bounds(loaded.min, loaded.max, rotation);
}

/// The box `[min, max]` turned by a quarter-turn rotation.
fn turned_bounds(min: Vec3, max: Vec3, rotation: Mat3) -> (Vec3, Vec3) {
    let (a, b) = (rotation * min, rotation * max);
    (a.min(b), a.max(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn up_axes_turn_to_y() {
        for (axis, v) in [(UpAxis::X, Vec3::X), (UpAxis::Y, Vec3::Y), (UpAxis::Z, Vec3::Z)] {
            assert_eq!(axis.to_y_up() * v, Vec3::Y, "{axis:?}");
            assert!((axis.to_y_up().determinant() - 1.0).abs() < 1e-6, "a rotation, not a mirror");
        }
    }

    #[test]
    fn the_default_view_is_kept_until_an_angle_is_given() {
        let default = MeshView::default().view_direction;
        assert_eq!(CameraOptions::default().view().view_direction, default);
        let same = CameraOptions { azimuth: None, elevation: None, ..Default::default() };
        assert_eq!(same.view().view_direction, default);
        let from_front = CameraOptions { azimuth: Some(0.0), elevation: Some(0.0), ..Default::default() };
        assert!((from_front.view().view_direction - -Vec3::Z).length() < 1e-6);
        let from_x = CameraOptions { azimuth: Some(90.0), elevation: Some(0.0), ..Default::default() };
        assert!((from_x.view().view_direction - -Vec3::X).length() < 1e-6);
    }
}
