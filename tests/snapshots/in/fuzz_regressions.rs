//! Minimized programs from the compiler fuzzer (`rt_tests::fuzz`), one per
//! bug it found, with the compiler fix. Each has the same signature so one
//! test (`tests/fuzz_compiler.rs`, `regressions_agree_on_cpu_and_gpu`) runs
//! them all natively and on the GPU: launch index `i` writes `SLOTS`
//! elements of each output from `i * SLOTS`.
use rt_std::prelude::*;

/// Elements of each output per launch index.
#[rt_const]
pub const SLOTS: u32 = 8;

/// Adds 10 to `state`, returns 1.
#[rt_function]
pub fn fuzz_bump(state: &mut u32) -> u32 {
    *state += 10;
    1
}

/// A later operand whose value needs statements (an `if` or `match` value,
/// a block) had them emitted before the whole expression, so an earlier
/// operand read the state they changed: `x * if .. { x += 1; 2 } ..` read
/// the new `x`. Earlier operands that read mutable state are now evaluated
/// first when a later one needs statements (binary operators, arguments,
/// fields, elements, indices, stored values).
#[rt_program(ray_generation)]
pub fn fuzz_eval_order(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    let mut n = a;
    let product = n * if b > 0 {
        n += 1;
        2
    } else {
        3
    };
    out_u.store(slot, product);
    let mut m = a;
    let sum = m + fuzz_bump(&mut m) + m;
    out_u.store(slot + 1, sum);
    let mut v = Vec2::new(x, 1.0);
    let w = vec2(
        v.x,
        match b & 1 {
            0 => {
                v.x = 5.0;
                v.y
            }
            _ => 2.0,
        },
    );
    out_f.store(slot, w.x + w.y);
    let mut k = a;
    out_u.store(
        slot + 2,
        k.wrapping_add(match b & 3 {
            1 => {
                k = 100;
                1
            }
            _ => 2,
        }),
    );
    out_u.store(slot + 3, n + m + k);
}

/// Rust evaluates an assignment's value before its place: `v[index] = e`
/// read `e` after the statements of `index`, which changed it (found as
/// `v9[if .. { v11[0] %= 3; .. } % 3] = v11[0]`).
#[rt_program(ray_generation)]
pub fn fuzz_assign_order(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    let mut source = [a, a + 1, a + 2];
    let mut dest = [0u32; 3];
    dest[(if b > 0 {
        source[0] = 7;
        1
    } else {
        2
    }) as usize] = source[0];
    out_u.store(slot, dest[0]);
    out_u.store(slot + 1, dest[1]);
    out_u.store(slot + 2, dest[2]);
    out_u.store(slot + 3, source[0]);
    out_f.store(slot, x);
}

/// A `break` in a `match` arm inside a loop left only the WGSL `switch` the
/// `match` became, and the loop went on. It now sets a flag that the code
/// after the `switch` tests (through nested `match`es too).
#[rt_program(ray_generation)]
pub fn fuzz_match_break(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    let mut n = 0u32;
    let mut i = 0u32;
    while i < 10 {
        i += 1;
        match (i + a) % 4 {
            3 => break,
            _ => n += i,
        }
    }
    out_u.store(slot, n);
    out_u.store(slot + 1, i);
    let mut steps = 0;
    for j in 0..8 {
        steps += 1;
        match j & 1 {
            1 => match (j + b) & 3 {
                0 => break,
                1 => steps += 100,
                _ => {}
            },
            _ => continue,
        }
        steps += 10;
    }
    out_u.store(slot + 2, steps as u32);
    out_f.store(slot, x);
}

/// Integer arithmetic on constants only is evaluated by WGSL when the shader
/// is created, where overflow and bits shifted out are errors (Rust wraps at
/// run time): `475240039u32 << 15`, `i32::MAX.wrapping_add(1)`, glam's
/// operators on constant vectors were rejected; `n.is_multiple_of(0)` was
/// too (`n % 0u`, even unselected). Such operands are now bound to `let`s,
/// which WGSL evaluates at run time.
#[rt_program(ray_generation)]
pub fn fuzz_const_ints(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    out_u.store(slot, (475240039u32 << 15) ^ a);
    out_u.store(slot + 1, (i32::MAX.wrapping_add(1) ^ b) as u32);
    let v = IVec2::splat(i32::MAX).wrapping_add(IVec2::ONE).wrapping_mul(IVec2::new(3, b));
    out_u.store(slot + 2, (v.x ^ v.y) as u32);
    out_u.store(slot + 3, UVec3::new(4000000000, 1, 2).element_sum() ^ a);
    out_u.store(slot + 4, a.is_multiple_of(0) as u32 + 7u32.is_multiple_of(0) as u32);
    let w = UVec2::splat(0x8000_0001).wrapping_mul(UVec2::splat(3));
    out_u.store(slot + 5, w.x ^ a);
    out_f.store(slot, x);
}

/// A shift amount WGSL can evaluate at shader creation must be below 32
/// there; Rust masks it (release builds; glam's vector shifts), so an amount
/// computed by a method (`5u32.reverse_bits()`, a `dot`) was rejected. Such
/// amounts are now masked with `& 31u`. And glam's `element_sum` of
/// constants that overflows. (Compiled only: in a debug build these
/// overflow.)
#[rt_program(ray_generation)]
pub fn fuzz_shift_amounts(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    out_u.store(slot, a >> 5u32.reverse_bits());
    let v = IVec2::splat(b) >> UVec2::splat(2278347882).dot(UVec2::splat(8));
    out_u.store(slot + 1, v.x as u32);
    out_u.store(slot + 2, UVec3::new(4000000000, 400000000, 2).element_sum());
    out_f.store(slot, x);
}

/// Invalid WGSL: a vector shifted by an `i32` (`vecN<u32>(i32)` is no
/// conversion), `bool ^=` (WGSL has no `^` on bool).
#[rt_program(ray_generation)]
pub fn fuzz_int_bool_ops(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    let mut v = UVec3::new(a, a + 1, 3) << (b & 7);
    v >>= b & 3;
    out_u.store(slot, v.x ^ v.y ^ v.z);
    let mut flag = a > 3;
    flag ^= b < 0;
    flag ^= true;
    out_u.store(slot + 1, flag as u32);
    out_f.store(slot, x);
}

/// glam's `Vec4` is SIMD wherever SIMD is available (SSE2, NEON, wasm) and
/// its `%` is then `x - floor(x / y) * y`, a floored remainder, unlike
/// `Vec2`/`Vec3` (`f32`'s `%` per component); the compiler used `f32`'s for
/// all three. `lerp` and rt-std's `mix` are `a * (1 - t) + b * t`, exact at
/// both ends, where WGSL's `mix` gave `b` plus an error at `t == 1`
/// (lavapipe computes `a + t * (b - a)`). `step` is rt-std's `x >= edge`
/// selecting 1 or 0: lavapipe folds a constant added to WGSL's `step` at
/// reduced precision (`step(e, x) - 0.001` lost the result's low 8 bits).
#[rt_program(ray_generation)]
pub fn fuzz_float_formulas(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    let r4 = Vec4::new(x, -x, 5.5, -5.5) % 2.0;
    let r3 = Vec3::new(x, -x, -5.5) % 2.0;
    out_f.store(slot, r4.x);
    out_f.store(slot + 1, r4.y);
    out_f.store(slot + 2, r4.w);
    out_f.store(slot + 3, r3.y);
    let t = (b & 1) as f32;
    out_f.store(slot + 4, Vec3::splat(-3.5).lerp(Vec3::splat(0.001), t).x);
    out_f.store(slot + 5, mix(-3.5f32, 0.001, t));
    out_f.store(slot + 6, step(x, -4.0) - 0.001);
    out_f.store(slot + 7, step(Vec2::splat(x), Vec2::new(-4.0, 4.0)).y + 0.1);
    out_u.store(slot, a);
}

/// `IVec2::ZERO.extend(b)` became `vec3<i32>(vec2<i32>(), b)`, which naga
/// translates to SPIR-V that makes lavapipe lose the device; zero vectors
/// are now spelled `vec2<i32>(0i)`. `normalize_or_zero` of a constant zero
/// vector computed `inverseSqrt(0.0)` at shader creation (an error even
/// unselected).
#[rt_program(ray_generation)]
pub fn fuzz_zero_vectors(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    let v = IVec2::ZERO.extend(b);
    out_u.store(slot, (v.x + v.y + v.z) as u32);
    let n = Vec2::new(0.001, 4.0).clamp(Vec2::splat(-0.5), Vec2::splat(0.0)).normalize_or_zero();
    out_f.store(slot, n.x + n.y + x);
    out_u.store(slot + 1, Vec3::default().extend(x).w as u32 + a);
}

/// `v[0] &= v[1]` did not build for the CPU: the place became an
/// `arith::at_mut(&mut v, 0)` borrow while the right side read `v` (the
/// arithmetic compound assignments already took their right side first).
/// Found once the fuzzer printed methods (the first program with such a
/// statement that rustc saw); the bitwise ones now take it first too.
#[rt_program(ray_generation)]
pub fn fuzz_bitwise_compound(
    #[var] a: u32,
    #[var] b: i32,
    #[var] x: f32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_f: RwBuffer<f32>,
) {
    let slot = launch_index().x * SLOTS;
    let mut v = [uvec2(a, 7), uvec2(3, a ^ 5)];
    v[0] &= v[1] | UVec2::splat(b as u32);
    v[1] ^= v[0];
    let mut m = [a, a + 1];
    m[1] |= m[0] << 2;
    out_u.store(slot, v[0].x + v[0].y);
    out_u.store(slot + 1, v[1].x ^ v[1].y);
    out_u.store(slot + 2, m[1]);
    out_f.store(slot, x);
}
