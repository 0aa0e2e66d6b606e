//! Buffers that stay on the GPU, and the wgpu handles behind them: what an
//! application needs to show a launch's output without a copy through the
//! host (the viewer presents from its device this way), as OptiX's
//! `RT_BUFFER_GPU_LOCAL` buffers and `rtBufferGetDevicePointer` do.

use super::Context;
use crate::backend::Backend;
pub use crate::backend::wgpu::{DeviceBuffer, WgpuDevice};
use crate::backend::wgpu::{Gpu, WgpuBackend};
use crate::error::{Result, SceneError};
use crate::scene::BufferId;
use std::any::Any;

impl Context {
    /// Keeps what programs write to buffer `b` on the device: a wgpu
    /// launch does not read it back to the host, and the next launch
    /// starts from the device's words (default: off, every output is read
    /// back). For images shown from the GPU ([`Context::wgpu_buffer`]) and
    /// for accumulation buffers only the device needs.
    ///
    /// The buffer still reads as it should everywhere:
    /// [`Context::read_buffer`] reads it from the device (one copy, then);
    /// a launch on another backend, or [`Context::use_wgpu_device`], first
    /// brings its words to the host; [`Context::write_buffer`] replaces
    /// them at the next launch. A launch that fails or is cancelled part way
    /// leaves it as it was, as every other buffer. The CPU backend writes
    /// the host's buffers in place, so there the flag changes nothing. A
    /// lost device loses what only it held: the buffer then holds what the
    /// host last had.
    #[doc(alias = "RT_BUFFER_GPU_LOCAL")]
    pub fn set_buffer_device_local(&mut self, b: BufferId, on: bool) -> Result<()> {
        let rec = self
            .scene
            .buffers
            .get_mut(b.index() as usize)
            .ok_or_else(|| SceneError::InvalidHandle(format!("{b:?}")))?;
        // Turning it off needs nothing now: the next launch reads the
        // buffer back, and until then reads come from the device.
        rec.device_local = on;
        Ok(())
    }

    /// Whether [`Context::set_buffer_device_local`] is on for `b`.
    pub fn buffer_device_local(&self, b: BufferId) -> Result<bool> {
        let rec =
            self.scene.buffers.get(b.index() as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{b:?}")))?;
        Ok(rec.device_local)
    }

    /// Where buffer `b` lies on the wgpu device after the last wgpu launch
    /// (OptiX's `rtBufferGetDevicePointer`). Work the application submits
    /// on the same queue after the launch sees what the launch wrote. A
    /// host write ([`Context::write_buffer`]) reaches the device at the
    /// next launch, not before. Fails, naming the buffer, when no wgpu
    /// launch has placed it yet.
    #[doc(alias = "rtBufferGetDevicePointer")]
    pub fn wgpu_buffer(&self, b: BufferId) -> Result<DeviceBuffer> {
        self.scene.buffers.get(b.index() as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{b:?}")))?;
        self.wgpu_backend_ref().and_then(|w| w.placed(b.index() as usize)).ok_or_else(|| {
            SceneError::BadBuffer {
                buffer: b.index(),
                problem: "is not on a wgpu device yet: launch on the wgpu backend first".into(),
            }
            .into()
        })
    }

    /// The wgpu device launches run on, once it is open (after a wgpu
    /// launch, [`Context::open_wgpu`] or [`Context::open_wgpu_for_surface`]).
    pub fn wgpu_device(&self) -> Option<WgpuDevice> {
        self.wgpu_backend_ref().and_then(WgpuBackend::handles)
    }

    /// Opens the runtime's wgpu device (its features and limits, as
    /// [`Context::open_wgpu`]) on an adapter of `instance` that can present
    /// to `surface`, makes wgpu the backend, and returns the device. A
    /// window then shows launches' buffers without a copy through the host
    /// ([`Context::wgpu_buffer`]). `instance` is the one `surface` was made
    /// from ([`crate::backend::wgpu::instance`] makes one as the runtime
    /// does).
    pub fn open_wgpu_for_surface(
        &mut self,
        instance: &wgpu::Instance,
        surface: &wgpu::Surface<'_>,
    ) -> Result<WgpuDevice> {
        let gpu = Gpu::open(instance, Some(surface))?;
        let _ = self.settle_device_buffers(None);
        self.wgpu_backend().use_device(gpu);
        self.run_on(Backend::Wgpu);
        Ok(self.wgpu_device().expect("opened above"))
    }

    /// The device's words of buffer `b` where a backend holds them newer
    /// than the host does, awaiting the device's read-back.
    pub(super) async fn device_words_async(&self, b: BufferId) -> Option<Result<Vec<u32>>> {
        let rec = self.scene.buffers.get(b.index() as usize)?;
        let read = self.wgpu_backend_ref()?.device_words_async(b.index() as usize, rec.host_version)?;
        Some(read.await)
    }

    /// Brings the words of device-local buffers that backends other than
    /// `except` hold newer than the host into the host's buffers (only the
    /// wgpu backend holds any).
    pub(super) fn settle_device_buffers(&mut self, except: Option<Backend>) -> Result<()> {
        let Context { backend, parked, scene, .. } = self;
        for b in std::iter::once(backend).chain(parked.iter_mut()) {
            if Some(b.kind()) != except
                && let Some(wgpu) = (&mut **b as &mut dyn Any).downcast_mut::<WgpuBackend>()
            {
                wgpu.settle(&mut scene.buffers)?;
            }
        }
        Ok(())
    }
}
