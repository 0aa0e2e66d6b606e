//! The heap: the records of the launch's program uses (their variables'
//! values), then the buffers' words, then sampler texels, all addressed by
//! word offset in the one read-write binding `rt_heap`.

use super::kernel;
use crate::buffer::{SamplerRec, SamplerShape};
use crate::error::{LaunchError, Result, RtError, SceneError};
use crate::link::{self, Record};
use crate::scene::{ProgramId, Scene};
use crate::vars::VarValue;
use rt_abi::records::{BufferTable, SamplerTable, layout_tag};
use rt_std::program::VariableKind;

/// The records of a launch's program uses, laid out before their values
/// are known: a record's size is fixed by its program's variables.
#[derive(Clone, Default)]
pub(crate) struct Records {
    pub(crate) uses: Vec<(ProgramId, Record)>,
    pub(crate) words: u32,
}

impl Records {
    /// A record for `p` used as `r`; returns its offset in the heap.
    pub(crate) fn add(&mut self, scene: &Scene, p: ProgramId, r: Record) -> Result<u32> {
        let at = self.words;
        let desc = scene.program(p)?.desc;
        self.words += desc.variables.iter().map(|v| kernel::variable_words(&v.kind, &v.ty)).sum::<u32>();
        self.uses.push((p, r));
        Ok(at)
    }
}

/// The heap of a launch: the values of `records` (resolved now, so a
/// changed variable takes effect), then the buffers' words, then sampler
/// texels, then the bindless buffer and sampler tables. Also returns the `(buffer index, heap offset, words)` of the
/// buffers programs may write, and every buffer's `(heap offset, words)`.
pub(crate) fn encode_heap(scene: &Scene, records: &Records) -> Result<EncodedHeap> {
    let base = records.words as usize;
    let mut heap: Vec<u32> = Vec::with_capacity(base);
    // Data follows the records: buffers, then sampler texels.
    let mut data: Vec<u32> = Vec::new();
    let mut buffer_offsets = Vec::with_capacity(scene.buffers.len());
    let mut outputs = Vec::new();
    let mut placed = Vec::with_capacity(scene.buffers.len());
    let mut table = Vec::with_capacity(1 + scene.buffers.len() * BufferTable::WORDS as usize);
    table.push(scene.buffers.len() as u32);
    for (i, b) in scene.buffers.iter().enumerate() {
        let start = data.len();
        b.storage.to_words(&mut data);
        buffer_offsets.push(base + start);
        placed.push((base + start, data.len() - start));
        if b.ty.writable_by_programs() {
            outputs.push((i, base + start, data.len() - start));
        }
        let layout = b.storage.layout();
        let entry = BufferTable {
            offset: (base + start) as u32,
            len: b.len(),
            tag: layout_tag(layout.rust),
            writable: b.ty.writable_by_programs() as u32,
        };
        table.extend(entry.words());
    }
    let mut sampler_offsets = Vec::with_capacity(scene.samplers.len());
    let mut samplers_placed = Vec::with_capacity(scene.samplers.len());
    for s in &scene.samplers {
        let start = data.len();
        sampler_offsets.push(base + start);
        for t in s.texels.iter() {
            data.extend(t.to_array().map(f32::to_bits));
        }
        samplers_placed.push((base + start, data.len() - start));
    }
    for &(p, r) in &records.uses {
        let desc = scene.program(p)?.desc;
        let values = link::resolve_values(scene, p, r)?;
        for (value, v) in values.into_iter().zip(desc.variables) {
            match (value, v.kind) {
                (VarValue::Data { words, .. }, _) => heap.extend(words),
                (VarValue::Buffer(b), VariableKind::Buffer { .. }) => {
                    let rec = &scene.buffers[b.index() as usize];
                    heap.extend([buffer_offsets[b.index() as usize] as u32, rec.len(), rec.width, rec.height]);
                }
                (VarValue::Sampler(s), _) => {
                    let rec = &scene.samplers[s.index() as usize];
                    let offset = sampler_offsets[s.index() as usize] as u32;
                    let mode = sampler_mode(rec);
                    // RtSampler (a cube map's too), or RtSampler3d with its
                    // depth.
                    match rec.shape {
                        SamplerShape::Volume(depth) => heap.extend([offset, rec.width, rec.height, depth, mode]),
                        _ => heap.extend([offset, rec.width, rec.height, mode]),
                    }
                }
                (VarValue::Object(n), _) => heap.push(n.index()),
                (VarValue::Buffer(_), _) => unreachable!("checked by resolve_values"),
            }
        }
    }
    // Sizes come from the programs' descriptors; resolved values have the
    // declared layouts (resolve_values checks), so the records fill exactly
    // the space laid out for them.
    if heap.len() != base {
        return Err(LaunchError::Internal {
            backend: "wgpu",
            problem: format!("internal: the records take {} words where {base} were laid out for them", heap.len()),
        }
        .into());
    }
    heap.extend(data);
    // The bindless buffer table last: never empty, so the heap is not.
    let buffer_table = heap.len() as u32;
    heap.extend(table);
    // The bindless sampler table right after it (`rt_texid` finds it by the
    // buffer table's count).
    heap.push(scene.samplers.len() as u32);
    for (rec, &offset) in scene.samplers.iter().zip(&sampler_offsets) {
        let (depth, shape) = match rec.shape {
            SamplerShape::Flat => (1, SamplerTable::SHAPE_2D),
            SamplerShape::Volume(d) => (d, SamplerTable::SHAPE_3D),
            SamplerShape::Cube => (1, SamplerTable::SHAPE_CUBE),
        };
        let entry = SamplerTable {
            offset: offset as u32,
            width: rec.width,
            height: rec.height,
            depth,
            mode: sampler_mode(rec),
            shape,
        };
        heap.extend(entry.words());
    }
    Ok(EncodedHeap { words: heap, outputs, placed, samplers_placed, buffer_table })
}

/// prelude.wgsl's `RtSampler.mode` of a sampler: wrap, filter and index
/// mode, mip filter and level count, a byte each.
fn sampler_mode(rec: &SamplerRec) -> u32 {
    let modes = rec.modes;
    let wrap = match modes.wrap {
        rt_std::WrapMode::Repeat => 0,
        rt_std::WrapMode::Clamp => 1,
        rt_std::WrapMode::Mirror => 2,
    };
    let filter = match modes.filter {
        rt_std::FilterMode::Nearest => 0,
        rt_std::FilterMode::Linear => 1,
    };
    let array = match modes.index {
        rt_std::IndexMode::NormalizedCoordinates => 0,
        rt_std::IndexMode::ArrayIndex => 1,
    };
    let mip = match modes.mip {
        rt_std::MipFilter::Nearest => 0,
        rt_std::MipFilter::Linear => 1,
    };
    wrap | (filter << 8) | (array << 9) | (mip << 16) | (rec.levels << 24)
}

/// A launch's heap: its words, the `(buffer index, heap offset, words)` of
/// the buffers programs may write, and every buffer's `(heap offset,
/// words)`.
pub(crate) struct EncodedHeap {
    pub(crate) words: Vec<u32>,
    pub(crate) outputs: Vec<(usize, usize, usize)>,
    pub(crate) placed: Vec<(usize, usize)>,
    /// Every sampler's `(heap offset, words)` of texels.
    pub(crate) samplers_placed: Vec<(usize, usize)>,
    /// The heap word of the bindless buffer table ([`BufferTable`]).
    pub(crate) buffer_table: u32,
}

/// The sampler whose texels end first past `max_words` of the heap
/// (`placed`, `samplers_placed` as [`EncodedHeap`] has them), as the error
/// that names it; `None` when none does, or a buffer (before the samplers
/// in the heap) already does: the launch's check of the whole heap says
/// that (the heap fits, or only the records or the tables cross the
/// limit). `limit` says how large one binding may be, and on what device.
pub(crate) fn sampler_past(
    max_words: usize,
    placed: &[(usize, usize)],
    samplers_placed: &[(usize, usize)],
    limit: impl Fn() -> String,
) -> Option<RtError> {
    let problem = |offset: usize, words: usize| {
        format!(
            "its {words} words of texels end at word {} of the launch's heap, but {}; the heap holds every \
             variable, buffer and sampler of the context: make the textures smaller, or fewer",
            offset + words,
            limit()
        )
    };
    if placed.iter().any(|(o, w)| o + w > max_words) {
        return None;
    }
    let (i, &(o, w)) = samplers_placed.iter().enumerate().find(|(_, (o, w))| o + w > max_words)?;
    Some(SceneError::BadSampler { sampler: i as u32, problem: problem(o, w) }.into())
}
