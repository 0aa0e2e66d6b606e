// Mutual recursion between helpers: reported once, at the call that closes
// the cycle.
use rt_std::prelude::*;

#[rt_function]
pub fn is_even(n: u32) -> bool {
    if n == 0 { true } else { is_odd(n - 1) }
}

#[rt_function]
pub fn is_odd(n: u32) -> bool {
    if n == 0 { false } else { is_even(n - 1) }
}

fn main() {}
