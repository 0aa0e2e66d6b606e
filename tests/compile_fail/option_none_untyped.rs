// `None` with nothing to say its type (`is_some` takes any `Option`):
// annotate the binding.
use rt_std::prelude::*;

#[rt_function]
pub fn fallback(x: f32) -> f32 {
    let o = None;
    if o.is_some() { 1.0 } else { x }
}

fn main() {}
