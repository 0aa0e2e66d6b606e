// Direct recursion in a helper: WGSL has no recursion.
use rt_std::prelude::*;

#[rt_function]
pub fn factorial(n: u32) -> u32 {
    if n == 0 { 1 } else { n * factorial(n - 1) }
}

fn main() {}
