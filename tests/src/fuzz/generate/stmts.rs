//! Statements: blocks, `let`s, assignments and their places, `if`,
//! loops, `match` arms, scratch stores and indices.

use super::*;

/// Whether a place's indices have effects or call a helper (the compiler
/// cannot tell which helpers have none).
/// The variable a place expression reads (`v`, `v.a[i]`, `*state`).
fn root_var(e: &Expr) -> Option<String> {
    match e {
        Expr::Var(n) | Expr::Deref(n) => Some(n.clone()),
        Expr::Field(x, ..) | Expr::Index(x, _) => root_var(x),
        _ => None,
    }
}

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

impl Gen {
    pub(super) fn block(&mut self, max: u64, tail: Option<(&Ty, bool)>) -> Block {
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

    pub(super) fn stmt(&mut self, out: &mut Vec<Stmt>) {
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
            if in_loop { self.breaks_weight() } else { 0 },                  // break / continue
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
                let s = match self.labels.first() {
                    // Out of the labelled loop, from a loop inside it.
                    Some(&n) if self.loop_depth >= 2 && self.r.chance(70) => Stmt::BreakTo(n),
                    _ if self.r.chance(50) => Stmt::Break,
                    _ => Stmt::Continue,
                };
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

    /// The weight of a `break` or `continue` statement: more inside a loop
    /// inside a labelled one, where it may leave the labelled one.
    fn breaks_weight(&self) -> u64 {
        if self.loop_depth >= 2 && !self.labels.is_empty() { 20 } else { 6 }
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
            // Locals a `&mut` struct helper (a `&mut self` method) can take.
            let mut_struct = self.mut_helper().and_then(|h| {
                self.p.helpers[h].params.iter().find_map(|p| match p {
                    Param::MutRef(_, t @ Ty::Struct(_)) => Some(t.clone()),
                    _ => None,
                })
            });
            let ty = match mut_struct {
                Some(t) if self.r.chance(35) => t,
                _ => self.var_ty(),
            };
            let init = self.expr(&ty, DEPTH, annotate);
            (ty, init)
        };
        let mutable = matches!(ty, Ty::Arr(..) | Ty::Struct(_)) || self.r.chance(55);
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
        // An outermost loop is labelled now and then, for the `break`s to
        // it from a loop inside.
        let label = (self.loop_depth == 0 && self.r.chance(35)).then(|| {
            self.fresh += 1;
            self.fresh
        });
        self.labels.extend(label);
        self.loop_depth += 1;
        match self.r.weighted(&[5, 3, 2, 3]) {
            3 => out.push(self.each_stmt()),
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
        if let Some(n) = label {
            self.labels.pop();
            let mut inner = out.pop().expect("the loop just pushed");
            // Ends with a loop that may leave it: `for i in 0..k { if c {
            // break 'fz_l<n>; } }`, `c` over the variables around.
            if let Stmt::For { body, .. } | Stmt::Each { body, .. } | Stmt::While(_, body) | Stmt::Loop(body) =
                &mut inner
            {
                let c = self.expr(&BOOL, 2, false);
                let leave = Stmt::If(c, Block { stmts: vec![Stmt::BreakTo(n)], tail: None }, None);
                body.stmts.push(Stmt::For {
                    var: self.name("i"),
                    ty: Scalar::U32,
                    start: 0,
                    end: lit(LitV::U32(self.r.range(1, 4) as u32), false),
                    inclusive: false,
                    body: Block { stmts: vec![leave], tail: None },
                });
            }
            out.push(Stmt::Labelled(n, Box::new(inner)));
        }
    }

    /// A loop over an array's elements (`Stmt::Each`): an array local in
    /// scope or a literal, by value or through `.iter()`, maybe reversed,
    /// maybe numbered.
    fn each_stmt(&mut self) -> Stmt {
        let n = self.r.pick(&[1u32, 2, 3, 4]);
        let et = if self.r.chance(70) {
            Ty::S(self.r.pick(&[Scalar::F32, Scalar::U32, Scalar::I32]))
        } else {
            self.r.pick(&self.vecs)
        };
        let ty = Ty::Arr(b_ty(et.clone()), n);
        let array = match self.readable(&ty) {
            cands if !cands.is_empty() && self.r.chance(60) => self.r.pick(&cands),
            _ => Expr::ArrayLit((0..n).map(|i| self.expr(&et, 2, i > 0)).collect()),
        };
        let var = self.name("e");
        let index = self.r.chance(40).then(|| (self.name("raw"), self.name("k")));
        let by_ref = index.is_some() || self.r.chance(50);
        let rev = self.r.chance(35);
        self.scopes.push(Vec::new());
        self.bind(&var, et, false, Kind::ReadOnly);
        let mut first = Vec::new();
        if let Some((raw, k)) = &index {
            first.push(Stmt::Let {
                name: k.clone(),
                mutable: false,
                ty: U32,
                annotate: false,
                init: Expr::Cast(b(Expr::Var(raw.clone())), Scalar::U32),
            });
            self.bind(k, U32, false, Kind::ReadOnly);
        }
        // `array.iter()` borrows the variable it reads for the whole loop:
        // the body must not assign it or pass it as `&mut`.
        let borrowed = if by_ref { root_var(&array) } else { None };
        self.no_write.extend(borrowed.clone());
        self.no_mut.extend(borrowed.clone());
        let mut body = self.block(4, None);
        if borrowed.is_some() {
            self.no_write.pop();
            self.no_mut.pop();
        }
        self.scopes.pop();
        first.append(&mut body.stmts);
        body.stmts = first;
        Stmt::Each { var, index, array, by_ref, rev, body }
    }

    /// A `match` scrutinee: the expression, its type and the values it
    /// can take.
    pub(super) fn scrutinee(&mut self) -> (Expr, Scalar, Vec<i64>) {
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
    pub(super) fn arms(&mut self, s: Scalar, vals: &[i64], value: Option<(&Ty, bool)>) -> Vec<Arm> {
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
    pub(super) fn scratch_index(&mut self) -> Expr {
        let k = if self.r.chance(70) {
            lit(LitV::U32(self.r.below(SCRATCH as u64) as u32), false)
        } else {
            let x = self.expr(&U32, 1, false);
            bin(BinOp::BitAnd, x, lit(LitV::U32(SCRATCH - 1), false))
        };
        bin(BinOp::Add, Expr::Var("slot".into()), k)
    }

    /// An index in `0..n` (`u32` or `i32`), literal or masked.
    pub(super) fn index_expr(&mut self, n: u32) -> Expr {
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
}
