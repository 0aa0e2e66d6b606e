//! Arithmetic on every scalar type: `+ - * / %` and unary minus on `f32`,
//! `i32` and `u32`, every compound assignment, and unsuffixed integer
//! literals that take their type from how they are used.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn ops_arith(
    #[var] a: f32,
    #[var] b: f32,
    #[var] n: i32,
    #[var] m: u32,
    #[var] out_f: RwBuffer<f32>,
    #[var] out_i: RwBuffer<i32>,
    #[var] out_u: RwBuffer<u32>,
) {
    let slot = launch_index().x;

    // f32: `%` is the truncated remainder (`fmod`), as in Rust.
    let sum = a + b;
    let diff = a - b;
    let prod = a * b;
    let quot = a / b;
    let rem = a % b;
    let neg = -a;
    let mut acc = sum;
    acc += diff;
    acc -= prod;
    acc *= 0.5;
    acc /= quot + 2.0;
    acc %= 7.0;
    out_f.store(slot, acc + rem * neg - (a - b) / (a + b));

    // i32: division truncates towards zero, `%` takes the dividend's sign.
    let mut k = n * 3 - 7;
    k += n / 2;
    k -= n % 3;
    k *= -2;
    k /= 3;
    k %= 5;
    let magnitude = 1.max(if n > 0 { n } else { -n });
    out_i.store(slot, -k + (n - 1) * (n + 1) - -n + magnitude);

    // u32, with literals inferred as u32.
    let mut w = m + 1;
    w *= 2;
    w -= 1;
    w /= 3;
    w %= 100;
    w += m % 7;
    out_u.store(slot, w * 3u32 + 10);
}
