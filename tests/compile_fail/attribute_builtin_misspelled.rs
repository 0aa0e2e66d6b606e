// A triangle's built-in attribute spelled otherwise (`texcoords`) or typed
// otherwise (`barycentrics: Vec3`) would read zero on every triangle.
use rt_std::prelude::*;

#[rt_attributes]
pub struct Hit {
    pub geometric_normal: Vec3,
    pub texcoords: Vec2,
    pub barycentrics: Vec3,
    pub tex_coord: Vec2,
    pub hit_distance: f32,
}

fn main() {}
