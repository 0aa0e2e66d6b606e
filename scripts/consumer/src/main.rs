//! README's first program, as a user writes it in a crate of their own:
//! the normals closest-hit and background miss programs over a square
//! seen head-on, rendered on the CPU backend into `consumer.png`. The
//! pixels are checked here: the square's normal `(0, 0, 1)` shades as
//! `(0.5, 0.5, 1)`, everything else is the background colour.

use rt_runtime::{Acceleration, BufferType, Context, Scope, TriangleMesh};
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
    pub importance: f32,
    pub depth: i32,
}

#[rt_attributes]
pub struct Normals {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
}

#[rt_program(closest_hit)]
pub fn normals(prd: &mut Radiance, attr: &Normals) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize() * 0.5 + 0.5;
}

#[rt_program(miss)]
pub fn background(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

/// One ray down -z per pixel, from the pixel's centre in `[-1, 1]^2`.
#[rt_program(ray_generation)]
pub fn camera(#[var] top: Object, #[var] mut image: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let p = (idx.as_vec2() + Vec2::splat(0.5)) / launch_dim().as_vec2() * 2.0 - Vec2::ONE;
    let mut prd = Radiance { result: Vec3::ZERO, importance: 1.0, depth: 0 };
    rt_trace(top, Ray::new(vec3(p.x, p.y, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0), &mut prd);
    image[idx] = prd.result.extend(1.0);
}

const SIZE: u32 = 8;
const BACKGROUND: Vec3 = Vec3::new(0.25, 0.5, 0.75);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut ctx = Context::new();
    let camera = ctx.create_program(&camera::PROGRAM);
    ctx.set_ray_generation_program(0, camera)?;
    let miss = ctx.create_program(&background::PROGRAM);
    ctx.set_miss_program(0, miss)?;
    ctx.set_var(Scope::Context, "bg_color", BACKGROUND)?;
    let material = ctx.create_material();
    let hit = ctx.create_program(&normals::PROGRAM);
    ctx.set_closest_hit_program(material, 0, hit)?;
    // The square [-0.5, 0.5]^2 at z = 0, facing +z.
    let square = ctx.create_triangles(TriangleMesh {
        positions: vec![vec3(-0.5, -0.5, 0.0), vec3(0.5, -0.5, 0.0), vec3(0.5, 0.5, 0.0), vec3(-0.5, 0.5, 0.0)],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        normals: None,
        texcoords: None,
        material_indices: None,
    })?;
    let instance = ctx.create_geometry_instance(square, &[material])?;
    let top = ctx.create_geometry_group(&[instance], Acceleration::default())?;
    ctx.set_var(Scope::Context, "top", top)?;
    let image = ctx.create_buffer_2d::<Vec4>(BufferType::Output, SIZE, SIZE)?;
    ctx.set_var(Scope::Context, "image", image)?;
    let report = ctx.launch(0, SIZE, SIZE)?;
    let out = std::env::args().nth(1).unwrap_or_else(|| "consumer.png".into());
    ctx.save_png(image, &out)?;
    let pixels = ctx.read_buffer::<Vec4>(image)?;
    let mut wrong = Vec::new();
    for y in 0..SIZE {
        for x in 0..SIZE {
            // Pixel centres at -0.875, -0.625, ..., 0.875: 2 to 5 are on the square.
            let on = |i: u32| (2..=5).contains(&i);
            let want = if on(x) && on(y) { Vec3::new(0.5, 0.5, 1.0) } else { BACKGROUND }.extend(1.0);
            let got = pixels[(y * SIZE + x) as usize];
            if got != want {
                wrong.push(format!("({x}, {y}): {got} (expected {want})"));
            }
        }
    }
    if !report.exceptions.is_empty() || report.rays != u64::from(SIZE * SIZE) {
        return Err(format!("{} rays, exceptions {:?}", report.rays, report.exceptions).into());
    }
    if !wrong.is_empty() {
        return Err(format!("{} of {} pixels wrong: {}", wrong.len(), SIZE * SIZE, wrong.join("; ")).into());
    }
    println!("rt-consumer: {SIZE}x{SIZE} pixels on the {:?} backend as expected ({out})", ctx.backend());
    Ok(())
}
