// A `let` inside a longer condition: nest an `if` inside the `if let`.
use rt_std::prelude::*;

#[rt_function]
pub fn small_even(x: i32) -> bool {
    if let 0..=9 = x && x % 2 == 0 { true } else { false }
}

fn main() {}
