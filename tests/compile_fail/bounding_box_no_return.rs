// A bounding-box program must return the primitive's Aabb.
use rt_std::prelude::*;

#[rt_program(bounding_box)]
pub fn bounds(prim: u32, #[var] radius: f32) {
    let _ = prim;
    let _ = Aabb::new(Vec3::splat(-radius), Vec3::splat(radius));
}

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &bounds::PROGRAM;

fn main() {}
