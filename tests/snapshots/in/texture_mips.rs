//! Mipmapped textures: `Sampler2d::sample_lod` at a LOD from a variable and
//! one read from a buffer (its argument spilled before the buffer is
//! written), `sample_grad` with a footprint from the ray's distance, and
//! `levels`, in a miss program.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(miss)]
pub fn mip_miss(prd: &mut Radiance, #[var] sky: Sampler2d, #[var] bias: f32, #[var] mut lods: RwBuffer<f32>) {
    let d = current_ray().direction;
    let uv = vec2(d.x * 0.5 + 0.5, d.y * 0.5 + 0.5);
    let blurred = sky.sample_lod(uv, bias + prd.depth as f32);
    let footprint = vec2(prd.importance / sky.size().x as f32, 0.0);
    let sharp = sky.sample_grad(uv, footprint, footprint.yx());
    let last = sky.sample_lod(
        uv * 2.0,
        lods[0] + {
            lods[0] = sky.levels() as f32;
            1.0
        },
    );
    prd.result = (blurred + sharp + last + sky.sample(uv)).xyz();
}
