//! Comparisons and boolean logic: `== != < <= > >=` on floats and both
//! integer types, `==`/`!=` on vectors (all/any components), `&&` and `||`
//! (short-circuiting, also when the right side calls a helper that mutates
//! state), the eager `& | ^` on `bool`, `!`, and `bool as u32`.
use rt_std::prelude::*;

/// A test with a side effect: counts its calls, so skipping it is visible.
#[rt_function]
pub fn counted_above(calls: &mut u32, v: f32, limit: f32) -> bool {
    *calls += 1;
    v > limit
}

#[rt_program(ray_generation)]
pub fn compare_logic(
    #[var] x: f32,
    #[var] y: f32,
    #[var] n: i32,
    #[var] m: u32,
    #[var] a: Vec3,
    #[var] b: Vec3,
    #[var] out: RwBuffer<u32>,
) {
    let lt = x < y;
    let le = x <= y;
    let gt = n > -3;
    let ge = m >= 10;
    let eq = n == 4 || m != 2;
    let same = a == b;
    let differ = a.xy() != b.xy();
    let mut calls = 0u32;
    let both = lt && counted_above(&mut calls, y, 0.5);
    let either = ge || counted_above(&mut calls, x, -0.5);
    let chained = !(le && gt) || (x > 0.0 && counted_above(&mut calls, x + y, 1.0));
    let all = le & gt & !eq;
    let any = same | differ;
    let one = both ^ either;
    let mut flags = 0u32;
    if all {
        flags |= 1;
    }
    if any {
        flags |= 2;
    }
    flags |= (one as u32) << 2;
    flags |= (chained as u32) << 3;
    flags |= ((same != differ) as u32) << 4;
    out.store(launch_index().x, flags + calls * 256);
}
