//! Plain `const` items (no `#[rt_const]`) named by programs, helpers and
//! impls of their own module: a scalar, a vector, an array, one computed
//! from another, one in an inline module, an `#[rt_const]` computed from
//! one, an array index; every
//! target gives what Rust computes. (A constant imported from another
//! module still needs `#[rt_const]`: `compile_fail/plain_const.rs`.)

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

const SCALE: f32 = 0.5;
pub const OFFSET: u32 = 3;
/// Computed from another plain constant.
const DOUBLE_SCALE: f32 = SCALE * 4.0;
const BIAS: Vec3 = Vec3::new(1.0, 2.0, 3.0);
const WEIGHTS: [f32; 3] = [0.25, 0.5, 0.75];

const LEN: usize = 3;

/// An `#[rt_const]` computed from a plain one.
#[rt_const]
pub const DECLARED: f32 = DOUBLE_SCALE * 5.0;

/// A helper naming a plain constant.
#[rt_function]
pub fn scaled(v: f32) -> f32 {
    v * SCALE + OFFSET as f32
}

#[rt_struct(impl)]
pub struct Gain {
    pub k: f32,
}

#[rt_impl]
impl Gain {
    /// An associated function naming a plain constant.
    pub fn doubled() -> Gain {
        Gain { k: DOUBLE_SCALE }
    }
}

#[rt_program(ray_generation)]
pub fn uses_plain_consts(#[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    let x = i as f32;
    let w = WEIGHTS[(i % 3) as usize];
    out[i] = scaled(x) + BIAS.y * w + Gain::doubled().k + DECLARED + (i + OFFSET) as f32 + WEIGHTS[LEN - 1];
}

/// What the program computes, in Rust.
fn expected(i: u32) -> f32 {
    let x = i as f32;
    let w = WEIGHTS[(i % 3) as usize];
    scaled(x) + BIAS.y * w + Gain::doubled().k + DECLARED + (i + OFFSET) as f32 + WEIGHTS[LEN - 1]
}

mod inner {
    use rt_std::prelude::*;

    /// The inline module's own constant, of the same name as the file's.
    const SCALE: f32 = -2.0;

    #[rt_program(ray_generation)]
    pub fn uses_inner_const(#[var] mut out: RwBuffer<f32>) {
        let i = launch_index().x;
        out[i] = i as f32 * SCALE;
    }
}

fn run(on: On, program: &'static rt_std::program::ProgramDescriptor, n: u32) -> Vec<f32> {
    let mut ctx = on.context();
    let out = ctx.create_buffer::<f32>(BufferType::InputOutput, vec![0.0; n as usize]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(program);
    ctx.set_ray_generation_program(0, rg).unwrap();
    ctx.launch_1d(0, n).unwrap();
    ctx.read_buffer::<f32>(out).unwrap()
}

#[test]
fn plain_constants_of_the_module_mean_what_rust_says_on_every_target() {
    let want: Vec<f32> = (0..6).map(expected).collect();
    let inner_want: Vec<f32> = (0..4).map(|i| i as f32 * -2.0).collect();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        assert_eq!(run(on, &uses_plain_consts::PROGRAM, 6), want, "{}", on.name());
        assert_eq!(run(on, &inner::uses_inner_const::PROGRAM, 4), inner_want, "{}", on.name());
    }
}
