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
//! - integer division or remainder by zero and `i32::MIN / -1` have the
//!   meaning `rt_std::arith` gives them on every backend (`x / 0` is `x`,
//!   `x % 0` is 0, `MIN / -1` wraps); the operators' divisors are still
//!   mostly built non-zero (see `generate`), the dividing methods
//!   (`div_euclid`, `rem_euclid`, `wrapping_div`, `saturating_div`) take
//!   any divisor, a zero one read as one;
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

mod exprs;
mod methods;
mod ops;
mod stmts;
mod values;

use methods::*;
use ops::*;
use values::*;

pub use values::ulp;

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
    /// `break 'fz_l<n>`: out of every loop up to the one labelled.
    BreakTo(u32),
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
