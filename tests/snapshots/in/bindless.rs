//! Bindless buffers: ids held in a variable, a buffer of ids, a struct
//! field and a payload field; reads (`load`, `[i]`, `len`) and a write
//! through them, each an id accessor (`rt_idload_<T>`, `rt_idlen_<T>`,
//! `rt_idstore_<T>`) that checks the id's element tag before the bounds
//! check; ids made from a `u32` and compared.
use rt_std::prelude::*;

#[rt_struct]
pub struct MeshData {
    pub colours: BindlessBuffer<Vec3>,
    pub gain: f32,
}

#[rt_payload]
pub struct Lit {
    pub colour: Vec3,
    pub source: BindlessBuffer<Vec3>,
}

#[rt_program(closest_hit)]
pub fn colour_by_instance(prd: &mut Lit, #[var] mesh: u32, #[var] meshes: Buffer<MeshData>) {
    let m = meshes[mesh];
    prd.colour = m.colours.load(primitive_index()) * m.gain;
    prd.source = m.colours;
}

#[rt_program(ray_generation)]
pub fn read_through_ids(
    #[var] first: BindlessBuffer<u32>,
    #[var] ids: Buffer<BindlessBuffer<u32>>,
    #[var] sink: RwBindlessBuffer<u32>,
    #[var] mut out: RwBuffer<u32>,
) {
    let i = launch_index().x;
    let b = ids[i % ids.len()];
    let mut n = b.len() + b[i];
    if b == first || b == BindlessBuffer::NONE {
        n += BindlessBuffer::<u32>::from_id(i).load(0);
    }
    sink.store(i, n + sink.len());
    out[i] = n;
}
