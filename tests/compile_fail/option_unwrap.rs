// `expect` with a message that is not a string literal: ray programs take
// the literal (the GPU has no strings to build one from).
use rt_std::prelude::*;

#[rt_function]
pub fn first(o: Option<f32>, code: u32) -> f32 {
    o.expect(if code > 0 { "positive" } else { "zero" })
}

fn main() {}
