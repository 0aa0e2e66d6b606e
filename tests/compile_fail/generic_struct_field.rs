// A struct without parameters holding an instance of a generic struct: the
// plain struct is host data, laid out once, and the generic one has no
// layout.
use rt_std::prelude::*;

#[rt_struct]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

#[rt_struct]
pub struct Hit {
    pub span: Pair<f32>,
    pub id: u32,
}

fn main() {}
