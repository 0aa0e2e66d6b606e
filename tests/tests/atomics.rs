//! Atomic updates of buffer elements (`RwBuffer<u32 | i32 | f32>::atomic_*`)
//! on every target, with exact results: 4096 launch indices contend for a
//! few elements, and what they leave (and the old values they got back)
//! is known whatever order they ran in.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

const N: u32 = 4096;
const BINS: u32 = 7;

/// A scramble of `i`, so that minima and maxima are not at the ends.
#[rt_function]
pub fn scramble(i: u32) -> u32 {
    let mut x = i * 2654435761u32;
    x ^= x >> 15;
    x * 2246822519u32
}

/// Counts `i` in its bin; the old count comes back (a helper, so the
/// kernel sees atomics through it).
#[rt_function]
pub fn count(bins: RwBuffer<u32>, i: u32) -> u32 {
    bins.atomic_add(i % 7, 1)
}

#[allow(clippy::too_many_arguments)]
#[rt_program(ray_generation)]
pub fn contend(
    #[var] bins: RwBuffer<u32>,
    #[var] mut olds: RwBuffer<u32>,
    #[var] words: RwBuffer<u32>,
    #[var] signed: RwBuffer<i32>,
    #[var] floats: RwBuffer<f32>,
    #[var] grid: RwBuffer2d<u32>,
    #[var] mut claimed: RwBuffer<u32>,
    #[var] step: u32,
) {
    let i = launch_index().x;
    olds[i] = count(bins, i);
    let s = scramble(i);
    words.atomic_min(0, s);
    words.atomic_max(1, s);
    words.atomic_or(2, 1u32 << (i % 32));
    words.atomic_and(3, !(1u32 << (i % 29)));
    words.atomic_xor(4, i);
    words.atomic_sub(5, step);
    // Who claims slot 6 first (a strong compare-exchange: exactly one).
    if words.atomic_compare_exchange(6, 0xffffffffu32, i) == 0xffffffffu32 {
        claimed.atomic_add(0, 1);
        claimed.store(1, i);
    }
    // A chain of exchanges: every index's value is left or handed back once.
    claimed[2 + i] = words.atomic_exchange(7, i + 1);
    let v = (s % 2001) as i32 - 1000;
    signed.atomic_min(0, v);
    signed.atomic_max(1, v);
    signed.atomic_add(2, v);
    signed.atomic_sub(3, v);
    floats.atomic_add(0, 0.5);
    floats.atomic_min(1, v as f32 * 0.25);
    floats.atomic_max(2, v as f32 * 0.25);
    // Bits, not values: 0.0 matches only 0.0, so -0.0 never exchanges.
    floats.atomic_compare_exchange(3, -0.0, 1.0);
    floats.atomic_compare_exchange(4, 0.0, 2.0);
    grid.atomic_add(uvec2(i % 3, (i / 3) % 2), 1);
    // Out of bounds: the exception, nothing changed, zero back.
    if i == 5 {
        claimed[4098] = bins.atomic_add(1000, 1) + 77;
    }
}

#[derive(Debug, PartialEq)]
struct Outcome {
    bins: Vec<u32>,
    /// Per bin, the old counts it handed out, sorted.
    olds: Vec<Vec<u32>>,
    words: Vec<u32>,
    signed: Vec<i32>,
    floats: Vec<u32>,
    grid: Vec<u32>,
    claims: u32,
    winner_is_slot: bool,
    /// The exchanged values and the last, sorted.
    chain: Vec<u32>,
    out_of_bounds: u32,
    exceptions: Vec<u32>,
}

fn run(on: On) -> Outcome {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let bins = ctx.create_buffer::<u32>(BufferType::InputOutput, vec![0; BINS as usize]);
    let olds = ctx.create_buffer::<u32>(BufferType::Output, vec![0; N as usize]);
    let words = ctx.create_buffer::<u32>(BufferType::InputOutput, vec![u32::MAX, 0, 0, u32::MAX, 0, 10, u32::MAX, 0]);
    let signed = ctx.create_buffer::<i32>(BufferType::InputOutput, vec![i32::MAX, i32::MIN, 0, 0]);
    let floats = ctx.create_buffer::<f32>(BufferType::InputOutput, vec![0.0, f32::MAX, f32::MIN, 0.0, 0.0]);
    let grid = ctx.create_buffer_2d::<u32>(BufferType::InputOutput, 3, 2).unwrap();
    let claimed = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 2 + N as usize + 1]);
    for (name, b) in [("bins", bins), ("olds", olds), ("words", words), ("signed", signed)] {
        ctx.set_var(Scope::Context, name, b).unwrap();
    }
    for (name, b) in [("floats", floats), ("grid", grid), ("claimed", claimed)] {
        ctx.set_var(Scope::Context, name, b).unwrap();
    }
    ctx.set_var(Scope::Context, "step", 3u32).unwrap();
    let rg = ctx.create_program(&contend::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, N).unwrap();
    let bins_after = ctx.read_buffer::<u32>(bins).unwrap();
    let olds_after = ctx.read_buffer::<u32>(olds).unwrap();
    let mut per_bin = vec![Vec::new(); BINS as usize];
    for (i, o) in olds_after.iter().enumerate() {
        per_bin[i % BINS as usize].push(*o);
    }
    for b in &mut per_bin {
        b.sort();
    }
    let words_after = ctx.read_buffer::<u32>(words).unwrap();
    let claimed_after = ctx.read_buffer::<u32>(claimed).unwrap();
    let mut chain: Vec<u32> = claimed_after[2..2 + N as usize].to_vec();
    chain.push(words_after[7]);
    chain.sort();
    Outcome {
        bins: bins_after,
        olds: per_bin,
        winner_is_slot: claimed_after[1] == words_after[6],
        words: words_after,
        signed: ctx.read_buffer::<i32>(signed).unwrap(),
        floats: ctx.read_buffer::<f32>(floats).unwrap().iter().map(|f| f.to_bits()).collect(),
        grid: ctx.read_buffer::<u32>(grid).unwrap(),
        claims: claimed_after[0],
        chain,
        out_of_bounds: claimed_after[1 + N as usize + 1],
        exceptions: report.exceptions.iter().map(|e| e.code).collect(),
    }
}

/// What every target must leave, computed here in plain Rust.
fn expected() -> Outcome {
    let scramble = |i: u32| {
        let mut x = i.wrapping_mul(2654435761);
        x ^= x >> 15;
        x.wrapping_mul(2246822519)
    };
    let counts: Vec<u32> = (0..BINS).map(|b| (0..N).filter(|i| i % BINS == b).count() as u32).collect();
    let values: Vec<i32> = (0..N).map(|i| (scramble(i) % 2001) as i32 - 1000).collect();
    let sum = values.iter().fold(0i32, |a, v| a.wrapping_add(*v));
    let mut grid = vec![0u32; 6];
    for i in 0..N {
        grid[((i / 3) % 2 * 3 + i % 3) as usize] += 1;
    }
    Outcome {
        olds: counts.iter().map(|&c| (0..c).collect()).collect(),
        bins: counts,
        words: vec![
            (0..N).map(scramble).min().unwrap(),
            (0..N).map(scramble).max().unwrap(),
            u32::MAX,
            !((1u32 << 29) - 1),
            (0..N).fold(0, |a, i| a ^ i),
            10u32.wrapping_sub(3 * N),
            // The winner's index: checked through winner_is_slot.
            0,
            0,
        ],
        signed: vec![*values.iter().min().unwrap(), *values.iter().max().unwrap(), sum, 0i32.wrapping_sub(sum)],
        floats: [
            N as f32 * 0.5,
            *values.iter().min().unwrap() as f32 * 0.25,
            *values.iter().max().unwrap() as f32 * 0.25,
            0.0,
            2.0,
        ]
        .iter()
        .map(|f| f.to_bits())
        .collect(),
        grid,
        claims: 1,
        winner_is_slot: true,
        chain: (0..=N).collect(),
        out_of_bounds: 77,
        exceptions: vec![EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS],
    }
}

#[test]
fn contended_atomic_updates_are_exact_on_every_target() {
    let want = expected();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut got = run(on);
        // Which index won the claim depends on the order; that it is the
        // one in the slot does not.
        assert!(got.words[6] < N, "{}: slot 6 holds {}", on.name(), got.words[6]);
        got.words[6] = 0;
        got.words[7] = 0;
        assert_eq!(got, want, "{}", on.name());
    }
}

/// A closest hit that counts its hits per primitive: atomics in a program
/// the kernel reaches through a trace; a second entry point reads the
/// counts with plain loads.
#[rt_payload]
pub struct Tally {
    pub hit: u32,
}

#[rt_program(ray_generation)]
pub fn shoot(#[var] top: Object) {
    let i = launch_index();
    let d = launch_dim();
    let uv = (vec2(i.x as f32, i.y as f32) + 0.5) / vec2(d.x as f32, d.y as f32) * 2.0 - 1.0;
    let mut prd = Tally { hit: 0 };
    rt_trace(top, Ray::new(vec3(uv.x * 1.5, uv.y * 1.5, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0), &mut prd);
}

#[rt_program(closest_hit)]
pub fn tally(prd: &mut Tally, #[var] per_primitive: RwBuffer<u32>) {
    prd.hit = 1;
    per_primitive.atomic_add(primitive_index(), 1);
}

#[rt_program(miss)]
pub fn tally_miss(prd: &mut Tally) {
    prd.hit = 0;
}

#[rt_program(ray_generation)]
pub fn total(#[var] per_primitive: RwBuffer<u32>, #[var] mut sum: RwBuffer<u32>) {
    sum[0] = per_primitive[0] + per_primitive[1];
}

#[test]
fn closest_hits_count_their_primitives_atomically_on_every_target() {
    let mut counts = Vec::new();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(1);
        ctx.set_entry_point_count(2);
        let g = ctx.create_triangles(rt_tests::meshes::unit_quad()).unwrap();
        let m = ctx.create_material();
        let ch = ctx.create_program(&tally::PROGRAM);
        ctx.set_closest_hit_program(m, 0, ch).unwrap();
        let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
        let top = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
        ctx.set_var(Scope::Context, "top", top).unwrap();
        let per = ctx.create_buffer::<u32>(BufferType::InputOutput, vec![0; 2]);
        ctx.set_var(Scope::Context, "per_primitive", per).unwrap();
        let sum = ctx.create_buffer::<u32>(BufferType::Output, vec![0]);
        ctx.set_var(Scope::Context, "sum", sum).unwrap();
        let rg = ctx.create_program(&shoot::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let rg2 = ctx.create_program(&total::PROGRAM);
        ctx.set_ray_generation_program(1, rg2).unwrap();
        let miss = ctx.create_program(&tally_miss::PROGRAM);
        ctx.set_miss_program(0, miss).unwrap();
        ctx.launch(0, 64, 48).unwrap();
        ctx.launch_1d(1, 1).unwrap();
        let per_after = ctx.read_buffer::<u32>(per).unwrap();
        assert_eq!(ctx.read_buffer::<u32>(sum).unwrap()[0], per_after[0] + per_after[1], "{}", on.name());
        counts.push((on.name(), per_after));
    }
    // The quad covers the middle 2/3 of the launch in each axis; the
    // diagonal splits it into two primitives of equal area. Every target
    // counts the same rays.
    let total: u32 = counts[0].1.iter().sum();
    // Pixel centres with |uv| <= 2/3: columns 11..=52 and rows 8..=39.
    assert_eq!(total, 42 * 32);
    for (name, c) in &counts {
        assert_eq!(c, &counts[0].1, "{name} against {}", counts[0].0);
    }
}
