// panic!: programs raise exceptions with rt_throw.
use rt_std::prelude::*;

#[rt_function]
pub fn checked_div(a: f32, b: f32) -> f32 {
    if b == 0.0 {
        panic!("division by zero");
    }
    a / b
}

fn main() {}
