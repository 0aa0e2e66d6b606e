//! Expressions of any type: literals, constants, readable places and
//! their projections, `if`/`match` values, calls, struct literals.

use super::*;

impl Gen {
    /// A literal of scalar type `s` (suffixed unless `typed`).
    pub(super) fn literal(&mut self, s: Scalar, typed: bool) -> Expr {
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
    pub(super) fn constant(&mut self, t: &Ty, typed: bool) -> Expr {
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
    pub(super) fn readable(&mut self, t: &Ty) -> Vec<Expr> {
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

    pub(super) fn leaf(&mut self, t: &Ty, typed: bool) -> Expr {
        let cands = self.readable(t);
        if !cands.is_empty() && self.r.chance(75) {
            return self.r.pick(&cands);
        }
        self.constant(t, typed)
    }

    /// An expression of type `t`; `typed`: the context fixes its type, so a
    /// literal may go unsuffixed.
    pub(super) fn expr(&mut self, t: &Ty, d: u32, typed: bool) -> Expr {
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
            16..=17 => return self.tuple_field(t, d),
            // Not in an index (depth 1): the compiler refuses a compound
            // assignment to a place whose index calls a helper.
            20..=21 if d >= 2 => {
                // The generic helper, at this type (nothing outside fixes
                // the arguments' types).
                let xs = vec![self.expr(t, d - 1, false), self.expr(t, d - 1, false)];
                return Expr::Pick(xs, self.r.below(2) as usize);
            }
            22..=26 if d >= 2 && self.value_depth < 2 => {
                if let Some(s) = self.sugar(t, d) {
                    return s;
                }
            }
            18..=19 if *t == Ty::S(Scalar::U32) => {
                let s = self.r.pick(&[Scalar::I32, Scalar::U32]);
                return Expr::EnumRound(b(self.expr(&Ty::S(s), d - 1, false)));
            }
            _ => {}
        }
        match t {
            Ty::S(Scalar::F32) => self.f32_expr(d, typed),
            Ty::S(s @ (Scalar::I32 | Scalar::U32)) => self.int_expr(*s, d, typed),
            Ty::S(Scalar::Bool) => self.bool_expr(d),
            Ty::V(n, Scalar::F32) => self.fvec_expr(*n, d, typed),
            Ty::V(n, s) => self.ivec_expr(*n, *s, d, typed),
            Ty::Struct(k) => match self.operator_call(*k, d) {
                Some(c) if self.r.chance(40) => c,
                _ => self.struct_lit(*k, d),
            },
            Ty::Arr(..) => unreachable!(),
        }
    }

    /// A call of one of struct `k`'s operator impls, `(a op b)`.
    fn operator_call(&mut self, k: usize, d: u32) -> Option<Expr> {
        let cands: Vec<usize> = (0..self.callable)
            .filter(|i| {
                self.p.helpers[*i].method.is_some_and(|m| m.of == k && matches!(m.form, MethodForm::Operator(_)))
            })
            .collect();
        if cands.is_empty() {
            return None;
        }
        let h = self.r.pick(&cands);
        Some(self.call_by_value(h, d))
    }

    /// A call of helper `h`, whose parameters are all values, with
    /// arguments of depth below `d`.
    fn call_by_value(&mut self, h: usize, d: u32) -> Expr {
        let params = self.p.helpers[h].params.clone();
        let args = params
            .iter()
            .map(|p| match p {
                Param::Val(_, pt) => Arg::Val(self.expr(pt, d - 1, true)),
                Param::MutRef(..) => unreachable!("the callers pick helpers without `&mut` parameters"),
            })
            .collect();
        Expr::Call(h, args)
    }

    /// `(x, other).0` or `(other, x).1`: a tuple literal with the value and
    /// one of another type, one element read.
    fn tuple_field(&mut self, t: &Ty, d: u32) -> Expr {
        let other = self.r.pick(&[
            Ty::S(Scalar::F32),
            Ty::S(Scalar::I32),
            Ty::S(Scalar::U32),
            Ty::S(Scalar::Bool),
            Ty::V(3, Scalar::F32),
        ]);
        // Nothing outside fixes the elements' types (`typed: false`).
        let x = self.expr(t, d - 1, false);
        let o = self.expr(&other, d - 1, false);
        if self.r.chance(50) { Expr::TupleField(vec![x, o], 0) } else { Expr::TupleField(vec![o, x], 1) }
    }

    /// Operands of a binary operator: one fixes the type, the other may
    /// then be an unsuffixed literal.
    pub(super) fn operands(&mut self, ta: &Ty, tb: &Ty, d: u32, typed: bool) -> (Expr, Expr) {
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

    /// A closure, an `Option` or an iterator's fold of type `t` (see
    /// [`Sugar`]); `None` where `t` has no such form. Where an operand came
    /// out with effects or a call, the expression it means (the printed
    /// form may evaluate operands in another order, or once more).
    fn sugar(&mut self, t: &Ty, d: u32) -> Option<Expr> {
        let arith = match t {
            Ty::S(Scalar::I32 | Scalar::U32) => Some(self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::BitXor])),
            Ty::S(Scalar::F32) => Some(self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul])),
            Ty::V(_, s) if *s != Scalar::Bool => Some(self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul])),
            _ => None,
        };
        self.fresh += 1;
        let id = self.fresh;
        let form = match (self.r.below(3), arith) {
            (0, Some(op)) => Sugar::Closure { op, ty: t.clone(), given: self.r.chance(50), id },
            (1, Some(op)) if !matches!(t, Ty::V(..)) => {
                let sum = *t == Ty::S(Scalar::F32) && op == BinOp::Add && self.r.chance(40);
                Sugar::Fold { op, ty: t.clone(), rev: self.r.chance(40), sum, id }
            }
            (_, _) if !matches!(t, Ty::Arr(..)) => Sugar::Option { form: self.r.below(4) as u8, id },
            _ => return None,
        };
        self.value_depth += 1;
        let xs: Vec<Expr> = match &form {
            Sugar::Closure { .. } => vec![self.expr(t, d - 1, false), self.expr(t, d - 1, false)],
            Sugar::Option { .. } => {
                vec![self.expr(&BOOL, d - 1, false), self.expr(t, d - 1, false), self.expr(t, d - 1, false)]
            }
            Sugar::Fold { sum: true, .. } => {
                let n = 2 + self.r.below(3) as usize;
                std::iter::once(lit(LitV::F32(0.0), true)).chain((0..n).map(|_| self.expr(t, d - 1, false))).collect()
            }
            Sugar::Fold { .. } => (0..3 + self.r.below(3) as usize).map(|_| self.expr(t, d - 1, false)).collect(),
        };
        self.value_depth -= 1;
        if xs.iter().any(|x| x.has_effects(&self.p) || x.calls_helper()) {
            return Some(form.meaning(&xs));
        }
        Some(Expr::Sugar(form, xs))
    }

    fn match_expr(&mut self, t: &Ty, _d: u32, typed: bool) -> Expr {
        let (scrut, s, vals) = self.scrutinee();
        self.value_depth += 1;
        let arms = self.arms(s, &vals, Some((t, typed)));
        self.value_depth -= 1;
        Expr::Match(b(scrut), arms)
    }

    /// A call of a helper (without `&mut` parameters) returning `t`.
    pub(super) fn call(&mut self, t: &Ty, d: u32) -> Option<Expr> {
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
        Some(self.call_by_value(h, d))
    }

    pub(super) fn mut_helper(&self) -> Option<usize> {
        (0..self.callable).find(|i| self.p.helpers[*i].params.iter().any(|p| matches!(p, Param::MutRef(..))))
    }

    /// A call of the `&mut` helper (of a `u32` or the last struct) on a
    /// local of that type (or on this helper's own `&mut` parameter), if
    /// its result type is `t`.
    pub(super) fn mut_call(&mut self, t: Option<&Ty>) -> Option<Expr> {
        let h = self.mut_helper()?;
        let helper = self.p.helpers[h].clone();
        if t.is_some_and(|t| helper.ret.as_ref() != Some(t)) {
            return None;
        }
        let target_ty = helper.params.iter().find_map(|p| match p {
            Param::MutRef(_, t) => Some(t.clone()),
            Param::Val(..) => None,
        })?;
        let targets: Vec<Var> = self
            .vars()
            .filter(|v| {
                v.ty == target_ty
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
}
