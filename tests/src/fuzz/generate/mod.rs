//! The generator: random, well-typed programs of the subset from a seed.
//!
//! Each program is a `#[rt_program(ray_generation)]` with a few plain-data
//! `#[var]` inputs (scalars, vectors, a struct) and output buffers
//! `out_u: RwBuffer<u32>`, `out_f: RwBuffer<f32>`, `out_v: RwBuffer<T>` (`T`
//! a vector, struct or `i32`), of which each launch index owns `slots`
//! elements from `launch_index().x * slots`. Its body mixes `let`s,
//! assignments (also compound, to vector components, struct fields and
//! array elements), nested `if`/`else` (statements and expressions),
//! bounded `for`, `while` and `loop` loops with `break`/`continue`,
//! `match` on integers, calls of `#[rt_function]` helpers (one may take a
//! `&mut u32` and is called with `&mut x` inside expressions), buffer loads
//! and stores; at the end every live local is written to the outputs.
//!
//! Programs stay inside what Rust defines in every build and what the
//! subset supports:
//!
//! - integer divisors are mostly non-zero (`(d & 15) + 1`, `-((d & 15) +
//!   2)`, `d | 1`, `(d % 7) + 1`, non-zero literals) and a quarter of the
//!   time `(d & 3) - 1` or `d & 3`, so that division and remainder by zero
//!   and `MIN / -1` are generated too (`rt_std::arith` defines them);
//! - float divisors are kept away from zero (`d.abs() + 0.5`, literals);
//!   arguments of `sqrt`, `ln`, `powf` are made positive, of `exp` clamped,
//!   of `sin`/`cos` reduced with `% 3.0` (mostly);
//! - indices are masked into range; loops are bounded by literals or by
//!   masked values, `while` and `loop` by a counter incremented first;
//! - clamp bounds are ordered literals;
//! - `&mut x` arguments name a `u32` local that no other argument of the
//!   call mentions (Rust's borrow rules), and calls with effects appear
//!   only where the generated Rust is accepted by the borrow checker.
//!
//! Integer overflow in `+ - *`, negation and `abs`, and shift amounts of
//! 32 or more, are generated freely: the interpreter gives them Rust's
//! wrapping (release-build) meaning, which is WGSL's (see `interp`).
//!
//! Unsuffixed literals are printed only where the context fixes their type
//! (the other operand of a binary operator, an argument, an annotated
//! `let`), as a Rust programmer writes them; elsewhere they carry a suffix.

use super::ast::*;

mod exprs;
mod items;
mod lanes;
mod operands;
mod scalars;
mod stmts;
mod vectors;

pub use lanes::lanes_variant;
use vectors::*;

/// `launch_index().x as i32`.
fn launch_x_i32() -> Expr {
    Expr::Cast(Box::new(Expr::LaunchX), Scalar::I32)
}

/// A small deterministic generator (splitmix64).
#[derive(Clone)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        let mut r = Rng(seed);
        r.next_u64();
        r
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }

    /// Uniform in `lo..=hi`.
    pub fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + self.below((hi - lo + 1) as u64) as i64
    }

    pub fn chance(&mut self, percent: u64) -> bool {
        self.below(100) < percent
    }

    pub fn pick<T: Clone>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len() as u64) as usize].clone()
    }

    /// An index chosen with the given weights.
    pub fn weighted(&mut self, weights: &[u64]) -> usize {
        let total: u64 = weights.iter().sum();
        let mut x = self.below(total);
        for (i, w) in weights.iter().enumerate() {
            if x < *w {
                return i;
            }
            x -= w;
        }
        unreachable!()
    }
}

/// The seed of program `id` of a run with `seed`.
pub fn program_seed(seed: u64, id: usize) -> u64 {
    seed ^ (id as u64).wrapping_add(1).wrapping_mul(0x2545_f491_4f6c_dd1d)
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    Local,
    Input,
    /// Read-only: loop variables, `match` bindings, value parameters.
    ReadOnly,
    /// A loop counter: read-only to the body.
    Counter,
    /// A `&mut u32` parameter (read as `*name`).
    RefParam,
}

#[derive(Clone, Debug)]
struct Var {
    name: String,
    ty: Ty,
    mutable: bool,
    kind: Kind,
    /// Possibly known to rustc's constant propagation (made of literals
    /// and constants only; see [`Gen::is_const`]).
    konst: bool,
}

/// Expression depth of initialisers and operands.
const DEPTH: u32 = 3;

/// Scratch elements per launch index in each output buffer (statements in
/// the body store to and load from these); the final dump follows.
const SCRATCH: u32 = 4;

struct Gen {
    r: Rng,
    p: Program,
    /// The vector types this program declares variables of.
    vecs: Vec<Ty>,
    scopes: Vec<Vec<Var>>,
    fresh: u32,
    loop_depth: u32,
    /// The labels of the labelled loops around (`Stmt::Labelled`).
    labels: Vec<u32>,
    /// Inside an `if`/`match` used as a value (no `break`/`return`).
    value_depth: u32,
    nest: u32,
    /// Inside a helper: its return type.
    ret: Option<Ty>,
    /// Variables the expression being generated must not name (the other
    /// arguments of a call that takes `&mut` of them).
    no_read: Vec<String>,
    /// Variables that must not be passed as `&mut` here.
    no_mut: Vec<String>,
    /// Whether calls with `&mut` arguments may be generated here.
    effects: bool,
    /// Helpers `0..callable` may be called.
    callable: usize,
    stmts_left: u32,
    projecting: u32,
    /// No buffer loads here (an `IndexMut` borrow of the buffer is live).
    no_buf: bool,
    /// Variables that must not be assigned here (borrowed by the
    /// assignment being generated).
    no_write: Vec<String>,
}

/// Generates program `id` of a run with `seed`.
pub fn program(seed: u64, id: usize) -> Program {
    let mut g = Gen {
        r: Rng::new(program_seed(seed, id)),
        p: Program {
            name: format!("fuzz{id}"),
            structs: Vec::new(),
            helpers: Vec::new(),
            inputs: Vec::new(),
            outputs: Vec::new(),
            slots: 0,
            body: Block::default(),
        },
        vecs: Vec::new(),
        scopes: Vec::new(),
        fresh: 0,
        loop_depth: 0,
        labels: Vec::new(),
        value_depth: 0,
        nest: 0,
        ret: None,
        no_read: Vec::new(),
        no_mut: Vec::new(),
        effects: true,
        callable: 0,
        stmts_left: 0,
        projecting: 0,
        no_buf: false,
        no_write: Vec::new(),
    };
    g.generate(id);
    g.p
}

/// A random input value of type `t` (exact: inputs are what both sides
/// load).
pub fn input_value(r: &mut Rng, p: &Program, t: &Ty) -> super::interp::V {
    use super::interp::V;
    match t {
        Ty::S(Scalar::Bool) => V::B(r.chance(50), false),
        Ty::S(Scalar::I32) => V::I(
            match r.weighted(&[5, 3, 1, 1]) {
                0 => r.range(-20, 20) as i32,
                1 => r.range(-100_000, 100_000) as i32,
                2 => r.next_u64() as i32,
                _ => r.pick(&[i32::MIN, i32::MAX, -1, 0, 1, 31, 32, 33]),
            },
            false,
        ),
        Ty::S(Scalar::U32) => V::U(
            match r.weighted(&[5, 3, 1, 1]) {
                0 => r.range(0, 40) as u32,
                1 => r.range(0, 200_000) as u32,
                2 => r.next_u64() as u32,
                _ => r.pick(&[u32::MAX, 0, 1, 31, 32, 33, 0x8000_0000]),
            },
            false,
        ),
        Ty::S(Scalar::F32) => V::F(
            match r.weighted(&[4, 4, 2, 1]) {
                0 => r.range(-16, 16) as f32 * 0.25,
                1 => (r.range(-100_000, 100_000) as f32) * 1e-3,
                2 => (r.range(-1_000_000, 1_000_000) as f32) * 1e-3 + 0.125,
                _ => r.pick(&[0.0, -0.0, 0.5, 1.0, -1.0, 1e-3, 1000.0, 3.0e4]),
            },
            0.0,
        ),
        Ty::V(n, s) => V::Vec((0..*n).map(|_| input_value(r, p, &Ty::S(*s))).collect()),
        Ty::Struct(i) => V::Struct(p.structs[*i].fields.iter().map(|(_, f)| input_value(r, p, f)).collect()),
        Ty::Arr(e, n) => V::Arr((0..*n).map(|_| input_value(r, p, e)).collect()),
    }
}

fn lit(v: LitV, suffix: bool) -> Expr {
    Expr::Lit(Lit { v, suffix })
}

fn b(e: Expr) -> Box<Expr> {
    Box::new(e)
}

fn bin(op: BinOp, a: Expr, c: Expr) -> Expr {
    Expr::Bin(op, b(a), b(c))
}

fn method(r: Expr, m: &'static str, args: Vec<Expr>) -> Expr {
    Expr::Method(b(r), m, args)
}

impl Gen {
    fn name(&mut self, prefix: &str) -> String {
        self.fresh += 1;
        format!("{prefix}{}", self.fresh)
    }

    fn bind(&mut self, name: &str, ty: Ty, mutable: bool, kind: Kind) {
        self.scopes.last_mut().unwrap().push(Var { name: name.into(), ty, mutable, kind, konst: false });
    }

    fn var(&self, n: &str) -> Option<&Var> {
        self.scopes.iter().rev().flat_map(|s| s.iter().rev()).find(|v| v.name == n)
    }

    /// Whether rustc's constant propagation may know the value of `e`
    /// (literals, constants, scalar operators, casts, and locals bound to
    /// such), conservatively. Rust rejects integer operations it can prove
    /// overflow (`arithmetic_overflow`, deny by default), so operators on
    /// two such operands are generated as `wrapping_*` methods instead.
    fn is_const(&self, e: &Expr) -> bool {
        match e {
            Expr::Lit(_) | Expr::Const(..) => true,
            Expr::Var(n) => self.var(n).is_some_and(|v| v.konst),
            Expr::Deref(_) | Expr::LaunchX | Expr::BufLoad(..) | Expr::Call(..) => false,
            Expr::Method(..) | Expr::Path(..) | Expr::Free(..) => false,
            Expr::Field(x, ..) | Expr::Unary(_, x) | Expr::Cast(x, _) | Expr::ArrayRepeat(x, _) => self.is_const(x),
            Expr::Index(a, i) => self.is_const(a) && self.is_const(i),
            Expr::Bin(_, a, c) => self.is_const(a) && self.is_const(c),
            Expr::StructLit(_, fs) => fs.iter().all(|(_, x)| self.is_const(x)),
            Expr::ArrayLit(xs) => xs.iter().all(|x| self.is_const(x)),
            Expr::If(_, t, e2) => {
                t.tail.as_ref().is_some_and(|x| self.is_const(x)) || e2.tail.as_ref().is_some_and(|x| self.is_const(x))
            }
            Expr::Match(_, arms) => arms.iter().any(|a| a.body.tail.as_ref().is_some_and(|x| self.is_const(x))),
            Expr::TupleField(xs, k) => self.is_const(&xs[*k]),
            // A call, a closure, an `Option`, a fold: evaluated at run time.
            Expr::Pick(..) | Expr::Sugar(..) => false,
            Expr::EnumRound(x) => self.is_const(x),
        }
    }

    /// `a op b` on scalar integers, as `a.wrapping_op(b)` when rustc could
    /// evaluate it (see [`Gen::is_const`]).
    fn int_op(&self, s: Scalar, op: BinOp, a: Expr, c: Expr) -> Expr {
        let m = match op {
            BinOp::Add => "wrapping_add",
            BinOp::Sub => "wrapping_sub",
            BinOp::Mul => "wrapping_mul",
            _ => return bin(op, a, c),
        };
        if self.is_const(&a) && self.is_const(&c) {
            // `i32::wrapping_add(a, c)`: the path types unsuffixed literals.
            let t = if s == Scalar::U32 { "u32" } else { "i32" };
            Expr::Path(t, m, vec![a, c])
        } else {
            bin(op, a, c)
        }
    }

    fn vars(&self) -> impl Iterator<Item = &Var> {
        self.scopes.iter().flatten().filter(|v| !self.no_read.contains(&v.name))
    }

    fn scalar(&mut self) -> Scalar {
        self.r.pick(&[Scalar::F32, Scalar::F32, Scalar::I32, Scalar::U32, Scalar::U32, Scalar::Bool])
    }

    /// A type for a variable: a scalar, one of the program's vectors or
    /// structs.
    fn var_ty(&mut self) -> Ty {
        match self.r.weighted(&[5, 4, if self.p.structs.is_empty() { 0 } else { 1 }]) {
            0 => Ty::S(self.scalar()),
            1 => self.r.pick(&self.vecs),
            _ => Ty::Struct(self.r.below(self.p.structs.len() as u64) as usize),
        }
    }
}

fn b_ty(t: Ty) -> Box<Ty> {
    Box::new(t)
}
