// Mutual recursion between helpers. Each helper's macro waits for the other's
// (see rt_compiler::expand), so neither is ever defined and rustc reports
// "cannot find macro" at both calls: a known weak message, pinned here.
// Direct recursion gets a proper message (recursion.rs).
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
