//! One-dimensional buffers: `Buffer` and `RwBuffer` of scalars, vectors and
//! structs, read with `load` and `[i]`, written with `store`, `[i] = v` and
//! compound assignment to an element or to one of its fields, and
//! `len`/`is_empty`: a scatter into per-bin statistics.
use rt_std::prelude::*;

/// Per-bin statistics.
#[rt_struct]
pub struct Bin {
    pub sum: Vec3,
    pub count: u32,
    pub max_value: f32,
}

#[rt_program(ray_generation)]
pub fn buffers(
    #[var] samples: Buffer<Vec3>,
    #[var] bin_of: Buffer<u32>,
    #[var] mut bins: RwBuffer<Bin>,
    #[var] mut totals: RwBuffer<f32>,
    #[var] mut order: RwBuffer<u32>,
) {
    let i = launch_index().x;
    if samples.is_empty() || i >= samples.len() {
        return;
    }
    let s = samples[i];
    let b = bin_of.load(i) % bins.len();
    bins[b].sum += s;
    bins[b].count += 1;
    if s.max_element() > bins[b].max_value {
        bins[b].max_value = s.max_element();
    }
    let mut bin = bins.load(b);
    bin.sum *= 0.5;
    bins.store((b + 1) % bins.len(), bin);
    totals[i] = s.element_sum();
    totals[i] += totals.load(i) * 0.5;
    order.store(i, order[i] + samples.len());
    order[i] |= 1;
}
