//! Device-local buffers ([`Context::set_buffer_device_local`]): what
//! programs write to them stays on the device across launches and is never
//! read back unless the host asks.
//!
//! The heap's mirror ([`super::device_mirror`]) is what the upload diffs the
//! host's words against. For a buffer the device holds newer ("held"), the
//! mirror keeps the host's older words, the same as the host's copy, so the
//! diff never writes them over the device's. What changes that:
//!
//! - a host write (a new [`BufferRec::host_version`]): the mirror's words
//!   of the buffer are made to differ, so the upload writes the host's,
//!   even where they equal the old ones;
//! - a heap laid out anew (a buffer added, a new size): the held words are
//!   copied on the device from where they were to where they go, after the
//!   upload wrote the host's there;
//! - a launch of several tiles: the held words are copied aside first, and
//!   if a tile fails they come back to the host, which the next launch
//!   uploads whole (a failed launch leaves every buffer as it was).
//!
//! [`Context::set_buffer_device_local`]: crate::Context::set_buffer_device_local

use super::device::Gpu;
use super::device_mirror::{DeviceLocal, Held};
use super::readback::read_back;
use crate::backend::futures;
use crate::buffer::BufferRec;
use crate::error::Result;
use crate::scene::Scene;

/// Where a buffer's elements lie on the wgpu device: `size` bytes from
/// byte `offset` of `buffer` (the heap every buffer of the context shares),
/// as the last wgpu launch left them. Valid until the next launch, which
/// may move the buffer or replace the heap.
#[derive(Clone, Debug)]
pub struct DeviceBuffer {
    /// The context's heap.
    pub buffer: wgpu::Buffer,
    /// A multiple of 4 (one word), not of the adapter's storage-binding
    /// alignment: copy the range (`copy_buffer_to_buffer`) or pass the
    /// offset to a shader that binds the whole buffer.
    pub offset: u64,
    /// The buffer's elements, in bytes.
    pub size: u64,
}

impl DeviceLocal {
    /// Before the first tile's upload of `heap` (every buffer at
    /// `placed`): forgets held buffers the host wrote since (their mirror
    /// words made to differ, so the upload writes them), copies the other
    /// held words aside when they move or the launch has `several_tiles`,
    /// and returns the copies [`DeviceLocal::after_upload`] puts in place.
    pub(crate) fn before_upload(
        gpu: &mut Gpu,
        scene: &Scene,
        placed: Vec<(usize, usize)>,
        heap: &[u32],
        several_tiles: bool,
    ) -> Vec<(u64, usize, usize)> {
        let Gpu { device, queue, resident, health, .. } = gpu;
        let this = &mut resident.device_local;
        this.saved_for.clear();
        let mirror = resident.heap.as_mut().filter(|m| m.words.len() == heap.len());
        let replaced = mirror.is_none();
        let mut mirror = mirror;
        let mut kept = Vec::new();
        for h in this.held.drain(..) {
            let (offset, words) = placed[h.buffer];
            if scene.buffers[h.buffer].host_version != h.version {
                if let Some(m) = mirror.as_mut() {
                    for (old, new) in m.words[offset..offset + words].iter_mut().zip(&heap[offset..offset + words]) {
                        *old = !*new;
                    }
                }
                continue;
            }
            kept.push((h, offset));
        }
        let moves = replaced || kept.iter().any(|(h, offset)| h.offset != *offset);
        this.placed = placed;
        if kept.is_empty() || !(moves || several_tiles) {
            this.held = kept.into_iter().map(|(h, _)| h).collect();
            return Vec::new();
        }
        let total: u64 = kept.iter().map(|(h, _)| h.words as u64 * 4).sum();
        if this.saved.as_ref().is_none_or(|b| b.size() < total) {
            this.saved = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("rt device-local words"),
                size: total.next_power_of_two().max(16),
                usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }));
        }
        let saved = this.saved.as_ref().expect("made above");
        let heap_buffer = &resident.heap.as_ref().expect("held words live in a heap").buffer;
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt save") });
        let mut at = 0;
        let mut copies = Vec::new();
        for (h, offset) in kept {
            encoder.copy_buffer_to_buffer(heap_buffer, h.offset as u64 * 4, saved, at, h.words as u64 * 4);
            let moved = Held { offset, ..h };
            if replaced || h.offset != offset {
                copies.push((at, offset, h.words));
            }
            this.saved_for.push((moved, at));
            this.held.push(moved);
            at += h.words as u64 * 4;
        }
        // Submitted now, before the upload's writes: those reach the
        // device ahead of the next submission's commands.
        queue.submit([encoder.finish()]);
        health.submitted();
        copies
    }

    /// The heap's word ranges the device holds newer, sorted: the upload
    /// leaves them alone.
    pub(crate) fn held_ranges(&self) -> Vec<std::ops::Range<usize>> {
        let mut ranges: Vec<_> = self.held.iter().map(|h| h.offset..h.offset + h.words).collect();
        ranges.sort_by_key(|r| r.start);
        ranges
    }

    /// After the upload: the held words that moved, from where
    /// [`DeviceLocal::before_upload`] put them aside to their new place.
    pub(crate) fn after_upload(gpu: &mut Gpu, copies: &[(u64, usize, usize)]) {
        if copies.is_empty() {
            return;
        }
        let Gpu { device, queue, resident, health, .. } = gpu;
        let saved = resident.device_local.saved.as_ref().expect("saved before the upload");
        let heap = &resident.heap.as_ref().expect("uploaded").buffer;
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt move") });
        for &(at, offset, words) in copies {
            encoder.copy_buffer_to_buffer(saved, at, heap, offset as u64 * 4, words as u64 * 4);
        }
        queue.submit([encoder.finish()]);
        health.submitted();
    }

    /// After a launch's last tile ran: the `outputs` (`(buffer, word
    /// offset, words)`) that were `kept` on the device (device-local ones,
    /// those a tail took there) are held, the others were read back.
    pub(crate) fn after_launch(
        &mut self,
        scene: &Scene,
        outputs: &[(usize, usize, usize)],
        kept: &dyn Fn(usize) -> bool,
    ) {
        self.saved_for.clear();
        for &(buffer, offset, words) in outputs {
            self.held.retain(|h| h.buffer != buffer);
            let rec = &scene.buffers[buffer];
            if kept(buffer) {
                self.held.push(Held { buffer, offset, words, version: rec.host_version });
            }
        }
    }

    /// After a launch of several tiles failed: the held buffers' words from
    /// before it go to the host (whose copy the next launch uploads whole),
    /// and nothing is held.
    pub(crate) fn restore(gpu: &mut Gpu, buffers: &mut [BufferRec]) {
        let Gpu { device, queue, resident, health, .. } = gpu;
        let this = &mut resident.device_local;
        this.held.clear();
        let saved_for = std::mem::take(&mut this.saved_for);
        let Some(saved) = this.saved.as_ref().filter(|_| !saved_for.is_empty()) else { return };
        let encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt restore") });
        let copies: Vec<_> = saved_for.iter().map(|(h, at)| (saved, *at, h.words as u64 * 4)).collect();
        // A device that cannot even give these back is lost: the host's
        // copies are what is left.
        health.submitted();
        let read = futures::now(read_back(device, queue, &mut None, encoder, &copies, false));
        if let Some(Ok(words)) = read {
            let mut at = 0;
            for (h, _) in &saved_for {
                buffers[h.buffer].storage.read_words(&words[at..at + h.words]);
                at += h.words;
            }
        }
    }

    /// The held buffers' words to the host; nothing is held after.
    pub(crate) fn settle(gpu: &mut Gpu, buffers: &mut [BufferRec]) -> Result<()> {
        let held = std::mem::take(&mut gpu.resident.device_local.held);
        if held.is_empty() {
            return Ok(());
        }
        let words = read_held(gpu, &held)?;
        let mut at = 0;
        for h in &held {
            buffers[h.buffer].storage.read_words(&words[at..at + h.words]);
            at += h.words;
        }
        Ok(())
    }

    /// The device's words of `buffer`, if it holds them newer than the
    /// host's copy at `host_version`.
    pub(crate) fn words(
        gpu: &Gpu,
        buffer: usize,
        host_version: u64,
    ) -> Option<futures::LocalBoxFuture<'_, Result<Vec<u32>>>> {
        let h = *gpu.resident.device_local.held.iter().find(|h| h.buffer == buffer && h.version == host_version)?;
        Some(Box::pin(async move { read_held_async(gpu, &[h]).await }))
    }

    /// Where the device's words of `buffer` lie in its heap, if it holds
    /// them newer than the host's copy at `host_version` (what
    /// [`DeviceLocal::words`] would read back).
    pub(crate) fn held(gpu: &Gpu, buffer: usize, host_version: u64) -> Option<DeviceBuffer> {
        let h = gpu.resident.device_local.held.iter().find(|h| h.buffer == buffer && h.version == host_version)?;
        let heap = gpu.resident.heap.as_ref()?;
        Some(DeviceBuffer { buffer: heap.buffer.clone(), offset: h.offset as u64 * 4, size: h.words as u64 * 4 })
    }

    /// Where `buffer` lies in the device's heap.
    pub(crate) fn placed(gpu: &Gpu, buffer: usize) -> Option<DeviceBuffer> {
        let heap = gpu.resident.heap.as_ref()?;
        let &(offset, words) = gpu.resident.device_local.placed.get(buffer)?;
        Some(DeviceBuffer { buffer: heap.buffer.clone(), offset: offset as u64 * 4, size: words as u64 * 4 })
    }
}

/// The heap words of `held`, concatenated, read with a staging buffer of
/// their own (the host may ask through `&Context`).
fn read_held(gpu: &Gpu, held: &[Held]) -> Result<Vec<u32>> {
    futures::block(read_held_async(gpu, held))
}

/// [`read_held`], awaiting the read-back.
async fn read_held_async(gpu: &Gpu, held: &[Held]) -> Result<Vec<u32>> {
    let heap = &gpu.resident.heap.as_ref().expect("held words live in a heap").buffer;
    let encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt read held") });
    let copies: Vec<_> = held.iter().map(|h| (heap, h.offset as u64 * 4, h.words as u64 * 4)).collect();
    gpu.health.submitted();
    read_back(&gpu.device, &gpu.queue, &mut None, encoder, &copies, false)
        .await
        .map_err(|what| gpu.health.failure(gpu.describe(), format!("reading a device-local buffer: {what}")))
}
