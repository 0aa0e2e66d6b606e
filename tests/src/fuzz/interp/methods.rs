//! Constants, free functions and methods of the subset (glam's, rt-std's
//! and Rust's formulas), with their error bounds.

use super::*;

/// Composite float helpers evaluated with glam's/rt-std's formulas and a
/// rounding allowance per operation (`loose`).
pub(super) mod loose {
    use super::*;

    pub fn dot(a: &[V], b: &[V]) -> R<F> {
        let mut acc = fmul(a[0].f(), b[0].f(), true)?;
        for (x, y) in a.iter().zip(b).skip(1) {
            acc = fadd(acc, fmul(x.f(), y.f(), true)?, true)?;
        }
        Ok(acc)
    }

    /// `sqrt` with WGSL's 5 ULP.
    pub fn sqrt(a: F) -> R<F> {
        let r = a.0.sqrt();
        funary(a, r, 5.0, 0.0, |x| x.max(0.0).sqrt())
    }

    pub fn length(a: &[V]) -> R<F> {
        sqrt(dot(a, a)?)
    }

    /// `a * (1 - t) + b * t`.
    pub fn mix(a: F, b: F, t: F) -> R<F> {
        let one = (1.0, 0.0);
        fadd(fmul(a, fsub(one, t, true)?, true)?, fmul(b, t, true)?, true)
    }
}

pub(super) fn constant(t: &str, n: &str) -> V {
    let f = |x: f32| V::F(x, 0.0);
    match (t, n) {
        ("", "PI") => f(std::f32::consts::PI),
        ("", "TAU") => f(std::f32::consts::TAU),
        ("", "E") => f(std::f32::consts::E),
        ("", "SQRT_2") => f(std::f32::consts::SQRT_2),
        ("f32", "EPSILON") => f(f32::EPSILON),
        ("f32", "MIN_POSITIVE") => f(f32::MIN_POSITIVE),
        // Only ever an operand of a comparison (see `generate`).
        ("f32", "NAN") => f(f32::NAN),
        ("i32", "MAX") => V::I(i32::MAX, false),
        ("i32", "MIN") => V::I(i32::MIN, false),
        ("u32", "MAX") => V::U(u32::MAX, false),
        ("u32", "MIN") => V::U(0, false),
        _ => {
            let Some(Ty::V(k, s)) = Ty::from_name(t) else { panic!("constant {t}::{n}") };
            let one = |x: i32| match s {
                Scalar::F32 => V::F(x as f32, 0.0),
                Scalar::I32 => V::I(x, false),
                _ => V::U(x as u32, false),
            };
            let axis = |i: usize, x: i32| V::Vec((0..k as usize).map(|j| one(if i == j { x } else { 0 })).collect());
            match n {
                "ZERO" => V::Vec(vec![one(0); k as usize]),
                "ONE" => V::Vec(vec![one(1); k as usize]),
                "NEG_ONE" => V::Vec(vec![one(-1); k as usize]),
                _ => {
                    let (neg, name) = match n.strip_prefix("NEG_") {
                        Some(r) => (true, r),
                        None => (false, n),
                    };
                    let i = "XYZW".find(name).unwrap_or_else(|| panic!("constant {t}::{n}"));
                    axis(i, if neg { -1 } else { 1 })
                }
            }
        }
    }
}

/// rt-std's and glam's free functions.
pub(super) fn free(f: &str, a: &[V]) -> R<V> {
    Ok(match f {
        "vec2" | "vec3" | "vec4" | "ivec2" | "ivec3" | "ivec4" | "uvec2" | "uvec3" | "uvec4" => V::Vec(a.to_vec()),
        // `a * (1 - t) + b * t`; `t` is one f32 or per component.
        "mix" => zip3(&a[0], &a[1], &a[2], &mut |x, y, t| fv(loose::mix(x.f(), y.f(), t.f())))?,
        "step" => zip(&a[0], &a[1], &mut |e, x| {
            let c = fcmp(BinOp::Ge, x.f(), e.f());
            let V::B(b, u) = c else { unreachable!() };
            Ok(V::F(if b { 1.0 } else { 0.0 }, if u { 1.0 } else { 0.0 }))
        })?,
        // `t = saturate((x - e0) / (e1 - e0)); t * t * (3 - 2 t)`.
        "smoothstep" => zip3(&a[0], &a[1], &a[2], &mut |e0, e1, x| {
            let t = fdiv(fsub(x.f(), e0.f(), true)?, fsub(e1.f(), e0.f(), true)?)?;
            let t = (t.0.max(0.0).min(1.0), t.1);
            let r = t.0 * t.0 * (3.0 - 2.0 * t.0);
            // |d/dt| <= 1.5; a few roundings of values <= 3.
            fv(fin(r, 1.5 * t.1 + 4.0 * ulp(3.0)))
        })?,
        "saturate" => map1(&a[0], &mut |x| {
            let (v, e) = x.f();
            Ok(V::F(v.max(0.0).min(1.0), e))
        })?,
        _ => panic!("free function {f}"),
    })
}

/// A method of a scalar or glam vector, Rust's/glam's semantics.
pub(super) fn method(r: &V, m: &str, a: &[V]) -> R<V> {
    // Swizzles and conversions first.
    if let V::Vec(c) = r {
        if (2..=4).contains(&m.len()) && m.chars().all(|ch| "xyzw".contains(ch)) {
            return Ok(V::Vec(m.chars().map(|ch| c["xyzw".find(ch).unwrap()].clone()).collect()));
        }
        for (p, s) in [("as_vec", Scalar::F32), ("as_ivec", Scalar::I32), ("as_uvec", Scalar::U32)] {
            if m.starts_with(p) {
                return cast(r, s);
            }
        }
    }
    if let Some(v) = vector_geometry(r, m, a)? {
        return Ok(v);
    }
    if let Some(v) = bool_vector(r, m, a)? {
        return Ok(v);
    }
    if let Some(v) = float_vector(r, m, a)? {
        return Ok(v);
    }
    component_wise(r, m, a)
}

/// Reductions and geometry on vectors (`dot`, `length`, `extend`, integer
/// `cross`, ...); `None` for another method.
fn vector_geometry(r: &V, m: &str, a: &[V]) -> R<Option<V>> {
    Ok(Some(match (r, m) {
        (V::Vec(c), "dot") => dot(c, a[0].comps())?,
        (V::Vec(c), "length_squared") => dot(c, c)?,
        (V::Vec(c), "length") => fv(loose::length(c))?,
        (V::Vec(_), "distance") => {
            let d = bin(BinOp::Sub, r, &a[0])?;
            fv(loose::length(d.comps()))?
        }
        (V::Vec(_), "distance_squared") => {
            let d = bin(BinOp::Sub, r, &a[0])?;
            dot(d.comps(), d.comps())?
        }
        (V::Vec(c), "element_sum") => c[1..].iter().try_fold(c[0].clone(), |acc, x| loose_bin(BinOp::Add, &acc, x))?,
        (V::Vec(c), "element_product") => {
            c[1..].iter().try_fold(c[0].clone(), |acc, x| loose_bin(BinOp::Mul, &acc, x))?
        }
        (V::Vec(c), "min_element") => c[1..].iter().try_fold(c[0].clone(), |acc, x| min_max(&acc, x, true))?,
        (V::Vec(c), "max_element") => c[1..].iter().try_fold(c[0].clone(), |acc, x| min_max(&acc, x, false))?,
        (V::Vec(c), "extend") => {
            let mut c = c.clone();
            c.push(a[0].clone());
            V::Vec(c)
        }
        (V::Vec(c), "truncate") => V::Vec(c[..c.len() - 1].to_vec()),
        (V::Vec(c), "cross") if !matches!(c[0], V::F(..)) => {
            let b = a[0].comps();
            let m2 = |i: usize, j: usize| -> R<V> {
                scalar_bin(BinOp::Sub, &scalar_bin(BinOp::Mul, &c[i], &b[j])?, &scalar_bin(BinOp::Mul, &b[i], &c[j])?)
            };
            V::Vec(vec![m2(1, 2)?, m2(2, 0)?, m2(0, 1)?])
        }
        (V::Vec(c), "manhattan_distance") => {
            let mut acc = V::U(0, false);
            for (x, y) in c.iter().zip(a[0].comps()) {
                let d = match (x, y) {
                    (V::I(p, pu), V::I(q, qu)) => V::U(p.abs_diff(*q), *pu || *qu),
                    (V::U(p, pu), V::U(q, qu)) => V::U(p.abs_diff(*q), *pu || *qu),
                    _ => panic!("manhattan_distance of {x:?}"),
                };
                acc = scalar_bin(BinOp::Add, &acc, &d)?;
            }
            acc
        }
        _ => return Ok(None),
    }))
}

/// Bool vectors' methods (`any`, `all`, `bitmask`), the comparisons that
/// make them (`cmp*`) and `select` by a mask; `None` for another method.
fn bool_vector(r: &V, m: &str, a: &[V]) -> R<Option<V>> {
    Ok(Some(match (r, m) {
        (V::Vec(c), "any" | "all") => {
            let want = m == "any";
            // A certain component equal to `want` decides; else an
            // uncertain one leaves it open.
            let decided = c.iter().any(|x| matches!(x, V::B(v, false) if *v == want));
            let unc = !decided && c.iter().any(|x| matches!(x, V::B(_, true)));
            V::B(if decided { want } else { !want }, unc)
        }
        (V::Vec(c), "bitmask") => {
            let mut bits = 0u32;
            let mut unc = false;
            for (i, x) in c.iter().enumerate() {
                let V::B(v, u) = x else { panic!("bitmask of {x:?}") };
                bits |= (*v as u32) << i;
                unc |= *u;
            }
            V::U(bits, unc)
        }
        (V::Vec(_), "cmpeq" | "cmpne" | "cmplt" | "cmple" | "cmpgt" | "cmpge") => {
            let op = match m {
                "cmpeq" => BinOp::Eq,
                "cmpne" => BinOp::Ne,
                "cmplt" => BinOp::Lt,
                "cmple" => BinOp::Le,
                "cmpgt" => BinOp::Gt,
                _ => BinOp::Ge,
            };
            zip(r, &a[0], &mut |x, y| scalar_bin(op, x, y))?
        }
        // `VecN::select(mask, if_true, if_false)`, the mask first.
        (V::Vec(mask), "select") => {
            let (t, f) = (a[0].comps(), a[1].comps());
            let picked = mask.iter().zip(t.iter().zip(f)).map(|(k, (x, y))| {
                let V::B(k, unc) = k else { panic!("select by {k:?}") };
                let v = if *k { x.clone() } else { y.clone() };
                match (v, unc) {
                    (v, false) => v,
                    // Either may be picked: uncertain by their difference.
                    (V::F(v, e), true) => {
                        let (V::F(p, pe), V::F(q, qe)) = (x, y) else { unreachable!() };
                        V::F(v, e.max(*pe).max(*qe) + (*p as f64 - *q as f64).abs())
                    }
                    (V::I(v, _), true) => V::I(v, true),
                    (V::U(v, _), true) => V::U(v, true),
                    (v, true) => panic!("select of {v:?}"),
                }
            });
            V::Vec(picked.collect())
        }
        _ => return Ok(None),
    }))
}

/// Float vectors' own methods (`cross`, `normalize_or_zero`, `lerp`,
/// `fract_gl`); `None` for another method.
fn float_vector(r: &V, m: &str, a: &[V]) -> R<Option<V>> {
    let comp_wise = |f: &mut dyn FnMut(&V) -> R<V>| -> R<V> { map1(r, &mut |s| f(s)) };
    Ok(Some(match (r, m) {
        (V::Vec(c), "cross") => {
            let b = a[0].comps();
            let m2 = |i: usize, j: usize| -> R<F> {
                fsub(fmul(c[i].f(), b[j].f(), true)?, fmul(b[i].f(), c[j].f(), true)?, true)
            };
            V::Vec(vec![fv(m2(1, 2))?, fv(m2(2, 0))?, fv(m2(0, 1))?])
        }
        (V::Vec(c), "normalize_or_zero") => {
            // glam: `self * (1 / length)` if that is finite and positive,
            // else zero; the compiler: `select(0, v * inverseSqrt(dot),
            // dot > 0)`.
            let d = loose::dot(c, c)?;
            let len = (d.0.sqrt(), 0.0);
            let rcp = 1.0 / len.0;
            if !(rcp.is_finite() && rcp > 0.0) {
                let unc = d.1 > 0.0;
                return Ok(Some(V::Vec(c.iter().map(|_| V::F(0.0, if unc { 2.0 } else { 0.0 })).collect())));
            }
            // Relative error of 1/len: half of dot's, plus a few ULP.
            let rel =
                if d.0 as f64 <= d.1 { f64::INFINITY } else { 0.5 * d.1 / (d.0 as f64 - d.1) + 4.0 * 2f64.powi(-23) };
            let out: R<Vec<V>> = c
                .iter()
                .map(|x| {
                    let (v, e) = x.f();
                    let r = v * rcp;
                    let err = (e * rcp as f64 + r.abs() as f64 * rel + ulp(r as f64)).min(2.0);
                    fv(fin(r, err))
                })
                .collect();
            V::Vec(out?)
        }
        (V::Vec(_), "lerp") => zip3(r, &a[0], &a[1], &mut |x, y, s| fv(loose::mix(x.f(), y.f(), s.f())))?,
        (V::Vec(_), "fract_gl") => comp_wise(&mut |s| fv(ffract(s.f(), f32::floor)))?,
        _ => return Ok(None),
    }))
}

/// The component-wise methods: of scalars, and of vectors where glam has
/// them.
fn component_wise(r: &V, m: &str, a: &[V]) -> R<V> {
    let comp_wise = |f: &mut dyn FnMut(&V) -> R<V>| -> R<V> { map1(r, &mut |s| f(s)) };
    let two = |f: &mut dyn FnMut(&V, &V) -> R<V>| -> R<V> { zip(r, &a[0], &mut |x, y| f(x, y)) };
    match m {
        "min" => two(&mut |x, y| min_max(x, y, true)),
        "max" => two(&mut |x, y| min_max(x, y, false)),
        "clamp" => zip3(r, &a[0], &a[1], &mut |x, lo, hi| min_max(&min_max(x, lo, false)?, hi, true)),
        "wrapping_add" => two(&mut |x, y| scalar_bin(BinOp::Add, x, y)),
        "wrapping_sub" => two(&mut |x, y| scalar_bin(BinOp::Sub, x, y)),
        "wrapping_mul" => two(&mut |x, y| scalar_bin(BinOp::Mul, x, y)),
        "div_euclid" | "rem_euclid" | "wrapping_div" | "saturating_div" => two(&mut |x, y| Ok(dividing(m, x, y))),
        "abs_diff" => Ok(match (r, &a[0]) {
            (V::I(x, xu), V::I(y, yu)) => V::U(x.abs_diff(*y), *xu || *yu),
            (V::U(x, xu), V::U(y, yu)) => V::U(x.abs_diff(*y), *xu || *yu),
            _ => panic!("abs_diff of {r:?}"),
        }),
        "midpoint" => Ok(match (r, &a[0]) {
            (V::I(x, xu), V::I(y, yu)) => V::I(x.midpoint(*y), *xu || *yu),
            (V::U(x, xu), V::U(y, yu)) => V::U(x.midpoint(*y), *xu || *yu),
            _ => panic!("midpoint of {r:?}"),
        }),
        // `pow` wraps (the GPU's meaning, where std panics in a debug build).
        "pow" | "wrapping_pow" | "saturating_pow" => {
            let V::U(e, eu) = a[0] else { panic!("{m} by {:?}", a[0]) };
            Ok(match r {
                V::I(x, u) if m == "saturating_pow" => V::I(x.saturating_pow(e), *u || eu),
                V::U(x, u) if m == "saturating_pow" => V::U(x.saturating_pow(e), *u || eu),
                V::I(x, u) => V::I(x.wrapping_pow(e), *u || eu),
                V::U(x, u) => V::U(x.wrapping_pow(e), *u || eu),
                _ => panic!("{m} of {r:?}"),
            })
        }
        "is_multiple_of" => {
            let (V::U(x, xu), V::U(y, yu)) = (r, &a[0]) else { panic!("is_multiple_of") };
            Ok(V::B(x.is_multiple_of(*y), *xu || *yu))
        }
        "powi" => {
            let V::I(n, nu) = a[0] else { panic!("powi") };
            assert!(!nu);
            comp_wise(&mut |s| {
                let (x, e) = s.f();
                let r = x.powi(n);
                // Repeated squaring on both sides (the compiler's `rt_powi`
                // is compiler-rt's loop); `1 / r` for negative `n` is a WGSL
                // division.
                let own = if n < 0 { 2.5 } else { 0.0 };
                fv(funary((x, e), r, own, 0.0, |v| v.powi(n)))
            })
        }
        "powf" => two(&mut |x, y| {
            let ((xv, xe), (yv, ye)) = (x.f(), y.f());
            let r = xv.powf(yv);
            // Inherited from exp2(y * log2(x)).
            let l = (xv as f64).log2();
            let dl = if (0.5..=2.0).contains(&xv) { 2f64.powi(-21) } else { 3.0 * ulp(l) };
            let t = yv as f64 * l;
            let dt = yv.abs() as f64
                * (dl + if xe > 0.0 { xe / ((xv as f64 - xe).max(0.0) * std::f64::consts::LN_2) } else { 0.0 })
                + l.abs() * ye
                + ulp(t);
            let rel = (dt * std::f64::consts::LN_2).exp_m1() + (3.0 + 2.0 * t.abs()) * 2f64.powi(-23);
            fv(fin(r, r.abs() as f64 * rel))
        }),
        "mul_add" => zip3(r, &a[0], &a[1], &mut |x, y, z| {
            let r = x.f().0.mul_add(y.f().0, z.f().0);
            // WGSL's fma is inherited from `a * b + c`: one more rounding
            // of the product.
            let p = fmul(x.f(), y.f(), true)?;
            let s = fadd(p, z.f(), true)?;
            fv(fin(r, s.1 + ulp(p.0 as f64)))
        }),
        _ => comp_wise(&mut |s| unary(s, m)),
    }
}

/// The dividing methods as the GPU (and `rt_std::arith`) computes them: a
/// zero divisor is read as one; `MIN / -1` wraps, `saturating_div`
/// saturates.
fn dividing(m: &str, x: &V, y: &V) -> V {
    match (x, y) {
        (V::I(x, xu), V::I(y, yu)) => {
            let y = if *y == 0 { 1 } else { *y };
            let r = match m {
                "div_euclid" => x.wrapping_div_euclid(y),
                "rem_euclid" => x.wrapping_rem_euclid(y),
                "wrapping_div" => x.wrapping_div(y),
                _ => x.saturating_div(y),
            };
            V::I(r, *xu || *yu)
        }
        (V::U(x, xu), V::U(y, yu)) => {
            let y = if *y == 0 { 1 } else { *y };
            let r = match m {
                "div_euclid" | "wrapping_div" | "saturating_div" => x / y,
                _ => x % y,
            };
            V::U(r, *xu || *yu)
        }
        _ => panic!("{m} of {x:?} and {y:?}"),
    }
}

/// min/max: exact, error of the larger operand error.
fn min_max(x: &V, y: &V, min: bool) -> R<V> {
    Ok(match (x, y) {
        (V::F(a, ea), V::F(b, eb)) => {
            let r = if min {
                if a < b { *a } else { *b }
            } else if a > b {
                *a
            } else {
                *b
            };
            V::F(r, ea.max(*eb))
        }
        (V::I(a, ua), V::I(b, ub)) => V::I(if min { *a.min(b) } else { *a.max(b) }, *ua || *ub),
        (V::U(a, ua), V::U(b, ub)) => V::U(if min { *a.min(b) } else { *a.max(b) }, *ua || *ub),
        _ => panic!("min/max of {x:?} and {y:?}"),
    })
}

pub(super) fn dot(a: &[V], b: &[V]) -> R<V> {
    match a[0] {
        V::F(..) => fv(loose::dot(a, b)),
        _ => {
            let mut acc = scalar_bin(BinOp::Mul, &a[0], &b[0])?;
            for (x, y) in a.iter().zip(b).skip(1) {
                acc = scalar_bin(BinOp::Add, &acc, &scalar_bin(BinOp::Mul, x, y)?)?;
            }
            Ok(acc)
        }
    }
}

/// One-operand methods on one scalar.
pub(super) fn unary(s: &V, m: &str) -> R<V> {
    let tiny = 2f64.powi(-21);
    Ok(match s {
        V::F(x, e) => {
            let a = (*x, *e);
            let xf = *x as f64;
            match m {
                "abs" => V::F(x.abs(), *e),
                "floor" => fv(fstep(a, f32::floor))?,
                "ceil" => fv(fstep(a, f32::ceil))?,
                "trunc" => fv(fstep(a, f32::trunc))?,
                "round" => fv(fstep(a, f32::round))?,
                "fract" => fv(ffract(a, f32::trunc))?,
                "signum" => {
                    let unc = *e > 0.0 && (x.abs() as f64) <= *e || *x == 0.0;
                    V::F(x.signum(), if unc { 2.0 } else { 0.0 })
                }
                "sqrt" => fv(loose::sqrt(a))?,
                "exp" => fv(funary(a, x.exp(), 3.0 + 2.0 * xf.abs(), 0.0, f64::exp))?,
                "exp2" => fv(funary(a, x.exp2(), 3.0 + 2.0 * xf.abs(), 0.0, f64::exp2))?,
                "ln" | "log2" => {
                    let r = if m == "ln" { x.ln() } else { x.log2() };
                    let (ulps, abs) = if (0.5..=2.0).contains(x) { (0.0, tiny) } else { (3.0, 0.0) };
                    let f = if m == "ln" { f64::ln } else { f64::log2 };
                    let spread_ok = xf - e > 0.0;
                    let (r, err) = funary(a, r, ulps, abs, |v| f(v.max(f64::MIN_POSITIVE)))?;
                    V::F(r, if spread_ok { err } else { f64::INFINITY })
                }
                "sin" | "cos" => {
                    let r = if m == "sin" { x.sin() } else { x.cos() };
                    let own = if x.abs() <= std::f32::consts::PI { 2f64.powi(-11) } else { 2.0 };
                    V::F(r, (e + own).min(2.0))
                }
                "atan" => fv(funary(a, x.atan(), 4096.0, 0.0, f64::atan))?,
                "recip" => fv(fdiv((1.0, 0.0), a))?,
                "to_radians" => fv(fmul(a, (std::f32::consts::PI / 180.0, 0.0), true))?,
                "to_degrees" => {
                    let r = x.to_degrees();
                    fv(fin(r, rounded(r, e * 57.3, true)))?
                }
                _ => panic!("f32::{m}"),
            }
        }
        V::I(x, u) => match m {
            "wrapping_neg" => V::I(x.wrapping_neg(), *u),
            // 0 where std has no answer (the GPU's meaning).
            "isqrt" => V::I(x.checked_isqrt().unwrap_or(0), *u),
            "ilog2" => V::U(x.checked_ilog2().unwrap_or(0), *u),
            "ilog10" => V::U(x.checked_ilog10().unwrap_or(0), *u),
            "count_zeros" => V::U(x.count_zeros(), *u),
            "leading_ones" => V::U(x.leading_ones(), *u),
            "trailing_ones" => V::U(x.trailing_ones(), *u),
            "abs" => V::I(x.wrapping_abs(), *u),
            "signum" => V::I(x.signum(), *u),
            "count_ones" => V::U(x.count_ones(), *u),
            "leading_zeros" => V::U(x.leading_zeros(), *u),
            "trailing_zeros" => V::U(x.trailing_zeros(), *u),
            "reverse_bits" => V::I(x.reverse_bits(), *u),
            _ => panic!("i32::{m}"),
        },
        V::U(x, u) => match m {
            "wrapping_neg" => V::U(x.wrapping_neg(), *u),
            "isqrt" => V::U(x.isqrt(), *u),
            "ilog2" => V::U(x.checked_ilog2().unwrap_or(0), *u),
            "ilog10" => V::U(x.checked_ilog10().unwrap_or(0), *u),
            "count_zeros" => V::U(x.count_zeros(), *u),
            "leading_ones" => V::U(x.leading_ones(), *u),
            "trailing_ones" => V::U(x.trailing_ones(), *u),
            "count_ones" => V::U(x.count_ones(), *u),
            "leading_zeros" => V::U(x.leading_zeros(), *u),
            "trailing_zeros" => V::U(x.trailing_zeros(), *u),
            "reverse_bits" => V::U(x.reverse_bits(), *u),
            _ => panic!("u32::{m}"),
        },
        other => panic!("{m} on {other:?}"),
    })
}
