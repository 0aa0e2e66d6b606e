//! Cross-crate tests. The library compiles the snapshot corpus
//! (`snapshots/in/*.rs`) through the real `#[rt_program]` macros, so every
//! snapshot program is also checked by rustc and runs as Rust; the tests in
//! `tests/` compare its WGSL with the checked-in snapshots.
#![allow(dead_code, clippy::too_many_arguments)]

#[path = "../snapshots/in/seed_common.rs"]
pub mod seed_common;
#[path = "../snapshots/in/seed_camera.rs"]
pub mod seed_camera;
#[path = "../snapshots/in/seed_normal.rs"]
pub mod seed_normal;
#[path = "../snapshots/in/seed_diffuse.rs"]
pub mod seed_diffuse;
#[path = "../snapshots/in/seed_phong.rs"]
pub mod seed_phong;
#[path = "../snapshots/in/seed_reflections.rs"]
pub mod seed_reflections;
#[path = "../snapshots/in/seed_envmap.rs"]
pub mod seed_envmap;
#[path = "../snapshots/in/seed_convex_hull.rs"]
pub mod seed_convex_hull;
