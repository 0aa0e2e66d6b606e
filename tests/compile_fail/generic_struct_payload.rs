// A generic payload: the runtime stores a payload by one layout, and an
// instance of a generic struct has none the host shares.
use rt_std::prelude::*;

#[rt_payload]
pub struct Carry<T> {
    pub value: T,
}

fn main() {}
