// A struct holding a bindless id of its own type (a linked list of
// buffers): its element type is resolved before the struct is built.
use rt_std::prelude::*;

#[rt_struct]
pub struct Chunk {
    pub value: u32,
    pub next: BindlessBuffer<Chunk>,
}

#[rt_program(ray_generation)]
pub fn walk(#[var] first: Chunk, #[var] mut out: RwBuffer<u32>) {
    out[0] = first.value;
}

fn main() {}
