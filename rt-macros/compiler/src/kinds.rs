//! The contract's program kinds and intrinsics (from `rt-abi`, shared with
//! rt-std and the runtime), and the `core` constants the subset knows.
//! The checker reads the intrinsic rows to reject, say, `rt_terminate_ray`
//! in a closest-hit program, and to type and lower plain intrinsic calls.

pub use rt_abi::constants::{CONSTANTS, constant};
pub use rt_abi::intrinsics::{AbiTy, Form, INTRINSICS, Intrinsic, WgslFn, intrinsic};
pub use rt_abi::kinds::{ALL_KINDS, Callers, Kind};

/// `core::f32::consts` the subset knows, with their f32 values.
pub const F32_CONSTS: &[(&str, f32)] = &[
    ("PI", std::f32::consts::PI),
    ("TAU", std::f32::consts::TAU),
    ("FRAC_PI_2", std::f32::consts::FRAC_PI_2),
    ("FRAC_PI_3", std::f32::consts::FRAC_PI_3),
    ("FRAC_PI_4", std::f32::consts::FRAC_PI_4),
    ("FRAC_PI_6", std::f32::consts::FRAC_PI_6),
    ("FRAC_PI_8", std::f32::consts::FRAC_PI_8),
    ("FRAC_1_PI", std::f32::consts::FRAC_1_PI),
    ("FRAC_2_PI", std::f32::consts::FRAC_2_PI),
    ("FRAC_1_SQRT_2", std::f32::consts::FRAC_1_SQRT_2),
    ("E", std::f32::consts::E),
    ("SQRT_2", std::f32::consts::SQRT_2),
    ("LN_2", std::f32::consts::LN_2),
    ("LN_10", std::f32::consts::LN_10),
];
