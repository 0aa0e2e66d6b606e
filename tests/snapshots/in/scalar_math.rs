//! `f32` methods and constants: roots, powers (`powi` with a negative base
//! included), exponentials and logarithms, trigonometry, rounding in its
//! Rust flavours (`round` half away from zero, `fract` as `x - trunc(x)`),
//! `signum`, `mul_add`, `hypot`, the NaN/infinity tests, `f32::consts`,
//! and `f32::max`-style calls.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn scalar_math(#[var] x: f32, #[var] y: f32, #[var] out: RwBuffer<f32>) {
    let slot = launch_index().x;
    let roots = x.abs().sqrt() + x.recip() + x.powf(1.5) + (x - 2.0).powi(3) + x.powi(-2);
    let exps = x.exp() + x.exp2() + y.abs().ln() + y.abs().log2() + x.to_radians() + y.to_degrees();
    let trig =
        x.sin() * y.cos() + x.tan() + x.clamp(-1.0, 1.0).asin() + y.clamp(-1.0, 1.0).acos() + x.atan() + y.atan2(x);
    let hyper = x.sinh() + x.cosh() + x.tanh() + x.asinh() + (y.abs() + 1.0).acosh() + (x * 0.5).tanh().atanh();
    let rounding = x.floor() + x.ceil() + x.round() + x.trunc() + x.fract() + x.signum() + x.round_ties_even();
    let misc = x.mul_add(y, 1.0) + x.hypot(y) + x.min(y) + x.max(y) + f32::max(x, 0.0) + f32::min(y, PI);
    let consts = TAU * FRAC_1_PI + E * LN_2 + SQRT_2 * FRAC_PI_4 + core::f32::consts::FRAC_PI_3 + f32::EPSILON;
    let mut total = roots + exps + trig + hyper + rounding + misc + consts;
    if total.is_nan() || total.is_infinite() || !total.is_finite() {
        total = f32::MAX.min(f32::MIN_POSITIVE + f32::MIN.abs());
    }
    out.store(slot, total);
}
