//! Work that rides in a launch's last submission: a command list's
//! post-processing stages after its launch ([`crate::command_list`]).
//!
//! A context arms the backend with a [`Tail`] before the launch
//! ([`super::WgpuBackend::arm_tail`]). The launch's last tile records it
//! into the same command encoder as its dispatches, after them, so the
//! launch and the work are one queue submission; the tail reads the
//! launch's outputs where they lie in the heap, and the buffers it takes
//! from there ([`Tail::keeps`]) are not read back: the device holds them,
//! newer than the host, as it holds device-local buffers, and a read of
//! one ([`crate::Context::read_buffer`]) copies it then. What the tail
//! asks to read back comes back with the launch's outputs, in the same
//! read, and the tail itself comes back with it, holding what it left on
//! the device (a temporal denoiser's history). A launch that fails, or
//! is cancelled before its last tile, records no tail and delivers
//! nothing.

use super::DeviceBuffer;
use crate::error::Result;
use crate::scene::Scene;

/// Work recorded after a launch's dispatches, in its last submission.
pub(crate) trait Tail: std::any::Any + Send + Sync {
    /// Whether the tail takes buffer `buffer` (by index) from the device:
    /// the launch leaves it there rather than read it back.
    fn keeps(&self, buffer: usize) -> bool;

    /// Records the work into `encoder`, on `device` (with its serial,
    /// which tells it from a device opened before). `on_device(b)` is where buffer
    /// `b`'s newest words lie in the heap, where the device has them (the
    /// launch wrote it, or holds it), else `None` (the host's words in
    /// `scene` are the newest).
    fn record(
        &mut self,
        device: (&wgpu::Device, u64),
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        on_device: &dyn Fn(usize) -> Option<DeviceBuffer>,
    ) -> Result<Recorded>;
}

/// What a tail recorded.
pub(crate) struct Recorded {
    /// The device buffers to read back whole once the submission ran, in
    /// the order [`super::WgpuBackend::take_tail`] gives their words.
    pub read_back: Vec<wgpu::Buffer>,
    /// How many of the buffers it reads it took from the device.
    pub from_device: u64,
}

/// A tail's state in the backend: armed, then run (after the launch's
/// last tile).
#[derive(Default)]
pub(crate) enum TailState {
    #[default]
    None,
    Armed(Box<dyn Tail>),
    Done(Ran),
}

/// A tail that ran: itself (holding what it left on the device), the
/// words of what it read back, and how many buffers it took from the
/// device.
pub(crate) struct Ran {
    pub tail: Box<dyn Tail>,
    pub words: Vec<Vec<u32>>,
    pub from_device: u64,
}

impl TailState {
    /// The armed tail, taken, where this is the launch's last tile: it
    /// rides in that tile's submission. Before it, the tail stays armed.
    pub(crate) fn take_if_last(&mut self, last_tile: bool) -> Option<Box<dyn Tail>> {
        match std::mem::take(self) {
            TailState::Armed(t) if last_tile => Some(t),
            other => {
                *self = other;
                None
            }
        }
    }
}
