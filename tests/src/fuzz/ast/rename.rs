//! A method's body as printed: its receiver parameter renamed `self`
//! (read through `(*self)` for `&self`).

use super::*;

pub fn block(b: &mut Block, from: &str, by_ref: bool) {
    for s in &mut b.stmts {
        stmt(s, from, by_ref);
    }
    if let Some(t) = &mut b.tail {
        expr(t, from, by_ref);
    }
}

fn name(n: &mut String, from: &str) {
    if n == from {
        *n = "self".into();
    }
}

fn stmt(s: &mut Stmt, from: &str, by_ref: bool) {
    match s {
        Stmt::Let { init, .. } => expr(init, from, by_ref),
        Stmt::Assign(p, _, v) => {
            place(p, from, by_ref);
            expr(v, from, by_ref);
        }
        Stmt::If(c, t, e) => {
            expr(c, from, by_ref);
            block(t, from, by_ref);
            if let Some(e) = e {
                block(e, from, by_ref);
            }
        }
        Stmt::For { end, body, .. } | Stmt::Each { array: end, body, .. } => {
            expr(end, from, by_ref);
            block(body, from, by_ref);
        }
        Stmt::While(c, body) => {
            expr(c, from, by_ref);
            block(body, from, by_ref);
        }
        Stmt::Loop(body) => block(body, from, by_ref),
        Stmt::Labelled(_, inner) => stmt(inner, from, by_ref),
        Stmt::Match(e, arms) => {
            expr(e, from, by_ref);
            arms.iter_mut().for_each(|a| block(&mut a.body, from, by_ref));
        }
        Stmt::Store { index, value, .. } => {
            expr(index, from, by_ref);
            expr(value, from, by_ref);
        }
        Stmt::Expr(e) | Stmt::Return(Some(e)) => expr(e, from, by_ref),
        Stmt::Break | Stmt::BreakTo(_) | Stmt::Continue | Stmt::Return(None) | Stmt::Trace(_) => {}
    }
}

fn place(p: &mut Place, from: &str, by_ref: bool) {
    match p {
        Place::Var(n) | Place::Deref(n) => name(n, from),
        Place::Field(b, ..) => place(b, from, by_ref),
        Place::Index(b, i) => {
            place(b, from, by_ref);
            expr(i, from, by_ref);
        }
    }
}

fn expr(e: &mut Expr, from: &str, by_ref: bool) {
    match e {
        Expr::Var(n) if n == from => {
            *e = if by_ref { Expr::Deref("self".into()) } else { Expr::Var("self".into()) };
        }
        Expr::Deref(n) => name(n, from),
        Expr::Lit(_) | Expr::Var(_) | Expr::LaunchX | Expr::Const(..) => {}
        Expr::Field(b, ..) | Expr::Unary(_, b) | Expr::Cast(b, _) | Expr::ArrayRepeat(b, _) | Expr::EnumRound(b) => {
            expr(b, from, by_ref)
        }
        Expr::Index(a, b) | Expr::Bin(_, a, b) => {
            expr(a, from, by_ref);
            expr(b, from, by_ref);
        }
        Expr::Method(r, _, args) => {
            expr(r, from, by_ref);
            args.iter_mut().for_each(|a| expr(a, from, by_ref));
        }
        Expr::Path(_, _, xs)
        | Expr::Free(_, xs)
        | Expr::ArrayLit(xs)
        | Expr::TupleField(xs, _)
        | Expr::Pick(xs, _)
        | Expr::Sugar(_, xs) => xs.iter_mut().for_each(|a| expr(a, from, by_ref)),
        Expr::Call(_, args) => args.iter_mut().for_each(|a| match a {
            Arg::Val(e) => expr(e, from, by_ref),
            Arg::MutRef(n) => name(n, from),
        }),
        Expr::StructLit(_, fields) => fields.iter_mut().for_each(|(_, v)| expr(v, from, by_ref)),
        Expr::If(c, t, f) => {
            expr(c, from, by_ref);
            block(t, from, by_ref);
            block(f, from, by_ref);
        }
        Expr::Match(x, arms) => {
            expr(x, from, by_ref);
            arms.iter_mut().for_each(|a| block(&mut a.body, from, by_ref));
        }
        Expr::BufLoad(_, i, _) => expr(i, from, by_ref),
    }
}
