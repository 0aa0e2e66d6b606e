//! 3D buffers and launches: a volume sampled along a ray by its cell
//! (reads checked in every axis), a counter of cells written per slice,
//! the volume's size; a 3D launch filling a volume cell by cell.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn march_volume(#[var] density: Buffer3d<f32>, #[var] mut out: RwBuffer2d<f32>, #[var] mut seen: RwBuffer3d<u32>) {
    let l = launch_index();
    let size = density.size();
    let mut sum = 0.0f32;
    let mut z = 0u32;
    while z < size.z {
        let cell = uvec3(l.x, l.y, z);
        sum += density[cell];
        seen[cell] = seen.load(cell) + 1;
        z += 1;
    }
    out[l] = sum / size.z as f32;
}

/// A 3D launch filling a volume: each launch index its own cell.
#[rt_program(ray_generation)]
pub fn fill_volume(#[var] mut volume: RwBuffer3d<Vec4>) {
    let i = launch_index_3d();
    let d = launch_dim_3d();
    volume[i] = (i.as_vec3() + Vec3::splat(0.5)).extend(1.0) / d.as_vec3().extend(1.0);
}
