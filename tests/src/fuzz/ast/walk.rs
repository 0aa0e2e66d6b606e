//! Questions about expressions and blocks: whether they have effects,
//! whether they call a helper, and a visit of every expression inside.

use super::*;

impl Expr {
    /// Whether evaluating the expression may change a variable or buffer
    /// of its context (a helper call with a `&mut` argument, or a block
    /// with assignments or stores).
    pub fn has_effects(&self, p: &Program) -> bool {
        let any = |xs: &[Expr]| xs.iter().any(|x| x.has_effects(p));
        match self {
            Expr::Lit(_) | Expr::Var(_) | Expr::Deref(_) | Expr::LaunchX | Expr::Const(..) => false,
            Expr::Field(b, ..)
            | Expr::Unary(_, b)
            | Expr::Cast(b, _)
            | Expr::ArrayRepeat(b, _)
            | Expr::EnumRound(b) => b.has_effects(p),
            Expr::TupleField(xs, _) | Expr::Pick(xs, _) | Expr::Sugar(_, xs) => any(xs),
            Expr::Index(a, b) | Expr::Bin(_, a, b) => a.has_effects(p) || b.has_effects(p),
            Expr::Method(r, _, args) => r.has_effects(p) || any(args),
            Expr::Path(_, _, args) | Expr::Free(_, args) | Expr::ArrayLit(args) => any(args),
            Expr::Call(_, args) => args.iter().any(|a| match a {
                Arg::MutRef(_) => true,
                Arg::Val(e) => e.has_effects(p),
            }),
            Expr::StructLit(_, fields) => fields.iter().any(|(_, e)| e.has_effects(p)),
            Expr::If(c, t, e) => c.has_effects(p) || t.has_effects(p) || e.has_effects(p),
            Expr::Match(x, arms) => x.has_effects(p) || arms.iter().any(|a| a.body.has_effects(p)),
            Expr::BufLoad(_, i, _) => i.has_effects(p),
        }
    }
}

impl Block {
    /// See [`Expr::has_effects`].
    pub fn has_effects(&self, p: &Program) -> bool {
        self.stmts.iter().any(|s| match s {
            Stmt::Let { init, .. } => init.has_effects(p),
            Stmt::Expr(e) => e.has_effects(p),
            _ => true,
        }) || self.tail.as_ref().is_some_and(|t| t.has_effects(p))
    }
}

impl Expr {
    /// Calls `f` on this expression and every expression inside it (also
    /// inside the blocks of `if` and `match` values).
    pub fn visit(&self, f: &mut dyn FnMut(&Expr)) {
        f(self);
        match self {
            Expr::Lit(_) | Expr::Var(_) | Expr::Deref(_) | Expr::LaunchX | Expr::Const(..) => {}
            Expr::Field(x, ..)
            | Expr::Unary(_, x)
            | Expr::Cast(x, _)
            | Expr::ArrayRepeat(x, _)
            | Expr::EnumRound(x) => x.visit(f),
            Expr::TupleField(xs, _) | Expr::Pick(xs, _) | Expr::Sugar(_, xs) => xs.iter().for_each(|a| a.visit(f)),
            Expr::Index(a, b) | Expr::Bin(_, a, b) => {
                a.visit(f);
                b.visit(f);
            }
            Expr::Method(r, _, args) => {
                r.visit(f);
                args.iter().for_each(|a| a.visit(f));
            }
            Expr::Path(_, _, args) | Expr::Free(_, args) | Expr::ArrayLit(args) => args.iter().for_each(|a| a.visit(f)),
            Expr::Call(_, args) => args.iter().for_each(|a| {
                if let Arg::Val(e) = a {
                    e.visit(f)
                }
            }),
            Expr::StructLit(_, fs) => fs.iter().for_each(|(_, e)| e.visit(f)),
            Expr::If(c, t, e) => {
                c.visit(f);
                t.visit(f);
                e.visit(f);
            }
            Expr::Match(x, arms) => {
                x.visit(f);
                arms.iter().for_each(|a| a.body.visit(f));
            }
            Expr::BufLoad(_, i, _) => i.visit(f),
        }
    }

    /// Whether the expression calls a helper (`fuzz_pick` too).
    pub fn calls_helper(&self) -> bool {
        let mut found = false;
        self.visit(&mut |e| found |= matches!(e, Expr::Call(..) | Expr::Pick(..)));
        found
    }
}

impl Block {
    /// [`Expr::visit`] over the block's expressions.
    pub fn visit(&self, f: &mut dyn FnMut(&Expr)) {
        for s in &self.stmts {
            match s {
                Stmt::Let { init: e, .. } | Stmt::Assign(_, _, e) | Stmt::Expr(e) | Stmt::Return(Some(e)) => e.visit(f),
                Stmt::If(c, t, e) => {
                    c.visit(f);
                    t.visit(f);
                    if let Some(e) = e {
                        e.visit(f);
                    }
                }
                Stmt::For { end, body, .. } | Stmt::Each { array: end, body, .. } => {
                    end.visit(f);
                    body.visit(f);
                }
                Stmt::While(c, body) => {
                    c.visit(f);
                    body.visit(f);
                }
                Stmt::Loop(body) => body.visit(f),
                Stmt::Labelled(_, inner) => Block { stmts: vec![(**inner).clone()], tail: None }.visit(f),
                Stmt::Match(e, arms) => {
                    e.visit(f);
                    arms.iter().for_each(|a| a.body.visit(f));
                }
                Stmt::Store { index, value, .. } => {
                    index.visit(f);
                    value.visit(f);
                }
                Stmt::Break | Stmt::BreakTo(_) | Stmt::Continue | Stmt::Return(None) | Stmt::Trace(_) => {}
            }
        }
        if let Some(t) = &self.tail {
            t.visit(f);
        }
    }
}
