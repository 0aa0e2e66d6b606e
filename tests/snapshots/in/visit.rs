//! A visit program: a level-of-detail selector that picks which child a
//! ray enters from the distance to the object's centre and the ray's
//! importance, returning the child index.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(visit)]
pub fn lod_visit(prd: &Radiance, #[var] center: Vec3, #[var] lod_distances: Vec3, #[var] children: u32) -> u32 {
    let ray = current_ray();
    let dist = (center - ray.origin).length();
    if prd.importance < 0.1 || prd.depth > 2 {
        return children - 1;
    }
    let mut child = 0u32;
    for i in 0..3 {
        if dist > lod_distances[i] {
            child = i as u32 + 1;
        }
    }
    child.min(children - 1)
}
