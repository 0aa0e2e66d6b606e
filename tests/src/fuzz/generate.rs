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

const COMP: [&str; 4] = ["x", "y", "z", "w"];

fn vec_name(n: u8, s: Scalar) -> &'static str {
    match (s, n) {
        (Scalar::F32, 2) => "Vec2",
        (Scalar::F32, 3) => "Vec3",
        (Scalar::F32, _) => "Vec4",
        (Scalar::I32, 2) => "IVec2",
        (Scalar::I32, 3) => "IVec3",
        (Scalar::I32, _) => "IVec4",
        (_, 2) => "UVec2",
        (_, 3) => "UVec3",
        _ => "UVec4",
    }
}

fn vec_fn(n: u8, s: Scalar) -> &'static str {
    match (s, n) {
        (Scalar::F32, 2) => "vec2",
        (Scalar::F32, 3) => "vec3",
        (Scalar::F32, _) => "vec4",
        (Scalar::I32, 2) => "ivec2",
        (Scalar::I32, 3) => "ivec3",
        (Scalar::I32, _) => "ivec4",
        (_, 2) => "uvec2",
        (_, 3) => "uvec3",
        _ => "uvec4",
    }
}

fn as_vec(n: u8, s: Scalar) -> &'static str {
    match (s, n) {
        (Scalar::F32, 2) => "as_vec2",
        (Scalar::F32, 3) => "as_vec3",
        (Scalar::F32, _) => "as_vec4",
        (Scalar::I32, 2) => "as_ivec2",
        (Scalar::I32, 3) => "as_ivec3",
        (Scalar::I32, _) => "as_ivec4",
        (_, 2) => "as_uvec2",
        (_, 3) => "as_uvec3",
        _ => "as_uvec4",
    }
}

fn swizzle_name(idx: &[usize]) -> &'static str {
    // Leaked once per distinct swizzle; there are at most 4^2+4^3+4^4.
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static NAMES: OnceLock<Mutex<HashMap<Vec<usize>, &'static str>>> = OnceLock::new();
    let mut m = NAMES.get_or_init(Default::default).lock().unwrap();
    m.entry(idx.to_vec())
        .or_insert_with(|| Box::leak(idx.iter().map(|i| COMP[*i]).collect::<String>().into_boxed_str()))
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

    fn generate(&mut self, id: usize) {
        let _ = id;
        // The program's vector types.
        let all: Vec<Ty> =
            [Scalar::F32, Scalar::I32, Scalar::U32].iter().flat_map(|s| (2..=4).map(move |n| Ty::V(n, *s))).collect();
        for _ in 0..self.r.range(2, 4) {
            let t = self.r.pick(&all);
            if !self.vecs.contains(&t) {
                self.vecs.push(t);
            }
        }
        // Structs (a later one may contain an earlier one).
        for i in 0..self.r.range(0, 2) as usize {
            let mut fields = Vec::new();
            for k in 0..self.r.range(2, 4) {
                let t = match self.r.weighted(&[4, 3, if i > 0 { 1 } else { 0 }]) {
                    0 => Ty::S(self.scalar()),
                    1 => self.r.pick(&self.vecs),
                    _ => Ty::Struct(i - 1),
                };
                fields.push((format!("f{k}"), t));
            }
            self.p
                .structs
                .push(StructDef { name: format!("Fz{}S{i}", self.p.name.trim_start_matches("fuzz")), fields });
        }
        // Helpers, each may call the earlier ones.
        let n_helpers = self.r.range(0, 3) as usize;
        let mut_helper =
            if n_helpers > 0 && self.r.chance(70) { Some(self.r.below(n_helpers as u64) as usize) } else { None };
        for i in 0..n_helpers {
            self.callable = i;
            let h = self.helper(i, mut_helper == Some(i));
            self.p.helpers.push(h);
        }
        self.callable = n_helpers;
        // Inputs and outputs.
        for k in 0..self.r.range(2, 5) {
            let t = self.var_ty();
            self.p.inputs.push((format!("in{k}"), t));
        }
        self.p.outputs.push(("out_u".into(), U32));
        self.p.outputs.push(("out_f".into(), F32));
        let mut v_types = self.vecs.clone();
        v_types.extend((0..self.p.structs.len()).map(Ty::Struct));
        v_types.push(I32);
        let vt = self.r.pick(&v_types);
        self.p.outputs.push(("out_v".into(), vt));
        // The body.
        self.scopes = vec![Vec::new()];
        for (n, t) in self.p.inputs.clone() {
            self.bind(&n, t, false, Kind::Input);
        }
        self.bind("slot", U32, false, Kind::ReadOnly);
        self.stmts_left = self.r.range(8, 28) as u32;
        let mut stmts = Vec::new();
        while self.stmts_left > 0 {
            self.stmts_left -= 1;
            self.stmt(&mut stmts);
        }
        // Every local still in scope, to the outputs.
        let mut counts = [SCRATCH; 3];
        let locals: Vec<Var> = self.scopes[0].iter().filter(|v| v.kind == Kind::Local).cloned().collect();
        for v in locals {
            self.dump(Expr::Var(v.name.clone()), &v.ty, &mut counts, &mut stmts);
        }
        let slots = counts.iter().copied().max().unwrap();
        self.p.slots = slots;
        stmts.insert(
            0,
            Stmt::Let {
                name: "slot".into(),
                mutable: false,
                ty: U32,
                annotate: false,
                init: bin(BinOp::Mul, Expr::LaunchX, lit(LitV::U32(slots), false)),
            },
        );
        self.p.body = Block { stmts, tail: None };
    }

    /// Stores `e` (of type `t`) into the next free output elements.
    fn dump(&mut self, e: Expr, t: &Ty, counts: &mut [u32; 3], out: &mut Vec<Stmt>) {
        const MAX: u32 = SCRATCH + 40;
        let store = |g: &mut Gen, buf: usize, value: Expr, counts: &mut [u32; 3], out: &mut Vec<Stmt>| {
            if counts[buf] >= MAX {
                return;
            }
            let index = bin(BinOp::Add, Expr::Var("slot".into()), lit(LitV::U32(counts[buf]), false));
            let form = if g.r.chance(50) { StoreForm::Method } else { StoreForm::Index };
            out.push(Stmt::Store { buf, index, value, form });
            counts[buf] += 1;
        };
        if *t == self.p.outputs[2].1 && self.r.chance(70) {
            return store(self, 2, e, counts, out);
        }
        match t {
            Ty::S(Scalar::F32) => store(self, 1, e, counts, out),
            Ty::S(Scalar::U32) => store(self, 0, e, counts, out),
            Ty::S(_) => store(self, 0, Expr::Cast(b(e), Scalar::U32), counts, out),
            Ty::V(n, s) => {
                for i in 0..*n as usize {
                    self.dump(Expr::Field(b(e.clone()), COMP[i].into(), i), &Ty::S(*s), counts, out);
                }
            }
            Ty::Struct(k) => {
                for (i, (f, ft)) in self.p.structs[*k].fields.clone().iter().enumerate() {
                    self.dump(Expr::Field(b(e.clone()), f.clone(), i), ft, counts, out);
                }
            }
            Ty::Arr(et, n) => {
                for i in 0..*n {
                    self.dump(Expr::Index(b(e.clone()), b(lit(LitV::U32(i), false))), et, counts, out);
                }
            }
        }
    }

    fn helper(&mut self, i: usize, takes_mut: bool) -> Helper {
        let name = format!("{}_h{i}", self.p.name);
        self.scopes = vec![Vec::new()];
        let mut params = Vec::new();
        if takes_mut {
            let n = format!("state{i}");
            self.bind(&n, U32, true, Kind::RefParam);
            params.push(Param::MutRef(n, U32));
        }
        for k in 0..self.r.range(if takes_mut { 0 } else { 1 }, 3) {
            let t = self.var_ty();
            let n = format!("p{i}_{k}");
            self.bind(&n, t.clone(), false, Kind::ReadOnly);
            params.push(Param::Val(n, t));
        }
        let ret = self.var_ty();
        self.ret = Some(ret.clone());
        self.stmts_left = self.r.range(1, 8) as u32;
        let mut stmts = Vec::new();
        while self.stmts_left > 0 {
            self.stmts_left -= 1;
            self.stmt(&mut stmts);
        }
        if takes_mut {
            // At least one write through the reference.
            let v = self.expr(&U32, DEPTH, true);
            let op = self.r.pick(&[None, Some(BinOp::Add), Some(BinOp::BitXor), Some(BinOp::Mul)]);
            stmts.push(Stmt::Assign(Place::Deref(format!("state{i}")), op, v));
        }
        let tail = self.expr(&ret, DEPTH, true);
        self.ret = None;
        Helper { name, params, ret: Some(ret), body: Block { stmts, tail: Some(tail) } }
    }

    // ---- statements ----

    fn block(&mut self, max: u64, tail: Option<(&Ty, bool)>) -> Block {
        self.scopes.push(Vec::new());
        self.nest += 1;
        let mut stmts = Vec::new();
        for _ in 0..self.r.range(0, max as i64) {
            if self.stmts_left == 0 {
                break;
            }
            self.stmts_left -= 1;
            self.stmt(&mut stmts);
        }
        let tail = tail.map(|(t, typed)| self.expr(t, DEPTH - 1, typed));
        self.nest -= 1;
        self.scopes.pop();
        Block { stmts, tail }
    }

    fn stmt(&mut self, out: &mut Vec<Stmt>) {
        let can_nest = self.nest < 3;
        let in_loop = self.loop_depth > 0 && self.value_depth == 0;
        let has_mut_helper = self.mut_helper().is_some();
        let w = [
            30,                                                              // let
            22,                                                              // assign
            if can_nest { 12 } else { 0 },                                   // if
            if can_nest && self.loop_depth < 2 { 9 } else { 0 },             // loops
            if can_nest { 5 } else { 0 },                                    // match
            if self.ret.is_none() && self.value_depth == 0 { 8 } else { 0 }, // store
            if has_mut_helper { 4 } else { 0 },                              // call statement
            if in_loop { 6 } else { 0 },                                     // break / continue
            if self.ret.is_some() && self.value_depth == 0 { 3 } else { 0 }, // early return
        ];
        match self.r.weighted(&w) {
            0 => self.let_stmt(out),
            1 => self.assign(out),
            2 => {
                let s = self.if_stmt(2);
                out.push(s);
            }
            3 => self.loop_stmt(out),
            4 => {
                let (scrut, s, vals) = self.scrutinee();
                let arms = self.arms(s, &vals, None);
                out.push(Stmt::Match(scrut, arms));
            }
            5 => self.scratch_store(out),
            6 => {
                if let Some(call) = self.mut_call(None) {
                    out.push(Stmt::Expr(call));
                }
            }
            7 => {
                let c = self.expr(&BOOL, 2, false);
                let s = if self.r.chance(50) { Stmt::Break } else { Stmt::Continue };
                out.push(Stmt::If(c, Block { stmts: vec![s], tail: None }, None));
            }
            _ => {
                let c = self.expr(&BOOL, 2, false);
                let ret = self.ret.clone().unwrap();
                let v = self.expr(&ret, DEPTH - 1, true);
                out.push(Stmt::If(c, Block { stmts: vec![Stmt::Return(Some(v))], tail: None }, None));
            }
        }
    }

    fn let_stmt(&mut self, out: &mut Vec<Stmt>) {
        let name = self.name("v");
        let annotate = self.r.chance(40);
        let (ty, init) = if self.r.chance(10) {
            // A local array.
            let n = self.r.pick(&[2u32, 3, 4]);
            let et = if self.r.chance(70) {
                Ty::S(self.r.pick(&[Scalar::F32, Scalar::U32, Scalar::I32]))
            } else {
                self.r.pick(&self.vecs)
            };
            let init = if self.r.chance(30) {
                Expr::ArrayRepeat(b(self.expr(&et, 1, annotate)), n)
            } else {
                let mut xs = vec![self.expr(&et, 2, annotate)];
                for _ in 1..n {
                    xs.push(self.expr(&et, 2, true));
                }
                Expr::ArrayLit(xs)
            };
            (Ty::Arr(b_ty(et), n), init)
        } else {
            let ty = self.var_ty();
            let init = self.expr(&ty, DEPTH, annotate);
            (ty, init)
        };
        let mutable = matches!(ty, Ty::Arr(..)) || self.r.chance(55);
        let konst = self.is_const(&init);
        out.push(Stmt::Let { name: name.clone(), mutable, ty: ty.clone(), annotate, init });
        self.bind(&name, ty, mutable, Kind::Local);
        self.scopes.last_mut().unwrap().last_mut().unwrap().konst = konst;
    }

    /// A place to assign to and its type: a mutable variable, a component,
    /// a field or an array element of one.
    fn place(&mut self) -> Option<(Place, Ty, String)> {
        let cands: Vec<Var> = self
            .vars()
            .filter(|v| v.mutable && matches!(v.kind, Kind::Local | Kind::RefParam) && !self.no_write.contains(&v.name))
            .cloned()
            .collect();
        if cands.is_empty() {
            return None;
        }
        let v = self.r.pick(&cands);
        // The indices of the place may not read the variable (glam's
        // `IndexMut` borrows it first).
        self.no_read.push(v.name.clone());
        let place = self.place_path(&v);
        self.no_read.pop();
        let (place, ty) = place;
        Some((place, ty, v.name))
    }

    fn place_path(&mut self, v: &Var) -> (Place, Ty) {
        let mut place =
            if v.kind == Kind::RefParam { Place::Deref(v.name.clone()) } else { Place::Var(v.name.clone()) };
        let mut ty = v.ty.clone();
        while self.r.chance(60) {
            match ty.clone() {
                Ty::V(n, s) => {
                    let i = self.r.below(n as u64) as usize;
                    if self.r.chance(75) {
                        place = Place::Field(Box::new(place), COMP[i].into(), i);
                    } else {
                        let idx = self.index_expr(n as u32);
                        place = Place::Index(Box::new(place), idx);
                    }
                    ty = Ty::S(s);
                }
                Ty::Struct(k) => {
                    let fields = self.p.structs[k].fields.clone();
                    let i = self.r.below(fields.len() as u64) as usize;
                    place = Place::Field(Box::new(place), fields[i].0.clone(), i);
                    ty = fields[i].1.clone();
                }
                Ty::Arr(e, n) => {
                    let idx = self.index_expr(n);
                    place = Place::Index(Box::new(place), idx);
                    ty = *e;
                }
                Ty::S(_) => break,
            }
        }
        if let Ty::Arr(e, n) = ty.clone() {
            // Arrays are assigned element-wise.
            let idx = self.index_expr(n);
            place = Place::Index(Box::new(place), idx);
            ty = *e;
        }
        (place, ty)
    }

    fn assign(&mut self, out: &mut Vec<Stmt>) {
        let Some((place, ty, base)) = self.place() else { return self.let_stmt(out) };
        let plain_var = matches!(place, Place::Var(_) | Place::Deref(_));
        // Compound operators the type has, with the right operand's type.
        let ops: Vec<(BinOp, Ty)> = match &ty {
            Ty::S(Scalar::F32) => {
                vec![(BinOp::Add, F32), (BinOp::Sub, F32), (BinOp::Mul, F32), (BinOp::Div, F32), (BinOp::Rem, F32)]
            }
            Ty::S(s @ (Scalar::I32 | Scalar::U32)) => [BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Rem]
                .into_iter()
                .chain([BinOp::BitAnd, BinOp::BitOr, BinOp::BitXor, BinOp::Shl, BinOp::Shr])
                .map(|o| (o, Ty::S(*s)))
                .collect(),
            Ty::S(Scalar::Bool) => vec![(BinOp::BitAnd, BOOL), (BinOp::BitOr, BOOL), (BinOp::BitXor, BOOL)],
            Ty::V(n, Scalar::F32) => vec![
                (BinOp::Add, ty.clone()),
                (BinOp::Sub, ty.clone()),
                (BinOp::Mul, ty.clone()),
                (BinOp::Mul, F32),
                (BinOp::Add, F32),
                (BinOp::Div, F32),
                (BinOp::Rem, F32),
                (BinOp::Div, Ty::V(*n, Scalar::F32)),
            ],
            Ty::V(_, s) => vec![
                (BinOp::Add, ty.clone()),
                (BinOp::Sub, ty.clone()),
                (BinOp::Mul, ty.clone()),
                (BinOp::BitAnd, ty.clone()),
                (BinOp::BitXor, Ty::S(*s)),
                (BinOp::BitOr, ty.clone()),
                (BinOp::Shl, U32),
                (BinOp::Shr, U32),
            ],
            _ => vec![],
        };
        // `x op= f(&mut x)` and `x = f(&mut x)` are fine for a `u32` local;
        // anything else that names the assigned variable is not.
        let allow_self_mut = plain_var && ty == U32;
        let pushed = !allow_self_mut;
        if pushed {
            self.no_mut.push(base.clone());
        }
        // A component, field or element place, or `op=` on a vector or
        // struct (a trait call taking `&mut` first), stays borrowed while
        // the value is evaluated: the value may not assign the variable.
        let base_ty = self.var(&base).map(|v| v.ty.clone());
        let borrowed = !plain_var || !matches!(base_ty, Some(Ty::S(_)));
        if borrowed {
            self.no_write.push(base.clone());
        }
        let base_const = self.var(&base).is_some_and(|v| v.konst);
        // `%=` on a float and `^=` on a bool are assignments of `place op
        // value` to the compiler, which rejects them where the place's
        // index has effects.
        let ops: Vec<(BinOp, Ty)> = if place_has_effects(&place, &self.p) {
            ops.into_iter()
                .filter(|(o, _)| {
                    !matches!((o, &ty), (BinOp::Rem, Ty::S(Scalar::F32)) | (BinOp::BitXor, Ty::S(Scalar::Bool)))
                })
                .collect()
        } else {
            ops
        };
        let stmt = if ops.is_empty() || self.r.chance(45) {
            let v = self.expr(&ty, DEPTH, true);
            Stmt::Assign(place, None, v)
        } else {
            let (op, rt) = self.r.pick(&ops);
            let v = self.operand_for(op, &rt, DEPTH);
            if base_const && self.is_const(&v) && ty.scalar().is_some_and(|s| s.is_int()) && matches!(ty, Ty::S(_)) {
                // `x op= c` rustc could evaluate: `x = x.wrapping_op(c)`.
                let cur = place_expr(&place);
                let e = self.int_op(ty.scalar().unwrap(), op, cur, v);
                Stmt::Assign(place, None, e)
            } else {
                Stmt::Assign(place, Some(op), v)
            }
        };
        if pushed {
            self.no_mut.pop();
        }
        if borrowed {
            self.no_write.pop();
        }
        // The variable stays known to rustc only while it is assigned
        // known values.
        let still_const = match &stmt {
            Stmt::Assign(_, _, v) => self.is_const(v),
            _ => false,
        };
        if let Some(v) = self.scopes.iter_mut().rev().flat_map(|s| s.iter_mut().rev()).find(|v| v.name == base) {
            v.konst &= still_const;
        }
        out.push(stmt);
    }

    /// The right operand of `op` (guarded divisors, shift amounts).
    fn operand_for(&mut self, op: BinOp, t: &Ty, d: u32) -> Expr {
        match (op, t) {
            (BinOp::Div | BinOp::Rem, _) => self.divisor(t, d),
            (BinOp::Shl | BinOp::Shr, _) => self.shift_amount(t, d),
            _ => self.expr(t, d, true),
        }
    }

    fn if_stmt(&mut self, chain: u32) -> Stmt {
        let c = self.expr(&BOOL, DEPTH, false);
        let t = self.block(4, None);
        let e = match self.r.below(3) {
            0 => None,
            1 if chain > 0 => Some(Block { stmts: vec![self.if_stmt(chain - 1)], tail: None }),
            _ => Some(self.block(3, None)),
        };
        Stmt::If(c, t, e)
    }

    fn loop_stmt(&mut self, out: &mut Vec<Stmt>) {
        self.loop_depth += 1;
        match self.r.weighted(&[5, 3, 2]) {
            0 => {
                let var = self.name("i");
                let ty = self.r.pick(&[Scalar::I32, Scalar::U32]);
                let start = self.r.range(0, 2);
                let inclusive = self.r.chance(30);
                let end = if self.r.chance(70) {
                    let k = start + self.r.range(0, 5);
                    lit(if ty == Scalar::I32 { LitV::I32(k as i32) } else { LitV::U32(k as u32) }, false)
                } else {
                    // A bound computed at run time, at most 7.
                    let x = self.expr(&Ty::S(ty), 2, false);
                    bin(BinOp::BitAnd, x, lit(if ty == Scalar::I32 { LitV::I32(7) } else { LitV::U32(7) }, false))
                };
                self.scopes.push(Vec::new());
                self.bind(&var, Ty::S(ty), false, Kind::ReadOnly);
                let body = self.block(4, None);
                self.scopes.pop();
                out.push(Stmt::For { var, ty, start, end, inclusive, body });
            }
            k => {
                // A counter, incremented first, bounds `while` and `loop`.
                let c = self.name("c");
                out.push(Stmt::Let {
                    name: c.clone(),
                    mutable: true,
                    ty: U32,
                    annotate: false,
                    init: lit(LitV::U32(0), true),
                });
                self.bind(&c, U32, true, Kind::Counter);
                let n = lit(LitV::U32(self.r.range(1, 5) as u32), false);
                let inc = Stmt::Assign(Place::Var(c.clone()), Some(BinOp::Add), lit(LitV::U32(1), false));
                let mut body = self.block(4, None);
                body.stmts.insert(0, inc);
                if k == 1 {
                    let mut cond = bin(BinOp::Lt, Expr::Var(c.clone()), n);
                    if self.r.chance(30) {
                        let extra = self.expr(&BOOL, 2, false);
                        cond = bin(BinOp::And, cond, extra);
                    }
                    out.push(Stmt::While(cond, body));
                } else {
                    // `loop { if c >= n { break; } c += 1; ... }`: a
                    // `continue` in the body cannot skip the test.
                    let stop = bin(BinOp::Ge, Expr::Var(c), n);
                    body.stmts.insert(0, Stmt::If(stop, Block { stmts: vec![Stmt::Break], tail: None }, None));
                    out.push(Stmt::Loop(body));
                }
            }
        }
        self.loop_depth -= 1;
    }

    /// A `match` scrutinee: the expression, its type and the values it
    /// can take.
    fn scrutinee(&mut self) -> (Expr, Scalar, Vec<i64>) {
        if self.r.chance(50) {
            let x = self.expr(&U32, 2, false);
            if self.r.chance(50) {
                (bin(BinOp::BitAnd, x, lit(LitV::U32(7), false)), Scalar::U32, (0..8).collect())
            } else {
                (bin(BinOp::Rem, x, lit(LitV::U32(5), false)), Scalar::U32, (0..5).collect())
            }
        } else {
            let x = self.expr(&I32, 2, false);
            if self.r.chance(50) {
                (bin(BinOp::Rem, x, lit(LitV::I32(4), false)), Scalar::I32, (-3..4).collect())
            } else {
                (bin(BinOp::BitAnd, x, lit(LitV::I32(3), false)), Scalar::I32, (0..4).collect())
            }
        }
    }

    /// Arms over some of `vals` and a catch-all (`_` or a binding); with
    /// `value`, each arm yields a value of that type.
    fn arms(&mut self, s: Scalar, vals: &[i64], value: Option<(&Ty, bool)>) -> Vec<Arm> {
        let mut left: Vec<i64> = vals.to_vec();
        let mut arms = Vec::new();
        for _ in 0..self.r.range(1, 3) {
            let mut pats = Vec::new();
            for _ in 0..self.r.range(1, 2) {
                if left.is_empty() {
                    break;
                }
                let v = left.remove(self.r.below(left.len() as u64) as usize);
                pats.push(if s == Scalar::I32 { LitV::I32(v as i32) } else { LitV::U32(v as u32) });
            }
            if pats.is_empty() {
                break;
            }
            let body = self.block(2, value);
            arms.push(Arm { pats, bind: None, body });
        }
        let bind = if self.r.chance(40) { Some(self.name("k")) } else { None };
        self.scopes.push(Vec::new());
        if let Some(n) = &bind {
            self.bind(n, Ty::S(s), false, Kind::ReadOnly);
        }
        let body = self.block(2, value);
        self.scopes.pop();
        arms.push(Arm { pats: Vec::new(), bind, body });
        arms
    }

    fn scratch_store(&mut self, out: &mut Vec<Stmt>) {
        let buf = self.r.below(3) as usize;
        let et = self.p.outputs[buf].1.clone();
        // `buf[i] = v` borrows `buf` mutably for `i`: no loads there. A
        // non-primitive element's `op=` takes that borrow before `v` too.
        let saved = self.no_buf;
        self.no_buf = true;
        let index = self.scratch_index();
        self.no_buf = saved;
        let ops: Vec<BinOp> = match &et {
            Ty::S(Scalar::F32) | Ty::V(_, Scalar::F32) => vec![BinOp::Add, BinOp::Sub, BinOp::Mul],
            Ty::S(_) | Ty::V(..) => vec![BinOp::Add, BinOp::BitXor, BinOp::BitOr],
            _ => vec![],
        };
        let form = match self.r.below(3) {
            0 => StoreForm::Method,
            1 => StoreForm::Index,
            _ if !ops.is_empty() => StoreForm::Compound(self.r.pick(&ops)),
            _ => StoreForm::Index,
        };
        let primitive = matches!(et, Ty::S(_));
        let (index, value) = if matches!(form, StoreForm::Compound(_)) && !primitive {
            self.no_buf = true;
            let v = self.expr(&et, DEPTH - 1, true);
            self.no_buf = saved;
            (bin(BinOp::Add, Expr::Var("slot".into()), lit(LitV::U32(self.r.below(SCRATCH as u64) as u32), false)), v)
        } else {
            (index, self.expr(&et, DEPTH - 1, true))
        };
        out.push(Stmt::Store { buf, index, value, form });
    }

    /// `slot + k` for a scratch element `k`, literal or masked.
    fn scratch_index(&mut self) -> Expr {
        let k = if self.r.chance(70) {
            lit(LitV::U32(self.r.below(SCRATCH as u64) as u32), false)
        } else {
            let x = self.expr(&U32, 1, false);
            bin(BinOp::BitAnd, x, lit(LitV::U32(SCRATCH - 1), false))
        };
        bin(BinOp::Add, Expr::Var("slot".into()), k)
    }

    // ---- expressions ----

    /// An index in `0..n` (`u32` or `i32`), literal or masked.
    fn index_expr(&mut self, n: u32) -> Expr {
        if self.r.chance(40) || self.projecting > 0 {
            return lit(LitV::U32(self.r.below(n as u64) as u32), false);
        }
        let s = self.r.pick(&[Scalar::U32, Scalar::I32]);
        let x = self.expr(&Ty::S(s), 1, false);
        let k = |v: u32| lit(if s == Scalar::I32 { LitV::I32(v as i32) } else { LitV::U32(v) }, false);
        if n.is_power_of_two() {
            bin(BinOp::BitAnd, x, k(n - 1))
        } else if s == Scalar::U32 {
            bin(BinOp::Rem, x, k(n))
        } else {
            bin(BinOp::BitAnd, x, k(1))
        }
    }

    /// A literal of scalar type `s` (suffixed unless `typed`).
    fn literal(&mut self, s: Scalar, typed: bool) -> Expr {
        let suffix = !typed || self.r.chance(40);
        let v = match s {
            Scalar::Bool => LitV::Bool(self.r.chance(50)),
            Scalar::I32 => LitV::I32(match self.r.weighted(&[6, 2, 1]) {
                0 => self.r.range(-9, 9) as i32,
                1 => self.r.range(-70_000, 70_000) as i32,
                _ => self.r.pick(&[i32::MIN, i32::MAX, 31, 32, -32]),
            }),
            Scalar::U32 => LitV::U32(match self.r.weighted(&[6, 2, 1]) {
                0 => self.r.range(0, 12) as u32,
                1 => self.r.next_u64() as u32,
                _ => self.r.pick(&[u32::MAX, 31, 32, 0x8000_0000, 0x9e37_79b9]),
            }),
            Scalar::F32 => LitV::F32(match self.r.weighted(&[6, 2, 1]) {
                0 => self.r.range(-12, 12) as f32 * 0.5,
                1 => self.r.range(-20_000, 20_000) as f32 * 0.01,
                _ => self.r.pick(&[0.1, 1e-3, 100.0, 0.3333, 2.5e3]),
            }),
        };
        lit(v, suffix)
    }

    /// A constant or literal value of any type.
    fn constant(&mut self, t: &Ty, typed: bool) -> Expr {
        match t {
            Ty::S(s) => {
                if self.r.chance(10) {
                    let c = match s {
                        Scalar::F32 => Some(self.r.pick(&[("", "PI"), ("", "TAU"), ("", "E"), ("f32", "EPSILON")])),
                        Scalar::I32 => Some(self.r.pick(&[("i32", "MAX"), ("i32", "MIN")])),
                        Scalar::U32 => Some(self.r.pick(&[("u32", "MAX"), ("u32", "MIN")])),
                        Scalar::Bool => None,
                    };
                    if let Some((a, n)) = c {
                        return Expr::Const(a, n);
                    }
                }
                self.literal(*s, typed)
            }
            Ty::V(n, s) => {
                let name = vec_name(*n, *s);
                match self.r.below(5) {
                    0 => {
                        let mut cs = vec!["ZERO", "ONE", "X", "Y"];
                        if *n >= 3 {
                            cs.push("Z");
                        }
                        if *n == 4 {
                            cs.push("W");
                        }
                        if *s != Scalar::U32 {
                            cs.extend(["NEG_ONE", "NEG_X", "NEG_Y"]);
                        }
                        Expr::Const(name, self.r.pick(&cs))
                    }
                    1 => Expr::Path(name, "splat", vec![self.literal(*s, true)]),
                    2 => Expr::Path(name, "new", (0..*n).map(|_| self.literal(*s, true)).collect()),
                    _ => Expr::Free(vec_fn(*n, *s), (0..*n).map(|_| self.literal(*s, true)).collect()),
                }
            }
            Ty::Struct(k) => self.struct_lit(*k, 0),
            Ty::Arr(e, n) => Expr::ArrayRepeat(b(self.constant(e, true)), *n),
        }
    }

    /// Expressions naming a variable (or a component, field or element of
    /// one) of type `t`.
    fn readable(&mut self, t: &Ty) -> Vec<Expr> {
        let vars: Vec<Var> = self.vars().cloned().collect();
        let mut out = Vec::new();
        // Dynamic indices of projections are themselves expressions: one
        // level only.
        self.projecting += 1;
        for v in &vars {
            let base = if v.kind == Kind::RefParam { Expr::Deref(v.name.clone()) } else { Expr::Var(v.name.clone()) };
            self.projections(base, &v.ty, t, 2, &mut out);
        }
        self.projecting -= 1;
        if *t == U32 {
            out.push(Expr::LaunchX);
        }
        out
    }

    fn projections(&mut self, e: Expr, have: &Ty, want: &Ty, depth: u32, out: &mut Vec<Expr>) {
        if have == want {
            out.push(e.clone());
        }
        if depth == 0 {
            return;
        }
        match have {
            Ty::V(n, s) if *want == Ty::S(*s) => {
                let i = self.r.below(*n as u64) as usize;
                if self.r.chance(80) {
                    out.push(Expr::Field(b(e), COMP[i].into(), i));
                } else {
                    let idx = self.index_expr(*n as u32);
                    out.push(Expr::Index(b(e), b(idx)));
                }
            }
            Ty::Struct(k) => {
                for (i, (f, ft)) in self.p.structs[*k].fields.clone().iter().enumerate() {
                    self.projections(Expr::Field(b(e.clone()), f.clone(), i), ft, want, depth - 1, out);
                }
            }
            Ty::Arr(et, n) => {
                let idx = self.index_expr(*n);
                self.projections(Expr::Index(b(e), b(idx)), et, want, depth - 1, out);
            }
            _ => {}
        }
    }

    fn leaf(&mut self, t: &Ty, typed: bool) -> Expr {
        let cands = self.readable(t);
        if !cands.is_empty() && self.r.chance(75) {
            return self.r.pick(&cands);
        }
        self.constant(t, typed)
    }

    /// An expression of type `t`; `typed`: the context fixes its type, so a
    /// literal may go unsuffixed.
    fn expr(&mut self, t: &Ty, d: u32, typed: bool) -> Expr {
        if d == 0 || self.r.chance(22) {
            return self.leaf(t, typed);
        }
        if let Ty::Arr(..) = t {
            return self.leaf(t, typed);
        }
        match self.r.below(100) {
            0..=4 if self.value_depth < 2 => return self.if_expr(t, d, typed),
            5..=7 if self.value_depth < 2 => return self.match_expr(t, d, typed),
            8..=13 => {
                if let Some(c) = self.call(t, d) {
                    return c;
                }
            }
            14..=15 if self.effects => {
                if let Some(c) = self.mut_call(Some(t)) {
                    return c;
                }
            }
            _ => {}
        }
        match t {
            Ty::S(Scalar::F32) => self.f32_expr(d, typed),
            Ty::S(s @ (Scalar::I32 | Scalar::U32)) => self.int_expr(*s, d, typed),
            Ty::S(Scalar::Bool) => self.bool_expr(d),
            Ty::V(n, Scalar::F32) => self.fvec_expr(*n, d, typed),
            Ty::V(n, s) => self.ivec_expr(*n, *s, d, typed),
            Ty::Struct(k) => self.struct_lit(*k, d),
            Ty::Arr(..) => unreachable!(),
        }
    }

    /// Operands of a binary operator: one fixes the type, the other may
    /// then be an unsuffixed literal.
    fn operands(&mut self, ta: &Ty, tb: &Ty, d: u32, typed: bool) -> (Expr, Expr) {
        if self.r.chance(50) {
            let ta_typed = typed && self.r.chance(50);
            let a = self.expr(ta, d - 1, ta_typed);
            (a, self.expr(tb, d - 1, true))
        } else {
            let tb_typed = typed && self.r.chance(50);
            let b2 = self.expr(tb, d - 1, tb_typed);
            (self.expr(ta, d - 1, true), b2)
        }
    }

    fn if_expr(&mut self, t: &Ty, d: u32, typed: bool) -> Expr {
        let c = self.expr(&BOOL, d - 1, false);
        self.value_depth += 1;
        let then = self.block(2, Some((t, typed)));
        let els = if self.r.chance(30) {
            // `else if`
            let c2 = self.expr(&BOOL, d - 1, false);
            let t2 = self.block(1, Some((t, typed)));
            let e2 = self.block(1, Some((t, typed)));
            Block { stmts: Vec::new(), tail: Some(Expr::If(b(c2), Box::new(t2), Box::new(e2))) }
        } else {
            self.block(2, Some((t, typed)))
        };
        self.value_depth -= 1;
        Expr::If(b(c), Box::new(then), Box::new(els))
    }

    fn match_expr(&mut self, t: &Ty, _d: u32, typed: bool) -> Expr {
        let (scrut, s, vals) = self.scrutinee();
        self.value_depth += 1;
        let arms = self.arms(s, &vals, Some((t, typed)));
        self.value_depth -= 1;
        Expr::Match(b(scrut), arms)
    }

    /// A call of a helper (without `&mut` parameters) returning `t`.
    fn call(&mut self, t: &Ty, d: u32) -> Option<Expr> {
        let cands: Vec<usize> = (0..self.callable)
            .filter(|i| {
                let h = &self.p.helpers[*i];
                h.ret.as_ref() == Some(t) && h.params.iter().all(|p| matches!(p, Param::Val(..)))
            })
            .collect();
        if cands.is_empty() {
            return None;
        }
        let h = self.r.pick(&cands);
        let params = self.p.helpers[h].params.clone();
        let args = params
            .iter()
            .map(|p| match p {
                Param::Val(_, pt) => Arg::Val(self.expr(pt, d - 1, true)),
                Param::MutRef(..) => unreachable!(),
            })
            .collect();
        Some(Expr::Call(h, args))
    }

    fn mut_helper(&self) -> Option<usize> {
        (0..self.callable).find(|i| self.p.helpers[*i].params.iter().any(|p| matches!(p, Param::MutRef(..))))
    }

    /// A call of the `&mut u32` helper on a `u32` local (or on this
    /// helper's own `&mut` parameter), if its result type is `t`.
    fn mut_call(&mut self, t: Option<&Ty>) -> Option<Expr> {
        let h = self.mut_helper()?;
        let helper = self.p.helpers[h].clone();
        if t.is_some_and(|t| helper.ret.as_ref() != Some(t)) {
            return None;
        }
        let targets: Vec<Var> = self
            .vars()
            .filter(|v| {
                v.ty == U32
                    && v.mutable
                    && matches!(v.kind, Kind::Local | Kind::RefParam)
                    && !self.no_mut.contains(&v.name)
                    && !self.no_write.contains(&v.name)
            })
            .cloned()
            .collect();
        if targets.is_empty() {
            return None;
        }
        let x = self.r.pick(&targets).name;
        let saved = self.effects;
        self.effects = false;
        self.no_read.push(x.clone());
        let mut args = Vec::new();
        for p in &helper.params {
            args.push(match p {
                Param::MutRef(..) => Arg::MutRef(x.clone()),
                Param::Val(_, pt) => Arg::Val(self.expr(pt, 1, true)),
            });
        }
        self.no_read.pop();
        self.effects = saved;
        Some(Expr::Call(h, args))
    }

    fn struct_lit(&mut self, k: usize, d: u32) -> Expr {
        let fields = self.p.structs[k].fields.clone();
        let mut order: Vec<usize> = (0..fields.len()).collect();
        if self.r.chance(40) {
            for i in (1..order.len()).rev() {
                let j = self.r.below(i as u64 + 1) as usize;
                order.swap(i, j);
            }
        }
        let vals = order.into_iter().map(|i| (i, self.expr(&fields[i].1, d.saturating_sub(1), true))).collect();
        Expr::StructLit(k, vals)
    }

    /// A divisor of type `t`: floats kept away from zero; integers mostly
    /// non-zero, a quarter of them from -1..=2 (zero and `-1` included:
    /// `rt_std::arith` defines both on every backend). Those mix in the
    /// launch index: naga rejects a division by a *constant* zero (its
    /// constant evaluator reports "Division by zero"), which a generated
    /// expression of literals could be.
    fn divisor(&mut self, t: &Ty, d: u32) -> Expr {
        let d = d.saturating_sub(1).max(1);
        match t {
            Ty::S(Scalar::F32) => {
                if self.r.chance(35) {
                    lit(LitV::F32(self.r.pick(&[0.5, 2.0, -3.0, 0.1, 7.0, -0.75])), true)
                } else {
                    let x = self.expr(&F32, d, false);
                    bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), false))
                }
            }
            Ty::S(Scalar::I32) => match self.r.below(4) {
                0 => lit(LitV::I32(self.r.pick(&[2, 3, -2, 7, -5, 16])), true),
                3 => {
                    // -1..=2: zero and -1 as often as not (`rt_std::arith`).
                    let x = bin(BinOp::BitXor, self.expr(&I32, d, false), launch_x_i32());
                    bin(BinOp::Sub, bin(BinOp::BitAnd, x, lit(LitV::I32(3), false)), lit(LitV::I32(1), false))
                }
                1 => {
                    let x = self.expr(&I32, d, false);
                    bin(BinOp::Add, bin(BinOp::BitAnd, x, lit(LitV::I32(15), false)), lit(LitV::I32(1), false))
                }
                _ => {
                    let x = self.expr(&I32, d, false);
                    let m = bin(BinOp::Add, bin(BinOp::BitAnd, x, lit(LitV::I32(15), false)), lit(LitV::I32(2), false));
                    Expr::Unary(UnOp::Neg, b(m))
                }
            },
            Ty::S(_) => match self.r.below(4) {
                0 => lit(LitV::U32(self.r.pick(&[2, 3, 7, 16, 1000])), true),
                3 => {
                    let x = bin(BinOp::BitXor, self.expr(&U32, d, false), Expr::LaunchX);
                    bin(BinOp::BitAnd, x, lit(LitV::U32(3), false))
                }
                1 => {
                    let x = self.expr(&U32, d, false);
                    bin(BinOp::BitOr, x, lit(LitV::U32(1), false))
                }
                _ => {
                    let x = self.expr(&U32, d, false);
                    bin(BinOp::Add, bin(BinOp::Rem, x, lit(LitV::U32(7), false)), lit(LitV::U32(1), false))
                }
            },
            Ty::V(n, Scalar::F32) => {
                let x = self.expr(&Ty::V(*n, Scalar::F32), d, false);
                bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), true))
            }
            Ty::V(n, Scalar::I32) => {
                let x = self.expr(&Ty::V(*n, Scalar::I32), d, false);
                if self.r.chance(25) {
                    let x = bin(BinOp::BitXor, x, launch_x_i32());
                    return bin(BinOp::Sub, bin(BinOp::BitAnd, x, lit(LitV::I32(3), true)), lit(LitV::I32(1), true));
                }
                bin(BinOp::Add, bin(BinOp::BitAnd, x, lit(LitV::I32(15), true)), lit(LitV::I32(1), true))
            }
            Ty::V(n, s) => {
                let x = self.expr(&Ty::V(*n, *s), d, false);
                if self.r.chance(25) {
                    return bin(BinOp::BitAnd, bin(BinOp::BitXor, x, Expr::LaunchX), lit(LitV::U32(3), true));
                }
                bin(BinOp::BitOr, x, lit(LitV::U32(1), true))
            }
            _ => unreachable!(),
        }
    }

    /// A shift amount for a value of type `t`: mostly masked or a literal
    /// below 32, sometimes anything (taken modulo 32, see `interp`).
    fn shift_amount(&mut self, t: &Ty, d: u32) -> Expr {
        let d = d.saturating_sub(1).max(1);
        let s = self.r.pick(&[Scalar::U32, Scalar::I32]);
        // A vector's shift amount literal needs its suffix: glam shifts by
        // every integer type.
        let vector = matches!(t, Ty::V(..));
        let k = |v: u32| lit(if s == Scalar::I32 { LitV::I32(v as i32) } else { LitV::U32(v) }, vector);
        match (self.r.below(10), t) {
            (0..=3, _) => lit(LitV::U32(self.r.below(32) as u32), vector),
            (4..=5, Ty::V(n, _)) => {
                let vs = self.r.pick(&[Scalar::U32, Scalar::I32]);
                let x = self.expr(&Ty::V(*n, vs), d, false);
                bin(BinOp::BitAnd, x, lit(if vs == Scalar::I32 { LitV::I32(31) } else { LitV::U32(31) }, true))
            }
            (4..=8, _) => {
                let x = self.expr(&Ty::S(s), d, false);
                bin(BinOp::BitAnd, x, k(31))
            }
            _ => {
                // Any amount, taken modulo 32; but an amount rustc can
                // evaluate must be below 32 (`arithmetic_overflow`).
                let x = self.expr(&U32, d, false);
                if self.is_const(&x) { bin(BinOp::BitAnd, x, lit(LitV::U32(31), vector)) } else { x }
            }
        }
    }

    /// A float vector type of the program, if any.
    fn fvec(&mut self) -> Ty {
        let fs: Vec<Ty> = self.vecs.iter().filter(|t| t.scalar() == Some(Scalar::F32)).cloned().collect();
        if fs.is_empty() { Ty::V(self.r.range(2, 4) as u8, Scalar::F32) } else { self.r.pick(&fs) }
    }

    fn ivec(&mut self, s: Scalar) -> Ty {
        let vs: Vec<Ty> = self.vecs.iter().filter(|t| t.scalar() == Some(s)).cloned().collect();
        if vs.is_empty() { Ty::V(self.r.range(2, 4) as u8, s) } else { self.r.pick(&vs) }
    }

    fn f32_expr(&mut self, d: u32, typed: bool) -> Expr {
        let d1 = d - 1;
        match self.r.below(100) {
            0..=29 => {
                let op =
                    [BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Rem][self.r.weighted(&[4, 4, 4, 2, 1])];
                if matches!(op, BinOp::Div | BinOp::Rem) {
                    let a = self.expr(&F32, d1, typed);
                    let c = self.divisor(&F32, d);
                    bin(op, a, c)
                } else {
                    let (a, c) = self.operands(&F32, &F32, d, typed);
                    bin(op, a, c)
                }
            }
            30..=33 => Expr::Unary(UnOp::Neg, b(self.expr(&F32, d1, typed))),
            34..=49 => {
                let x = self.expr(&F32, d1, false);
                let m = self.r.pick(&[
                    "abs",
                    "floor",
                    "ceil",
                    "trunc",
                    "round",
                    "fract",
                    "signum",
                    "atan",
                    "to_radians",
                    "to_degrees",
                ]);
                method(x, m, vec![])
            }
            50..=57 => {
                let x = self.expr(&F32, d1, false);
                match self.r.below(6) {
                    0 => method(method(x, "abs", vec![]), "sqrt", vec![]),
                    1 => {
                        let m = self.r.pick(&["exp", "exp2"]);
                        method(
                            method(x, "clamp", vec![lit(LitV::F32(-8.0), false), lit(LitV::F32(8.0), false)]),
                            m,
                            vec![],
                        )
                    }
                    2 => {
                        let m = self.r.pick(&["ln", "log2"]);
                        method(bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), false)), m, vec![])
                    }
                    3 | 4 => {
                        let m = self.r.pick(&["sin", "cos"]);
                        if self.r.chance(85) {
                            method(bin(BinOp::Rem, x, lit(LitV::F32(3.0), false)), m, vec![])
                        } else {
                            method(x, m, vec![])
                        }
                    }
                    _ => method(self.divisor(&F32, d), "recip", vec![]),
                }
            }
            58..=67 => {
                let x = self.expr(&F32, d1, false);
                match self.r.below(6) {
                    0 => method(x, self.r.pick(&["min", "max"]), vec![self.expr(&F32, d1, true)]),
                    1 => {
                        let lo = self.r.range(-8, 4) as f32 * 0.5;
                        let hi = lo + self.r.range(0, 8) as f32 * 0.5;
                        method(x, "clamp", vec![lit(LitV::F32(lo), true), lit(LitV::F32(hi), true)])
                    }
                    2 => {
                        let n = self.r.range(-3, 4) as i32;
                        let base = if n < 0 {
                            bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), false))
                        } else {
                            x
                        };
                        method(base, "powi", vec![lit(LitV::I32(n), self.r.chance(30))])
                    }
                    3 => {
                        let base = bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), false));
                        let y = self.expr(&F32, d1, false);
                        method(
                            base,
                            "powf",
                            vec![method(y, "clamp", vec![lit(LitV::F32(-3.0), false), lit(LitV::F32(3.0), false)])],
                        )
                    }
                    4 => method(x, "mul_add", vec![self.expr(&F32, d1, true), self.expr(&F32, d1, true)]),
                    _ => Expr::Path("f32", self.r.pick(&["min", "max"]), vec![x, self.expr(&F32, d1, true)]),
                }
            }
            68..=74 => {
                let s = self.r.pick(&[Scalar::I32, Scalar::U32]);
                Expr::Cast(b(self.expr(&Ty::S(s), d1, false)), Scalar::F32)
            }
            75..=84 => {
                let vt = self.fvec();
                let v = self.expr(&vt, d1, false);
                let Ty::V(n, _) = vt else { unreachable!() };
                match self.r.below(9) {
                    0 => method(v, "dot", vec![self.expr(&vt, d1, true)]),
                    1 => method(v, "length", vec![]),
                    2 => method(v, "length_squared", vec![]),
                    3 => method(v, "distance", vec![self.expr(&vt, d1, true)]),
                    4 => method(
                        v,
                        self.r.pick(&["element_sum", "element_product", "min_element", "max_element"]),
                        vec![],
                    ),
                    5 => method(v, "distance_squared", vec![self.expr(&vt, d1, true)]),
                    6 => {
                        let idx = self.index_expr(n as u32);
                        Expr::Index(b(v), b(idx))
                    }
                    _ => {
                        let i = self.r.below(n as u64) as usize;
                        Expr::Field(b(v), COMP[i].into(), i)
                    }
                }
            }
            85..=92 => {
                // rt-std's generic math: literals suffixed (the parameter
                // types are generic).
                match self.r.below(4) {
                    0 => Expr::Free("saturate", vec![self.expr(&F32, d1, false)]),
                    1 => Expr::Free("step", vec![self.expr(&F32, d1, false), self.expr(&F32, d1, false)]),
                    2 => {
                        let lo = self.r.range(-4, 2) as f32;
                        let hi = lo + self.r.range(1, 4) as f32;
                        let x = self.expr(&F32, d1, false);
                        Expr::Free("smoothstep", vec![lit(LitV::F32(lo), true), lit(LitV::F32(hi), true), x])
                    }
                    _ => Expr::Free(
                        "mix",
                        vec![self.expr(&F32, d1, false), self.expr(&F32, d1, false), self.expr(&F32, d1, false)],
                    ),
                }
            }
            93..=96 if self.ret.is_none() && !self.no_buf => {
                let i = self.scratch_index();
                Expr::BufLoad(1, b(i), self.r.chance(50))
            }
            _ => self.leaf(&F32, typed),
        }
    }

    fn int_expr(&mut self, s: Scalar, d: u32, typed: bool) -> Expr {
        let t = Ty::S(s);
        let d1 = d - 1;
        let other = if s == Scalar::I32 { Scalar::U32 } else { Scalar::I32 };
        match self.r.below(100) {
            0..=24 => {
                let op =
                    [BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Rem][self.r.weighted(&[4, 4, 3, 2, 2])];
                if matches!(op, BinOp::Div | BinOp::Rem) {
                    let a = self.expr(&t, d1, typed);
                    let c = self.divisor(&t, d);
                    bin(op, a, c)
                } else {
                    let (a, c) = self.operands(&t, &t, d, typed);
                    self.int_op(s, op, a, c)
                }
            }
            25..=29 => {
                let m = self.r.pick(&["wrapping_add", "wrapping_sub", "wrapping_mul"]);
                let x = self.expr(&t, d1, false);
                method(x, m, vec![self.expr(&t, d1, true)])
            }
            30..=44 => {
                let op = self.r.pick(&[BinOp::BitAnd, BinOp::BitOr, BinOp::BitXor]);
                let (a, c) = self.operands(&t, &t, d, typed);
                bin(op, a, c)
            }
            45..=54 => {
                let op = self.r.pick(&[BinOp::Shl, BinOp::Shr]);
                let a = self.expr(&t, d1, false);
                let c = self.shift_amount(&t, d);
                bin(op, a, c)
            }
            55..=59 => {
                let x = self.expr(&t, d1, typed);
                // `-x` of a constant `i32::MIN` is a Rust compile error.
                if s == Scalar::I32 && self.r.chance(50) && !self.is_const(&x) {
                    Expr::Unary(UnOp::Neg, b(x))
                } else {
                    Expr::Unary(UnOp::Not, b(x))
                }
            }
            60..=64 => {
                let x = self.expr(&t, d1, false);
                match self.r.below(4) {
                    0 if s == Scalar::I32 => method(x, self.r.pick(&["abs", "signum"]), vec![]),
                    1 => {
                        let lo = self.r.range(-20, 10);
                        let hi = lo + self.r.range(0, 30);
                        let (lo, hi) = if s == Scalar::U32 { (lo.max(0), hi.max(0)) } else { (lo, hi) };
                        let l = |v: i64| {
                            lit(if s == Scalar::I32 { LitV::I32(v as i32) } else { LitV::U32(v as u32) }, true)
                        };
                        method(x, "clamp", vec![l(lo), l(hi)])
                    }
                    _ => method(x, self.r.pick(&["min", "max"]), vec![self.expr(&t, d1, true)]),
                }
            }
            65..=69 => {
                let src = self.r.pick(&[s, other]);
                let x = self.expr(&Ty::S(src), d1, false);
                let m = self.r.pick(&["count_ones", "leading_zeros", "trailing_zeros", "reverse_bits"]);
                let e = method(x, m, vec![]);
                let result = if m == "reverse_bits" { src } else { Scalar::U32 };
                if result == s { e } else { Expr::Cast(b(e), s) }
            }
            70..=79 => {
                let from = self.r.pick(&[Scalar::F32, Scalar::F32, other, Scalar::Bool]);
                let d2 = if from == Scalar::Bool { d1.min(1) } else { d1 };
                Expr::Cast(b(self.expr(&Ty::S(from), d2, false)), s)
            }
            80..=87 => {
                let vt = self.ivec(s);
                let Ty::V(n, _) = vt else { unreachable!() };
                let v = self.expr(&vt, d1, false);
                match self.r.below(5) {
                    0 => method(v, "dot", vec![self.expr(&vt, d1, true)]),
                    1 => method(
                        v,
                        self.r.pick(&["element_sum", "element_product", "min_element", "max_element"]),
                        vec![],
                    ),
                    2 => {
                        let idx = self.index_expr(n as u32);
                        Expr::Index(b(v), b(idx))
                    }
                    _ => {
                        let i = self.r.below(n as u64) as usize;
                        Expr::Field(b(v), COMP[i].into(), i)
                    }
                }
            }
            88..=91 if self.ret.is_none() && !self.no_buf => {
                let i = self.scratch_index();
                let load = Expr::BufLoad(0, b(i), self.r.chance(50));
                if s == Scalar::U32 { load } else { Expr::Cast(b(load), s) }
            }
            92..=94 => {
                let x = self.expr(&U32, d1, false);
                let y = self.expr(&U32, d1, true);
                let c = method(x, "is_multiple_of", vec![y]);
                Expr::Cast(b(c), s)
            }
            _ => self.leaf(&t, typed),
        }
    }

    fn bool_expr(&mut self, d: u32) -> Expr {
        let d1 = d - 1;
        match self.r.below(100) {
            0..=27 => {
                let op = self.r.pick(&[BinOp::Lt, BinOp::Le, BinOp::Gt, BinOp::Ge, BinOp::Eq, BinOp::Ne]);
                let (a, c) = self.operands(&F32, &F32, d, false);
                bin(op, a, c)
            }
            28..=47 => {
                let op = self.r.pick(&[BinOp::Lt, BinOp::Le, BinOp::Gt, BinOp::Ge, BinOp::Eq, BinOp::Ne]);
                let t = Ty::S(self.r.pick(&[Scalar::I32, Scalar::U32]));
                let (a, c) = self.operands(&t, &t, d, false);
                bin(op, a, c)
            }
            48..=52 => {
                let t = self.r.pick(&self.vecs);
                let op = self.r.pick(&[BinOp::Eq, BinOp::Ne]);
                let (a, c) = self.operands(&t, &t, d, false);
                bin(op, a, c)
            }
            53..=67 => {
                let op = self.r.pick(&[BinOp::And, BinOp::Or]);
                bin(op, self.expr(&BOOL, d1, false), self.expr(&BOOL, d1, false))
            }
            68..=75 => Expr::Unary(UnOp::Not, b(self.expr(&BOOL, d1, false))),
            76..=83 => {
                let op = self.r.pick(&[BinOp::BitAnd, BinOp::BitOr, BinOp::BitXor, BinOp::Eq, BinOp::Ne]);
                bin(op, self.expr(&BOOL, d1, false), self.expr(&BOOL, d1, false))
            }
            84..=89 => {
                let x = self.expr(&U32, d1, false);
                method(x, "is_multiple_of", vec![self.expr(&U32, d1, true)])
            }
            _ => self.leaf(&BOOL, false),
        }
    }

    fn fvec_expr(&mut self, n: u8, d: u32, typed: bool) -> Expr {
        let t = Ty::V(n, Scalar::F32);
        let d1 = d - 1;
        let name = vec_name(n, Scalar::F32);
        match self.r.below(100) {
            0..=9 => {
                let args: Vec<Expr> = (0..n).map(|_| self.expr(&F32, d1, true)).collect();
                match self.r.below(3) {
                    0 => Expr::Path(name, "new", args),
                    1 => Expr::Path(name, "splat", vec![self.expr(&F32, d1, true)]),
                    _ => Expr::Free(vec_fn(n, Scalar::F32), args),
                }
            }
            10..=29 => {
                let op = self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul]);
                let (a, c) = self.operands(&t, &t, d, false);
                bin(op, a, c)
            }
            30..=39 => {
                let op = self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Rem]);
                let a = self.expr(&t, d1, false);
                let c = if matches!(op, BinOp::Div | BinOp::Rem) {
                    self.divisor(&F32, d)
                } else {
                    self.expr(&F32, d1, false)
                };
                bin(op, a, c)
            }
            40..=43 => {
                // A scalar on the left: suffixed.
                let a = self.expr(&F32, d1, false);
                bin(BinOp::Mul, a, self.expr(&t, d1, false))
            }
            44..=46 => {
                let a = self.expr(&t, d1, false);
                let c = self.divisor(&t, d);
                bin(self.r.pick(&[BinOp::Div, BinOp::Rem]), a, c)
            }
            47..=49 => Expr::Unary(UnOp::Neg, b(self.expr(&t, d1, false))),
            50..=59 => {
                let x = self.expr(&t, d1, false);
                let m = self.r.pick(&["abs", "floor", "ceil", "round", "trunc", "fract", "fract_gl", "signum"]);
                method(x, m, vec![])
            }
            60..=66 => {
                let x = self.expr(&t, d1, false);
                match self.r.below(6) {
                    0 => method(method(x, "abs", vec![]), "sqrt", vec![]),
                    1 => {
                        let lo = Expr::Path(name, "splat", vec![lit(LitV::F32(-6.0), false)]);
                        let hi = Expr::Path(name, "splat", vec![lit(LitV::F32(6.0), false)]);
                        method(method(x, "clamp", vec![lo, hi]), "exp", vec![])
                    }
                    2 => method(bin(BinOp::Rem, x, lit(LitV::F32(3.0), true)), self.r.pick(&["sin", "cos"]), vec![]),
                    3 => {
                        let base = bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), true));
                        let y = self.expr(&F32, d1, false);
                        method(
                            base,
                            "powf",
                            vec![method(y, "clamp", vec![lit(LitV::F32(-3.0), false), lit(LitV::F32(3.0), false)])],
                        )
                    }
                    4 => method(x, "mul_add", vec![self.expr(&t, d1, true), self.expr(&t, d1, true)]),
                    _ => method(x, "normalize_or_zero", vec![]),
                }
            }
            67..=74 => {
                let x = self.expr(&t, d1, false);
                match self.r.below(4) {
                    0 => method(x, self.r.pick(&["min", "max"]), vec![self.expr(&t, d1, true)]),
                    1 => {
                        let lo = self.r.range(-6, 2) as f32 * 0.5;
                        let hi = lo + self.r.range(0, 6) as f32 * 0.5;
                        let lo = Expr::Path(name, "splat", vec![lit(LitV::F32(lo), true)]);
                        let hi = Expr::Path(name, "splat", vec![lit(LitV::F32(hi), true)]);
                        method(x, "clamp", vec![lo, hi])
                    }
                    2 => method(x, "lerp", vec![self.expr(&t, d1, true), self.expr(&F32, d1, true)]),
                    _ if n == 3 => method(x, "cross", vec![self.expr(&t, d1, true)]),
                    _ => method(x, "lerp", vec![self.expr(&t, d1, true), self.expr(&F32, d1, true)]),
                }
            }
            75..=81 => match self.r.below(4) {
                0 => Expr::Free("saturate", vec![self.expr(&t, d1, false)]),
                1 => Expr::Free("step", vec![self.expr(&t, d1, false), self.expr(&t, d1, false)]),
                2 => {
                    let lo = self.r.range(-4, 2) as f32;
                    let hi = lo + self.r.range(1, 4) as f32;
                    let x = self.expr(&t, d1, false);
                    let lo = Expr::Path(name, "splat", vec![lit(LitV::F32(lo), true)]);
                    let hi = Expr::Path(name, "splat", vec![lit(LitV::F32(hi), true)]);
                    Expr::Free("smoothstep", vec![lo, hi, x])
                }
                _ => {
                    let tt = if self.r.chance(50) { F32 } else { t.clone() };
                    Expr::Free(
                        "mix",
                        vec![self.expr(&t, d1, false), self.expr(&t, d1, false), self.expr(&tt, d1, false)],
                    )
                }
            },
            82..=91 => self.reshape(n, Scalar::F32, d1),
            92..=95 => {
                let s = self.r.pick(&[Scalar::I32, Scalar::U32]);
                let x = self.expr(&Ty::V(n, s), d1, false);
                method(x, as_vec(n, Scalar::F32), vec![])
            }
            _ => self.leaf(&t, typed),
        }
    }

    /// A vector of `n` `s`s made from another vector: a swizzle, `extend`
    /// or `truncate`.
    fn reshape(&mut self, n: u8, s: Scalar, d: u32) -> Expr {
        match self.r.below(4) {
            0 if n > 2 => {
                let x = self.expr(&Ty::V(n - 1, s), d, false);
                method(x, "extend", vec![self.expr(&Ty::S(s), d, true)])
            }
            1 if n < 4 => method(self.expr(&Ty::V(n + 1, s), d, false), "truncate", vec![]),
            _ => {
                let m = self.r.range(2, 4) as u8;
                let x = self.expr(&Ty::V(m, s), d, false);
                let idx: Vec<usize> = (0..n).map(|_| self.r.below(m as u64) as usize).collect();
                method(x, swizzle_name(&idx), vec![])
            }
        }
    }

    fn ivec_expr(&mut self, n: u8, s: Scalar, d: u32, typed: bool) -> Expr {
        let t = Ty::V(n, s);
        let d1 = d - 1;
        let name = vec_name(n, s);
        match self.r.below(100) {
            0..=9 => {
                let args: Vec<Expr> = (0..n).map(|_| self.expr(&Ty::S(s), d1, true)).collect();
                match self.r.below(3) {
                    0 => Expr::Path(name, "new", args),
                    1 => Expr::Path(name, "splat", vec![self.expr(&Ty::S(s), d1, true)]),
                    _ => Expr::Free(vec_fn(n, s), args),
                }
            }
            10..=24 => {
                let op = self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul]);
                if self.r.chance(70) {
                    let (a, c) = self.operands(&t, &t, d, false);
                    bin(op, a, c)
                } else {
                    let a = self.expr(&t, d1, false);
                    bin(op, a, self.expr(&Ty::S(s), d1, false))
                }
            }
            25..=29 => {
                let m = self.r.pick(&["wrapping_add", "wrapping_sub", "wrapping_mul"]);
                method(self.expr(&t, d1, false), m, vec![self.expr(&t, d1, true)])
            }
            30..=36 => {
                let op = self.r.pick(&[BinOp::Div, BinOp::Rem]);
                let a = self.expr(&t, d1, false);
                let c = if self.r.chance(60) { self.divisor(&t, d) } else { self.divisor(&Ty::S(s), d) };
                bin(op, a, c)
            }
            37..=49 => {
                let op = self.r.pick(&[BinOp::BitAnd, BinOp::BitOr, BinOp::BitXor]);
                let a = self.expr(&t, d1, false);
                let c = if self.r.chance(60) { self.expr(&t, d1, true) } else { self.expr(&Ty::S(s), d1, false) };
                bin(op, a, c)
            }
            50..=57 => {
                let op = self.r.pick(&[BinOp::Shl, BinOp::Shr]);
                let a = self.expr(&t, d1, false);
                let c = self.shift_amount(&t, d);
                bin(op, a, c)
            }
            58..=62 => {
                let x = self.expr(&t, d1, false);
                if s == Scalar::I32 && self.r.chance(50) {
                    Expr::Unary(UnOp::Neg, b(x))
                } else {
                    Expr::Unary(UnOp::Not, b(x))
                }
            }
            63..=72 => {
                let x = self.expr(&t, d1, false);
                match self.r.below(4) {
                    0 if s == Scalar::I32 => method(x, self.r.pick(&["abs", "signum"]), vec![]),
                    1 => {
                        let lo = if s == Scalar::I32 { self.r.range(-20, 5) } else { self.r.range(0, 5) };
                        let hi = lo + self.r.range(0, 30);
                        let l = |v: i64| {
                            lit(if s == Scalar::I32 { LitV::I32(v as i32) } else { LitV::U32(v as u32) }, true)
                        };
                        method(
                            x,
                            "clamp",
                            vec![Expr::Path(name, "splat", vec![l(lo)]), Expr::Path(name, "splat", vec![l(hi)])],
                        )
                    }
                    _ => method(x, self.r.pick(&["min", "max"]), vec![self.expr(&t, d1, true)]),
                }
            }
            73..=84 => self.reshape(n, s, d1),
            85..=94 => {
                let from = self.r.pick(&[Scalar::F32, if s == Scalar::I32 { Scalar::U32 } else { Scalar::I32 }]);
                let x = self.expr(&Ty::V(n, from), d1, false);
                method(x, as_vec(n, s), vec![])
            }
            _ => self.leaf(&t, typed),
        }
    }
}

/// Whether a place's indices have effects or call a helper (the compiler
/// cannot tell which helpers have none).
fn place_has_effects(p: &Place, prog: &Program) -> bool {
    match p {
        Place::Var(_) | Place::Deref(_) => false,
        Place::Field(x, ..) => place_has_effects(x, prog),
        Place::Index(x, i) => place_has_effects(x, prog) || i.has_effects(prog) || i.calls_helper(),
    }
}

/// The value of a place, as an expression.
fn place_expr(p: &Place) -> Expr {
    match p {
        Place::Var(n) => Expr::Var(n.clone()),
        Place::Deref(n) => Expr::Deref(n.clone()),
        Place::Field(x, f, i) => Expr::Field(b(place_expr(x)), f.clone(), *i),
        Place::Index(x, i) => Expr::Index(b(place_expr(x)), b(i.clone())),
    }
}

fn b_ty(t: Ty) -> Box<Ty> {
    Box::new(t)
}
