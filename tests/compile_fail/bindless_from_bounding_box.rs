// A bounding-box program reading through a bindless id: it runs at build
// time, outside any launch.
use rt_std::prelude::*;

#[rt_program(bounding_box)]
pub fn bounds(prim: u32, #[var] boxes: BindlessBuffer<Aabb>) -> Aabb {
    boxes.load(prim)
}

fn main() {}
