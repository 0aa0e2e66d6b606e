//! Type inference: unsuffixed integer literals get an inference variable
//! (union-find over `ivars`), unified as later uses demand and `i32` by
//! default, as in Rust; coercion to an expected type, reads through
//! references, and probing an expression's type without emitting it.

use super::*;

impl FnLowerer<'_> {
    pub(super) fn find(&self, v: u32) -> u32 {
        let mut v = v;
        while self.ivars[v as usize].0 != v {
            v = self.ivars[v as usize].0;
        }
        v
    }

    pub(super) fn new_ivar(&mut self) -> u32 {
        let id = self.ivars.len() as u32;
        self.ivars.push((id, None));
        id
    }

    /// The type with every resolved inference variable replaced.
    pub(super) fn resolved(&self, t: &Ty) -> Ty {
        match t {
            Ty::IntVar(v) => {
                let r = self.find(*v);
                match self.ivars[r as usize].1 {
                    Some(s) => Ty::Scalar(s),
                    None => Ty::IntVar(r),
                }
            }
            Ty::Array(e, n) => Ty::Array(Box::new(self.resolved(e)), *n),
            Ty::Ref(m, e) => Ty::Ref(*m, Box::new(self.resolved(e))),
            Ty::Tuple(ts) => Ty::Tuple(ts.iter().map(|t| self.resolved(t)).collect()),
            Ty::Option(e) => Ty::Option(Box::new(self.resolved(e))),
            other => other.clone(),
        }
    }

    /// The type as the finished function has it: every inference variable
    /// resolved, `i32` where nothing decided (Rust's default).
    pub(super) fn settled(&self, t: &Ty) -> Ty {
        match self.resolved(t) {
            Ty::IntVar(v) => Ty::Scalar(self.resolve_var(v)),
            Ty::Array(e, n) => Ty::Array(Box::new(self.settled(&e)), n),
            Ty::Ref(m, e) => Ty::Ref(m, Box::new(self.settled(&e))),
            Ty::Tuple(ts) => Ty::Tuple(ts.iter().map(|t| self.settled(t)).collect()),
            Ty::Option(e) => Ty::Option(Box::new(self.settled(&e))),
            other => other,
        }
    }

    /// Makes `a` and `b` the same type if they can be; false otherwise.
    pub(super) fn unify(&mut self, a: &Ty, b: &Ty) -> bool {
        let (a, b) = (self.resolved(a), self.resolved(b));
        match (&a, &b) {
            (Ty::Never, _) | (_, Ty::Never) => true,
            (Ty::IntVar(x), Ty::IntVar(y)) => {
                self.ivars[*x as usize].0 = *y;
                true
            }
            (Ty::IntVar(x), Ty::Scalar(s)) | (Ty::Scalar(s), Ty::IntVar(x)) if s.is_int() => {
                self.ivars[*x as usize].1 = Some(*s);
                true
            }
            (Ty::Array(x, n), Ty::Array(y, m)) => n == m && self.unify(x, y),
            // Element by element (a tuple literal's integers may still be
            // open); a mismatch may leave earlier elements unified, which
            // only matters for the error that follows.
            (Ty::Tuple(xs), Ty::Tuple(ys)) => xs.len() == ys.len() && xs.iter().zip(ys).all(|(x, y)| self.unify(x, y)),
            (Ty::Option(x), Ty::Option(y)) => self.unify(x, y),
            _ => a == b,
        }
    }

    pub(super) fn is_int(&self, t: &Ty) -> bool {
        match self.resolved(t) {
            Ty::IntVar(_) => true,
            Ty::Scalar(s) => s.is_int(),
            _ => false,
        }
    }

    pub(super) fn coerce(&mut self, v: Val, want: &Ty, span: Span) -> Result<Val> {
        self.note_none_use(&v, want);
        if self.unify(&v.ty, want) {
            Ok(Val { code: v.code, ty: self.resolved(want), effects: v.effects, reads: v.reads })
        } else {
            Err(Error::new(
                span,
                format!("mismatched types: expected `{}`, found `{}`", self.resolved(want), self.resolved(&v.ty)),
            ))
        }
    }

    /// Reads through a reference parameter.
    pub(super) fn deref(&self, v: Val) -> Val {
        match v.ty {
            Ty::Ref(true, t) => Val::new(format!("(*{})", v.code), *t).with_effects(v.effects).with_reads(v.reads),
            Ty::Ref(false, t) => Val::new(v.code, *t).with_effects(v.effects).with_reads(v.reads),
            _ => v,
        }
    }

    /// The type an expression would have, without emitting anything (used to
    /// pick an overload). Only cheap, side-effect-free forms are probed.
    pub(super) fn peek_type(&mut self, e: &Expr) -> Result<Option<Ty>> {
        let saved = self.snapshot();
        let r = self.expr(e, None);
        self.restore(saved, true);
        Ok(r.ok().map(|v| self.deref(v).ty))
    }
}
