//! Cross-crate tests. The library compiles the snapshot corpus
//! (`snapshots/in/*.rs`) through the real `#[rt_program]` macros, so every
//! snapshot program is also checked by rustc and runs as Rust; the tests in
//! `tests/` compare its WGSL with the checked-in snapshots.
#![allow(dead_code, clippy::too_many_arguments)]

pub mod fuzz;
pub mod scene_fuzz;
pub mod targets;

#[path = "../snapshots/in/buffers.rs"]
pub mod buffers;
#[path = "../snapshots/in/buffers_2d.rs"]
pub mod buffers_2d;
#[path = "../snapshots/in/casts.rs"]
pub mod casts;
#[path = "../snapshots/in/compare_logic.rs"]
pub mod compare_logic;
#[path = "../snapshots/in/consts.rs"]
pub mod consts;
#[path = "../snapshots/in/control_flow.rs"]
pub mod control_flow;
#[path = "../snapshots/in/exceptions.rs"]
pub mod exceptions;
#[path = "../snapshots/in/fuzz_regressions.rs"]
pub mod fuzz_regressions;
#[path = "../snapshots/in/helpers_refs.rs"]
pub mod helpers_refs;
#[path = "../snapshots/in/instancing.rs"]
pub mod instancing;
#[path = "../snapshots/in/intersection_sphere.rs"]
pub mod intersection_sphere;
#[path = "../snapshots/in/loops.rs"]
pub mod loops;
#[path = "../snapshots/in/match_int.rs"]
pub mod match_int;
#[path = "../snapshots/in/math_helpers.rs"]
pub mod math_helpers;
#[path = "../snapshots/in/matrices.rs"]
pub mod matrices;
#[path = "../snapshots/in/ops_arith.rs"]
pub mod ops_arith;
#[path = "../snapshots/in/ops_bits.rs"]
pub mod ops_bits;
#[path = "../snapshots/in/path_tracer.rs"]
pub mod path_tracer;
#[path = "../snapshots/in/printf.rs"]
pub mod printf;
#[path = "../snapshots/in/ray_flags.rs"]
pub mod ray_flags;
#[path = "../snapshots/in/scalar_math.rs"]
pub mod scalar_math;
#[path = "../snapshots/in/seed_camera.rs"]
pub mod seed_camera;
#[path = "../snapshots/in/seed_common.rs"]
pub mod seed_common;
#[path = "../snapshots/in/seed_convex_hull.rs"]
pub mod seed_convex_hull;
#[path = "../snapshots/in/seed_diffuse.rs"]
pub mod seed_diffuse;
#[path = "../snapshots/in/seed_envmap.rs"]
pub mod seed_envmap;
#[path = "../snapshots/in/seed_normal.rs"]
pub mod seed_normal;
#[path = "../snapshots/in/seed_phong.rs"]
pub mod seed_phong;
#[path = "../snapshots/in/seed_reflections.rs"]
pub mod seed_reflections;
#[path = "../snapshots/in/structs_arrays.rs"]
pub mod structs_arrays;
#[path = "../snapshots/in/textures.rs"]
pub mod textures;
#[path = "../snapshots/in/vectors.rs"]
pub mod vectors;
#[path = "../snapshots/in/vectors_int.rs"]
pub mod vectors_int;
#[path = "../snapshots/in/visit.rs"]
pub mod visit;
