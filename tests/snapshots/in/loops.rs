//! Loops: `for` over `a..b` and `a..=b` with literal and computed bounds,
//! `continue`, nested loops, `while` (also with a condition that calls a
//! helper mutating state), and `loop` with `break`.
use rt_std::prelude::*;

/// Pops the lowest set bit of `mask`; false when none is left.
#[rt_function]
pub fn pop_bit(mask: &mut u32, bit: &mut u32) -> bool {
    if *mask == 0 {
        return false;
    }
    *bit = mask.trailing_zeros();
    *mask &= *mask - 1;
    true
}

#[rt_program(ray_generation)]
pub fn loops(#[var] n: u32, #[var] mask: u32, #[var] out: RwBuffer<f32>) {
    let slot = launch_index().x;
    let mut sum = 0.0;
    for i in 0..n {
        if i % 2 == 0 {
            continue;
        }
        sum += i as f32;
    }
    for i in 1..=4 {
        sum *= 0.5 + i as f32;
    }
    for row in 0..3u32 {
        for col in row..=n + 1 {
            sum += (row * col) as f32;
        }
    }
    let mut k = slot + 1;
    let mut steps = 0;
    while k > 1 {
        if k.is_multiple_of(2) {
            k /= 2;
        } else {
            k = 3 * k + 1;
        }
        steps += 1;
    }
    let mut remaining = mask;
    let mut bit = 0u32;
    let mut bits_seen = 0u32;
    while steps > 0 && pop_bit(&mut remaining, &mut bit) {
        bits_seen += bit;
    }
    // Newton's iteration for sqrt(2).
    let mut x = 1.0f32;
    let mut iters = 0;
    loop {
        x = 0.5 * (x + 2.0 / x);
        iters += 1;
        if iters == 8 || (x * x - 2.0).abs() < 1e-6 {
            break;
        }
    }
    out.store(slot, sum + x + steps as f32 + bits_seen as f32);
}
