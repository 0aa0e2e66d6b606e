//! Bindless ids (OptiX's `rtBufferGetId`, `rtTextureSamplerGetId`):
//! the ids programs read buffers and sample textures through, each checked
//! against the element type or sampler shape it is asked for.

use super::Context;
use crate::error::{Result, SceneError};
use crate::scene::*;
use rt_std::RtData;

impl Context {
    /// The bindless id of buffer `b` (OptiX `rtBufferGetId`): a
    /// [`BindlessBuffer<T>`](rt_std::BindlessBuffer) programs read the
    /// buffer through, set as a variable or stored in a buffer, payload or
    /// struct. Errors if the buffer's elements are not `T`, naming the
    /// buffer and both types. A two-dimensional buffer reads as its
    /// `width * height` elements, row by row.
    #[doc(alias = "rtBufferGetId")]
    pub fn buffer_id<T: RtData>(&self, b: BufferId) -> Result<rt_std::BindlessBuffer<T>> {
        self.check_bindless::<T>(b, false)?;
        Ok(rt_std::BindlessBuffer::from_id(b.bindless_id()))
    }

    /// The writable bindless id of buffer `b`, an
    /// [`RwBindlessBuffer<T>`](rt_std::RwBindlessBuffer): as
    /// [`buffer_id`](Self::buffer_id), and the buffer must be one programs
    /// may write (`Output` or `InputOutput`).
    #[doc(alias = "rtBufferGetId")]
    pub fn rw_buffer_id<T: RtData>(&self, b: BufferId) -> Result<rt_std::RwBindlessBuffer<T>> {
        self.check_bindless::<T>(b, true)?;
        Ok(rt_std::RwBindlessBuffer::from_id(b.bindless_id()))
    }

    /// The bindless id of sampler `s` (OptiX `rtTextureSamplerGetId`): a
    /// [`BindlessSampler<S>`](rt_std::BindlessSampler) programs sample
    /// through, set as a variable or stored in a buffer, payload or struct.
    /// `S` is the sampler's shape, [`Sampler2d`](rt_std::Sampler2d) for
    /// the 2D forms of `create_sampler*`, [`Sampler3d`](rt_std::Sampler3d)
    /// for `create_sampler_3d`, [`SamplerCube`](rt_std::SamplerCube) for
    /// `create_sampler_cube`; errors naming the sampler and both shapes if
    /// it is another. Ids are not bound to the adapter's sampled-texture
    /// slots (samplers live in the heap on every backend), so any number
    /// of samplers may have ids.
    #[doc(alias = "rtTextureSamplerGetId")]
    pub fn sampler_id<S: rt_std::bindless_sampler::SamplerShape>(
        &self,
        s: SamplerId,
    ) -> Result<rt_std::BindlessSampler<S>> {
        let rec =
            self.scene.samplers.get(s.index() as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{s:?}")))?;
        if rec.type_name() != S::NAME {
            return Err(SceneError::BadSampler {
                sampler: s.index(),
                problem: format!(
                    "asked for a bindless id of a `{}`, but the sampler is a `{}` (ask for a `BindlessSampler<{}>`)",
                    S::NAME,
                    rec.type_name(),
                    rec.type_name()
                ),
            }
            .into());
        }
        Ok(rt_std::BindlessSampler::from_id(s.bindless_id()))
    }

    fn check_bindless<T: RtData>(&self, b: BufferId, writable: bool) -> Result<()> {
        let rec =
            self.scene.buffers.get(b.index() as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{b:?}")))?;
        let held = rec.storage.layout().rust;
        if !crate::link::layout_compatible(&rec.storage.layout(), &T::LAYOUT) {
            return Err(SceneError::BadBuffer {
                buffer: b.index(),
                problem: format!(
                    "asked for a bindless id of `{}` elements, but the buffer holds `{held}` ({})",
                    T::LAYOUT.rust,
                    rec.type_name()
                ),
            }
            .into());
        }
        if writable && !rec.ty.writable_by_programs() {
            return Err(SceneError::BadBuffer {
                buffer: b.index(),
                problem: format!(
                    "asked for a writable bindless id, but programs may not write an {:?} buffer ({}); ask `buffer_id` for a read-only one",
                    rec.ty,
                    rec.type_name()
                ),
            }.into());
        }
        Ok(())
    }
}
