//! Two-dimensional buffers: `Buffer2d` and `RwBuffer2d` read with `load`
//! and `[UVec2]`, written with `store` and `[UVec2] = v`, read-modify-write
//! of an element, and `size`: a 3x3 box blur with clamped borders into an
//! accumulation buffer.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn buffers_2d(
    #[var] input: Buffer2d<Vec4>,
    #[var] mut accum: RwBuffer2d<Vec4>,
    #[var] mut samples: RwBuffer2d<u32>,
    #[var] frame: u32,
) {
    let idx = launch_index();
    let size = input.size();
    if idx.x >= size.x || idx.y >= size.y {
        return;
    }
    let mut sum = Vec4::ZERO;
    for dy in -1..=1 {
        for dx in -1..=1 {
            let p = (idx.as_ivec2() + ivec2(dx, dy)).clamp(IVec2::ZERO, size.as_ivec2() - 1);
            sum += input[p.as_uvec2()];
        }
    }
    let blurred = sum / 9.0;
    let prev = accum.load(idx);
    let n = samples[idx] as f32;
    accum.store(idx, (prev * n + blurred) / (n + 1.0));
    samples[idx] += 1;
    if frame == 0 {
        accum[idx] = blurred;
        samples[uvec2(idx.x, idx.y)] = 1;
    }
    let corner = accum.size() - UVec2::ONE;
    accum[corner] = input.load(UVec2::ZERO);
}
