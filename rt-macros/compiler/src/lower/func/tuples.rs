//! Tuples: `(a, b)` values, which are WGSL structs (`Ty::Tuple`'s
//! spelling, declared once per module from `ModuleCtx::tuples`); their
//! `.0` fields (in `expr.rs`'s `field_of`); tuple patterns in `let`
//! (destructuring into locals) and in `match` arms, lowered to an `if`
//! chain because WGSL's `switch` takes integers only.

use super::*;

impl FnLowerer<'_> {
    /// `(a, b, ...)`: the elements in Rust's order, then the constructor.
    /// An element that is still an unsuffixed integer stays open to
    /// inference, as in Rust (`let t = (5, 2.0); let x: u32 = t.0;`): the
    /// tuple's WGSL name spells it as a placeholder, resolved with the rest
    /// of the function's text, and the struct is declared once the function
    /// is lowered ([`FnLowerer::finish`]).
    pub(super) fn tuple_lit(&mut self, t: &syn::ExprTuple, want: Option<&Ty>) -> Result<Val> {
        let want_elems = match want.map(|w| self.resolved(w)) {
            Some(Ty::Tuple(e)) if e.len() == t.elems.len() => Some(e),
            _ => None,
        };
        let mut vals: Vec<Val> = Vec::new();
        for (i, e) in t.elems.iter().enumerate() {
            let at = self.here();
            let w = want_elems.as_ref().map(|w| w[i].clone());
            let v = self.expr(e, w.as_ref())?;
            let v = self.deref(v);
            let v = match &w {
                Some(w) => self.coerce(v, w, e.span())?,
                None => v,
            };
            self.spill(at, &mut vals.iter_mut().collect::<Vec<_>>());
            vals.push(v);
        }
        let mut elems = Vec::new();
        for (v, e) in vals.iter().zip(&t.elems) {
            let ty = self.resolved(&v.ty);
            if !matches!(ty, Ty::IntVar(_)) {
                crate::lower::resolve::check_tuple_element(&ty, e.span())?;
            }
            elems.push(ty);
        }
        let ty = Ty::Tuple(elems);
        self.note_tuple(&ty);
        let effects = any_effects(&vals);
        let reads = any_reads(&vals);
        Ok(Val::new(format!("{}({})", ty.wgsl(), codes(&vals).join(", ")), ty).with_effects(effects).with_reads(reads))
    }

    /// Declares the tuple type `ty` in the module, or, while an element is
    /// an integer not yet inferred, once the function is lowered.
    pub(super) fn note_tuple(&mut self, ty: &Ty) {
        if has_int_var(&self.resolved(ty)) {
            self.pending_tuples.push(ty.clone());
        } else {
            self.m.note_tuples(&self.resolved(ty));
        }
    }

    /// `(a, b).k`: every element evaluated, in order, and element `k` the
    /// value, with its own type (an unsuffixed integer stays open to
    /// inference, as in Rust, rather than becoming the `i32` a tuple
    /// value would need).
    pub(super) fn tuple_lit_field(&mut self, t: &syn::ExprTuple, k: usize) -> Result<Val> {
        let mut picked: Option<Val> = None;
        for (i, e) in t.elems.iter().enumerate() {
            let at = self.here();
            let v = self.expr(e, None)?;
            let v = self.deref(v);
            if let Some(p) = picked.as_mut() {
                self.spill(at, &mut [p]);
            }
            if i == k {
                picked = Some(v);
            } else if v.effects {
                let tmp = self.tmp();
                self.emit_let(format!("let {tmp} = {};", v.code), &v);
            }
        }
        Ok(picked.expect("k is in range"))
    }

    /// `let (a, (b, _)) = value;`: the value once, then each name bound to
    /// its element.
    pub(super) fn let_tuple(&mut self, pat: &syn::Pat, annot: Option<&Ty>, init: &Expr, span: Span) -> Result<()> {
        let v = self.expr(init, annot)?;
        let v = self.deref(v);
        let v = match annot {
            Some(a) => self.coerce(v, a, init.span())?,
            None => v,
        };
        let ty = self.resolved(&v.ty);
        let whole = self.fresh("tuple");
        self.declare_local(&whole, false, ty.clone(), Some(v), span);
        self.bind_elements(pat, Val::new(whole, ty), span)
    }

    fn bind_elements(&mut self, pat: &syn::Pat, v: Val, span: Span) -> Result<()> {
        match pat {
            syn::Pat::Tuple(pt) => {
                let elems = self.tuple_elements(&v.ty, pt.elems.len(), pt.span())?;
                for (i, (p, ety)) in pt.elems.iter().zip(elems).enumerate() {
                    self.bind_elements(p, Val::new(format!("{}.f{i}", v.code), ety), span)?;
                }
                Ok(())
            }
            syn::Pat::Paren(p) => self.bind_elements(&p.pat, v, span),
            syn::Pat::TupleStruct(ts) if !options::is_some_path(&ts.path) => {
                let fields = self.tuple_struct_fields(ts, &v.ty)?;
                for (p, (f, fty)) in ts.elems.iter().zip(fields) {
                    self.bind_elements(p, Val::new(format!("{}.{f}", v.code), fty), span)?;
                }
                Ok(())
            }
            syn::Pat::Wild(_) => Ok(()),
            syn::Pat::Ident(pi) if pi.by_ref.is_none() && pi.subpat.is_none() => {
                let name = pi.ident.to_string();
                let wname = self.fresh(&name);
                let ty = v.ty.clone();
                self.declare_local(&wname, pi.mutability.is_some(), ty.clone(), Some(v), span);
                let var = pi.mutability.is_some() || matches!(ty, Ty::Array(..) | Ty::Mat(_));
                self.bind(&name, Local { wgsl: wname, ty, var });
                Ok(())
            }
            other => Err(Error::unsupported(
                other.span(),
                "this pattern in a tuple",
                "bind names, `_` and nested tuples: `let (a, (b, _)) = t;`",
            )),
        }
    }

    /// The element types of a tuple of `n` elements, or the error at a
    /// pattern that does not fit `ty`.
    fn tuple_elements(&self, ty: &Ty, n: usize, span: Span) -> Result<Vec<Ty>> {
        match self.resolved(ty) {
            Ty::Tuple(elems) if elems.len() == n => Ok(elems),
            Ty::Tuple(elems) => Err(Error::new(
                span,
                format!("mismatched types: a tuple of {} elements, matched by a pattern of {n}", elems.len()),
            )),
            other => Err(Error::new(span, format!("mismatched types: expected `{other}`, found a tuple pattern"))),
        }
    }

    /// `match (a, b) { (0, x) => .., (_, 1) | (1, _) => .., _ => .. }`: the
    /// scrutinee once, then one `if` per arm, in order (Rust's first
    /// matching arm), each testing its literal elements and binding its
    /// names.
    pub(super) fn match_tuple(&mut self, m: &syn::ExprMatch, want: Option<&Ty>, scrut: Val, sty: Ty) -> Result<Val> {
        let s = self.fresh("scrutinee");
        self.emit_let(format!("let {s} = {};", scrut.code), &scrut);
        let t = self.tmp();
        let mut result_ty: Option<Ty> = None;
        let mut branches: Vec<(Vec<String>, Vec<String>)> = Vec::new();
        for arm in &m.arms {
            if let Some((if_token, _)) = &arm.guard {
                return Err(Error::unsupported(if_token.span, "a match guard", "use if/else inside the arm"));
            }
            let mut alternatives = Vec::new();
            let mut names = Vec::new();
            self.tuple_arm(&arm.pat, &s, &sty, &mut alternatives, &mut names)?;
            self.scopes.push(Vec::new());
            self.blocks.push(Block::default());
            for (name, code, ty) in names {
                let w = self.fresh(&name);
                self.emit(format!("let {w} = {code};"));
                self.bind(&name, Local { wgsl: w, ty, var: false });
            }
            let want_arm = result_ty.clone().or(want.cloned());
            let r = self.expr(&arm.body, want_arm.as_ref());
            let mut lines = self.blocks.pop().unwrap().lines;
            self.scopes.pop();
            let v = r?;
            let vty = self.resolved(&v.ty);
            if !matches!(vty, Ty::Unit | Ty::Never) {
                let v = match &result_ty {
                    Some(rt) => self.coerce(v, &rt.clone(), arm.body.span())?,
                    None => {
                        result_ty = Some(vty);
                        v
                    }
                };
                lines.push(format!("{t} = {};", v.code));
            }
            let always = alternatives.iter().any(|a: &String| a.is_empty());
            branches.push((if always { Vec::new() } else { alternatives }, lines));
            if always {
                break;
            }
        }
        if let Some(rt) = &result_ty {
            self.emit(format!("var {t}: {};", rt.wgsl()));
        }
        let mut text = String::new();
        for (i, (alts, lines)) in branches.iter().enumerate() {
            let body = indent(&lines.join("\n"));
            if alts.is_empty() {
                // The catch-all: `else { .. }` after the others, or a bare
                // block when it is the first arm.
                text.push_str(&format!("{{\n{body}}}"));
                break;
            }
            let cond = alts.iter().map(|a| format!("({a})")).collect::<Vec<_>>().join(" || ");
            text.push_str(&format!("if {cond} {{\n{body}}}"));
            if i + 1 < branches.len() {
                text.push_str(" else ");
            }
        }
        let text = self.mark(m.span(), &text);
        self.emit(text);
        Ok(match result_ty {
            Some(rt) => Val::new(t, rt),
            None => Val::new("", Ty::Unit),
        })
    }

    /// One arm's pattern over the tuple `base` of type `ty`: each
    /// alternative's condition (empty: always matches) and the names it
    /// binds, `(name, element, type)`.
    fn tuple_arm(
        &mut self,
        p: &syn::Pat,
        base: &str,
        ty: &Ty,
        alternatives: &mut Vec<String>,
        names: &mut Vec<(String, String, Ty)>,
    ) -> Result<()> {
        match p {
            syn::Pat::Or(o) => {
                for c in &o.cases {
                    let mut bound = Vec::new();
                    self.tuple_arm(c, base, ty, alternatives, &mut bound)?;
                    if !bound.is_empty() {
                        return Err(Error::unsupported(
                            c.span(),
                            "a binding in one of several tuple patterns",
                            "bind in an arm of its own, or match the element again inside the arm",
                        ));
                    }
                }
                Ok(())
            }
            syn::Pat::Paren(pp) => self.tuple_arm(&pp.pat, base, ty, alternatives, names),
            _ => {
                let mut conds = Vec::new();
                self.element_pattern(p, base, ty, &mut conds, names)?;
                alternatives.push(conds.join(" && "));
                Ok(())
            }
        }
    }

    /// The conditions one pattern puts on the value `code` of type `ty`.
    pub(super) fn element_pattern(
        &mut self,
        p: &syn::Pat,
        code: &str,
        ty: &Ty,
        conds: &mut Vec<String>,
        names: &mut Vec<(String, String, Ty)>,
    ) -> Result<()> {
        match p {
            syn::Pat::Tuple(pt) => {
                let elems = self.tuple_elements(ty, pt.elems.len(), pt.span())?;
                for (i, (ep, ety)) in pt.elems.iter().zip(elems).enumerate() {
                    self.element_pattern(ep, &format!("{code}.f{i}"), &ety, conds, names)?;
                }
                Ok(())
            }
            syn::Pat::Paren(pp) => self.element_pattern(&pp.pat, code, ty, conds, names),
            syn::Pat::TupleStruct(ts) if !options::is_some_path(&ts.path) => {
                let fields = self.tuple_struct_fields(ts, ty)?;
                for (ep, (f, fty)) in ts.elems.iter().zip(fields) {
                    self.element_pattern(ep, &format!("{code}.{f}"), &fty, conds, names)?;
                }
                Ok(())
            }
            syn::Pat::Wild(_) => Ok(()),
            _ if matches!(self.resolved(ty), Ty::Option(_)) => self.option_pattern(p, code, ty, conds, names),
            _ if matches!(self.resolved(ty), Ty::Tuple(_)) => {
                Err(Error::unsupported(p.span(), "this pattern for a tuple", "write a tuple pattern, `_` or a name"))
            }
            _ => {
                let mut labels = Vec::new();
                let mut binding = None;
                self.match_pattern(p, ty, &mut labels, &mut binding)?;
                if let Some(b) = binding {
                    if !labels.is_empty() {
                        return Err(Error::unsupported(
                            p.span(),
                            "a binding among literal patterns",
                            "bind the element in an arm of its own",
                        ));
                    }
                    names.push((b, code.to_string(), self.resolved(ty)));
                } else if !labels.is_empty() {
                    let any = labels.iter().map(|l| format!("{code} == {l}")).collect::<Vec<_>>().join(" || ");
                    conds.push(format!("({any})"));
                }
                Ok(())
            }
        }
    }
}

/// Whether a type still holds an integer inference variable.
pub(super) fn has_int_var(t: &Ty) -> bool {
    match t {
        Ty::IntVar(_) => true,
        Ty::Tuple(ts) => ts.iter().any(has_int_var),
        Ty::Array(t, _) | Ty::Ref(_, t) | Ty::Option(t) => has_int_var(t),
        _ => false,
    }
}
