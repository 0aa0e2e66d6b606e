//! Operators on user types: `a + b`, `-a`, `a += b` and `a[i]` where `a`
//! is a type with an `#[rt_impl]` of the operator's trait (see
//! `crate::operators`): a call of the impl's method, the impl chosen by
//! the right operand's type, as rustc chooses it.

use super::*;
use crate::lower::generics::{self, GenericArg, Instance};
use crate::operators::{OPERATORS, OpKind, key_prefix};

impl FnLowerer<'_> {
    /// The user type a value of type `t` is.
    fn operand_owner(&self, t: &Ty) -> Option<String> {
        match self.known(t) {
            Ty::Struct(d) => Some(d.name.clone()),
            Ty::Enum(e) => Some(e.name.clone()),
            _ => None,
        }
    }

    /// The signatures of the impls of the operator whose method is
    /// `method` for the left operand's type `t` (one per right-hand type);
    /// `Err` silent where such an impl failed (its error is reported).
    fn operator_impls(&mut self, t: &Ty, method: &str, span: Span) -> Result<Vec<HelperSig>> {
        let t = self.known(t);
        if let Ty::Struct(d) = &t
            && let Some((name, args)) = &d.generic
        {
            return self.generic_operator_impls(name, args, method, span);
        }
        let Some(owner) = self.operand_owner(&t) else { return Ok(Vec::new()) };
        let prefix = key_prefix(&owner, method);
        if self.m.failed.iter().any(|k| k.starts_with(&prefix)) {
            return Err(Error::silent(span));
        }
        let mut sigs: Vec<HelperSig> =
            self.m.helpers.iter().filter(|(k, _)| k.starts_with(&prefix)).map(|(_, s)| s.clone()).collect();
        sigs.sort_by(|a, b| a.name.cmp(&b.name));
        Ok(sigs)
    }

    /// The impls of the operator `method` of the generic struct `name`
    /// (`impl<T: ..> Add for Pair<T>`), each instantiated at the left
    /// operand's arguments `args`: the instance's signature, which a pass
    /// that lacks the instance records as wanted and types from the
    /// instantiated signature, as a generic call does
    /// (`lower/generics.rs`).
    fn generic_operator_impls(&mut self, name: &str, args: &[Ty], method: &str, span: Span) -> Result<Vec<HelperSig>> {
        let prefix = key_prefix(name, method);
        if self.m.failed.iter().any(|k| k.starts_with(&prefix)) {
            return Err(Error::silent(span));
        }
        let mut generic: Vec<(String, std::rc::Rc<syn::ItemFn>)> = self
            .m
            .generics
            .iter()
            .filter(|(k, _)| k.starts_with(&prefix))
            .map(|(k, g)| (k.clone(), g.clone()))
            .collect();
        generic.sort_by(|a, b| a.0.cmp(&b.0));
        let mut sigs = Vec::new();
        for (key, g) in generic {
            let inst = Instance { generic: key, args: args.iter().cloned().map(GenericArg::Type).collect() };
            if let Some(sig) = self.m.helpers.get(&inst.key()) {
                sigs.push(sig.clone());
                continue;
            }
            if self.m.failed.contains(&inst.key()) {
                return Err(Error::silent(span));
            }
            let f = generics::instantiate(&g, &inst.args);
            let mut params = Vec::new();
            for input in &f.sig.inputs {
                if let syn::FnArg::Typed(pt) = input {
                    params.push(self.m.resolve_type(&pt.ty).map_err(|e| Error::silent(e.span))?);
                }
            }
            let ret = match &f.sig.output {
                syn::ReturnType::Default => Ty::Unit,
                syn::ReturnType::Type(_, t) => self.m.resolve_type(t).map_err(|e| Error::silent(e.span))?,
            };
            sigs.push(HelperSig {
                name: inst.key(),
                wgsl_name: inst.wgsl_name(),
                params,
                ret,
                intrinsics: Vec::new(),
                traced: Vec::new(),
                resumable: false,
                has_receiver: true,
            });
            let mut wanted = self.m.wanted.borrow_mut();
            if !wanted.contains(&inst) {
                wanted.push(inst);
            }
        }
        Ok(sigs)
    }

    /// Whether the unit has any operator impl (else no operand is probed).
    fn has_operator_impls(&self) -> bool {
        self.m.helpers.keys().chain(self.m.failed.iter()).chain(self.m.generics.keys()).any(|k| k.contains(" op "))
    }

    /// A type as far as it is known; an integer a probe (`peek_type`)
    /// left unsettled stays an integer variable.
    fn known(&self, t: &Ty) -> Ty {
        match t {
            Ty::IntVar(v) if *v as usize >= self.ivars.len() => t.clone(),
            _ => self.resolved(t),
        }
    }

    /// Of `sigs`, the impl whose right-hand parameter takes `rt`.
    fn pick_impl(&self, sigs: &[HelperSig], rt: &Ty) -> Option<HelperSig> {
        let rt = self.known(rt);
        let rhs = |s: &HelperSig| match s.params.get(1) {
            Some(Ty::Ref(_, t)) => (**t).clone(),
            Some(t) => t.clone(),
            None => Ty::Unit,
        };
        if let Some(s) = sigs.iter().find(|s| rhs(s) == rt) {
            return Some(s.clone());
        }
        // An integer literal: the one impl whose right side is an integer
        // (the caller coerces the operand to it).
        let ints: Vec<&HelperSig> = sigs.iter().filter(|s| self.is_int(&rhs(s))).collect();
        match (&rt, ints.as_slice()) {
            (Ty::IntVar(_), [s]) => Some((*s).clone()),
            _ => None,
        }
    }

    /// `l op r` (both lowered) where `l` is a user type with an impl of
    /// the operator; `None` where it has none (the built-in operators'
    /// errors follow).
    pub(super) fn user_binary(
        &mut self,
        op: &BinOp,
        l: Val,
        r: Val,
        start: usize,
        span: Span,
    ) -> Result<std::result::Result<Val, (Val, Val)>> {
        let Some(owner) = self.operand_owner(&l.ty) else { return Ok(Err((l, r))) };
        let Some(o) = OPERATORS.iter().find(|o| o.kind == OpKind::Binary && o.method == binary_method(op)) else {
            return Ok(Err((l, r)));
        };
        let sigs = self.operator_impls(&l.ty, o.method, span)?;
        if sigs.is_empty() {
            return Ok(Err((l, r)));
        }
        let Some(sig) = self.pick_impl(&sigs, &r.ty) else {
            let rt = self.known(&r.ty);
            return Err(Error::new(
                span,
                format!(
                    "no `impl {}<{rt}> for {owner}`: `{owner} {} {rt}` is not defined; convert the right side, or \
                     implement the operator for it with #[rt_impl]",
                    o.trait_name,
                    op_symbol(op)
                ),
            ));
        };
        self.method_calls.push((sig.name.clone(), span));
        let want = sig.params[1].clone();
        let want = match want {
            Ty::Ref(_, t) => *t,
            t => t,
        };
        let r = self.coerce(r, &want, span)?;
        self.finish_helper_call(&sig, vec![l, r], start, span).map(Ok)
    }

    /// `a.add(b)`, `a.neg()`: an operator trait's method called by name on
    /// a user type with an impl of that trait, lowered as the operator
    /// itself (`a + b`, `-a`), so the impl is chosen as for the operator.
    /// `None` for any other call (a method the type declares by that name
    /// was taken before).
    pub(super) fn operator_by_name(&mut self, m: &syn::ExprMethodCall, want: Option<&Ty>) -> Result<Option<Val>> {
        if !self.has_operator_impls() || m.turbofish.is_some() {
            return Ok(None);
        }
        let name = m.method.to_string();
        let binary = match OPERATORS.iter().find(|o| o.method == name).map(|o| &o.kind) {
            Some(OpKind::Binary) => true,
            Some(OpKind::Unary) => false,
            _ => return Ok(None),
        };
        if m.args.len() != usize::from(binary) {
            return Ok(None);
        }
        let Some(t) = self.peek_type(&m.receiver)? else { return Ok(None) };
        let (t, by_ref) = match t {
            Ty::Ref(_, t) => (*t, true),
            t => (t, false),
        };
        if self.operand_owner(&t).is_none() || self.operator_impls(&t, &name, m.span())?.is_empty() {
            return Ok(None);
        }
        let recv = &m.receiver;
        let span = m.span();
        let a: Expr =
            if by_ref { syn::parse_quote_spanned!(span=> (*#recv)) } else { syn::parse_quote_spanned!(span=> (#recv)) };
        let e: Expr = match (name.as_str(), m.args.first()) {
            ("neg", None) => syn::parse_quote_spanned!(span=> -#a),
            ("not", None) => syn::parse_quote_spanned!(span=> !#a),
            ("add", Some(b)) => syn::parse_quote_spanned!(span=> #a + (#b)),
            ("sub", Some(b)) => syn::parse_quote_spanned!(span=> #a - (#b)),
            ("mul", Some(b)) => syn::parse_quote_spanned!(span=> #a * (#b)),
            ("div", Some(b)) => syn::parse_quote_spanned!(span=> #a / (#b)),
            ("rem", Some(b)) => syn::parse_quote_spanned!(span=> #a % (#b)),
            ("bitand", Some(b)) => syn::parse_quote_spanned!(span=> #a & (#b)),
            ("bitor", Some(b)) => syn::parse_quote_spanned!(span=> #a | (#b)),
            ("bitxor", Some(b)) => syn::parse_quote_spanned!(span=> #a ^ (#b)),
            _ => return Ok(None),
        };
        self.expr(&e, want).map(Some)
    }

    /// `-a`, `!a` of a user type with an impl of `Neg`, `Not`.
    pub(super) fn user_unary(&mut self, u: &syn::ExprUnary) -> Result<Option<Val>> {
        let method = match u.op {
            UnOp::Neg(_) => "neg",
            UnOp::Not(_) => "not",
            _ => return Ok(None),
        };
        if !self.has_operator_impls() {
            return Ok(None);
        }
        let Some(t) = self.peek_type(&u.expr)? else { return Ok(None) };
        if self.operand_owner(&t).is_none() {
            return Ok(None);
        }
        let sigs = self.operator_impls(&t, method, u.span())?;
        let Some(sig) = sigs.first() else { return Ok(None) };
        self.method_calls.push((sig.name.clone(), u.span()));
        let start = self.here();
        let v = self.expr(&u.expr, None)?;
        let v = self.deref(v);
        self.finish_helper_call(sig, vec![v], start, u.span()).map(Some)
    }

    /// `a op= b` of a user type with an impl of `AddAssign` (and the rest):
    /// the method takes the place by pointer.
    pub(super) fn user_compound(&mut self, b: &syn::ExprBinary) -> Result<Option<Val>> {
        let Some(method) = compound_method(&b.op) else { return Ok(None) };
        if !self.has_operator_impls() {
            return Ok(None);
        }
        let Some(t) = self.peek_type(&b.left)? else { return Ok(None) };
        let Some(owner) = self.operand_owner(&t) else { return Ok(None) };
        let sigs = self.operator_impls(&t, method, b.op.span())?;
        if sigs.is_empty() {
            return Ok(None);
        }
        let rt = self.peek_type(&b.right)?.unwrap_or(Ty::Unit);
        let Some(sig) = self.pick_impl(&sigs, &rt) else {
            let rt = self.known(&rt);
            let trait_name = OPERATORS.iter().find(|o| o.method == method).map_or("", |o| o.trait_name);
            return Err(Error::new(
                b.op.span(),
                format!(
                    "no `impl {trait_name}<{rt}> for {owner}`: convert the right side, or implement the operator for it with #[rt_impl]"
                ),
            ));
        };
        self.method_calls.push((sig.name.clone(), b.op.span()));
        let place = &b.left;
        let receiver: Expr = syn::parse_quote_spanned!(place.span()=> &mut #place);
        self.helper_call(&sig, &[&receiver, &b.right], b.op.span()).map(Some)
    }

    /// `a[i]` of a user type with an impl of `Index`: its element, by value.
    pub(super) fn user_index(
        &mut self,
        base: Val,
        index: &Expr,
        start: usize,
        span: Span,
    ) -> Result<std::result::Result<Val, Val>> {
        let Some(owner) = self.operand_owner(&base.ty) else { return Ok(Err(base)) };
        let sigs = self.operator_impls(&base.ty, "index", span)?;
        if sigs.is_empty() {
            return Ok(Err(base));
        }
        let it = self.peek_type(index)?.unwrap_or(Ty::Unit);
        let Some(sig) = self.pick_impl(&sigs, &it) else {
            let it = self.known(&it);
            return Err(Error::new(
                index.span(),
                format!("no `impl Index<{it}> for {owner}`: index it with the type its `Index` impl takes"),
            ));
        };
        self.method_calls.push((sig.name.clone(), span));
        let want = sig.params[1].clone();
        let i = self.expr(index, Some(&want))?;
        let i = self.deref(i);
        let i = self.coerce(i, &want, index.span())?;
        self.finish_helper_call(&sig, vec![base, i], start, span).map(Ok)
    }
}

/// The method of the binary operator `op`'s trait.
fn binary_method(op: &BinOp) -> &'static str {
    match op {
        BinOp::Add(_) => "add",
        BinOp::Sub(_) => "sub",
        BinOp::Mul(_) => "mul",
        BinOp::Div(_) => "div",
        BinOp::Rem(_) => "rem",
        BinOp::BitAnd(_) => "bitand",
        BinOp::BitOr(_) => "bitor",
        BinOp::BitXor(_) => "bitxor",
        _ => "",
    }
}

/// The method of the compound assignment `op`'s trait.
fn compound_method(op: &BinOp) -> Option<&'static str> {
    Some(match op {
        BinOp::AddAssign(_) => "add_assign",
        BinOp::SubAssign(_) => "sub_assign",
        BinOp::MulAssign(_) => "mul_assign",
        BinOp::DivAssign(_) => "div_assign",
        BinOp::RemAssign(_) => "rem_assign",
        BinOp::BitAndAssign(_) => "bitand_assign",
        BinOp::BitOrAssign(_) => "bitor_assign",
        BinOp::BitXorAssign(_) => "bitxor_assign",
        _ => return None,
    })
}
