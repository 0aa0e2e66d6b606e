//! The dividing methods of `i32`/`u32` and their vectors
//! (`div_euclid`, `rem_euclid`, `wrapping_div`, `saturating_div`) with
//! WGSL's meaning of an integer division, the one `rt_std::arith` gives
//! the CPU copy: a zero divisor divides by one (`a / 0` is `a`, `a % 0`
//! is 0) and `i32::MIN / -1` is `i32::MIN` (`wrapping_div`,
//! `div_euclid`) or `i32::MAX` (`saturating_div`). Rust panics in both
//! cases; the CPU copy calls `rt_std::arith::Gpu`'s methods of those names
//! instead (`cpu_semantics.rs`).
//!
//! Each is a WGSL function of the module, not an expression: its operands
//! are then values at run time, and WGSL never sees a constant zero
//! divisor or a constant overflow (both are shader-creation errors). The
//! divisor is made safe first (`rt_safe_divisor_*`: 1 where the divisor is
//! 0, or where `i32::MIN / -1` would overflow), which gives WGSL's own
//! answers for those cases without leaning on the driver.

use super::MethodSig;
use crate::types::{Scalar, Ty};

/// The safe divisor and the four signed methods for one `i32` shape
/// (`$sfx` names it in the functions' names, `$t` is its WGSL type).
macro_rules! signed {
    ($sfx:literal, $t:literal) => {
        [
            (
                concat!("rt_safe_divisor_", $sfx),
                concat!(
                    "fn rt_safe_divisor_",
                    $sfx,
                    "(a: ",
                    $t,
                    ", b: ",
                    $t,
                    ") -> ",
                    $t,
                    " {\n",
                    "    return select(b, ",
                    $t,
                    "(1), (b == ",
                    $t,
                    "(0)) | ((a == ",
                    $t,
                    "(-2147483648)) & (b == ",
                    $t,
                    "(-1))));\n",
                    "}\n"
                ),
            ),
            (
                concat!("rt_div_euclid_", $sfx),
                concat!(
                    "fn rt_div_euclid_",
                    $sfx,
                    "(a: ",
                    $t,
                    ", b: ",
                    $t,
                    ") -> ",
                    $t,
                    " {\n",
                    "    let d = rt_safe_divisor_",
                    $sfx,
                    "(a, b);\n",
                    "    return a / d - select(",
                    $t,
                    "(0), sign(d), a % d < ",
                    $t,
                    "(0));\n",
                    "}\n"
                ),
            ),
            (
                concat!("rt_rem_euclid_", $sfx),
                concat!(
                    "fn rt_rem_euclid_",
                    $sfx,
                    "(a: ",
                    $t,
                    ", b: ",
                    $t,
                    ") -> ",
                    $t,
                    " {\n",
                    "    let d = rt_safe_divisor_",
                    $sfx,
                    "(a, b);\n",
                    "    let r = a % d;\n",
                    "    return select(r, select(r + d, r - d, d < ",
                    $t,
                    "(0)), r < ",
                    $t,
                    "(0));\n",
                    "}\n"
                ),
            ),
            (
                concat!("rt_wrapping_div_", $sfx),
                concat!(
                    "fn rt_wrapping_div_",
                    $sfx,
                    "(a: ",
                    $t,
                    ", b: ",
                    $t,
                    ") -> ",
                    $t,
                    " {\n",
                    "    return a / rt_safe_divisor_",
                    $sfx,
                    "(a, b);\n",
                    "}\n"
                ),
            ),
            (
                concat!("rt_saturating_div_", $sfx),
                concat!(
                    "fn rt_saturating_div_",
                    $sfx,
                    "(a: ",
                    $t,
                    ", b: ",
                    $t,
                    ") -> ",
                    $t,
                    " {\n",
                    "    return select(a / rt_safe_divisor_",
                    $sfx,
                    "(a, b), ",
                    $t,
                    "(2147483647), (a == ",
                    $t,
                    "(-2147483648)) & (b == ",
                    $t,
                    "(-1)));\n",
                    "}\n"
                ),
            ),
        ]
    };
}

/// `/` and `%` of one `u32` shape with a zero divisor read as one: every
/// unsigned dividing method is one of them (no quotient overflows, no
/// remainder is negative).
macro_rules! unsigned {
    ($sfx:literal, $t:literal) => {
        [
            (
                concat!("rt_div_", $sfx),
                concat!(
                    "fn rt_div_",
                    $sfx,
                    "(a: ",
                    $t,
                    ", b: ",
                    $t,
                    ") -> ",
                    $t,
                    " {\n",
                    "    return a / select(b, ",
                    $t,
                    "(1), b == ",
                    $t,
                    "(0));\n",
                    "}\n"
                ),
            ),
            (
                concat!("rt_rem_", $sfx),
                concat!(
                    "fn rt_rem_",
                    $sfx,
                    "(a: ",
                    $t,
                    ", b: ",
                    $t,
                    ") -> ",
                    $t,
                    " {\n",
                    "    return a % select(b, ",
                    $t,
                    "(1), b == ",
                    $t,
                    "(0));\n",
                    "}\n"
                ),
            ),
        ]
    };
}

type Support = (&'static str, &'static str);

fn signed_fns(n: u8) -> [Support; 5] {
    match n {
        1 => signed!("i32", "i32"),
        2 => signed!("vec2i", "vec2<i32>"),
        3 => signed!("vec3i", "vec3<i32>"),
        _ => signed!("vec4i", "vec4<i32>"),
    }
}

fn unsigned_fns(n: u8) -> [Support; 2] {
    match n {
        1 => unsigned!("u32", "u32"),
        2 => unsigned!("vec2u", "vec2<u32>"),
        3 => unsigned!("vec3u", "vec3<u32>"),
        _ => unsigned!("vec4u", "vec4<u32>"),
    }
}

/// `recv.name(divisor)` for an `i32`/`u32` scalar or vector receiver.
pub fn method(recv: &Ty, name: &str) -> Option<MethodSig> {
    let (n, s) = match recv {
        Ty::Scalar(s) => (1, *s),
        Ty::Vec(n, s) => (*n, *s),
        _ => return None,
    };
    let (f, support): (Support, Vec<Support>) = match s {
        Scalar::I32 => {
            let fns = signed_fns(n);
            let f = match name {
                "div_euclid" => fns[1],
                "rem_euclid" => fns[2],
                "wrapping_div" => fns[3],
                "saturating_div" => fns[4],
                _ => return None,
            };
            (f, vec![fns[0], f])
        }
        Scalar::U32 => {
            let fns = unsigned_fns(n);
            // (glam's `UVecN` has no `div_euclid`/`rem_euclid`; `u32` has.)
            let f = match name {
                "div_euclid" if n == 1 => fns[0],
                "rem_euclid" if n == 1 => fns[1],
                "wrapping_div" | "saturating_div" => fns[0],
                _ => return None,
            };
            (f, vec![f])
        }
        _ => return None,
    };
    let call = f.0;
    Some(MethodSig {
        params: vec![recv.clone()],
        ret: recv.clone(),
        lower: Box::new(move |a| format!("{call}({}, {})", a[0], a[1])),
        support,
    })
}
