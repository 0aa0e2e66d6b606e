//! Residency: the buffers a context keeps on its device between launches,
//! mirrored on the host so a launch uploads only the pages that changed.

use super::encode::{NewScene, ResidentScene};
use super::kernel::SCENE_SECTIONS;
use std::ops::Range;
use wgpu::util::DeviceExt;

/// The buffers a context keeps on its device between launches.
///
/// The heap and the scene are mirrored: the host keeps a copy of the words
/// the device buffer holds, so a launch writes only the 4 KiB pages whose
/// words changed (none, when only the camera moved but one page of records)
/// and allocates a new buffer only when the size changed. After a launch
/// the output buffers' words are read back into both the context and the
/// mirror, so the mirror stays what the device holds. The log is reset by
/// writing its four header words; only the words a launch wrote (output
/// buffers, the log header, then the exceptions and prints it counted) come
/// back.
#[derive(Default)]
pub(crate) struct Resident {
    pub(crate) heap: Option<Mirrored>,
    /// One per scene binding.
    pub(crate) scene: Vec<Option<Mirrored>>,
    pub(crate) log: Option<wgpu::Buffer>,
    /// One 256-byte-aligned launch uniform per dispatch tile.
    pub(crate) uniforms: Option<(wgpu::Buffer, u32)>,
    pub(crate) readback: Option<wgpu::Buffer>,
    /// The scene the `scene` buffers hold, and its records' layout.
    pub(crate) held: Option<ResidentScene>,
    /// Two timestamps (start and end of the launch's compute pass) and the
    /// buffer they resolve to, on devices with timestamp queries.
    pub(crate) timestamps: Option<(wgpu::QuerySet, wgpu::Buffer)>,
    /// Bind groups per tile, over the buffers above (cleared when one of
    /// them is replaced).
    pub(crate) bind_groups: Vec<wgpu::BindGroup>,
    /// The TLAS slots of the layout the bind groups were made for.
    pub(crate) bind_slots: u32,
    /// Bytes written to the device by the last launch (for tests).
    pub(crate) uploaded: u64,
    /// Bytes the last launch read back (outputs, the log, timestamps).
    pub(crate) downloaded: u64,
    /// Device-local buffers the device holds newer than the host, and
    /// where every buffer lies in the heap.
    pub(crate) device_local: DeviceLocal,
}

/// A device storage buffer and the words it holds.
pub(crate) struct Mirrored {
    pub(crate) buffer: wgpu::Buffer,
    pub(crate) words: Vec<u32>,
}

/// Diff granularity of mirrored buffers, in words.
pub(crate) const PAGE_WORDS: usize = 1024;

impl Resident {
    /// Makes `slot`'s device buffer hold `words`, but for the word ranges
    /// `except` (sorted) when it keeps its size; returns true if it had to
    /// be replaced (a new size).
    pub(crate) fn sync(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        slot: &mut Option<Mirrored>,
        (words, except): (Vec<u32>, &[Range<usize>]),
        label: &str,
        uploaded: &mut u64,
    ) -> bool {
        if let Some(m) = slot
            && m.words.len() == words.len()
        {
            write_changed(queue, &m.buffer, (&mut m.words, &words, except), 0, uploaded);
            return false;
        }
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: words_to_bytes(&words),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        });
        *uploaded += (words.len() * 4) as u64;
        *slot = Some(Mirrored { buffer, words });
        true
    }

    /// Makes `slot`'s device buffer hold `head`, then what it holds now from
    /// `head.len()` to `keep_end`, then `tail`: the words in between are
    /// neither compared nor written. Returns true if the buffer had to be
    /// replaced (a new size: then all of it is uploaded).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn sync_around(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        slot: &mut Option<Mirrored>,
        head: &[u32],
        keep_end: usize,
        tail: Vec<u32>,
        label: &str,
        uploaded: &mut u64,
    ) -> bool {
        let Some(m) = slot.as_mut().filter(|m| m.words.len() >= keep_end) else {
            unreachable!("a section kept on the device is mirrored")
        };
        if m.words.len() == keep_end + tail.len() {
            write_changed(queue, &m.buffer, (&mut m.words[..head.len()], head, &[]), 0, uploaded);
            write_changed(queue, &m.buffer, (&mut m.words[keep_end..], &tail, &[]), keep_end, uploaded);
            return false;
        }
        let mut words = std::mem::take(&mut m.words);
        words[..head.len()].copy_from_slice(head);
        words.truncate(keep_end);
        words.extend(tail);
        *slot = None;
        Resident::sync(device, queue, slot, (words, &[]), label, uploaded)
    }
}

/// Writes the pages of `new` that differ from `old` (the device's words
/// from word `at` of `buffer` on, same length) into the buffer, a run of
/// changed pages at a time but for the word ranges `except` (sorted, of
/// `new`: words the device holds newer, see [`super::device_local`]), and
/// copies them into `old`.
pub(crate) fn write_changed(
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
    (old, new, except): (&mut [u32], &[u32], &[Range<usize>]),
    at: usize,
    uploaded: &mut u64,
) {
    let end = |p: usize| (p * PAGE_WORDS).min(new.len());
    let mut page = 0;
    while page * PAGE_WORDS < new.len() {
        let start = page * PAGE_WORDS;
        if old[start..end(page + 1)] == new[start..end(page + 1)] {
            page += 1;
            continue;
        }
        // A run of changed pages: one write.
        let mut last = page + 1;
        while last * PAGE_WORDS < new.len() && old[end(last)..end(last + 1)] != new[end(last)..end(last + 1)] {
            last += 1;
        }
        let run = start..end(last);
        let mut from = run.start;
        for kept in except.iter().filter(|k| k.end > run.start && k.start < run.end) {
            write_words(queue, buffer, at, new, from..kept.start.max(from), uploaded);
            from = kept.end.max(from);
        }
        write_words(queue, buffer, at, new, from..run.end.max(from), uploaded);
        old[run.clone()].copy_from_slice(&new[run]);
        page = last;
    }
}

/// Writes `new[words]` at word `at + words.start` of `buffer` (nothing when
/// empty).
fn write_words(
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
    at: usize,
    new: &[u32],
    words: Range<usize>,
    uploaded: &mut u64,
) {
    if !words.is_empty() {
        queue.write_buffer(buffer, ((at + words.start) * 4) as u64, words_to_bytes(&new[words.clone()]));
        *uploaded += (words.len() * 4) as u64;
    }
}

pub(crate) fn words_to_bytes(w: &[u32]) -> &[u8] {
    // SAFETY: u32 has no padding and any byte pattern is a valid u8.
    unsafe { std::slice::from_raw_parts(w.as_ptr() as *const u8, std::mem::size_of_val(w)) }
}

/// Makes the device hold the launch's `heap` (but for the word ranges
/// `kept`, which it holds newer), its new scene when there is one
/// (`fresh`: the sections and the scene they then hold) and a log of
/// `log_words` with its counters reset. Counts the bytes written in
/// `res.uploaded`; returns true if a buffer was replaced (the bind groups
/// over it are stale).
pub(crate) fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    res: &mut Resident,
    (heap, kept): (Vec<u32>, &[Range<usize>]),
    fresh: Option<(NewScene, ResidentScene)>,
    log_words: u32,
) -> bool {
    res.uploaded = 0;
    let mut replaced = Resident::sync(device, queue, &mut res.heap, (heap, kept), "rt_heap", &mut res.uploaded);
    if let Some((sections, held)) = fresh {
        res.held = None;
        match sections {
            NewScene::Whole(sections) => {
                res.scene.resize_with(sections.len(), || None);
                for (s, words) in sections.into_iter().enumerate() {
                    let label = SCENE_SECTIONS[s].binding;
                    replaced |=
                        Resident::sync(device, queue, &mut res.scene[s], (words, &[]), label, &mut res.uploaded);
                }
            }
            NewScene::AroundGeometry { header, tails } => {
                for (s, tail) in tails.into_iter().enumerate() {
                    let head: &[u32] = if s == 0 { &header } else { &[] };
                    let (end, label) = (held.geometry.ends[s], SCENE_SECTIONS[s].binding);
                    replaced |= Resident::sync_around(
                        device,
                        queue,
                        &mut res.scene[s],
                        head,
                        end,
                        tail,
                        label,
                        &mut res.uploaded,
                    );
                }
            }
        }
        res.held = Some(held);
    }
    if res.log.is_none() {
        res.log = Some(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rt_log"),
            size: log_words as u64 * 4,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
        replaced = true;
    }
    let log = res.log.as_ref().expect("created above");
    // Counters: exceptions, print words, rays, (unused).
    queue.write_buffer(log, 0, words_to_bytes(&[0u32; 4]));
    res.uploaded += 16;
    replaced
}

/// A buffer whose words the device holds newer than the host.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Held {
    pub(crate) buffer: usize,
    /// Word offset in the heap, and length.
    pub(crate) offset: usize,
    pub(crate) words: usize,
    /// The host's version of the buffer when the device took it over.
    pub(crate) version: u64,
}

/// What the device holds of device-local buffers, and where every buffer
/// lies in its heap (the functions are in [`super::device_local`]).
#[derive(Default)]
pub(crate) struct DeviceLocal {
    pub(crate) held: Vec<Held>,
    /// `(word offset, words)` of every buffer in the heap the device holds.
    pub(crate) placed: Vec<(usize, usize)>,
    /// The held words from before the launch running now, and where each
    /// buffer's start in it (bytes), with its place in the new heap.
    pub(crate) saved: Option<wgpu::Buffer>,
    pub(crate) saved_for: Vec<(Held, u64)>,
}
