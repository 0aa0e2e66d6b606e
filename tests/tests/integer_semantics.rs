//! One integer semantics on both backends (`rt_std::arith`): overflow wraps,
//! division and remainder by zero, `MIN / -1`, shifts by 32 or more, float
//! to integer casts of NaN and out-of-range values, and out-of-range local
//! indices give the same values on the CPU (debug and release builds) and
//! on wgpu, with no panic and no exception.

use rt_runtime::*;
use rt_std::prelude::*;

#[rt_function]
fn bump(x: &mut u32, by: u32) {
    *x += by;
    *x *= by;
}

#[rt_program(ray_generation)]
#[allow(clippy::too_many_arguments, clippy::cast_abs_to_unsigned)]
pub fn edge_cases(
    #[var] mut out: RwBuffer<u32>,
    #[var] a: u32,
    #[var] zero: u32,
    #[var] min: i32,
    #[var] minus_one: i32,
    #[var] k: u32,
    #[var] nan: f32,
    #[var] negative: f32,
    #[var] big: f32,
) {
    let arr = [1u32, 2, 3, 4];
    let mut local = [10i32, 20, 30];
    out[0] = a * a;
    out[1] = a / zero;
    out[2] = a % zero;
    out[3] = (min / minus_one) as u32;
    out[4] = (min % minus_one) as u32;
    out[5] = a << k;
    out[6] = a >> k;
    out[7] = (min >> k) as u32;
    out[8] = nan as u32;
    out[9] = nan as i32 as u32;
    out[10] = negative as u32;
    out[11] = big as i32 as u32;
    out[12] = arr[(k - 29) as usize];
    out[13] = (min / (minus_one + 1)) as u32;
    out[14] = (min % (minus_one + 1)) as u32;
    out[15] = (-min) as u32;
    out[16] = min.abs() as u32;
    out[17] = zero - a;
    out[18] = (min * min) as u32;
    out[19] = big as u32;
    out[20] = (7i32 / (minus_one + 1)) as u32;
    out[21] = ((-7i32) % (minus_one + 1)) as u32;
    out[22] = (min << k) as u32;
    local[k as usize] += min;
    out[23] = local[2] as u32;
    let mut h = a;
    h += a;
    h *= 2654435761u32;
    h -= a * 3;
    h <<= k;
    bump(&mut h, a);
    out[24] = h;
    out[25] = a.clamp(k, zero);
    let v = uvec3(a, a, 7) * 5u32 / uvec3(zero, 2, zero);
    out[26] = v.x;
    out[27] = v.y;
    out[28] = v.z;
    out[29] = (min - 1) as u32;
    // glam's sums and products of integer vectors, and path forms.
    let big = IVec3::splat(min - 1);
    out[30] = big.element_sum() as u32;
    out[31] = big.element_product() as u32;
    out[32] = big.dot(IVec3::splat(2)) as u32;
    out[33] = big.length_squared() as u32;
    out[34] = IVec3::dot(big, big) as u32;
    out[35] = i32::abs(min) as u32;
    out[36] = uvec3(a, a, a).element_sum();
    out[37] = UVec3::cross(uvec3(0, 1, 0), uvec3(1, 0, 0)).z;
    out[38] = ivec2(min - 1, 2).perp_dot(ivec2(3, 1)) as u32;
    out[39] = big.manhattan_distance(IVec3::splat(min));
    out[40] = IVec2::splat(min - 1).rotate(ivec2(2, 0)).x as u32;
    out[41] = ivec2(a as i32, 0).distance_squared(ivec2(0, a as i32)) as u32;
    out[42] = i32::clamp(5, k as i32, 0) as u32;
    out[43] = big.dot_into_vec(IVec3::ONE).y as u32;
    // glam's in-place methods past the end: the last row or component.
    let mut m = Mat3::IDENTITY;
    m.set_row(k as usize, vec3(4.0, 5.0, 6.0));
    out[44] = (m.x_axis.z + 10.0 * m.y_axis.z + 100.0 * m.z_axis.z + 1000.0 * m.x_axis.x) as u32;
    let mut mask = BVec3::splat(false);
    mask.set(k as usize, true);
    out[45] = mask.bitmask();
    out[46] = mask.test(k as usize) as u32 + 2 * mask.test(0) as u32;
    *m.col_mut(k as usize) = vec3(7.0, 8.0, 9.0);
    m.col_mut(k as usize).x += 1.0;
    out[47] = (m.z_axis.x + 10.0 * m.z_axis.y + 100.0 * m.z_axis.z) as u32;
    // std's integer methods where std panics.
    out[48] = (min + 3).pow(k) as u32;
    out[49] = a.wrapping_rem(zero) + (min.wrapping_div_euclid(zero as i32) as u32);
    out[50] = zero.ilog2() + (min.ilog10() << 8) + (a.ilog(1) << 16) + ((min.isqrt() as u32) << 24);
    out[51] = a.div_ceil(zero);
    out[52] = a.next_multiple_of(zero);
    out[53] = (a | 0x8000_0000).next_power_of_two() + 2 * u32::pow(a, 2);
    let (q, over) = min.overflowing_div(zero as i32);
    let (r, over_r) = a.overflowing_rem_euclid(zero);
    out[54] = q as u32 + r + over as u32 + 2 * over_r as u32;
    // glam's minors past the last row and column: the last ones left out.
    let big =
        Mat4::from_cols_array(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0, 16.0]);
    let minor = Mat3::from_mat4_minor(big, k as usize, 9);
    let small = Mat2::from_mat3_minor(minor, 0, k as usize);
    out[55] = (minor.z_axis.z + 100.0 * small.x_axis.y + 10000.0 * small.y_axis.y) as u32;
}

/// `(index, value, what)`: the defined results.
fn expected() -> Vec<(usize, u32, &'static str)> {
    let a = 0x9e37_79b9u32;
    let mut h = a.wrapping_add(a).wrapping_mul(2654435761).wrapping_sub(a.wrapping_mul(3)) << 1;
    h = h.wrapping_add(a).wrapping_mul(a);
    vec![
        (0, a.wrapping_mul(a), "a * a wraps"),
        (1, a, "a / 0 is a"),
        (2, 0, "a % 0 is 0"),
        (3, i32::MIN as u32, "MIN / -1 is MIN"),
        (4, 0, "MIN % -1 is 0"),
        (5, a << 1, "a << 33 is a << 1"),
        (6, a >> 1, "a >> 33 is a >> 1"),
        (7, (i32::MIN >> 1) as u32, "MIN >> 33 is arithmetic, by 1"),
        (8, 0, "NaN as u32 is 0"),
        (9, 0, "NaN as i32 is 0"),
        (10, 0, "-5.0 as u32 saturates to 0"),
        (11, i32::MAX as u32, "3e9 as i32 saturates"),
        (12, 4, "arr[4] of a 4-element local array reads the last element"),
        (13, i32::MIN as u32, "MIN / 0 is MIN"),
        (14, 0, "MIN % 0 is 0"),
        (15, i32::MIN as u32, "-MIN wraps to MIN"),
        (16, i32::MIN as u32, "MIN.abs() is MIN"),
        (17, 0u32.wrapping_sub(a), "0 - a wraps"),
        (18, 0, "MIN * MIN wraps to 0"),
        (19, 3_000_000_000, "3e9 as u32"),
        (20, 7, "7 / 0 is 7"),
        (21, 0, "-7 % 0 is 0"),
        (22, 0, "MIN << 33 is MIN << 1, 0"),
        (23, 30i32.wrapping_add(i32::MIN) as u32, "local[33] += MIN writes the last element"),
        (24, h, "compound assignments wrap, also through &mut in a helper"),
        (25, 0, "a.clamp(33, 0) is min(max(a, 33), 0)"),
        (26, a.wrapping_mul(5), "vector / 0 per component is the dividend"),
        (27, a.wrapping_mul(5) / 2, "vector division"),
        (28, 35, "7 * 5 / 0"),
        (29, i32::MAX as u32, "MIN - 1 wraps to MAX"),
        (30, i32::MAX.wrapping_mul(3) as u32, "IVec3::splat(MAX).element_sum() wraps"),
        (31, i32::MAX as u32, "element_product: MAX^3 wraps to MAX"),
        (32, i32::MAX.wrapping_mul(6) as u32, "dot wraps"),
        (33, 3, "length_squared: 3 MAX^2 wraps to 3"),
        (34, 3, "IVec3::dot(big, big), the path form"),
        (35, i32::MIN as u32, "i32::abs(MIN), the path form, is MIN"),
        (36, a.wrapping_mul(3), "uvec3 element_sum wraps"),
        (37, u32::MAX, "UVec3::cross(Y, X).z is 0 - 1"),
        (38, i32::MAX.wrapping_sub(6) as u32, "perp_dot wraps"),
        (39, u32::MAX.wrapping_mul(3), "manhattan_distance wraps"),
        (40, -2i32 as u32, "IVec2 rotate wraps"),
        (41, a.wrapping_mul(a).wrapping_mul(2), "distance_squared wraps"),
        (42, 0, "i32::clamp(5, 33, 0), the path form, is min(max(5, 33), 0)"),
        (43, i32::MAX.wrapping_mul(3) as u32, "dot_into_vec wraps"),
        (44, 1654, "m.set_row(33, ..) sets the last row"),
        (45, 4, "mask.set(33, true) sets the last component"),
        (46, 1, "mask.test(33) reads the last component"),
        (47, 988, "m.col_mut(33) is the last column"),
        (48, (i32::MIN + 3).wrapping_pow(33) as u32, "i32 pow wraps"),
        (49, (i32::MIN as u32), "wrapping_rem(0) is 0, wrapping_div_euclid(0) is the dividend"),
        (50, 0, "ilog2(0), ilog10 of a negative, ilog to base 1, isqrt of a negative: 0"),
        (51, a, "div_ceil(0) reads the divisor as one"),
        (52, a, "next_multiple_of(0) reads the divisor as one"),
        (53, a.wrapping_mul(a).wrapping_mul(2), "next_power_of_two past 2^31 is 0; u32::pow wraps"),
        (54, i32::MIN as u32, "overflowing_div(0) and overflowing_rem_euclid(0) read the divisor as one"),
        (55, 100_611, "from_mat4_minor(m, 33, 9) and from_mat3_minor(.., 0, 33) leave out the last column and row"),
    ]
}

fn run(backend: Backend) -> Vec<u32> {
    let mut ctx = Context::new();
    ctx.set_backend(backend);
    ctx.set_ray_type_count(0);
    let out = ctx.create_buffer::<u32>(BufferType::InputOutput, vec![0xdead; 60]);
    let p = ctx.create_program(&edge_cases::PROGRAM);
    ctx.set_ray_generation_program(0, p).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "a", 0x9e37_79b9u32).unwrap();
    ctx.set_var(Scope::Context, "zero", 0u32).unwrap();
    ctx.set_var(Scope::Context, "min", i32::MIN).unwrap();
    ctx.set_var(Scope::Context, "minus_one", -1i32).unwrap();
    ctx.set_var(Scope::Context, "k", 33u32).unwrap();
    ctx.set_var(Scope::Context, "nan", f32::NAN).unwrap();
    ctx.set_var(Scope::Context, "negative", -5.0f32).unwrap();
    ctx.set_var(Scope::Context, "big", 3e9f32).unwrap();
    let report = ctx.launch(0, 1, 1).unwrap();
    assert_eq!(report.exceptions, vec![], "{backend:?}: no exception");
    ctx.read_buffer::<u32>(out).unwrap()
}

fn check(backend: Backend) {
    let got = run(backend);
    let wrong: Vec<String> = expected()
        .into_iter()
        .filter(|&(i, want, _)| got[i] != want)
        .map(|(i, want, what)| format!("out[{i}] = {:#x}, want {want:#x}: {what}", got[i]))
        .collect();
    assert!(wrong.is_empty(), "{backend:?}:\n{}", wrong.join("\n"));
}

#[test]
fn cpu_gives_the_defined_values_without_panicking() {
    check(Backend::Cpu);
}

#[test]
fn wgpu_gives_the_defined_values() {
    check(Backend::Wgpu);
}

#[rt_program(ray_generation)]
pub fn divides(#[var] mut out: RwBuffer<u32>, #[var] a: u32, #[var] zero: u32) {
    out[0] = a / zero;
    out[1] = a * a;
}

#[rt_program(exception)]
pub fn record_code(#[var] mut out: RwBuffer<u32>) {
    out[2] = exception_code();
}

fn context_for(program: &'static rt_std::program::ProgramDescriptor, backend: Backend) -> (Context, BufferId) {
    let mut ctx = Context::new();
    ctx.set_backend(backend);
    ctx.set_ray_type_count(0);
    ctx.set_integer_exceptions(true);
    let out = ctx.create_buffer::<u32>(BufferType::InputOutput, vec![0xdead; 60]);
    let p = ctx.create_program(program);
    ctx.set_ray_generation_program(0, p).unwrap();
    let ex = ctx.create_program(&record_code::PROGRAM);
    ctx.set_exception_program(0, ex).unwrap();
    for (name, v) in [("a", 0x9e37_79b9u32), ("zero", 0), ("k", 33)] {
        ctx.set_var(Scope::Context, name, v).unwrap();
    }
    ctx.set_var(Scope::Context, "out", out).unwrap();
    (ctx, out)
}

#[test]
fn integer_exceptions_on_the_cpu_name_the_operator_and_reach_the_exception_program() {
    let (mut ctx, out) = context_for(&divides::PROGRAM, Backend::Cpu);
    let report = ctx.launch(0, 1, 1).unwrap();
    assert_eq!(report.exceptions.len(), 1, "{:?}", report.exceptions);
    let e = report.exceptions[0];
    assert_eq!((e.launch_index, e.code), (glam::UVec2::ZERO, EXCEPTION_INTEGER_DIVIDE_BY_ZERO));
    let at = e.location.expect("the operator's place");
    assert!(at.file().ends_with("integer_semantics.rs"), "{at}");
    let line = include_str!("integer_semantics.rs").lines().position(|l| l == "    out[0] = a / zero;").unwrap() + 1;
    assert_eq!((at.line(), at.column()), (line as u32, 16), "the `/` of `a / zero`");
    let got = ctx.read_buffer::<u32>(out).unwrap();
    // The program went on with the defined values; the exception program
    // saw the code.
    assert_eq!(&got[..3], &[0x9e37_79b9, 0x9e37_79b9u32.wrapping_mul(0x9e37_79b9), EXCEPTION_INTEGER_DIVIDE_BY_ZERO]);
}

#[test]
fn integer_exceptions_report_the_first_overflow_and_keep_the_wrapped_values() {
    let (mut ctx, out) = context_for(&edge_cases::PROGRAM, Backend::Cpu);
    for (name, v) in [("min", i32::MIN), ("minus_one", -1)] {
        ctx.set_var(Scope::Context, name, v).unwrap();
    }
    for (name, v) in [("nan", f32::NAN), ("negative", -5.0), ("big", 3e9)] {
        ctx.set_var(Scope::Context, name, v).unwrap();
    }
    let report = ctx.launch(0, 1, 1).unwrap();
    let e = report.exceptions[..].first().copied().expect("an exception");
    assert_eq!(e.code, EXCEPTION_INTEGER_OVERFLOW);
    let at = e.location.unwrap();
    assert_eq!((at.line(), at.column()), (31, 16), "the `*` of `a * a`");
    let got = ctx.read_buffer::<u32>(out).unwrap();
    for (i, want, what) in expected() {
        if i != 2 {
            assert_eq!(got[i], want, "{what}");
        }
    }
    assert_eq!(got[2], EXCEPTION_INTEGER_OVERFLOW, "out[2], written by the exception program");
}

#[test]
fn integer_exceptions_are_off_by_default_and_raise_nothing_on_wgpu() {
    let (mut ctx, out) = context_for(&divides::PROGRAM, Backend::Wgpu);
    let report = ctx.launch(0, 1, 1).unwrap();
    assert_eq!(report.exceptions, vec![]);
    assert_eq!(
        ctx.read_buffer::<u32>(out).unwrap()[..3],
        [0x9e37_79b9, 0x9e37_79b9u32.wrapping_mul(0x9e37_79b9), 0xdead]
    );
    ctx.set_backend(Backend::Cpu);
    ctx.set_integer_exceptions(false);
    assert_eq!(ctx.launch(0, 1, 1).unwrap().exceptions, vec![]);
}
