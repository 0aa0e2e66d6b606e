//! Buffers: creating them in one, two or three dimensions, reading and
//! writing their elements, their sizes.

use super::Context;
use crate::backend;
use crate::buffer::{BufferRec, BufferType, Typed};
use crate::error::{Result, SceneError};
use crate::scene::*;
use rt_std::RtData;

impl Context {
    /// A 1D buffer holding `data`.
    pub fn create_buffer<T: RtData + Send + Sync>(&mut self, ty: BufferType, data: Vec<T>) -> BufferId {
        let len = data.len() as u32;
        self.scene.buffers.push(BufferRec::new(Box::new(Typed::new(data)), ty, [len, 1, 1], 1));
        BufferId(self.scene.buffers.len() as u32 - 1)
    }

    /// A 2D buffer of `width` x `height` zeroed elements.
    pub fn create_buffer_2d<T: RtData + Send + Sync>(
        &mut self,
        ty: BufferType,
        width: u32,
        height: u32,
    ) -> Result<BufferId> {
        let n = (width as u64) * (height as u64);
        if n > (u32::MAX as u64) {
            return Err(SceneError::BadBuffer {
                buffer: self.scene.buffers.len() as u32,
                problem: format!("{width}x{height} elements do not fit in 32-bit indices"),
            }
            .into());
        }
        let zero = T::read_words(&vec![0u32; T::LAYOUT.words as usize]);
        self.scene.buffers.push(BufferRec::new(
            Box::new(Typed::new(vec![zero; n as usize])),
            ty,
            [width, height, 1],
            2,
        ));
        Ok(BufferId(self.scene.buffers.len() as u32 - 1))
    }

    /// A 3D buffer (OptiX's `rtBuffer<T, 3>`, programs' `Buffer3d<T>` and
    /// `RwBuffer3d<T>`) of `width` x `height` x `depth` zeroed elements,
    /// stored as `depth` slices of `height` rows: element `(x, y, z)` is
    /// element `x + (y + z * height) * width` of [`read_buffer`](Self::read_buffer)
    /// and [`write_buffer`](Self::write_buffer).
    #[doc(alias = "rtBufferSetSize3D")]
    pub fn create_buffer_3d<T: RtData + Send + Sync>(
        &mut self,
        ty: BufferType,
        width: u32,
        height: u32,
        depth: u32,
    ) -> Result<BufferId> {
        let n = (width as u64) * (height as u64) * (depth as u64);
        if n > (u32::MAX as u64) {
            return Err(SceneError::BadBuffer {
                buffer: self.scene.buffers.len() as u32,
                problem: format!("{width}x{height}x{depth} elements do not fit in 32-bit indices"),
            }
            .into());
        }
        let zero = T::read_words(&vec![0u32; T::LAYOUT.words as usize]);
        let storage = Box::new(Typed::new(vec![zero; n as usize]));
        self.scene.buffers.push(BufferRec::new(storage, ty, [width, height, depth], 3));
        Ok(BufferId(self.scene.buffers.len() as u32 - 1))
    }

    pub(super) fn typed<T: RtData + Send + Sync>(&self, b: BufferId) -> Result<&Typed<T>> {
        let rec = self.scene.buffers.get(b.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{b:?}")))?;
        rec.storage.as_any().downcast_ref::<Typed<T>>().ok_or_else(|| {
            SceneError::BadBuffer {
                buffer: b.0,
                problem: format!("holds `{}`, not `{}`", rec.storage.layout().rust, T::LAYOUT.rust),
            }
            .into()
        })
    }

    /// Reads a buffer's elements back (row-major for 2D buffers). A
    /// device-local buffer ([`Context::set_buffer_device_local`]) that a
    /// wgpu launch wrote is read from the device.
    pub fn read_buffer<T: RtData + Send + Sync>(&self, b: BufferId) -> Result<Vec<T>> {
        backend::futures::block(self.read_buffer_async(b))
    }

    /// [`Context::read_buffer`] for a caller that must not block (a
    /// browser page): a device-local buffer
    /// ([`Context::set_buffer_device_local`]) is read from the device,
    /// awaited; any other buffer is the host's copy, as always.
    pub async fn read_buffer_async<T: RtData + Send + Sync>(&self, b: BufferId) -> Result<Vec<T>> {
        let typed = self.typed::<T>(b)?;
        match self.device_words_async(b).await {
            Some(words) => {
                let w = T::LAYOUT.words as usize;
                Ok(words?.chunks_exact(w).take(typed.len()).map(T::read_words).collect())
            }
            None => Ok(typed.to_vec()),
        }
    }

    /// Overwrites a buffer's elements (same count). Never relinks.
    pub fn write_buffer<T: RtData + Send + Sync>(&mut self, b: BufferId, data: &[T]) -> Result<()> {
        let len = self.typed::<T>(b)?.len();
        if data.len() != len {
            return Err(SceneError::BadBuffer {
                buffer: b.0,
                problem: format!("{} elements written to a buffer of {len}", data.len()),
            }
            .into());
        }
        let rec = &mut self.scene.buffers[b.0 as usize];
        rec.storage.as_any_mut().downcast_mut::<Typed<T>>().expect("checked above").write(data);
        rec.host_version += 1;
        Ok(())
    }

    /// `(width, height)` of a buffer (height 1 for 1D buffers; a 3D
    /// buffer's depth: [`buffer_size_3d`](Self::buffer_size_3d)).
    pub fn buffer_size(&self, b: BufferId) -> Result<(u32, u32)> {
        let rec = self.scene.buffers.get(b.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{b:?}")))?;
        Ok((rec.width, rec.height))
    }

    /// `(width, height, depth)` of a buffer (depth 1 for 1D and 2D
    /// buffers).
    pub fn buffer_size_3d(&self, b: BufferId) -> Result<(u32, u32, u32)> {
        let rec = self.scene.buffers.get(b.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{b:?}")))?;
        Ok((rec.width, rec.height, rec.depth))
    }
}
