//! A greedy test-case reducer for failing programs: deletes statements,
//! flattens `if`s, loops and `match`es into their bodies, replaces
//! expressions by their operands, drops helpers, and keeps each change under
//! which the program still fails the same way (the compiler rejects it with
//! the same message, or the GPU still disagrees with the interpreter).
//! Candidates that no longer type-check are simply rejected by the compiler
//! and skipped. Candidates are tried in batches, one shader module each.

use super::Failure;
use super::ast::*;
use super::gpu::Gpu;
use std::time::{Duration, Instant};

/// One edit site visitor: counts sites in a fixed order and applies the
/// `target`th.
struct Editor {
    target: usize,
    count: usize,
    /// Whether expression sites count (a first pass deletes statements only).
    exprs: bool,
}

impl Editor {
    fn hit(&mut self) -> bool {
        self.count += 1;
        self.count - 1 == self.target
    }

    fn done(&self) -> bool {
        self.count > self.target
    }

    fn program(&mut self, p: &mut Program) {
        // Dropping a helper renumbers the calls of later ones.
        for h in (0..p.helpers.len()).rev() {
            if self.hit() {
                p.helpers.remove(h);
                renumber(&mut p.body, h);
                for g in p.helpers.iter_mut() {
                    renumber(&mut g.body, h);
                }
                return;
            }
        }
        self.block(&mut p.body);
        for h in p.helpers.iter_mut() {
            if self.done() {
                return;
            }
            self.block(&mut h.body);
        }
    }

    fn block(&mut self, b: &mut Block) {
        let mut i = 0;
        while i < b.stmts.len() {
            if self.hit() {
                b.stmts.remove(i);
                return;
            }
            // Flatten a compound statement into one of its blocks.
            let inner: Vec<Block> = match &b.stmts[i] {
                Stmt::If(_, t, e) => std::iter::once(t.clone()).chain(e.clone()).collect(),
                Stmt::For { body, .. } | Stmt::While(_, body) | Stmt::Loop(body) => vec![body.clone()],
                // (Its body names the element: not flattened.)
                Stmt::Each { .. } => Vec::new(),
                Stmt::Match(_, arms) => arms.iter().map(|a| a.body.clone()).collect(),
                _ => Vec::new(),
            };
            for blk in inner {
                if self.hit() {
                    b.stmts.splice(i..=i, blk.stmts);
                    return;
                }
            }
            self.stmt(&mut b.stmts[i]);
            if self.done() {
                return;
            }
            i += 1;
        }
        if let Some(t) = &mut b.tail {
            self.expr(t);
        }
    }

    fn stmt(&mut self, s: &mut Stmt) {
        match s {
            Stmt::Let { init, .. } => self.expr(init),
            Stmt::Assign(_, _, v) | Stmt::Expr(v) => self.expr(v),
            Stmt::If(c, t, e) => {
                self.expr(c);
                self.block(t);
                if let Some(e) = e {
                    self.block(e);
                }
            }
            Stmt::For { end, body, .. } | Stmt::Each { array: end, body, .. } => {
                self.expr(end);
                self.block(body);
            }
            Stmt::While(c, body) => {
                self.expr(c);
                self.block(body);
            }
            Stmt::Loop(body) => self.block(body),
            Stmt::Labelled(_, inner) => self.stmt(inner),
            Stmt::Match(e, arms) => {
                self.expr(e);
                for a in arms {
                    self.block(&mut a.body);
                }
            }
            Stmt::Store { index, value, .. } => {
                self.expr(index);
                self.expr(value);
            }
            Stmt::Return(Some(e)) => self.expr(e),
            Stmt::Break | Stmt::BreakTo(_) | Stmt::Continue | Stmt::Return(None) | Stmt::Trace(_) => {}
        }
    }

    fn expr(&mut self, e: &mut Expr) {
        if self.done() || !self.exprs {
            return;
        }
        // Replace the expression by one of its operands (of the same type,
        // or the candidate is rejected).
        let children: Vec<Expr> = match &*e {
            Expr::Field(x, ..) | Expr::Unary(_, x) | Expr::Cast(x, _) | Expr::ArrayRepeat(x, _) => vec![(**x).clone()],
            Expr::Index(a, _) => vec![(**a).clone()],
            Expr::Bin(_, a, c) => vec![(**a).clone(), (**c).clone()],
            Expr::Method(r, _, args) => std::iter::once((**r).clone()).chain(args.iter().cloned()).collect(),
            Expr::Path(_, _, args) | Expr::Free(_, args) => args.clone(),
            Expr::If(_, t, f) => t.tail.iter().chain(f.tail.iter()).cloned().collect(),
            Expr::Match(_, arms) => arms.iter().filter_map(|a| a.body.tail.clone()).collect(),
            Expr::TupleField(xs, k) | Expr::Pick(xs, k) => vec![xs[*k].clone()],
            Expr::Sugar(s, xs) => std::iter::once(s.meaning(xs)).chain(s.same_typed(xs).iter().cloned()).collect(),
            _ => Vec::new(),
        };
        for c in children {
            if self.hit() {
                *e = c;
                return;
            }
        }
        match e {
            Expr::Field(x, ..)
            | Expr::Unary(_, x)
            | Expr::Cast(x, _)
            | Expr::ArrayRepeat(x, _)
            | Expr::EnumRound(x) => self.expr(x),
            Expr::TupleField(xs, _) | Expr::Pick(xs, _) | Expr::Sugar(_, xs) => {
                xs.iter_mut().for_each(|a| self.expr(a))
            }
            Expr::Index(a, i) | Expr::Bin(_, a, i) => {
                self.expr(a);
                self.expr(i);
            }
            Expr::Method(r, _, args) => {
                self.expr(r);
                args.iter_mut().for_each(|a| self.expr(a));
            }
            Expr::Path(_, _, args) | Expr::Free(_, args) | Expr::ArrayLit(args) => {
                args.iter_mut().for_each(|a| self.expr(a))
            }
            Expr::Call(_, args) => {
                for a in args {
                    if let Arg::Val(x) = a {
                        self.expr(x);
                    }
                }
            }
            Expr::StructLit(_, fs) => fs.iter_mut().for_each(|(_, x)| self.expr(x)),
            Expr::If(c, t, f) => {
                self.expr(c);
                self.block(t);
                self.block(f);
            }
            Expr::Match(x, arms) => {
                self.expr(x);
                for a in arms {
                    self.block(&mut a.body);
                }
            }
            Expr::BufLoad(_, i, _) => self.expr(i),
            Expr::Lit(_) | Expr::Var(_) | Expr::Deref(_) | Expr::LaunchX | Expr::Const(..) => {}
        }
    }
}

/// After helper `removed` is dropped: calls of later helpers move down one
/// (calls of the dropped one stay, dangling, and the candidate is rejected).
fn renumber(b: &mut Block, removed: usize) {
    fn expr(e: &mut Expr, r: usize) {
        match e {
            Expr::Call(h, args) => {
                if *h > r {
                    *h -= 1;
                } else if *h == r {
                    *h = usize::MAX;
                }
                for a in args {
                    if let Arg::Val(x) = a {
                        expr(x, r);
                    }
                }
            }
            Expr::Field(x, ..)
            | Expr::Unary(_, x)
            | Expr::Cast(x, _)
            | Expr::ArrayRepeat(x, _)
            | Expr::EnumRound(x) => expr(x, r),
            Expr::TupleField(xs, _) | Expr::Pick(xs, _) | Expr::Sugar(_, xs) => xs.iter_mut().for_each(|a| expr(a, r)),
            Expr::Index(a, c) | Expr::Bin(_, a, c) => {
                expr(a, r);
                expr(c, r);
            }
            Expr::Method(x, _, args) => {
                expr(x, r);
                args.iter_mut().for_each(|a| expr(a, r));
            }
            Expr::Path(_, _, args) | Expr::Free(_, args) | Expr::ArrayLit(args) => {
                args.iter_mut().for_each(|a| expr(a, r))
            }
            Expr::StructLit(_, fs) => fs.iter_mut().for_each(|(_, x)| expr(x, r)),
            Expr::If(c, t, f) => {
                expr(c, r);
                renumber(t, r);
                renumber(f, r);
            }
            Expr::Match(x, arms) => {
                expr(x, r);
                arms.iter_mut().for_each(|a| renumber(&mut a.body, r));
            }
            Expr::BufLoad(_, i, _) => expr(i, r),
            Expr::Lit(_) | Expr::Var(_) | Expr::Deref(_) | Expr::LaunchX | Expr::Const(..) => {}
        }
    }
    fn stmt(s: &mut Stmt, r: usize) {
        match s {
            Stmt::Let { init, .. } => expr(init, r),
            Stmt::Assign(_, _, v) | Stmt::Expr(v) | Stmt::Return(Some(v)) => expr(v, r),
            Stmt::If(c, t, e) => {
                expr(c, r);
                renumber(t, r);
                if let Some(e) = e {
                    renumber(e, r);
                }
            }
            Stmt::For { end, body, .. } | Stmt::Each { array: end, body, .. } => {
                expr(end, r);
                renumber(body, r);
            }
            Stmt::While(c, body) => {
                expr(c, r);
                renumber(body, r);
            }
            Stmt::Loop(body) => renumber(body, r),
            Stmt::Labelled(_, inner) => stmt(inner, r),
            Stmt::Match(e, arms) => {
                expr(e, r);
                arms.iter_mut().for_each(|a| renumber(&mut a.body, r));
            }
            Stmt::Store { index, value, .. } => {
                expr(index, r);
                expr(value, r);
            }
            Stmt::Break | Stmt::BreakTo(_) | Stmt::Continue | Stmt::Return(None) | Stmt::Trace(_) => {}
        }
    }
    for s in &mut b.stmts {
        stmt(s, removed);
    }
    if let Some(t) = &mut b.tail {
        expr(t, removed);
    }
}

/// The number of edit sites of `p`.
fn sites(p: &Program, exprs: bool) -> usize {
    let mut e = Editor { target: usize::MAX, count: 0, exprs };
    e.program(&mut p.clone());
    e.count
}

/// `p` with edit site `k` applied.
fn edited(p: &Program, k: usize, exprs: bool) -> Program {
    let mut q = p.clone();
    Editor { target: k, count: 0, exprs }.program(&mut q);
    q
}

/// Makes item names unique to candidate `k`, so candidates share a module.
fn renamed(p: &Program, k: usize) -> Program {
    let mut q = p.clone();
    q.name = format!("{}c{k}", p.name);
    for s in &mut q.structs {
        s.name = format!("{}C{k}", s.name);
    }
    for h in &mut q.helpers {
        h.name = format!("{}c{k}", h.name);
    }
    q
}

/// Which candidates still fail as `original` did.
fn fails_batch(gpu: &Gpu, seed: u64, original: &Failure, cands: &[Program]) -> Vec<bool> {
    if original.kind == "rejected" {
        let want = original.detail.lines().nth(1).unwrap_or("").to_string();
        return cands
            .iter()
            .map(|c| match rt_compiler::lower_source(&c.source(), &c.name) {
                Err(e) => e.messages().first().is_some_and(|m| format!("error: {m}") == want),
                Ok(_) => false,
            })
            .collect();
    }
    let mut index = Vec::new();
    let mut batch = Vec::new();
    for (i, c) in cands.iter().enumerate() {
        // An edit can break what the generator guarantees (a divisor's
        // guard, a loop counter): the interpreter's panic rejects it.
        let c = renamed(c, i);
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| super::prepare_program(seed, original.id, c)));
        if let Ok(Ok(p)) = r {
            index.push(i);
            batch.push(p);
        }
    }
    let mut out = vec![false; cands.len()];
    let mut report = super::Report { device: String::new(), stats: Default::default(), failures: Vec::new() };
    super::run_batch(gpu, &batch, &mut report);
    for f in report.failures.iter().filter(|f| f.kind == original.kind) {
        if let Some(k) = batch.iter().position(|p| p.program.name == f.program) {
            out[index[k]] = true;
        }
    }
    out
}

/// Reduces `program` (which fails as `failure` says) for at most `budget`;
/// returns the smallest failing version found.
pub fn minimize(gpu: &Gpu, seed: u64, failure: &Failure, program: Program, budget: Duration) -> Program {
    const BATCH: usize = 32;
    let start = Instant::now();
    let mut cur = program;
    let mut k = 0;
    let mut changed = false;
    // Statements first (few sites, big steps), then everything.
    let mut exprs = false;
    while start.elapsed() < budget {
        let n = sites(&cur, exprs);
        if k >= n {
            if !changed {
                if exprs {
                    break;
                }
                exprs = true;
            }
            changed = false;
            k = 0;
            continue;
        }
        let ks: Vec<usize> = (k..n.min(k + BATCH)).collect();
        let cands: Vec<Program> = ks.iter().map(|&s| edited(&cur, s, exprs)).collect();
        let fails = fails_batch(gpu, seed, failure, &cands);
        match fails.iter().position(|f| *f) {
            Some(i) => {
                cur = cands[i].clone();
                changed = true;
                k = ks[i];
            }
            None => k += BATCH,
        }
    }
    cur
}
