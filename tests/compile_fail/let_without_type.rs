// A `let` with neither type nor initializer.
use rt_std::prelude::*;

#[rt_function]
pub fn pick(a: f32, b: f32, first: bool) -> f32 {
    let x;
    if first {
        x = a;
    } else {
        x = b;
    }
    x
}

fn main() {}
