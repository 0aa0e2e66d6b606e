//! Read-back: copies of device buffers mapped back to the host, and the
//! launch's log (exceptions and `rt_printf!` records) decoded.

use super::device::Gpu;
use crate::backend::futures::Delivery;
use crate::error::{DeviceError, Result};
use crate::scene::Scene;
use glam::UVec2;
use std::collections::HashMap;

/// Capacity of the exception log (records past it are counted, not kept).
pub(crate) const LOG_EXCEPTIONS: u32 = 4096;

/// Words for `rt_printf!` records.
pub(crate) const LOG_PRINT_WORDS: u32 = 1 << 16;

/// Submits `encoder` with copies of `(buffer, byte offset, bytes)` ranges
/// appended, waits, and returns their words, concatenated. The staging
/// buffer is kept and grown as needed. `lose` destroys the device once the
/// work is submitted (a simulated device loss, for tests). Errors are
/// described for [`Health::failure`].
pub(crate) async fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    staging: &mut Option<wgpu::Buffer>,
    mut encoder: wgpu::CommandEncoder,
    copies: &[(&wgpu::Buffer, u64, u64)],
    lose: bool,
) -> std::result::Result<Vec<u32>, String> {
    let total: u64 = copies.iter().map(|c| c.2).sum();
    if staging.as_ref().is_none_or(|b| b.size() < total) {
        *staging = Some(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rt readback"),
            size: total.max(16).next_power_of_two(),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
    }
    let dst = staging.as_ref().expect("created above");
    let mut at = 0;
    for &(src, offset, bytes) in copies {
        if bytes > 0 {
            encoder.copy_buffer_to_buffer(src, offset, dst, at, bytes);
        }
        at += bytes;
    }
    queue.submit([encoder.finish()]);
    if lose {
        device.destroy();
    }
    if total == 0 {
        return Ok(Vec::new());
    }
    let slice = dst.slice(..total);
    let (mapped, deliver) = Delivery::new();
    slice.map_async(wgpu::MapMode::Read, deliver);
    // Natively the mapping is done once the device is idle; in a browser
    // the page's event loop delivers it, awaited below.
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| format!("waiting for the device: {e}"))?;
    let done = match mapped.take() {
        Some(done) => done,
        None if cfg!(target_arch = "wasm32") => mapped.await,
        None => return Err("reading results back: the device never finished its work".into()),
    };
    if let Err(e) = done {
        return Err(format!("reading results back: {e}"));
    }
    let bytes = slice.get_mapped_range().map_err(|e| format!("reading results back: {e}"))?;
    let words = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    drop(bytes);
    dst.unmap();
    Ok(words)
}

/// Formats `rt_printf!` records with the formats of every program.
pub(crate) fn decode_prints(scene: &Scene, words: &[u32], used: usize) -> Vec<(UVec2, String)> {
    let formats: HashMap<u32, &rt_std::program::PrintfFormat> =
        scene.programs.iter().flat_map(|p| p.desc.printf.iter().map(|f| (f.id, f))).collect();
    let mut out = Vec::new();
    let mut at = 0;
    let used = used.min(words.len());
    while at + 4 <= used {
        let (id, x, y, n) = (words[at], words[at + 1], words[at + 2], words[at + 3] as usize);
        let args = &words[(at + 4).min(used)..(at + 4 + n).min(used)];
        at += 4 + n;
        let Some(fmt) = formats.get(&id) else { continue };
        out.push((UVec2::new(x, y), format_print(fmt, args)));
    }
    out.sort_by_key(|(i, _)| (i.y, i.x));
    out
}

/// Formats like the CPU's `format!`: scalars with `{}`, vectors as glam
/// prints them.
pub(crate) fn format_print(fmt: &rt_std::program::PrintfFormat, words: &[u32]) -> String {
    let mut values = Vec::new();
    let mut w = words.iter().copied();
    for ty in fmt.args {
        let (n, scalar) = match *ty {
            "f32" | "i32" | "u32" | "bool" => (1, *ty),
            t => {
                let n = t[3..4].parse::<usize>().unwrap_or(1);
                (n, &t[5..t.len() - 1])
            }
        };
        let comps: Vec<String> = (0..n)
            .map(|_| {
                let v = w.next().unwrap_or(0);
                match scalar {
                    "f32" => format!("{}", f32::from_bits(v)),
                    "i32" => format!("{}", v as i32),
                    "bool" => format!("{}", v != 0),
                    _ => format!("{v}"),
                }
            })
            .collect();
        values.push(if n == 1 && !ty.starts_with("vec") {
            comps[0].clone()
        } else {
            format!("[{}]", comps.join(", "))
        });
    }
    let mut out = String::new();
    let mut vals = values.into_iter();
    let mut chars = fmt.format.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '{' if chars.peek() == Some(&'{') => {
                chars.next();
                out.push('{');
            }
            '{' if chars.peek() == Some(&'}') => {
                chars.next();
                out.push_str(&vals.next().unwrap_or_default());
            }
            '}' if chars.peek() == Some(&'}') => {
                chars.next();
                out.push('}');
            }
            c => out.push(c),
        }
    }
    out
}

/// What the launch's first read-back gives: the output buffers' words (in
/// the order of the outputs), the log's header (exceptions, print words,
/// rays) and the device's time for the launch, where it has timestamps.
pub(crate) struct Results {
    pub words: Vec<u32>,
    pub header: [u32; 4],
    pub kernel: Option<std::time::Duration>,
    /// The words of each of the `extra` buffers read back whole.
    pub extra: Vec<Vec<u32>>,
}

/// Submits `encoder` with copies of the output buffers (`(buffer index,
/// heap offset, words)`), the log's header and the timestamps, and reads
/// them back, with the `extra` buffers whole (a tail's, `super::tail`);
/// the heap's mirror takes the outputs' new words. A device lost or an
/// error wgpu reported fails the launch.
pub(crate) async fn results(
    gpu: &mut Gpu,
    mut encoder: wgpu::CommandEncoder,
    outputs: &[(usize, usize, usize)],
    extra: &[wgpu::Buffer],
    lose: bool,
) -> Result<Results> {
    let adapter = gpu.describe();
    let Gpu { device, queue, resident: res, health, .. } = gpu;
    let heap_buffer = &res.heap.as_ref().expect("synced above").buffer;
    let log = res.log.as_ref().expect("created by the upload");
    // Read back: the output buffers' words, then the log's header, then
    // the timestamps.
    let mut copies: Vec<(&wgpu::Buffer, u64, u64)> =
        outputs.iter().map(|&(_, offset, n)| (heap_buffer, offset as u64 * 4, n as u64 * 4)).collect();
    copies.push((log, 0, 16));
    if let Some((set, resolved)) = &res.timestamps {
        encoder.resolve_query_set(set, 0..2, resolved, 0);
        copies.push((resolved, 0, 16));
    }
    copies.extend(extra.iter().map(|b| (b, 0, b.size())));
    res.downloaded = copies.iter().map(|c| c.2).sum();
    health.submitted();
    let mut words = read_back(device, queue, &mut res.readback, encoder, &copies, lose)
        .await
        .map_err(|what| health.failure(adapter.clone(), what))?;
    if let Some(errors) = health.take_errors() {
        // wgpu refused part of the launch: its results cannot be trusted.
        return Err(DeviceError::Gpu(format!("the launch on {adapter} failed: {errors}")).into());
    }
    let mut at = 0;
    let heap_mirror = &mut res.heap.as_mut().expect("synced above").words;
    for (_, offset, n) in outputs {
        heap_mirror[*offset..offset + n].copy_from_slice(&words[at..at + n]);
        at += n;
    }
    let header = [words[at], words[at + 1], words[at + 2], words[at + 3]];
    let kernel = res.timestamps.as_ref().map(|_| {
        let t = &words[at + 4..at + 8];
        let (start, end) = (t[0] as u64 | (t[1] as u64) << 32, t[2] as u64 | (t[3] as u64) << 32);
        let ns = end.saturating_sub(start) as f64 * queue.get_timestamp_period() as f64;
        std::time::Duration::from_nanos(ns as u64)
    });
    let mut tail = words.split_off(at + 4 + if res.timestamps.is_some() { 4 } else { 0 });
    let mut extra_words = Vec::new();
    for b in extra.iter().rev() {
        extra_words.push(tail.split_off(tail.len() - (b.size() / 4) as usize));
    }
    extra_words.reverse();
    Ok(Results { words, header, kernel, extra: extra_words })
}

/// The log's exception records and print words, when the launch (its log
/// `header`) counted any: a second, small read.
pub(crate) async fn log(gpu: &mut Gpu, header: [u32; 4]) -> Result<(Vec<u32>, Vec<u32>)> {
    let exceptions = header[0].min(LOG_EXCEPTIONS) as u64;
    let print_used = (header[1] as u64).min(LOG_PRINT_WORDS as u64);
    if exceptions + print_used == 0 {
        return Ok((Vec::new(), Vec::new()));
    }
    let adapter = gpu.describe();
    let Gpu { device, queue, resident: res, health, .. } = gpu;
    let log = res.log.as_ref().expect("created by the upload");
    let encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt log") });
    let print_base = (4 + LOG_EXCEPTIONS * 3) as u64 * 4;
    let mut copies = vec![(log, 16, exceptions * 12)];
    copies.push((log, print_base, print_used * 4));
    res.downloaded += copies.iter().map(|c| c.2).sum::<u64>();
    health.submitted();
    let mut words = read_back(device, queue, &mut res.readback, encoder, &copies, false)
        .await
        .map_err(|what| health.failure(adapter.clone(), what))?;
    let prints = words.split_off(exceptions as usize * 3);
    Ok((words, prints))
}
