// `None` with nothing to say its type: annotate the binding.
use rt_std::prelude::*;

#[rt_function]
pub fn fallback(x: f32) -> f32 {
    let o = None;
    if x > 0.0 { x } else { o.unwrap_or(1.0) }
}

fn main() {}
