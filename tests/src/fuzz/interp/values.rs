//! Values and error bounds: ULPs, rounding allowances, the float
//! operations with their bounds, words, maps over components.

use super::*;

/// The spacing of `f32`s at magnitude `x`.
pub fn ulp(x: f64) -> f64 {
    let x = x.abs();
    let f = if x >= f32::MAX as f64 { f32::MAX } else { x as f32 };
    if f < f32::MIN_POSITIVE {
        return 2f64.powi(-149);
    }
    let e = ((f.to_bits() >> 23) & 0xff) as i32 - 127;
    2f64.powi(e - 23)
}

pub(super) type F = (f32, f64);

/// A float result: NaN and infinities stop the launch index; subnormal
/// values may be flushed.
pub(super) fn fin(r: f32, e: f64) -> R<F> {
    if !r.is_finite() {
        return Err(Stop::NonFinite(format!("{r}")));
    }
    let mut e = if e.is_finite() && e < 1e35 { e } else { f64::INFINITY };
    if r != 0.0 && r.abs() < f32::MIN_POSITIVE {
        e += f32::MIN_POSITIVE as f64;
    }
    Ok((r, e))
}

/// Adds one rounding to a propagated error when the result may differ
/// (`loose`: the GPU may compute it another way even from exact operands).
pub(super) fn rounded(r: f32, e: f64, loose: bool) -> f64 {
    if e.is_nan() {
        // `inf * 0`: an unbounded error times an exact zero.
        f64::INFINITY
    } else if e > 0.0 || loose {
        e + ulp(r.abs() as f64 + e)
    } else {
        0.0
    }
}

/// Whether `v` is a small multiple of 2^-10: sums of up to 16 such values
/// are exact in any order.
fn nice(v: f32) -> bool {
    v.abs() < 1024.0 && (v * 1024.0).fract() == 0.0
}

/// Shader compilers reassociate float `+`/`-` chains and `*` chains (Mesa
/// does for every float operation SPIR-V does not mark exact: after
/// inlining, `(x - n * y) + z` became `(x + z) - n * y`), which rounds the
/// intermediate sums differently: an error of about one ULP of the largest
/// operand, unless every value is small enough that every order is exact.
/// A sum that cancels hides its operands' magnitude from the next one
/// (`(x - trunc(x)) - c` computed as `x - (trunc(x) + c)`): it gets the
/// error even when exact.
fn reassociation(a: f32, b: f32, r: f32, mul: bool) -> f64 {
    let cancels = !mul && r.abs() < a.abs().max(b.abs());
    if nice(a) && nice(b) && nice(r) && !cancels {
        0.0
    } else if mul {
        2.0 * ulp(r.abs() as f64)
    } else {
        ulp(a.abs().max(b.abs()).max(r.abs()) as f64)
    }
}

pub(super) fn fadd(a: F, b: F, loose: bool) -> R<F> {
    let r = a.0 + b.0;
    fin(r, rounded(r, a.1 + b.1 + reassociation(a.0, b.0, r, false), loose))
}

pub(super) fn fsub(a: F, b: F, loose: bool) -> R<F> {
    let r = a.0 - b.0;
    fin(r, rounded(r, a.1 + b.1 + reassociation(a.0, b.0, r, false), loose))
}

pub(super) fn fmul(a: F, b: F, loose: bool) -> R<F> {
    let r = a.0 * b.0;
    let prod = |x: f64, y: f64| if x == 0.0 || y == 0.0 { 0.0 } else { x * y };
    let e = prod(a.0.abs() as f64, b.1) + prod(b.0.abs() as f64, a.1) + prod(a.1, b.1);
    fin(r, rounded(r, e + reassociation(a.0, b.0, r, true), loose))
}

/// `/`: 2.5 ULP in WGSL.
pub(super) fn fdiv(a: F, b: F) -> R<F> {
    let r = a.0 / b.0;
    let bm = b.0.abs() as f64;
    let e = if bm <= b.1 { f64::INFINITY } else { (a.1 + r.abs() as f64 * b.1) / (bm - b.1) };
    fin(r, e + 2.5 * ulp(r.abs() as f64 + e))
}

/// Rust's `%` (fmod), which the compiler lowers to an exact `rt_fmod`: a
/// jump of `|b|` where the quotient crosses an integer within the error.
pub(super) fn frem(a: F, b: F) -> R<F> {
    let r = a.0 % b.0;
    if a.1 == 0.0 && b.1 == 0.0 {
        return fin(r, 0.0);
    }
    let bm = b.0.abs() as f64;
    if bm <= b.1 {
        return fin(r, f64::INFINITY);
    }
    let q = a.0 as f64 / b.0 as f64;
    let qe = (a.1 + q.abs() * b.1) / (bm - b.1);
    let e = if (q - qe).trunc() != (q + qe).trunc() || (a.0.abs() as f64) <= a.1 {
        2.0 * (bm + b.1)
    } else {
        a.1 + q.trunc().abs() * b.1
    };
    fin(r, rounded(r, e, false))
}

/// The largest change of `f` over `[x - e, x + e]` for `f` monotonic on
/// each side of 0.
fn spread(x: f64, e: f64, f: impl Fn(f64) -> f64) -> f64 {
    if e == 0.0 {
        return 0.0;
    }
    if !e.is_finite() {
        return f64::INFINITY;
    }
    let y = f(x);
    let mut m: f64 = 0.0;
    for p in [x - e, x + e] {
        m = m.max((f(p) - y).abs());
    }
    if x - e < 0.0 && x + e > 0.0 {
        m = m.max((f(0.0) - y).abs());
    }
    if m.is_nan() { f64::INFINITY } else { m }
}

/// A result that is `f` of an operand, with `ulps` ULP of its own error
/// plus `abs` absolute.
pub(super) fn funary(a: F, r: f32, ulps: f64, abs: f64, f: impl Fn(f64) -> f64) -> R<F> {
    let e = spread(a.0 as f64, a.1, f) + ulps * ulp(r.abs() as f64) + abs;
    fin(r, e)
}

/// A monotonic step function of `a` (floor, trunc...): exact, but the
/// error may jump.
pub(super) fn fstep(a: F, f: impl Fn(f32) -> f32) -> R<F> {
    let r = f(a.0);
    if a.1 == 0.0 {
        return fin(r, 0.0);
    }
    if !a.1.is_finite() {
        return fin(r, f64::INFINITY);
    }
    let lo = f((a.0 as f64 - a.1) as f32) as f64;
    let hi = f((a.0 as f64 + a.1) as f32) as f64;
    fin(r, (r as f64 - lo).abs().max((hi - r as f64).abs()))
}

/// `fract` (`x - trunc(x)`, `f` the truncation): continuous between
/// integers, a jump of 1 at each.
///
/// The compiler lowers it as a subtraction, which a shader compiler may
/// reassociate with the next one (`(x - trunc(x)) - c` as `x - (trunc(x) +
/// c)`): see [`reassociation`].
pub(super) fn ffract(a: F, f: impl Fn(f32) -> f32) -> R<F> {
    let r = a.0 - f(a.0);
    let re = reassociation(a.0, f(a.0), r, false);
    if a.1 == 0.0 {
        return fin(r, re);
    }
    let crosses = f((a.0 as f64 - a.1) as f32) != f((a.0 as f64 + a.1) as f32);
    fin(r, re + if crosses { 1.0 + a.1 } else { a.1 })
}

pub(super) fn fcmp(op: BinOp, a: F, b: F) -> V {
    let r = match op {
        BinOp::Eq => a.0 == b.0,
        BinOp::Ne => a.0 != b.0,
        BinOp::Lt => a.0 < b.0,
        BinOp::Le => a.0 <= b.0,
        BinOp::Gt => a.0 > b.0,
        BinOp::Ge => a.0 >= b.0,
        _ => unreachable!(),
    };
    let e = a.1 + b.1;
    V::B(r, e > 0.0 && ((a.0 as f64) - (b.0 as f64)).abs() <= e)
}

/// Float to integer `as` (saturating), uncertain where the error bound
/// straddles an integer.
pub(super) fn f2i(a: F, signed: bool) -> V {
    let conv = |x: f64| if signed { (x as f32) as i32 as i64 } else { (x as f32) as u32 as i64 };
    let unc = a.1 > 0.0 && (!a.1.is_finite() || conv(a.0 as f64 - a.1) != conv(a.0 as f64 + a.1));
    if signed { V::I(a.0 as i32, unc) } else { V::U(a.0 as u32, unc) }
}

/// Integer to float `as`: WGSL may round either way where the integer is
/// not representable.
pub(super) fn i2f(x: f64, unc: bool) -> R<V> {
    let r = x as f32;
    let e = if unc {
        f64::INFINITY
    } else if x.abs() > 16777216.0 {
        ulp(r.abs() as f64)
    } else {
        0.0
    };
    let (r, e) = fin(r, e)?;
    Ok(V::F(r, e))
}

impl V {
    pub(super) fn f(&self) -> F {
        match self {
            V::F(v, e) => (*v, *e),
            other => panic!("expected an f32, found {other:?}"),
        }
    }

    pub(super) fn comps(&self) -> &[V] {
        match self {
            V::Vec(c) => c,
            other => panic!("expected a vector, found {other:?}"),
        }
    }

    pub(super) fn uncertain(&self) -> bool {
        match self {
            V::B(_, u) | V::I(_, u) | V::U(_, u) => *u,
            V::F(_, e) => *e > 0.0,
            V::Vec(c) | V::Struct(c) | V::Arr(c) => c.iter().any(|v| v.uncertain()),
        }
    }

    /// The value as an index or loop bound: certain, or the launch index
    /// diverges.
    pub(super) fn certain_u64(&self, what: &str) -> R<i64> {
        if self.uncertain() {
            return Err(Stop::Diverged(what.into()));
        }
        Ok(match self {
            V::I(i, _) => *i as i64,
            V::U(u, _) => *u as i64,
            other => panic!("expected an integer, found {other:?}"),
        })
    }

    pub(super) fn certain_bool(&self, what: &str) -> R<bool> {
        match self {
            V::B(_, true) => Err(Stop::Diverged(what.into())),
            V::B(b, false) => Ok(*b),
            other => panic!("expected a bool, found {other:?}"),
        }
    }

    /// Packs the value into words (the runtime's layout).
    pub fn words(&self, out: &mut Vec<Word>) {
        match self {
            V::B(b, u) => out.push(Word::Int(*b as u32, *u)),
            V::I(i, u) => out.push(Word::Int(*i as u32, *u)),
            V::U(x, u) => out.push(Word::Int(*x, *u)),
            V::F(f, e) => out.push(Word::Float(*f, *e)),
            V::Vec(c) | V::Struct(c) | V::Arr(c) => c.iter().for_each(|v| v.words(out)),
        }
    }

    /// The exact input value of type `t` from `words` (as the GPU loads it).
    pub fn from_words(p: &Program, t: &Ty, words: &mut impl Iterator<Item = u32>) -> V {
        match t {
            Ty::S(Scalar::Bool) => V::B(words.next().unwrap() != 0, false),
            Ty::S(Scalar::I32) => V::I(words.next().unwrap() as i32, false),
            Ty::S(Scalar::U32) => V::U(words.next().unwrap(), false),
            Ty::S(Scalar::F32) => V::F(f32::from_bits(words.next().unwrap()), 0.0),
            Ty::V(n, s) => V::Vec((0..*n).map(|_| V::from_words(p, &Ty::S(*s), words)).collect()),
            Ty::Struct(i) => V::Struct(p.structs[*i].fields.iter().map(|(_, f)| V::from_words(p, f, words)).collect()),
            Ty::Arr(e, n) => V::Arr((0..*n).map(|_| V::from_words(p, e, words)).collect()),
        }
    }

    /// A value of type `t` read back from interpreter words.
    pub(super) fn from_interp_words(p: &Program, t: &Ty, words: &mut impl Iterator<Item = Word>) -> V {
        let mut scalar = |s: Scalar| match (s, words.next().unwrap()) {
            (Scalar::F32, Word::Float(f, e)) => V::F(f, e),
            (Scalar::F32, Word::Int(b, u)) => V::F(f32::from_bits(b), if u { f64::INFINITY } else { 0.0 }),
            (Scalar::Bool, Word::Int(b, u)) => V::B(b != 0, u),
            (Scalar::I32, Word::Int(b, u)) => V::I(b as i32, u),
            (Scalar::U32, Word::Int(b, u)) => V::U(b, u),
            (s, w) => panic!("a {s:?} element holds {w:?}"),
        };
        match t {
            Ty::S(s) => scalar(*s),
            Ty::V(n, s) => V::Vec((0..*n).map(|_| scalar(*s)).collect()),
            Ty::Struct(i) => {
                V::Struct(p.structs[*i].fields.iter().map(|(_, f)| V::from_interp_words(p, f, words)).collect())
            }
            Ty::Arr(e, n) => V::Arr((0..*n).map(|_| V::from_interp_words(p, e, words)).collect()),
        }
    }
}

pub(super) fn map1(v: &V, f: &mut impl FnMut(&V) -> R<V>) -> R<V> {
    match v {
        V::Vec(c) => Ok(V::Vec(c.iter().map(&mut *f).collect::<R<_>>()?)),
        s => f(s),
    }
}

/// Applies a scalar operation component-wise, broadcasting scalars.
pub(super) fn zip(a: &V, b: &V, f: &mut impl FnMut(&V, &V) -> R<V>) -> R<V> {
    match (a, b) {
        (V::Vec(x), V::Vec(y)) => Ok(V::Vec(x.iter().zip(y).map(|(p, q)| f(p, q)).collect::<R<_>>()?)),
        (V::Vec(x), s) => Ok(V::Vec(x.iter().map(|p| f(p, s)).collect::<R<_>>()?)),
        (s, V::Vec(y)) => Ok(V::Vec(y.iter().map(|q| f(s, q)).collect::<R<_>>()?)),
        (p, q) => f(p, q),
    }
}

pub(super) fn zip3(a: &V, b: &V, c: &V, f: &mut impl FnMut(&V, &V, &V) -> R<V>) -> R<V> {
    let n = [a, b, c].iter().find_map(|v| if let V::Vec(x) = v { Some(x.len()) } else { None });
    match n {
        None => f(a, b, c),
        Some(n) => {
            let at = |v: &V, i: usize| if let V::Vec(x) = v { x[i].clone() } else { v.clone() };
            Ok(V::Vec((0..n).map(|i| f(&at(a, i), &at(b, i), &at(c, i))).collect::<R<_>>()?))
        }
    }
}

pub(super) fn fv(r: R<F>) -> R<V> {
    r.map(|(v, e)| V::F(v, e))
}
