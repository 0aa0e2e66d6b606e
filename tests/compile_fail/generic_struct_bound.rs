// A method of a generic struct's block called on an instance whose
// argument lacks the block's bound: rustc's error at the call, and the
// instance's own (WGSL has no `+` of bools).
use core::ops::Add;
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

#[rt_impl]
impl<T: Copy + Add<Output = T>> Pair<T> {
    pub fn total(&self) -> T {
        self.a + self.b
    }
}

#[rt_program(ray_generation)]
pub fn render(#[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    let p = Pair { a: true, b: false };
    out[i] = p.total() as u32;
}

fn main() {}
