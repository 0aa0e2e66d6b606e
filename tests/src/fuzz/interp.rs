//! The CPU side: an interpreter of the generator's AST with Rust's
//! semantics, which tracks how far a conforming GPU may stray from each
//! value.
//!
//! ## Semantics
//! Values are computed exactly as the Rust program computes them on the
//! host (x86-64 or aarch64): glam's formulas for vector methods (`Vec4` is
//! SIMD there, and its `%` is `x - floor(x / y) * y`, unlike `Vec2`/`Vec3`'s
//! `f32` `%`), rt-std's for `mix`, `step`, `smoothstep`, `saturate`, Rust's
//! own `f32` methods; the order of evaluation and of borrows is Rust's
//! (operands left to right, an assignment's value before its place unless
//! it is a trait `op=`). `native` checks all this against rustc. Where Rust
//! itself has more than one behaviour the interpreter picks the one the
//! compiler lowers to:
//!
//! - integer `+ - *`, negation, `abs`, glam's vector `+ - *`, `dot` and
//!   `element_sum`/`element_product` **wrap** (Rust with overflow checks
//!   off, as in release builds; WGSL's integer arithmetic wraps);
//! - shift amounts are taken **modulo 32** (Rust's release behaviour,
//!   `wrapping_shl`; WGSL's rule for shifts);
//! - integer division or remainder by zero and `i32::MIN / -1` panic in
//!   Rust whatever the build: the generator never produces them (divisors
//!   are built to be non-zero and not -1, see `generate`) and the
//!   interpreter panics if one occurs, as a generator bug;
//! - float-to-integer `as` saturates and truncates (Rust; the compiler
//!   lowers it so). NaN never reaches a cast: see below.
//!
//! ## What a GPU may do differently
//! Every `f32` carries an absolute error bound `err`: how far the GPU's
//! value may be from the interpreter's while both conform, following WGSL's
//! accuracy rules (WGSL §"Floating Point Accuracy", f32): comparisons,
//! `abs`/`min`/`max`/`clamp`, rounding functions, `fract`, casts and
//! scalar `%` (the compiler's exact `fmod`) are exact; `+ - *` are
//! correctly rounded, but shader compilers reassociate chains of them
//! (Mesa does for every operation SPIR-V does not mark exact), so they get
//! one ULP of the larger operand (two of the result for `*`) unless every
//! value is a small multiple of 2^-10 and no sum cancels, when every order
//! is exact; `/` is
//! 2.5 ULP; `sqrt` (inherited from `1 / inverseSqrt`) 5 ULP; `exp`/`exp2`
//! `3 + 2|x|` ULP; `ln`/`log2` 2^-21 absolute in [0.5, 2], else 3 ULP;
//! `sin`/`cos` 2^-11 absolute in [-pi, pi] and unbounded (within [-1, 1])
//! outside; `atan` 4096 ULP; `powf` inherited from `exp2(y * log2(x))`;
//! functions WGSL defines by a formula (`fma` as `a * b + c` — lavapipe's
//! `fma` is not fused —, `smoothstep`, `dot`, `length`, `distance`,
//! `normalize`, `cross`, `radians`...) and the compiler's formulas (`mix`
//! and `lerp` as `a * (1 - t) + b * t`) are evaluated with glam's/Rust's
//! formula and an allowance of one rounding per operation, since the GPU
//! may order, fuse or split them differently. Errors propagate through later
//! operations (interval-style, by magnitude; step functions and `fract`
//! jump where the interval crosses an integer). Integer and bool values
//! carry an `uncertain` flag instead: set when they derive from a float
//! whose error bound straddles a decision (a comparison within the error,
//! a cast or `floor` near an integer).
//!
//! A launch index is left out of the comparison (a *skip*, counted and
//! reported) only where WGSL leaves the result undefined or the bounds above
//! cannot decide it:
//!
//! - a NaN or infinite `f32` anywhere (WGSL implementations may assume
//!   they do not occur; overflowing products, `exp` of large values);
//! - control flow, an index or a `match` that depends on an uncertain
//!   value (the GPU may legitimately take the other path);
//!
//! and single output words are left out when they are uncertain integers
//! or floats with an unbounded error. Everything else must match: integers
//! and bools exactly, floats within `err` plus 2 ULP, with `+0.0 == -0.0`
//! and subnormals equal to zero (WGSL promises neither the sign of a zero
//! nor subnormal support; a subnormal intermediate adds `MIN_POSITIVE` to
//! its error).

use super::ast::*;

/// A value, with what a conforming GPU may differ by.
#[derive(Clone, Debug, PartialEq)]
pub enum V {
    /// A bool and whether it is uncertain.
    B(bool, bool),
    I(i32, bool),
    U(u32, bool),
    /// An `f32` and its absolute error bound.
    F(f32, f64),
    Vec(Vec<V>),
    Struct(Vec<V>),
    Arr(Vec<V>),
}

/// Why a launch index is not compared.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    NonFinite(String),
    Diverged(String),
}

/// One word of an output buffer as the interpreter wrote it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Word {
    /// An integer or bool word, and whether it is uncertain.
    Int(u32, bool),
    /// A float word and its error bound.
    Float(f32, f64),
}

enum Flow {
    Normal,
    Break,
    Continue,
    Return(Option<V>),
}

type R<T> = Result<T, Stop>;

/// Runs `p` for launch index `lane` with `inputs` (one value per input, in
/// order); returns each output buffer's words for this lane (`slots`
/// elements from `lane * slots`).
pub fn run(p: &Program, lane: u32, inputs: &[V]) -> Result<Vec<Vec<Word>>, Stop> {
    let outputs = p.outputs.iter().map(|(_, t)| vec![Word::Int(0, false); (p.words(t) * p.slots) as usize]).collect();
    let mut it = Interp { p, scopes: vec![Vec::new()], outputs, lane, steps: 0 };
    for ((n, _), v) in p.inputs.iter().zip(inputs) {
        it.bind(n, v.clone());
    }
    match it.block(&p.body)? {
        (Flow::Normal | Flow::Return(_), _) => {}
        _ => panic!("break or continue outside a loop"),
    }
    Ok(it.outputs)
}

struct Interp<'p> {
    p: &'p Program,
    scopes: Vec<Vec<(String, V)>>,
    outputs: Vec<Vec<Word>>,
    lane: u32,
    steps: u64,
}

// ---- float error arithmetic ----

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

type F = (f32, f64);

/// A float result: NaN and infinities stop the launch index; subnormal
/// values may be flushed.
fn fin(r: f32, e: f64) -> R<F> {
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
fn rounded(r: f32, e: f64, loose: bool) -> f64 {
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

fn fadd(a: F, b: F, loose: bool) -> R<F> {
    let r = a.0 + b.0;
    fin(r, rounded(r, a.1 + b.1 + reassociation(a.0, b.0, r, false), loose))
}

fn fsub(a: F, b: F, loose: bool) -> R<F> {
    let r = a.0 - b.0;
    fin(r, rounded(r, a.1 + b.1 + reassociation(a.0, b.0, r, false), loose))
}

fn fmul(a: F, b: F, loose: bool) -> R<F> {
    let r = a.0 * b.0;
    let prod = |x: f64, y: f64| if x == 0.0 || y == 0.0 { 0.0 } else { x * y };
    let e = prod(a.0.abs() as f64, b.1) + prod(b.0.abs() as f64, a.1) + prod(a.1, b.1);
    fin(r, rounded(r, e + reassociation(a.0, b.0, r, true), loose))
}

/// `/`: 2.5 ULP in WGSL.
fn fdiv(a: F, b: F) -> R<F> {
    let r = a.0 / b.0;
    let bm = b.0.abs() as f64;
    let e = if bm <= b.1 { f64::INFINITY } else { (a.1 + r.abs() as f64 * b.1) / (bm - b.1) };
    fin(r, e + 2.5 * ulp(r.abs() as f64 + e))
}

/// Rust's `%` (fmod), which the compiler lowers to an exact `rt_fmod`: a
/// jump of `|b|` where the quotient crosses an integer within the error.
fn frem(a: F, b: F) -> R<F> {
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
fn funary(a: F, r: f32, ulps: f64, abs: f64, f: impl Fn(f64) -> f64) -> R<F> {
    let e = spread(a.0 as f64, a.1, f) + ulps * ulp(r.abs() as f64) + abs;
    fin(r, e)
}

/// A monotonic step function of `a` (floor, trunc...): exact, but the
/// error may jump.
fn fstep(a: F, f: impl Fn(f32) -> f32) -> R<F> {
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
fn ffract(a: F, f: impl Fn(f32) -> f32) -> R<F> {
    let r = a.0 - f(a.0);
    let re = reassociation(a.0, f(a.0), r, false);
    if a.1 == 0.0 {
        return fin(r, re);
    }
    let crosses = f((a.0 as f64 - a.1) as f32) != f((a.0 as f64 + a.1) as f32);
    fin(r, re + if crosses { 1.0 + a.1 } else { a.1 })
}

fn fcmp(op: BinOp, a: F, b: F) -> V {
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
fn f2i(a: F, signed: bool) -> V {
    let conv = |x: f64| if signed { (x as f32) as i32 as i64 } else { (x as f32) as u32 as i64 };
    let unc = a.1 > 0.0 && (!a.1.is_finite() || conv(a.0 as f64 - a.1) != conv(a.0 as f64 + a.1));
    if signed { V::I(a.0 as i32, unc) } else { V::U(a.0 as u32, unc) }
}

/// Integer to float `as`: WGSL may round either way where the integer is
/// not representable.
fn i2f(x: f64, unc: bool) -> R<V> {
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
    fn f(&self) -> F {
        match self {
            V::F(v, e) => (*v, *e),
            other => panic!("expected an f32, found {other:?}"),
        }
    }

    fn comps(&self) -> &[V] {
        match self {
            V::Vec(c) => c,
            other => panic!("expected a vector, found {other:?}"),
        }
    }

    fn uncertain(&self) -> bool {
        match self {
            V::B(_, u) | V::I(_, u) | V::U(_, u) => *u,
            V::F(_, e) => *e > 0.0,
            V::Vec(c) | V::Struct(c) | V::Arr(c) => c.iter().any(|v| v.uncertain()),
        }
    }

    /// The value as an index or loop bound: certain, or the launch index
    /// diverges.
    fn certain_u64(&self, what: &str) -> R<i64> {
        if self.uncertain() {
            return Err(Stop::Diverged(what.into()));
        }
        Ok(match self {
            V::I(i, _) => *i as i64,
            V::U(u, _) => *u as i64,
            other => panic!("expected an integer, found {other:?}"),
        })
    }

    fn certain_bool(&self, what: &str) -> R<bool> {
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
    fn from_interp_words(p: &Program, t: &Ty, words: &mut impl Iterator<Item = Word>) -> V {
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

fn map1(v: &V, f: &mut impl FnMut(&V) -> R<V>) -> R<V> {
    match v {
        V::Vec(c) => Ok(V::Vec(c.iter().map(&mut *f).collect::<R<_>>()?)),
        s => f(s),
    }
}

/// Applies a scalar operation component-wise, broadcasting scalars.
fn zip(a: &V, b: &V, f: &mut impl FnMut(&V, &V) -> R<V>) -> R<V> {
    match (a, b) {
        (V::Vec(x), V::Vec(y)) => Ok(V::Vec(x.iter().zip(y).map(|(p, q)| f(p, q)).collect::<R<_>>()?)),
        (V::Vec(x), s) => Ok(V::Vec(x.iter().map(|p| f(p, s)).collect::<R<_>>()?)),
        (s, V::Vec(y)) => Ok(V::Vec(y.iter().map(|q| f(s, q)).collect::<R<_>>()?)),
        (p, q) => f(p, q),
    }
}

fn zip3(a: &V, b: &V, c: &V, f: &mut impl FnMut(&V, &V, &V) -> R<V>) -> R<V> {
    let n = [a, b, c].iter().find_map(|v| if let V::Vec(x) = v { Some(x.len()) } else { None });
    match n {
        None => f(a, b, c),
        Some(n) => {
            let at = |v: &V, i: usize| if let V::Vec(x) = v { x[i].clone() } else { v.clone() };
            Ok(V::Vec((0..n).map(|i| f(&at(a, i), &at(b, i), &at(c, i))).collect::<R<_>>()?))
        }
    }
}

fn fv(r: R<F>) -> R<V> {
    r.map(|(v, e)| V::F(v, e))
}

/// A binary operator on scalars (both sides of one type, except shifts).
fn scalar_bin(op: BinOp, a: &V, b: &V) -> R<V> {
    use BinOp::*;
    Ok(match (a, b) {
        (V::F(..), V::F(..)) => {
            let (x, y) = (a.f(), b.f());
            match op {
                Add => fv(fadd(x, y, false))?,
                Sub => fv(fsub(x, y, false))?,
                Mul => fv(fmul(x, y, false))?,
                Div => fv(fdiv(x, y))?,
                Rem => fv(frem(x, y))?,
                Eq | Ne | Lt | Le | Gt | Ge => fcmp(op, x, y),
                _ => panic!("{op:?} on f32"),
            }
        }
        (V::I(x, u), _) if matches!(op, Shl | Shr) => {
            let (s, su) = shift_amount(b);
            let r = if op == Shl { x.wrapping_shl(s) } else { x.wrapping_shr(s) };
            V::I(r, *u || su)
        }
        (V::U(x, u), _) if matches!(op, Shl | Shr) => {
            let (s, su) = shift_amount(b);
            let r = if op == Shl { x.wrapping_shl(s) } else { x.wrapping_shr(s) };
            V::U(r, *u || su)
        }
        (V::I(x, xu), V::I(y, yu)) => {
            let u = *xu || *yu;
            let (x, y) = (*x, *y);
            match op {
                Add => V::I(x.wrapping_add(y), u),
                Sub => V::I(x.wrapping_sub(y), u),
                Mul => V::I(x.wrapping_mul(y), u),
                // `rt_std::arith`: `x / 0` is `x`, `x % 0` is 0, `MIN / -1`
                // wraps.
                Div | Rem if y == 0 => V::I(if op == Div { x } else { 0 }, u),
                Div => V::I(x.wrapping_div(y), u),
                Rem => V::I(x.wrapping_rem(y), u),
                BitAnd => V::I(x & y, u),
                BitOr => V::I(x | y, u),
                BitXor => V::I(x ^ y, u),
                Eq => V::B(x == y, u),
                Ne => V::B(x != y, u),
                Lt => V::B(x < y, u),
                Le => V::B(x <= y, u),
                Gt => V::B(x > y, u),
                Ge => V::B(x >= y, u),
                _ => panic!("{op:?} on i32"),
            }
        }
        (V::U(x, xu), V::U(y, yu)) => {
            let u = *xu || *yu;
            let (x, y) = (*x, *y);
            match op {
                Add => V::U(x.wrapping_add(y), u),
                Sub => V::U(x.wrapping_sub(y), u),
                Mul => V::U(x.wrapping_mul(y), u),
                Div | Rem if y == 0 => V::U(if op == Div { x } else { 0 }, u),
                Div => V::U(x / y, u),
                Rem => V::U(x % y, u),
                BitAnd => V::U(x & y, u),
                BitOr => V::U(x | y, u),
                BitXor => V::U(x ^ y, u),
                Eq => V::B(x == y, u),
                Ne => V::B(x != y, u),
                Lt => V::B(x < y, u),
                Le => V::B(x <= y, u),
                Gt => V::B(x > y, u),
                Ge => V::B(x >= y, u),
                _ => panic!("{op:?} on u32"),
            }
        }
        (V::B(x, xu), V::B(y, yu)) => {
            let u = *xu || *yu;
            match op {
                BitAnd | And => V::B(*x & *y, u),
                BitOr | Or => V::B(*x | *y, u),
                BitXor | Ne => V::B(*x ^ *y, u),
                Eq => V::B(x == y, u),
                _ => panic!("{op:?} on bool"),
            }
        }
        _ => panic!("{op:?} on {a:?} and {b:?}"),
    })
}

fn shift_amount(b: &V) -> (u32, bool) {
    match b {
        V::I(s, u) => (*s as u32, *u),
        V::U(s, u) => (*s, *u),
        other => panic!("shift by {other:?}"),
    }
}

/// `a op b` on scalars or vectors (glam's operators are component-wise;
/// vector `==` compares all components).
fn bin(op: BinOp, a: &V, b: &V) -> R<V> {
    match (op, a, b) {
        (BinOp::Eq | BinOp::Ne, V::Vec(x), V::Vec(y)) => {
            // Three-valued: a certain difference decides.
            let mut any_diff = false;
            let mut unc = false;
            for (p, q) in x.iter().zip(y) {
                match scalar_bin(BinOp::Ne, p, q)? {
                    V::B(true, false) => any_diff = true,
                    V::B(_, true) => unc = true,
                    _ => {}
                }
            }
            let ne = if any_diff { (true, false) } else { (false, unc) };
            Ok(V::B(if op == BinOp::Ne { ne.0 } else { !ne.0 }, ne.1))
        }
        // glam's `Vec4` is SIMD (SSE2 here, NEON, wasm) and its `%` is
        // `x - floor(x / y) * y`, unlike `f32`'s `%` (`Vec2`, `Vec3`).
        (BinOp::Rem, V::Vec(x), _) if x.len() == 4 && matches!(x[0], V::F(..)) => zip(a, b, &mut |p, q| {
            let (x, y) = (p.f(), q.f());
            let n = fstep(fdiv(x, y)?, f32::floor)?;
            fv(fsub(x, fmul(n, y, false)?, false))
        }),
        (BinOp::Rem, _, V::Vec(y)) if y.len() == 4 && matches!(y[0], V::F(..)) => {
            bin(op, &V::Vec(vec![a.clone(); 4]), b)
        }
        _ => zip(a, b, &mut |p, q| scalar_bin(op, p, q)),
    }
}

/// Composite float helpers evaluated with glam's/rt-std's formulas and a
/// rounding allowance per operation (`loose`).
mod loose {
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

impl Interp<'_> {
    fn bind(&mut self, n: &str, v: V) {
        self.scopes.last_mut().unwrap().push((n.to_string(), v));
    }

    fn var(&self, n: &str) -> V {
        self.scopes
            .iter()
            .rev()
            .flat_map(|s| s.iter().rev())
            .find(|(m, _)| m == n)
            .map(|(_, v)| v.clone())
            .unwrap_or_else(|| panic!("no variable `{n}`"))
    }

    fn var_mut(&mut self, n: &str) -> &mut V {
        self.scopes
            .iter_mut()
            .rev()
            .flat_map(|s| s.iter_mut().rev())
            .find(|(m, _)| m == n)
            .map(|(_, v)| v)
            .unwrap_or_else(|| panic!("no variable `{n}`"))
    }

    /// `RT_FUZZ_TRACE=<launch index>` prints every value bound or assigned.
    fn trace(&self, name: &str, v: &V) {
        if std::env::var("RT_FUZZ_TRACE").ok().and_then(|l| l.parse::<u32>().ok()) == Some(self.lane) {
            eprintln!("[{}] {name} = {v:?}", self.lane);
        }
    }

    fn tick(&mut self) {
        self.steps += 1;
        assert!(self.steps < 1_000_000, "generator bug: a program runs too long");
    }

    fn block(&mut self, b: &Block) -> R<(Flow, Option<V>)> {
        self.scopes.push(Vec::new());
        let r = self.block_inner(b);
        self.scopes.pop();
        r
    }

    fn block_inner(&mut self, b: &Block) -> R<(Flow, Option<V>)> {
        for s in &b.stmts {
            match self.stmt(s)? {
                Flow::Normal => {}
                f => return Ok((f, None)),
            }
        }
        match &b.tail {
            Some(e) => Ok((Flow::Normal, Some(self.expr(e)?))),
            None => Ok((Flow::Normal, None)),
        }
    }

    /// A block used as a value: its tail, or the value it returns from the
    /// helper (`Flow::Return`) passed up.
    fn value_block(&mut self, b: &Block) -> R<Result<V, Flow>> {
        match self.block(b)? {
            (Flow::Normal, Some(v)) => Ok(Ok(v)),
            (f @ (Flow::Return(_) | Flow::Break | Flow::Continue), _) => Ok(Err(f)),
            (Flow::Normal, None) => panic!("a value block without a value"),
        }
    }

    fn stmt(&mut self, s: &Stmt) -> R<Flow> {
        self.tick();
        match s {
            Stmt::Let { name, init, .. } => {
                let v = self.expr(init)?;
                self.trace(name, &v);
                self.bind(name, v);
            }
            Stmt::Assign(place, op, value) => {
                // Rust evaluates the value, then the place (indices); but
                // `op=` on a vector or struct is a trait call whose `&mut`
                // place comes first.
                let place_first = op.is_some() && !self.place_is_scalar(place);
                let early = if place_first { Some(self.place_path(place)?) } else { None };
                let v = self.expr(value)?;
                let path = match early {
                    Some(p) => p,
                    None => self.place_path(place)?,
                };
                let cur = self.read_path(&path);
                let new = match op {
                    None => v,
                    Some(op) => bin(*op, &cur, &v)?,
                };
                self.trace(&path.0, &new);
                self.write_path(&path, new);
            }
            Stmt::If(c, t, e) => {
                let c = self.expr(c)?.certain_bool("an `if` condition")?;
                let r = if c {
                    self.block(t)?
                } else if let Some(e) = e {
                    self.block(e)?
                } else {
                    (Flow::Normal, None)
                };
                return Ok(r.0);
            }
            Stmt::For { var, ty, start, end, inclusive, body } => {
                let end = self.expr(end)?.certain_u64("a loop bound")?;
                let last = if *inclusive { end } else { end - 1 };
                let mut i = *start;
                while i <= last {
                    self.tick();
                    self.scopes.push(Vec::new());
                    let v = if *ty == Scalar::I32 { V::I(i as i32, false) } else { V::U(i as u32, false) };
                    self.bind(var, v);
                    let r = self.block(body);
                    self.scopes.pop();
                    match r?.0 {
                        Flow::Break => break,
                        f @ Flow::Return(_) => return Ok(f),
                        _ => {}
                    }
                    i += 1;
                }
            }
            Stmt::While(c, body) => loop {
                self.tick();
                if !self.expr(c)?.certain_bool("a `while` condition")? {
                    break;
                }
                match self.block(body)?.0 {
                    Flow::Break => break,
                    f @ Flow::Return(_) => return Ok(f),
                    _ => {}
                }
            },
            Stmt::Loop(body) => loop {
                self.tick();
                match self.block(body)?.0 {
                    Flow::Break => break,
                    f @ Flow::Return(_) => return Ok(f),
                    _ => {}
                }
            },
            Stmt::Break => return Ok(Flow::Break),
            Stmt::Continue => return Ok(Flow::Continue),
            Stmt::Match(e, arms) => {
                let v = self.expr(e)?;
                let arm = self.pick_arm(&v, arms)?;
                self.scopes.push(Vec::new());
                if let Some(b) = &arm.bind {
                    self.bind(b, v.clone());
                }
                let r = self.block(&arm.body);
                self.scopes.pop();
                return Ok(r?.0);
            }
            Stmt::Store { buf, index, value, form } => {
                // `buf.store(i, v)` evaluates `i` first; `buf[i] = v` (and
                // `op=`) evaluates `v` first, as Rust does for `IndexMut`
                // assignments of `Copy` values.
                let (i, v) = match form {
                    StoreForm::Method => {
                        let i = self.expr(index)?;
                        (i, self.expr(value)?)
                    }
                    _ => {
                        let v = self.expr(value)?;
                        (self.expr(index)?, v)
                    }
                };
                let i = i.certain_u64("a store index")?;
                let v = match form {
                    StoreForm::Compound(op) => bin(*op, &self.load(*buf, i), &v)?,
                    _ => v,
                };
                self.store(*buf, i, &v);
            }
            Stmt::Expr(e) => {
                self.expr(e)?;
            }
            Stmt::Return(e) => {
                let v = e.as_ref().map(|e| self.expr(e)).transpose()?;
                return Ok(Flow::Return(v));
            }
        }
        Ok(Flow::Normal)
    }

    fn local_index(&self, i: i64) -> usize {
        let slots = self.p.slots as i64;
        assert!(i / slots == self.lane as i64 && i >= 0, "generator bug: lane {} accesses element {i}", self.lane);
        (i % slots) as usize
    }

    fn load(&self, buf: usize, i: i64) -> V {
        let t = &self.p.outputs[buf].1;
        let w = self.p.words(t) as usize;
        let k = self.local_index(i);
        let mut it = self.outputs[buf][k * w..(k + 1) * w].iter().copied();
        V::from_interp_words(self.p, t, &mut it)
    }

    fn store(&mut self, buf: usize, i: i64, v: &V) {
        let w = self.p.words(&self.p.outputs[buf].1) as usize;
        let k = self.local_index(i);
        let mut words = Vec::new();
        v.words(&mut words);
        assert_eq!(words.len(), w);
        self.outputs[buf][k * w..(k + 1) * w].copy_from_slice(&words);
    }

    fn pick_arm<'a>(&self, v: &V, arms: &'a [Arm]) -> R<&'a Arm> {
        let x = v.certain_u64("a `match` scrutinee")?;
        for a in arms {
            let hit = a.pats.is_empty()
                || a.pats.iter().any(|p| match p {
                    LitV::I32(i) => *i as i64 == x,
                    LitV::U32(u) => *u as i64 == x,
                    _ => false,
                });
            if hit {
                return Ok(a);
            }
        }
        panic!("generator bug: no arm matches {x}");
    }

    /// A place as a variable name and a path of component indices, with
    /// index expressions evaluated.
    fn place_path(&mut self, p: &Place) -> R<(String, Vec<usize>)> {
        Ok(match p {
            Place::Var(n) | Place::Deref(n) => (n.clone(), Vec::new()),
            Place::Field(b, _, i) => {
                let (n, mut path) = self.place_path(b)?;
                path.push(*i);
                (n, path)
            }
            Place::Index(b, i) => {
                let (n, mut path) = self.place_path(b)?;
                let k = self.expr(i)?.certain_u64("an index")?;
                path.push(k as usize);
                (n, path)
            }
        })
    }

    /// Whether a place holds a scalar (its indices unevaluated).
    fn place_is_scalar(&self, p: &Place) -> bool {
        fn at(v: V, p: &Place, interp: &Interp<'_>) -> V {
            match p {
                Place::Var(n) | Place::Deref(n) => interp.var(n),
                Place::Field(b, _, i) => match at(v, b, interp) {
                    V::Vec(c) | V::Struct(c) | V::Arr(c) => c[*i].clone(),
                    other => other,
                },
                Place::Index(b, _) => match at(v, b, interp) {
                    V::Vec(c) | V::Struct(c) | V::Arr(c) => c[0].clone(),
                    other => other,
                },
            }
        }
        matches!(at(V::B(false, false), p, self), V::B(..) | V::I(..) | V::U(..) | V::F(..))
    }

    fn read_path(&self, (n, path): &(String, Vec<usize>)) -> V {
        let mut v = self.var(n);
        for i in path {
            v = match v {
                V::Vec(c) | V::Struct(c) | V::Arr(c) => c[*i].clone(),
                other => panic!("cannot index {other:?}"),
            };
        }
        v
    }

    fn write_path(&mut self, (n, path): &(String, Vec<usize>), new: V) {
        let mut v = self.var_mut(n);
        for i in path {
            v = match v {
                V::Vec(c) | V::Struct(c) | V::Arr(c) => &mut c[*i],
                other => panic!("cannot index {other:?}"),
            };
        }
        *v = new;
    }

    fn exprs(&mut self, xs: &[Expr]) -> R<Vec<V>> {
        xs.iter().map(|x| self.expr(x)).collect()
    }

    pub fn expr(&mut self, e: &Expr) -> R<V> {
        Ok(match e {
            Expr::Lit(l) => match l.v {
                LitV::Bool(b) => V::B(b, false),
                LitV::I32(i) => V::I(i, false),
                LitV::U32(u) => V::U(u, false),
                LitV::F32(f) => V::F(f, 0.0),
            },
            Expr::Var(n) | Expr::Deref(n) => self.var(n),
            Expr::LaunchX => V::U(self.lane, false),
            Expr::Field(b, _, i) => match self.expr(b)? {
                V::Vec(c) | V::Struct(c) => c[*i].clone(),
                other => panic!("field of {other:?}"),
            },
            Expr::Index(b, i) => {
                let base = self.expr(b)?;
                let k = self.expr(i)?.certain_u64("an index")? as usize;
                match base {
                    V::Vec(c) | V::Arr(c) => c[k].clone(),
                    other => panic!("index into {other:?}"),
                }
            }
            Expr::Unary(op, x) => {
                let v = self.expr(x)?;
                map1(&v, &mut |s| {
                    Ok(match (op, s) {
                        (UnOp::Neg, V::F(f, e)) => V::F(-f, *e),
                        (UnOp::Neg, V::I(i, u)) => V::I(i.wrapping_neg(), *u),
                        (UnOp::Not, V::I(i, u)) => V::I(!i, *u),
                        (UnOp::Not, V::U(i, u)) => V::U(!i, *u),
                        (UnOp::Not, V::B(b, u)) => V::B(!b, *u),
                        (op, v) => panic!("{op:?} on {v:?}"),
                    })
                })?
            }
            Expr::Bin(op @ (BinOp::And | BinOp::Or), a, b) => {
                let l = self.expr(a)?;
                let V::B(lv, lu) = l else { panic!("&& on {l:?}") };
                let and = *op == BinOp::And;
                if lu {
                    if b.has_effects(self.p) {
                        return Err(Stop::Diverged("a short-circuit with effects on an uncertain bool".into()));
                    }
                    let r = self.expr(b)?;
                    let V::B(rv, _) = r else { panic!() };
                    return Ok(V::B(if and { lv && rv } else { lv || rv }, true));
                }
                if lv != and {
                    return Ok(V::B(lv, false));
                }
                self.expr(b)?
            }
            Expr::Bin(op, a, b) => {
                let l = self.expr(a)?;
                let r = self.expr(b)?;
                bin(*op, &l, &r)?
            }
            Expr::Cast(x, s) => {
                let v = self.expr(x)?;
                cast(&v, *s)?
            }
            Expr::Method(r, m, args) => {
                let recv = self.expr(r)?;
                let args = self.exprs(args)?;
                method(&recv, m, &args)?
            }
            Expr::Path(t, f, args) => {
                let args = self.exprs(args)?;
                match *f {
                    "new" => V::Vec(args),
                    "splat" => {
                        let Some(Ty::V(n, _)) = Ty::from_name(t) else { panic!("{t}::splat") };
                        V::Vec(vec![args[0].clone(); n as usize])
                    }
                    _ => method(&args[0], f, &args[1..])?,
                }
            }
            Expr::Free(f, args) => {
                let args = self.exprs(args)?;
                free(f, &args)?
            }
            Expr::Const(t, n) => constant(t, n),
            Expr::Call(h, args) => self.call(*h, args)?,
            Expr::StructLit(i, fields) => {
                let mut vals = vec![None; self.p.structs[*i].fields.len()];
                for (k, x) in fields {
                    vals[*k] = Some(self.expr(x)?);
                }
                V::Struct(vals.into_iter().map(|v| v.expect("every field")).collect())
            }
            Expr::ArrayLit(xs) => V::Arr(self.exprs(xs)?),
            Expr::ArrayRepeat(x, n) => V::Arr(vec![self.expr(x)?; *n as usize]),
            Expr::If(c, t, e) => {
                let c = self.expr(c)?.certain_bool("an `if` condition")?;
                match self.value_block(if c { t } else { e })? {
                    Ok(v) => v,
                    Err(_) => panic!("generator bug: control flow out of an `if` expression"),
                }
            }
            Expr::Match(x, arms) => {
                let v = self.expr(x)?;
                let arm = self.pick_arm(&v, arms)?;
                self.scopes.push(Vec::new());
                if let Some(b) = &arm.bind {
                    self.bind(b, v.clone());
                }
                let r = self.value_block(&arm.body);
                self.scopes.pop();
                match r? {
                    Ok(v) => v,
                    Err(_) => panic!("generator bug: control flow out of a `match` expression"),
                }
            }
            Expr::BufLoad(b, i, _) => {
                let k = self.expr(i)?.certain_u64("a load index")?;
                self.load(*b, k)
            }
        })
    }

    fn call(&mut self, h: usize, args: &[Arg]) -> R<V> {
        let helper = &self.p.helpers[h];
        // Arguments left to right; `&mut x` is copied in and out (no other
        // argument may name `x`, as Rust's borrow checker requires).
        let mut frame = Vec::new();
        let mut refs = Vec::new();
        for (a, p) in args.iter().zip(&helper.params) {
            match (a, p) {
                (Arg::Val(e), Param::Val(n, _)) => frame.push((n.clone(), self.expr(e)?)),
                (Arg::MutRef(v), Param::MutRef(n, _)) => {
                    frame.push((n.clone(), self.var(v)));
                    refs.push((v.clone(), n.clone()));
                }
                _ => panic!("argument kinds of `{}`", helper.name),
            }
        }
        let saved = std::mem::replace(&mut self.scopes, vec![frame]);
        let r = self.block(&helper.body);
        let callee = std::mem::replace(&mut self.scopes, saved);
        let (flow, tail) = r?;
        for (caller, param) in refs {
            let v = callee[0].iter().find(|(n, _)| *n == param).expect("the parameter").1.clone();
            *self.var_mut(&caller) = v;
        }
        let ret = match flow {
            Flow::Return(v) => v,
            Flow::Normal => tail,
            _ => panic!("break out of a helper"),
        };
        assert_eq!(ret.is_some(), helper.ret.is_some(), "helper `{}` returns", helper.name);
        Ok(ret.unwrap_or(V::B(false, false)))
    }
}

/// `as` between scalars (component-wise for glam's `as_*vecN`).
fn cast(v: &V, to: Scalar) -> R<V> {
    map1(v, &mut |s| {
        Ok(match (s, to) {
            (V::F(f, e), Scalar::I32) => f2i((*f, *e), true),
            (V::F(f, e), Scalar::U32) => f2i((*f, *e), false),
            (V::F(f, e), Scalar::F32) => V::F(*f, *e),
            (V::I(i, u), Scalar::F32) => i2f(*i as f64, *u)?,
            (V::U(i, u), Scalar::F32) => i2f(*i as f64, *u)?,
            (V::I(i, u), Scalar::I32) => V::I(*i, *u),
            (V::I(i, u), Scalar::U32) => V::U(*i as u32, *u),
            (V::U(i, u), Scalar::I32) => V::I(*i as i32, *u),
            (V::U(i, u), Scalar::U32) => V::U(*i, *u),
            (V::B(b, u), Scalar::I32) => V::I(*b as i32, *u),
            (V::B(b, u), Scalar::U32) => V::U(*b as u32, *u),
            (v, s) => panic!("cast {v:?} as {s:?}"),
        })
    })
}

fn constant(t: &str, n: &str) -> V {
    let f = |x: f32| V::F(x, 0.0);
    match (t, n) {
        ("", "PI") => f(std::f32::consts::PI),
        ("", "TAU") => f(std::f32::consts::TAU),
        ("", "E") => f(std::f32::consts::E),
        ("", "SQRT_2") => f(std::f32::consts::SQRT_2),
        ("f32", "EPSILON") => f(f32::EPSILON),
        ("f32", "MIN_POSITIVE") => f(f32::MIN_POSITIVE),
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
fn free(f: &str, a: &[V]) -> R<V> {
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
fn method(r: &V, m: &str, a: &[V]) -> R<V> {
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
    let comp_wise = |f: &mut dyn FnMut(&V) -> R<V>| -> R<V> { map1(r, &mut |s| f(s)) };
    match (r, m) {
        // ---- reductions and geometry on vectors ----
        (V::Vec(c), "dot") => return dot(c, a[0].comps()),
        (V::Vec(c), "length_squared") => return dot(c, c),
        (V::Vec(c), "length") => return fv(loose::length(c)),
        (V::Vec(_), "distance") => {
            let d = bin(BinOp::Sub, r, &a[0])?;
            return fv(loose::length(d.comps()));
        }
        (V::Vec(_), "distance_squared") => {
            let d = bin(BinOp::Sub, r, &a[0])?;
            return dot(d.comps(), d.comps());
        }
        (V::Vec(c), "element_sum") => {
            return c[1..].iter().try_fold(c[0].clone(), |acc, x| loose_bin(BinOp::Add, &acc, x));
        }
        (V::Vec(c), "element_product") => {
            return c[1..].iter().try_fold(c[0].clone(), |acc, x| loose_bin(BinOp::Mul, &acc, x));
        }
        (V::Vec(c), "min_element") => return c[1..].iter().try_fold(c[0].clone(), |acc, x| min_max(&acc, x, true)),
        (V::Vec(c), "max_element") => return c[1..].iter().try_fold(c[0].clone(), |acc, x| min_max(&acc, x, false)),
        (V::Vec(c), "extend") => {
            let mut c = c.clone();
            c.push(a[0].clone());
            return Ok(V::Vec(c));
        }
        (V::Vec(c), "truncate") => return Ok(V::Vec(c[..c.len() - 1].to_vec())),
        (V::Vec(c), "cross") => {
            let b = a[0].comps();
            let m2 = |i: usize, j: usize| -> R<F> {
                fsub(fmul(c[i].f(), b[j].f(), true)?, fmul(b[i].f(), c[j].f(), true)?, true)
            };
            return Ok(V::Vec(vec![fv(m2(1, 2))?, fv(m2(2, 0))?, fv(m2(0, 1))?]));
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
                return Ok(V::Vec(c.iter().map(|_| V::F(0.0, if unc { 2.0 } else { 0.0 })).collect()));
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
            return Ok(V::Vec(out?));
        }
        (V::Vec(_), "lerp") => return zip3(r, &a[0], &a[1], &mut |x, y, s| fv(loose::mix(x.f(), y.f(), s.f()))),
        (V::Vec(_), "fract_gl") => return comp_wise(&mut |s| fv(ffract(s.f(), f32::floor))),
        _ => {}
    }
    // ---- component-wise methods (scalars, and vectors where glam has them) ----
    let two = |f: &mut dyn FnMut(&V, &V) -> R<V>| -> R<V> { zip(r, &a[0], &mut |x, y| f(x, y)) };
    match m {
        "min" => two(&mut |x, y| min_max(x, y, true)),
        "max" => two(&mut |x, y| min_max(x, y, false)),
        "clamp" => zip3(r, &a[0], &a[1], &mut |x, lo, hi| min_max(&min_max(x, lo, false)?, hi, true)),
        "wrapping_add" => two(&mut |x, y| scalar_bin(BinOp::Add, x, y)),
        "wrapping_sub" => two(&mut |x, y| scalar_bin(BinOp::Sub, x, y)),
        "wrapping_mul" => two(&mut |x, y| scalar_bin(BinOp::Mul, x, y)),
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

fn loose_bin(op: BinOp, x: &V, y: &V) -> R<V> {
    match (x, y) {
        (V::F(..), V::F(..)) => match op {
            BinOp::Add => fv(fadd(x.f(), y.f(), true)),
            BinOp::Mul => fv(fmul(x.f(), y.f(), true)),
            _ => unreachable!(),
        },
        _ => scalar_bin(op, x, y),
    }
}

fn dot(a: &[V], b: &[V]) -> R<V> {
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
fn unary(s: &V, m: &str) -> R<V> {
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
            "abs" => V::I(x.wrapping_abs(), *u),
            "signum" => V::I(x.signum(), *u),
            "count_ones" => V::U(x.count_ones(), *u),
            "leading_zeros" => V::U(x.leading_zeros(), *u),
            "trailing_zeros" => V::U(x.trailing_zeros(), *u),
            "reverse_bits" => V::I(x.reverse_bits(), *u),
            _ => panic!("i32::{m}"),
        },
        V::U(x, u) => match m {
            "count_ones" => V::U(x.count_ones(), *u),
            "leading_zeros" => V::U(x.leading_zeros(), *u),
            "trailing_zeros" => V::U(x.trailing_zeros(), *u),
            "reverse_bits" => V::U(x.reverse_bits(), *u),
            _ => panic!("u32::{m}"),
        },
        other => panic!("{m} on {other:?}"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `%`'s error is the dividend's plus the quotient times the divisor's
    /// (here `atan`'s 4096 ULP).
    #[test]
    fn remainder_error_grows_with_the_quotient() {
        let b = unary(&V::F(-24.158, 0.0), "atan").unwrap();
        let V::F(bv, be) = b else { panic!() };
        assert!(be > 4e-4, "{be}");
        let (_, e) = frem((-24.158, 0.0), (bv, be)).unwrap();
        assert!(e > 15.0 * 4e-4, "{e}");
    }

    fn var(n: &str) -> Expr {
        Expr::Var(n.into())
    }

    /// A bug the fuzzer found in the interpreter: an unbounded error times an
    /// exact 0 gave a NaN error, taken for 0 (`v *= c.round()` after a loop
    /// that made `v`'s error unbounded).
    #[test]
    fn unbounded_error_times_an_exact_value_stays_unbounded() {
        let (_, e) = fmul((99.7, f64::INFINITY), (1.0, 0.0), false).unwrap();
        assert!(e.is_infinite());
    }

    /// Statements in an `op=`'s value (a loop changing the variable) keep the
    /// errors they add.
    #[test]
    fn loop_in_a_compound_value_keeps_errors() {
        let f = |x: f32| Expr::Lit(Lit { v: LitV::F32(x), suffix: true });
        let rem =
            Expr::Bin(BinOp::Rem, Box::new(var("v1")), Box::new(Expr::Method(Box::new(var("in4")), "atan", vec![])));
        let body = Block {
            stmts: vec![
                Stmt::Assign(
                    Place::Var("c".into()),
                    Some(BinOp::Add),
                    Expr::Lit(Lit { v: LitV::U32(1), suffix: true }),
                ),
                Stmt::Assign(Place::Var("v1".into()), Some(BinOp::Div), rem),
            ],
            tail: None,
        };
        let cond = Expr::Bin(BinOp::Lt, Box::new(var("c")), Box::new(Expr::Lit(Lit { v: LitV::U32(3), suffix: true })));
        let value = Expr::If(
            Box::new(Expr::Lit(Lit { v: LitV::Bool(false), suffix: true })),
            Box::new(Block { stmts: vec![], tail: Some(f(1.0)) }),
            Box::new(Block {
                stmts: vec![
                    Stmt::Let {
                        name: "c".into(),
                        mutable: true,
                        ty: U32,
                        annotate: false,
                        init: Expr::Lit(Lit { v: LitV::U32(0), suffix: true }),
                    },
                    Stmt::While(cond, body),
                ],
                tail: Some(f(-1.0)),
            }),
        );
        let p = Program {
            name: "t".into(),
            structs: vec![],
            helpers: vec![],
            inputs: vec![("in4".into(), F32)],
            outputs: vec![("out_f".into(), F32)],
            slots: 1,
            body: Block {
                stmts: vec![
                    Stmt::Let { name: "v1".into(), mutable: true, ty: F32, annotate: false, init: var("in4") },
                    Stmt::Assign(Place::Var("v1".into()), Some(BinOp::Div), value),
                    Stmt::Store {
                        buf: 0,
                        index: Expr::Lit(Lit { v: LitV::U32(0), suffix: true }),
                        value: var("v1"),
                        form: StoreForm::Method,
                    },
                ],
                tail: None,
            },
        };
        let out = run(&p, 0, &[V::F(-24.158, 0.0)]).unwrap();
        let Word::Float(_, e) = out[0][0] else { panic!() };
        assert!(e > 0.01, "{e}");
    }
}
