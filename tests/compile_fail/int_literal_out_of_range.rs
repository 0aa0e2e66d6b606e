// An integer literal that does not fit its type.
use rt_std::prelude::*;

#[rt_function]
pub fn big() -> i32 {
    let x: i32 = 3000000000;
    x
}

fn main() {}
