//! # The worked examples
//!
//! The seed lecture's seven examples, each building on the one before, and
//! five more that put the framework to work on real meshes, on a
//! non-graphics use and on callable programs:
//!
//! | module | shows |
//! | --- | --- |
//! | [`normal`] | a pinhole camera (ray generation), the normal shader (closest hit), a background (miss `bg_color`) |
//! | [`diffuse`] | ambient plus Lambert over a `Buffer<BasicLight>` |
//! | [`phong`] | Blinn-Phong highlights |
//! | [`shadows`] | a second ray type whose any-hit program blocks and terminates |
//! | [`reflections`] | a checkerboard floor and a chrome sphere, recursion stopped by depth and importance |
//! | [`envmap`] | a miss program sampling a lat/long sky texture made in code |
//! | [`convex_hull`] | custom geometry (planes in a buffer, a bounding-box program) rendered as glass |
//! | [`cornell`] | a progressive path tracer over the Cornell box OBJ and its area light |
//! | [`bunny`] | the Stanford bunny with a key light, shadows and ambient occlusion |
//! | [`instances`] | a hundred transformed instances of one teapot sharing one BVH |
//! | [`receiver_grid`] | a sound source's rays counted per cell of a receiver grid with atomic adds, direct and reflected |
//! | [`callable_brdfs`] | the tutorial's objects each shaded by its own BRDF, a callable program chosen per material from a buffer of ids |
//! | [`motion_blur`] | a sphere sliding under matrix motion keys and a teapot turning under scale-rotate-translate keys, each sample traced at its own time (`rt_trace_at`) |
//!
//! [`common`] holds what the Whitted-style examples share on the device side
//! (payloads, attributes, lights, the camera), [`guides`] what the path
//! tracers keep for a denoiser beside the radiance, [`tutorial`] the scene of
//! examples 1 to 7, [`scene`] the host side of every example (settings,
//! camera, rendering to an [`Image`]), and [`mesh`] OBJ loading with
//! line-precise errors; [`viewer`] is the live viewer's progressive
//! rendering, [`present`] its way to a window from the GPU, and [`model`] a user's OBJ or glTF file framed by the
//! camera they ask for. Each module builds its scene with the public API of
//! `rt-runtime` only.
//!
//! ```no_run
//! let mut scene = examples::normal::scene(&examples::Settings::new(320, 240))?;
//! let rendered = scene.render(&mut |_| {})?;
//! rendered.image.save_png(std::path::Path::new("normal.png"))?;
//! # Ok::<(), examples::Error>(())
//! ```
//!
//! The `tour` binary renders them all; `render` shows any OBJ file the way
//! [`bunny`] shows the bunny, and `viewer` shows it in a window.

// Ray programs take their variables as parameters.
#![allow(clippy::too_many_arguments)]

pub mod bunny;
pub mod callable_brdfs;
pub mod common;
pub mod convex_hull;
pub mod cornell;
pub mod denoised;
pub mod diffuse;
pub mod envmap;
pub mod guides;
pub mod instances;
#[cfg(not(target_arch = "wasm32"))]
pub mod limits;
#[cfg(not(target_arch = "wasm32"))]
pub mod model;
pub mod motion_blur;
/// OBJ loading, moved to `rt-scene` ([`rt_scene::obj`]); kept here by its
/// old name.
pub use rt_scene::obj as mesh;
pub mod normal;
pub mod parts;
pub mod phong;
#[cfg(not(target_arch = "wasm32"))]
pub mod present;
#[cfg(not(target_arch = "wasm32"))]
pub mod progress_bar;
pub mod receiver_grid;
pub mod reflections;
pub mod scene;
pub mod shadows;
pub mod tutorial;
#[cfg(not(target_arch = "wasm32"))]
pub mod viewer;

pub use scene::{Aovs, BackendChoice, Camera, Error, Image, Rendered, Scene, Settings};

/// One example: its name (the tour's file name) and how to build its scene.
pub struct Example {
    pub name: &'static str,
    /// What it shows, in a few words.
    pub summary: &'static str,
    pub build: fn(&Settings) -> Result<Scene, Error>,
    /// Whether `Settings::spp` sets its launch count.
    pub progressive: bool,
}

/// Every example, in the tour's order.
pub const EXAMPLES: [Example; 13] = [
    Example { name: "normal", summary: "normal shader", build: normal::scene, progressive: false },
    Example { name: "diffuse", summary: "ambient + Lambert", build: diffuse::scene, progressive: false },
    Example { name: "phong", summary: "Blinn-Phong", build: phong::scene, progressive: false },
    Example { name: "shadows", summary: "shadow rays, any-hit terminate", build: shadows::scene, progressive: false },
    Example {
        name: "reflections",
        summary: "reflections by depth and importance",
        build: reflections::scene,
        progressive: false,
    },
    Example { name: "envmap", summary: "lat/long environment map", build: envmap::scene, progressive: false },
    Example { name: "convex_hull", summary: "convex hull as glass", build: convex_hull::scene, progressive: false },
    Example { name: "cornell", summary: "path-traced Cornell box", build: cornell::scene, progressive: true },
    Example { name: "bunny", summary: "bunny, shadows and ambient occlusion", build: bunny::scene, progressive: true },
    Example { name: "instances", summary: "100 instances of one BVH", build: instances::scene, progressive: false },
    Example {
        name: "receiver_grid",
        summary: "rays reaching a receiver grid, counted atomically",
        build: receiver_grid::scene,
        progressive: true,
    },
    Example {
        name: "callable_brdfs",
        summary: "a BRDF per material, a callable from a buffer",
        build: callable_brdfs::scene,
        progressive: false,
    },
    Example {
        name: "motion_blur",
        summary: "a sliding sphere and a turning teapot, time sampled per path",
        build: motion_blur::scene,
        progressive: true,
    },
];

/// The example called `name`.
pub fn example(name: &str) -> Option<&'static Example> {
    EXAMPLES.iter().find(|e| e.name == name)
}
