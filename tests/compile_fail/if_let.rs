// `if let`: programs compare values with if/else.
use rt_std::prelude::*;

#[rt_function]
pub fn is_zero(x: i32) -> bool {
    if let 0 = x { true } else { false }
}

fn main() {}
