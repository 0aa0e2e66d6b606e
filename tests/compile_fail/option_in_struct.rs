// An `Option` as a struct field: the host shares no layout for it.
use rt_std::prelude::*;

#[rt_struct]
pub struct Hit {
    pub t: Option<f32>,
}

fn main() {}
