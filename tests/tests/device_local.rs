//! Device-local buffers (`Context::set_buffer_device_local`, OptiX's
//! `RT_BUFFER_GPU_LOCAL`) and the device's view of a buffer
//! (`Context::wgpu_buffer`, `rtBufferGetDevicePointer`): a wgpu launch
//! leaves what programs write on the device, reads back only its log, and
//! every way of reading or changing the buffer still gives what a context
//! without the flag gives: host reads, host writes (also of the very words
//! the host held before), a heap laid out anew, a switch to the CPU
//! backend and back, launches cut into tiles and a cancelled one.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// Adds `step` to every element of `acc` and writes twice the sum to `out`.
#[rt_program(ray_generation)]
pub fn accumulate(#[var] mut acc: RwBuffer<u32>, #[var] mut out: RwBuffer<u32>, #[var] step: u32) {
    let i = launch_index().x;
    let sum = acc[i] + step;
    acc[i] = sum;
    out[i] = sum * 2;
}

const N: u32 = 1000;

fn start() -> Vec<u32> {
    (0..N).map(|i| i * 7).collect()
}

struct Accumulator {
    ctx: Context,
    acc: BufferId,
    out: BufferId,
}

impl Accumulator {
    fn new(on: On, device_local: bool) -> Accumulator {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let acc = ctx.create_buffer::<u32>(BufferType::InputOutput, start());
        let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; N as usize]);
        ctx.set_buffer_device_local(acc, device_local).unwrap();
        ctx.set_buffer_device_local(out, device_local).unwrap();
        ctx.set_var(Scope::Context, "acc", acc).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&accumulate::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        Accumulator { ctx, acc, out }
    }

    fn step(&mut self, step: u32) -> LaunchReport {
        self.ctx.set_var(Scope::Context, "step", step).unwrap();
        self.ctx.launch_1d(0, N).unwrap()
    }

    /// `acc` and `out` as `read_buffer` gives them, checked against the
    /// start plus `added`.
    fn assert_added(&self, added: u32, what: &str) {
        let acc = self.ctx.read_buffer::<u32>(self.acc).unwrap();
        let out = self.ctx.read_buffer::<u32>(self.out).unwrap();
        let want: Vec<u32> = start().iter().map(|v| v + added).collect();
        let first_wrong = |got: &[u32], want: &[u32]| got.iter().zip(want).position(|(a, b)| a != b);
        if let Some(i) = first_wrong(&acc, &want) {
            panic!("acc[{i}] after {what}: {} where {} was due", acc[i], want[i]);
        }
        let want_out: Vec<u32> = want.iter().map(|v| v * 2).collect();
        if let Some(i) = first_wrong(&out, &want_out) {
            panic!("out[{i}] after {what}: {} where {} was due", out[i], want_out[i]);
        }
    }
}

#[test]
fn device_local_buffers_are_not_read_back_and_read_as_host_buffers_do() {
    let mut plain = Accumulator::new(On::COMPUTE, false);
    plain.step(1);
    let read_back_plain = plain.ctx.last_read_back_bytes();
    assert!(read_back_plain >= 2 * N as u64 * 4, "{read_back_plain}");

    let mut kept = Accumulator::new(On::COMPUTE, true);
    assert!(kept.ctx.buffer_device_local(kept.acc).unwrap());
    kept.step(1);
    kept.step(2);
    // The log's header and the timestamps, not the 8000 bytes of buffers.
    let read_back = kept.ctx.last_read_back_bytes();
    assert!(read_back <= 64, "a launch with device-local outputs read back {read_back} bytes");
    kept.assert_added(3, "two launches");

    // The host writes the words it held before the launches (the device's
    // mirror of them is the same): they still replace the device's.
    kept.ctx.write_buffer(kept.acc, &start()).unwrap();
    assert_eq!(kept.ctx.read_buffer::<u32>(kept.acc).unwrap(), start(), "acc after a host write");
    kept.step(2); // The same step: only the buffer's words changed.
    kept.assert_added(2, "a host write and a launch");

    // A new buffer makes a larger heap: the device-local words move with it.
    let extra = kept.ctx.create_buffer::<u32>(BufferType::Input, vec![9; 3000]);
    kept.ctx.set_var(Scope::Context, "unused", extra).unwrap();
    kept.step(1);
    kept.assert_added(3, "a new heap");

    // On the CPU backend and back: the device's words go to the host first.
    kept.ctx.set_backend(Backend::Cpu);
    kept.step(10);
    kept.assert_added(13, "a CPU launch");
    kept.ctx.set_backend(Backend::Wgpu);
    kept.step(100);
    kept.assert_added(113, "back on wgpu");

    // Tiles of 64 indices: the outputs stay on the device between them and
    // after the last.
    kept.ctx.set_tile_budget(TileBudget::Indices(64));
    let tiled = kept.step(1000);
    assert!(tiled.tiles > 1, "{} tiles", tiled.tiles);
    kept.assert_added(1113, "a launch of several tiles");
    // Cancelled after its first tile: every buffer as it was.
    kept.ctx.set_var(Scope::Context, "step", 5000u32).unwrap();
    let cancelled = kept.ctx.launch_with_progress(0, N, 1, |_| LaunchControl::Cancel);
    assert!(matches!(cancelled, Err(RtError::Launch(LaunchError::LaunchCancelled { .. }))), "{cancelled:?}");
    kept.assert_added(1113, "a cancelled launch");
    kept.step(1);
    kept.assert_added(1114, "a launch after the cancelled one");

    // Turned off: the next launch reads the buffers back again.
    kept.ctx.set_tile_budget(TileBudget::Whole);
    kept.ctx.set_buffer_device_local(kept.acc, false).unwrap();
    kept.ctx.set_buffer_device_local(kept.out, false).unwrap();
    kept.step(3);
    assert!(kept.ctx.last_read_back_bytes() >= 2 * N as u64 * 4);
    kept.assert_added(1117, "turning it off");
}

/// The device's view of a buffer: the words `read_buffer` gives, where
/// `wgpu_buffer` says, read through the context's own device.
#[test]
fn wgpu_buffer_says_where_the_launch_left_a_buffer() {
    let mut kept = Accumulator::new(On::COMPUTE, true);
    let err = kept.ctx.wgpu_buffer(kept.out).unwrap_err().to_string();
    assert!(err.contains("is not on a wgpu device yet: launch on the wgpu backend first"), "{err}");
    assert!(kept.ctx.wgpu_device().is_none());
    kept.step(4);
    let at = kept.ctx.wgpu_buffer(kept.out).unwrap();
    assert_eq!(at.size, N as u64 * 4);
    assert_eq!(at.offset % 4, 0);
    let wgpu = kept.ctx.wgpu_device().expect("the launch opened it");
    assert!(wgpu.adapter.is_some());
    let staging = wgpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: at.size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = wgpu.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(&at.buffer, at.offset, &staging, 0, at.size);
    wgpu.queue.submit([encoder.finish()]);
    staging.slice(..).map_async(wgpu::MapMode::Read, |r| r.unwrap());
    wgpu.device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let words: Vec<u32> = staging
        .slice(..)
        .get_mapped_range()
        .unwrap()
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(words, kept.ctx.read_buffer::<u32>(kept.out).unwrap());
    assert_eq!(words[10], (70 + 4) * 2);
}

/// The CPU backend writes the host's buffers in place: the flag changes
/// nothing there.
#[test]
fn device_local_changes_nothing_on_the_cpu_backend() {
    let mut kept = Accumulator::new(On::CPU, true);
    kept.step(2);
    kept.step(3);
    kept.assert_added(5, "two CPU launches");
}
