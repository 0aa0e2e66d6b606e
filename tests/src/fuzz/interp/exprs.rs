//! Expressions and calls of helpers.

use super::*;

impl Interp<'_> {
    pub(super) fn exprs(&mut self, xs: &[Expr]) -> R<Vec<V>> {
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
                unary_op(*op, &v)?
            }
            Expr::Bin(op @ (BinOp::And | BinOp::Or), a, b) => self.short_circuit(*op == BinOp::And, a, b)?,
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
                path_call(t, f, args)?
            }
            Expr::Free(f, args) => {
                let args = self.exprs(args)?;
                free(f, &args)?
            }
            Expr::Const(t, n) => constant(t, n),
            Expr::Call(h, args) => self.call(*h, args)?,
            Expr::StructLit(i, fields) => self.struct_lit(*i, fields)?,
            Expr::ArrayLit(xs) => V::Arr(self.exprs(xs)?),
            Expr::ArrayRepeat(x, n) => V::Arr(vec![self.expr(x)?; *n as usize]),
            Expr::If(c, t, e) => {
                let c = self.expr(c)?.certain_bool("an `if` condition")?;
                match self.value_block(if c { t } else { e })? {
                    Ok(v) => v,
                    Err(_) => panic!("generator bug: control flow out of an `if` expression"),
                }
            }
            Expr::Match(x, arms) => self.match_value(x, arms)?,
            Expr::BufLoad(b, i, _) => {
                let k = self.expr(i)?.certain_u64("a load index")?;
                self.load(*b, k)
            }
            Expr::TupleField(xs, k) | Expr::Pick(xs, k) => self.exprs(xs)?.swap_remove(*k),
            Expr::Sugar(s, xs) => self.expr(&s.meaning(xs))?,
            Expr::EnumRound(x) => {
                let k = self.expr(x)?.certain_u64("an enum's integer")?;
                enum_round(k)
            }
        })
    }

    /// `a && b` or `a || b`: `b` only where `a` does not decide, and on an
    /// uncertain `a` both (where `b` has no effects).
    fn short_circuit(&mut self, and: bool, a: &Expr, b: &Expr) -> R<V> {
        let l = self.expr(a)?;
        let V::B(lv, lu) = l else { panic!("&& on {l:?}") };
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
        self.expr(b)
    }

    /// Struct `i` from its fields' expressions, in the order written.
    fn struct_lit(&mut self, i: usize, fields: &[(usize, Expr)]) -> R<V> {
        let mut vals = vec![None; self.p.structs[i].fields.len()];
        for (k, x) in fields {
            vals[*k] = Some(self.expr(x)?);
        }
        Ok(V::Struct(vals.into_iter().map(|v| v.expect("every field")).collect()))
    }

    /// A `match` expression's value: the arm `x` picks, its binding in a
    /// scope of its own.
    fn match_value(&mut self, x: &Expr, arms: &[Arm]) -> R<V> {
        let v = self.expr(x)?;
        let arm = self.pick_arm(&v, arms)?;
        self.scopes.push(Vec::new());
        if let Some(b) = &arm.bind {
            self.bind(b, v.clone());
        }
        let r = self.value_block(&arm.body);
        self.scopes.pop();
        Ok(match r? {
            Ok(v) => v,
            Err(_) => panic!("generator bug: control flow out of a `match` expression"),
        })
    }

    pub(super) fn call(&mut self, h: usize, args: &[Arg]) -> R<V> {
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

/// `-x` or `!x`, component-wise.
fn unary_op(op: UnOp, v: &V) -> R<V> {
    map1(v, &mut |s| {
        Ok(match (op, s) {
            (UnOp::Neg, V::F(f, e)) => V::F(-f, *e),
            (UnOp::Neg, V::I(i, u)) => V::I(i.wrapping_neg(), *u),
            (UnOp::Not, V::I(i, u)) => V::I(!i, *u),
            (UnOp::Not, V::U(i, u)) => V::U(!i, *u),
            (UnOp::Not, V::B(b, u)) => V::B(!b, *u),
            (op, v) => panic!("{op:?} on {v:?}"),
        })
    })
}

/// A type's associated function `t::f(args)`: a vector's constructors, or
/// a method called in path form.
fn path_call(t: &str, f: &str, args: Vec<V>) -> R<V> {
    Ok(match f {
        "new" => V::Vec(args),
        "from_array" => match &args[0] {
            V::Arr(items) => V::Vec(items.clone()),
            other => panic!("{t}::from_array of {other:?}"),
        },
        "splat" => {
            let Some(Ty::V(n, _)) = Ty::from_name(t) else { panic!("{t}::splat") };
            V::Vec(vec![args[0].clone(); n as usize])
        }
        _ => method(&args[0], f, &args[1..])?,
    })
}

/// The `FuzzKind` round trip of `k` (see [`Expr::EnumRound`]): 10, 5 or 7.
fn enum_round(k: i64) -> V {
    V::U(
        match k % 3 {
            0 => 10,
            1 => 5,
            _ => 7,
        },
        false,
    )
}
