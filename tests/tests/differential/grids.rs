//! Input grids: floats, integers, vectors and matrices the programs run over.

use super::*;

// ---------------------------------------------------------------------------
// Input grids
// ---------------------------------------------------------------------------

/// Floats for binary operators (16, so pairs are 256): signs, zero,
/// fractions, halves, small and large magnitudes whose products and
/// quotients stay finite and normal.
pub(super) const F16: [f32; 16] =
    [0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 2.5, -3.75, 0.1, -0.3, 7.0, 1e-3, -2.5e-4, 12345.678, -98765.43, 3.0e7];

/// Floats for unary functions (64): the above, rounding edges (halves, the
/// floats next to 0.5, values around 2^23 from where every float is an
/// integer), powers of two, wide magnitudes, and random values.
pub(super) fn f64_grid() -> Vec<f32> {
    let mut v = F16.to_vec();
    v.extend([
        1.5,
        -1.5,
        3.5,
        -4.5,
        0.49999997,
        -0.49999997,
        0.50000006,
        8388607.5,
        -8388607.5,
        8388608.0,
        8388609.0,
        -8388609.0,
        16777216.0,
        2.0,
        4.0,
        1024.0,
        0.25,
        -0.125,
        1.0e-20,
        -1.0e-20,
        1.0e20,
        -1.0e20,
        3.4e37,
        -3.4e37,
        0.999,
        -0.999,
        1.001,
        99.5,
        -99.5,
        100.49,
        1e-37,
        123.456,
    ]);
    v.extend(random(16, 7, |b| unit(b, -1000.0, 1000.0)));
    assert_eq!(v.len(), 64);
    v
}

/// `n` floats spread over `[lo, hi]`: both ends, and evenly in between.
pub(super) fn spread(n: usize, lo: f32, hi: f32) -> Vec<f32> {
    (0..n).map(|i| lo + (hi - lo) * i as f32 / (n - 1) as f32).collect()
}

/// `i32`s for binary operators whose results must not overflow (16).
pub(super) const I16: [i32; 16] = [0, 1, -1, 2, -2, 3, -3, 7, -7, 8, -8, 100, -100, 12345, -12345, 46340];

/// `i32` edges and bit patterns (16).
pub(super) const I32_EDGES: [i32; 16] = [
    0,
    1,
    -1,
    i32::MAX,
    i32::MIN,
    i32::MAX - 1,
    i32::MIN + 1,
    0x5555_5555,
    -0x5555_5555,
    1 << 30,
    -(1 << 30),
    (1 << 24) + 1,
    -(1 << 24) - 1,
    65535,
    -65536,
    -7,
];

/// `i32`s over the whole range (64): the above and random values.
pub(super) fn i64_grid() -> Vec<i32> {
    let mut v = I16.to_vec();
    v.extend(I32_EDGES);
    v.extend(random(32, 11, |b| b as i32));
    assert_eq!(v.len(), 64);
    v
}

/// `u32`s for binary operators whose results must not overflow (16).
pub(super) const U16: [u32; 16] = [0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 100, 255, 256, 4096, 12345, 65535];

/// `u32` edges and bit patterns (16).
pub(super) const U32_EDGES: [u32; 16] = [
    0,
    1,
    u32::MAX,
    u32::MAX - 1,
    0x8000_0000,
    0x7fff_ffff,
    0x5555_5555,
    0xaaaa_aaaa,
    0xdead_beef,
    (1 << 24) + 1,
    0xff00_ff00,
    0x00ff_00ff,
    0x1234_5678,
    0x8000_0001,
    3_000_000_000,
    7,
];

/// `u32`s over the whole range (64).
pub(super) fn u64_grid() -> Vec<u32> {
    let mut v = U16.to_vec();
    v.extend(U32_EDGES);
    v.extend(random(32, 13, |b| b));
    assert_eq!(v.len(), 64);
    v
}

/// Shift amounts Rust and WGSL both define: 0 to 31.
pub(super) fn shifts() -> Vec<u32> {
    (0..32).collect()
}

/// `Vec3`s with components in `[-r, r]` (`n` of them, the first few
/// special: zero, axes, a negative zero, halves).
pub(super) fn vec3s(n: usize, r: f32, seed: u32) -> Vec<Vec3> {
    let mut v = vec![Vec3::ZERO, Vec3::X, -Vec3::Y, vec3(-0.0, 0.5, -0.5), vec3(1.5, -2.5, 0.25)];
    let bits = random(3 * n, seed, |b| unit(b, -r, r));
    v.extend(bits.chunks(3).map(|c| vec3(c[0], c[1], c[2])));
    v.truncate(n);
    v
}

/// `Vec3`s with no zero component (divisors).
pub(super) fn vec3s_nonzero(n: usize, seed: u32) -> Vec<Vec3> {
    random(3 * n, seed, |b| {
        let x = unit(b, 0.25, 8.0);
        if b & 1 == 0 { x } else { -x }
    })
    .chunks(3)
    .map(|c| vec3(c[0], c[1], c[2]))
    .collect()
}

/// Unit `Vec3`s.
pub(super) fn units(n: usize, seed: u32) -> Vec<Vec3> {
    vec3s(n + 8, 1.0, seed).into_iter().filter(|v| v.length() > 0.1).map(|v| v.normalize()).take(n).collect()
}

/// `Vec4`s with components in `[-r, r]`.
pub(super) fn vec4s(n: usize, r: f32, seed: u32) -> Vec<Vec4> {
    random(4 * n, seed, |b| unit(b, -r, r)).chunks(4).map(|c| vec4(c[0], c[1], c[2], c[3])).collect()
}

/// `Vec3`s whose components are taken from the unary float grid (rounding
/// edges included).
pub(super) fn vec3s_from_grid() -> Vec<Vec3> {
    let g = f64_grid();
    (0..64).map(|i| vec3(g[i], g[(i + 21) % 64], g[(i + 43) % 64])).collect()
}

/// Integer vectors.
pub(super) fn ivec3s(n: usize, r: i32, seed: u32) -> Vec<IVec3> {
    random(3 * n, seed, |b| (b % (2 * r as u32 + 1)).wrapping_sub(r as u32) as i32)
        .chunks(3)
        .map(|c| ivec3(c[0], c[1], c[2]))
        .collect()
}

pub(super) fn uvec3s(n: usize, r: u32, seed: u32) -> Vec<UVec3> {
    random(3 * n, seed, |b| b % r.saturating_add(1)).chunks(3).map(|c| uvec3(c[0], c[1], c[2])).collect()
}

/// 3x3 and 4x4 matrices with entries in `[-4, 4]`.
pub(super) fn mat3s(n: usize, seed: u32) -> Vec<Mat3> {
    let mut v = vec![Mat3::IDENTITY, Mat3::ZERO, Mat3::from_diagonal(vec3(2.0, -1.0, 0.5))];
    v.extend(random(9 * n, seed, |b| unit(b, -4.0, 4.0)).chunks(9).map(Mat3::from_cols_slice));
    v.truncate(n);
    v
}

pub(super) fn mat4s(n: usize, seed: u32) -> Vec<Mat4> {
    let mut v =
        vec![Mat4::IDENTITY, Mat4::from_translation(vec3(1.0, -2.0, 3.0)), Mat4::from_scale(vec3(2.0, 0.5, -1.0))];
    v.extend(random(16 * n, seed, |b| unit(b, -4.0, 4.0)).chunks(16).map(Mat4::from_cols_slice));
    v.truncate(n);
    v
}
