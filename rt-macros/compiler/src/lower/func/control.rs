//! Control flow: `if`, blocks, `loop`, `while`, `for` over ranges, `match`
//! on integers (a WGSL `switch`), `break`, `continue` and `return`.

use super::*;

/// A `loop`'s value: the variable its `break`s assign, and its type.
type LoopValue = (String, Ty);

impl FnLowerer<'_> {
    pub(super) fn cond(&mut self, e: &Expr) -> Result<String> {
        let v = self.expr(e, Some(&BOOL))?;
        let v = self.deref(v);
        Ok(self.coerce(v, &BOOL, e.span())?.code)
    }

    pub(super) fn if_expr(&mut self, i: &syn::ExprIf, want: Option<&Ty>) -> Result<Val> {
        let cond = self.cond(&i.cond)?;
        let (then_lines, then_val) = self.sub_block(&i.then_branch.stmts, want)?;
        let then_ty = then_val.as_ref().map(|v| self.resolved(&v.ty)).unwrap_or(Ty::Unit);
        let valued =
            !matches!(then_ty, Ty::Unit | Ty::Never) || (i.else_branch.is_some() && want.is_some_and(|w| w.is_value()));
        let else_want = if matches!(then_ty, Ty::Never) { want.cloned() } else { Some(then_ty.clone()) };
        let else_part = match &i.else_branch {
            Some((_, e)) => match &**e {
                // `else { ... }`: lower the block's statements in place.
                Expr::Block(b) if b.label.is_none() => {
                    let (lines, v) = self.sub_block(&b.block.stmts, else_want.as_ref())?;
                    let span = b.block.stmts.last().map(|s| s.span()).unwrap_or(b.span());
                    Some((lines, v.unwrap_or(Val::new("", Ty::Unit)), span))
                }
                _ => {
                    self.blocks.push(Block::default());
                    self.scopes.push(Vec::new());
                    let r = self.expr(e, else_want.as_ref());
                    self.scopes.pop();
                    let lines = self.blocks.pop().unwrap().lines;
                    Some((lines, r?, e.span()))
                }
            },
            None => None,
        };
        // `if c { return; } else { v }` is a value too.
        let valued = valued
            || (matches!(then_ty, Ty::Never)
                && else_part.as_ref().is_some_and(|(_, v, _)| self.resolved(&v.ty).is_value()));
        if !valued
            || else_part.as_ref().is_some_and(|(_, v, _)| matches!(v.ty, Ty::Unit) && !matches!(then_ty, Ty::Never))
        {
            // A statement `if`.
            let mut then_lines = then_lines;
            if let Some(v) = then_val
                && !v.code.is_empty()
                && !matches!(v.ty, Ty::Unit | Ty::Never)
            {
                then_lines.push(format!("_ = {};", v.code));
            }
            let mut text = format!("if {cond} {{\n{}}}", indent(&then_lines.join("\n")));
            if let Some((mut lines, v, _)) = else_part {
                if !v.code.is_empty() && !matches!(v.ty, Ty::Unit | Ty::Never) {
                    lines.push(format!("_ = {};", v.code));
                }
                text.push_str(&format!(" else {{\n{}}}", indent(&lines.join("\n"))));
            }
            self.emit(text);
            return Ok(Val::new("", Ty::Unit));
        }
        let Some((mut else_lines, else_val, else_span)) = else_part else {
            return Err(Error::new(i.span(), "an `if` used as a value needs an `else` branch"));
        };
        let then_val = then_val.unwrap();
        let ty = if matches!(then_ty, Ty::Never) { self.resolved(&else_val.ty) } else { then_ty.clone() };
        let else_val = self.coerce(else_val, &ty, else_span)?;
        let t = self.tmp();
        let mut then_lines = then_lines;
        if !matches!(then_ty, Ty::Never) {
            then_lines.push(format!("{t} = {};", then_val.code));
        }
        if !matches!(else_val.ty, Ty::Never) && !else_val.code.is_empty() {
            else_lines.push(format!("{t} = {};", else_val.code));
        }
        self.emit(format!("var {t}: {};", ty.wgsl()));
        self.emit(format!(
            "if {cond} {{\n{}}} else {{\n{}}}",
            indent(&then_lines.join("\n")),
            indent(&else_lines.join("\n"))
        ));
        Ok(Val::new(t, ty))
    }

    pub(super) fn block_expr(&mut self, stmts: &[Stmt], want: Option<&Ty>, _span: Span) -> Result<Val> {
        let (lines, val) = self.sub_block(stmts, want)?;
        match val {
            Some(v) if !matches!(self.resolved(&v.ty), Ty::Unit | Ty::Never) => {
                let ty = self.resolved(&v.ty);
                let t = self.tmp();
                self.emit(format!("var {t}: {};", ty.wgsl()));
                let mut lines = lines;
                lines.push(format!("{t} = {};", v.code));
                self.emit(format!("{{\n{}}}", indent(&lines.join("\n"))));
                Ok(Val::new(t, ty))
            }
            v => {
                let mut lines = lines;
                if let Some(v) = &v
                    && !v.code.is_empty()
                    && matches!(v.ty, Ty::Unit)
                {
                    lines.push(format!("_ = {};", v.code));
                }
                self.emit(format!("{{\n{}}}", indent(&lines.join("\n"))));
                Ok(Val::new("", v.map(|v| v.ty).unwrap_or(Ty::Unit)))
            }
        }
    }

    /// `break;` out of the innermost loop (see `breaks`).
    pub(super) fn break_text(&mut self) -> String {
        match self.breaks.last_mut() {
            Some(Some((flag, used))) => {
                *used = true;
                format!("{flag} = true;\nbreak;")
            }
            _ => "break;".to_string(),
        }
    }

    pub(super) fn loop_body(&mut self, stmts: &[Stmt]) -> Result<Vec<String>> {
        self.loop_values.push(None);
        let r = self.loop_body_inner(stmts);
        self.loop_values.pop();
        r
    }

    /// A `loop`'s body, whose `break`s may carry a value: the body's
    /// lines and, if a `break` had a value, the variable it was assigned to
    /// and its type.
    fn value_loop_body(&mut self, stmts: &[Stmt]) -> Result<(Vec<String>, Option<LoopValue>)> {
        self.loop_values.push(Some(None));
        let r = self.loop_body_inner(stmts);
        let value = self.loop_values.pop().flatten().flatten();
        Ok((r?, value))
    }

    fn loop_body_inner(&mut self, stmts: &[Stmt]) -> Result<Vec<String>> {
        self.loop_depth += 1;
        self.breaks.push(None);
        let r = self.sub_block(stmts, Some(&Ty::Unit));
        self.breaks.pop();
        self.loop_depth -= 1;
        let (mut lines, v) = r?;
        if let Some(v) = v
            && !v.code.is_empty()
            && !matches!(self.resolved(&v.ty), Ty::Unit | Ty::Never)
        {
            lines.push(format!("_ = {};", v.code));
        }
        Ok(lines)
    }

    pub(super) fn while_loop(&mut self, w: &syn::ExprWhile) -> Result<Val> {
        if let Some(l) = &w.label {
            return Err(Error::unsupported(l.span(), "a labeled loop", "WGSL has no labels; use a flag variable"));
        }
        if let Expr::Let(l) = &*w.cond {
            return Err(Error::unsupported(
                l.let_token.span,
                "`while let`",
                "loop with a plain condition (`while n > 0`), or `loop` with `if ... { break; }`",
            ));
        }
        self.blocks.push(Block::default());
        let cond = self.cond(&w.cond);
        let hoisted = self.blocks.pop().unwrap().lines;
        let cond = cond?;
        let body = self.loop_body(&w.body.stmts)?;
        let text = if hoisted.is_empty() {
            format!("while {cond} {{\n{}}}", indent(&body.join("\n")))
        } else {
            let mut all = hoisted;
            all.push(format!("if !({cond}) {{\n    break;\n}}"));
            all.extend(body);
            format!("loop {{\n{}}}", indent(&all.join("\n")))
        };
        let text = self.mark(w.span(), &text);
        self.emit(text);
        Ok(Val::new("", Ty::Unit))
    }

    pub(super) fn loop_expr(&mut self, l: &syn::ExprLoop) -> Result<Val> {
        if let Some(lb) = &l.label {
            return Err(Error::unsupported(lb.span(), "a labeled loop", "WGSL has no labels; use a flag variable"));
        }
        let at = self.blocks.last().map_or(0, Block::len);
        let (body, value) = self.value_loop_body(&l.body.stmts)?;
        let text = self.mark(l.span(), &format!("loop {{\n{}}}", indent(&body.join("\n"))));
        self.emit(text);
        match value {
            // The `break`s assigned the loop's value to a variable declared
            // just before it.
            Some((var, ty)) => {
                if let Some(block) = self.blocks.last_mut() {
                    block.insert(at, format!("var {var}: {};", ty.wgsl()), false);
                }
                Ok(Val::new(var, ty).with_reads(true))
            }
            // A `loop` without `break` never ends; with plain `break`s it
            // yields no value.
            None => Ok(Val::new("", Ty::Unit)),
        }
    }

    pub(super) fn for_loop(&mut self, f: &syn::ExprForLoop) -> Result<Val> {
        if let Some(l) = &f.label {
            return Err(Error::unsupported(l.span(), "a labeled loop", "WGSL has no labels; use a flag variable"));
        }
        let name = match &*f.pat {
            syn::Pat::Ident(pi) if pi.by_ref.is_none() && pi.subpat.is_none() => pi.ident.to_string(),
            syn::Pat::Wild(_) => "_".to_string(),
            other => return Err(Error::unsupported(other.span(), "this loop pattern", "use `for i in a..b`")),
        };
        let range = match &*f.expr {
            Expr::Range(r) => r,
            Expr::Paren(p) if matches!(&*p.expr, Expr::Range(_)) => match &*p.expr {
                Expr::Range(r) => r,
                _ => unreachable!(),
            },
            other => {
                return Err(Error::unsupported(
                    other.span(),
                    "iterating over this expression",
                    "loop over an index range: `for i in 0..n`",
                ));
            }
        };
        let (Some(start), Some(end)) = (&range.start, &range.end) else {
            return Err(Error::unsupported(range.span(), "an open range", "give both bounds: `a..b`"));
        };
        let s = self.expr(start, None)?;
        let s = self.deref(s);
        let e = self.expr(end, Some(&s.ty))?;
        let e = self.deref(e);
        if !self.is_int(&s.ty) || !self.unify(&s.ty, &e.ty) {
            return Err(Error::new(
                range.span(),
                format!(
                    "a `for` range needs integer bounds of one type, found `{}` and `{}`",
                    self.resolved(&s.ty),
                    self.resolved(&e.ty)
                ),
            ));
        }
        let ty = self.resolved(&s.ty);
        // Rust evaluates the end once: hoist it unless it is a literal.
        let end_code = if matches!(&**end, Expr::Lit(_)) {
            e.code
        } else {
            let t = self.fresh("end");
            self.emit_let(format!("let {t} = {};", e.code), &e);
            t
        };
        self.scopes.push(Vec::new());
        let var = self.fresh(if name == "_" { "i" } else { &name });
        self.bind(&name, Local { wgsl: var.clone(), ty: ty.clone(), var: false });
        let body = self.loop_body(&f.body.stmts);
        self.scopes.pop();
        let body = body?;
        // `a..=b` stops after `b` without computing `b + 1`, which for
        // `b == u32::MAX` would wrap and never stop: unless `b` is a literal
        // below the maximum, the loop tests for the last value itself.
        let end_below_max = match &**end {
            Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }) => {
                let max = if matches!(ty, Ty::Scalar(Scalar::U32 | Scalar::Usize)) {
                    u32::MAX as u64
                } else {
                    i32::MAX as u64
                };
                i.base10_parse::<u64>().is_ok_and(|v| v < max)
            }
            _ => false,
        };
        let text = if matches!(range.limits, syn::RangeLimits::Closed(_)) && !end_below_max {
            let last = self.fresh("last");
            let looped = format!(
                "loop {{\n{}    continuing {{\n        let {last} = {var} == {end_code};\n        {var}++;\n        break if {last};\n    }}\n}}",
                indent(&body.join("\n"))
            );
            let guarded = format!("if {var} <= {end_code} {{\n{}}}", indent(&looped));
            format!("{{\n    var {var}: {} = {};\n{}}}", ty.wgsl(), s.code, indent(&guarded))
        } else {
            let cmp = if matches!(range.limits, syn::RangeLimits::Closed(_)) { "<=" } else { "<" };
            format!(
                "for (var {var}: {} = {}; {var} {cmp} {end_code}; {var}++) {{\n{}}}",
                ty.wgsl(),
                s.code,
                indent(&body.join("\n"))
            )
        };
        let text = self.mark(f.span(), &text);
        self.emit(text);
        Ok(Val::new("", Ty::Unit))
    }

    /// `break`: out of the innermost loop, through a `match` arm's flag (see
    /// `breaks`).
    pub(super) fn break_expr(&mut self, b: &syn::ExprBreak) -> Result<Val> {
        if let Some(l) = &b.label {
            return Err(Error::unsupported(l.span(), "a labeled `break`", "WGSL has no labels; use a flag variable"));
        }
        if self.loop_depth == 0 {
            return Err(Error::new(b.span(), "`break` outside of a loop"));
        }
        if let Some(v) = &b.expr {
            self.break_value(v)?;
        }
        let text = self.break_text();
        let line = self.mark(b.span(), &text);
        self.emit(line);
        Ok(Val::new("", Ty::Never))
    }

    /// `break value`'s value, assigned to its `loop`'s variable (the
    /// loop's type set by the first such `break`, the others coerced to
    /// it).
    fn break_value(&mut self, v: &Expr) -> Result<()> {
        if self.resume.is_some() {
            // The resumable form keeps its locals in frames; this variable
            // is not one of them.
            return Err(Error::unsupported(
                v.span(),
                "`break` with a value in a tracing program's resumable form",
                "assign to a variable before `break`",
            ));
        }
        let Some(Some(value)) = self.loop_values.last().cloned() else {
            return Err(Error::new(
                v.span(),
                "`break` with a value inside a `while` or `for` loop: only `loop` has one",
            ));
        };
        let val = self.expr(v, value.as_ref().map(|(_, t)| t))?;
        if matches!(val.ty, Ty::Unit | Ty::Never) {
            return Ok(());
        }
        let (var, val) = match value {
            Some((var, t)) => (var, self.coerce(val, &t, v.span())?),
            // The first value names the loop's variable and sets its type.
            None => {
                let var = self.fresh("loop_value");
                if let Some(Some(slot)) = self.loop_values.last_mut() {
                    *slot = Some((var.clone(), val.ty.clone()));
                }
                (var, val)
            }
        };
        self.emit(format!("{var} = {};", val.code));
        Ok(())
    }

    /// `continue`.
    pub(super) fn continue_expr(&mut self, c: &syn::ExprContinue) -> Result<Val> {
        if let Some(l) = &c.label {
            return Err(Error::unsupported(
                l.span(),
                "a labeled `continue`",
                "WGSL has no labels; use a flag variable",
            ));
        }
        if self.loop_depth == 0 {
            return Err(Error::new(c.span(), "`continue` outside of a loop"));
        }
        let line = self.mark(c.span(), "continue;");
        self.emit(line);
        Ok(Val::new("", Ty::Never))
    }

    /// `return`, with a value or without.
    pub(super) fn return_expr(&mut self, r: &syn::ExprReturn) -> Result<Val> {
        let ret = self.ret.clone();
        match &r.expr {
            Some(v) => {
                let val = self.expr(v, Some(&ret))?;
                let val = self.coerce(val, &ret, v.span())?;
                // (A unit value, `return ()` or a call of a function
                // without a result, has no WGSL expression to discard.)
                let line = if matches!(ret, Ty::Unit) && val.code.trim().is_empty() {
                    "return;".to_string()
                } else if matches!(ret, Ty::Unit) {
                    format!("_ = {};\nreturn;", val.code)
                } else {
                    format!("return {};", val.code)
                };
                let line = self.mark(r.span(), &line);
                self.emit(line);
            }
            None => {
                if !matches!(ret, Ty::Unit) {
                    return Err(Error::new(r.span(), format!("`return` needs a value of type `{ret}`")));
                }
                let line = self.mark(r.span(), "return;");
                self.emit(line);
            }
        }
        Ok(Val::new("", Ty::Never))
    }

    pub(super) fn match_expr(&mut self, m: &syn::ExprMatch, want: Option<&Ty>) -> Result<Val> {
        let scrut = self.expr(&m.expr, None)?;
        let mut scrut = self.deref(scrut);
        let sty = self.resolved(&scrut.ty);
        // A binding arm (`n => ...`) reads the scrutinee again: evaluate one
        // with side effects once.
        fn binds(p: &syn::Pat) -> bool {
            match p {
                syn::Pat::Ident(_) => true,
                syn::Pat::Or(o) => o.cases.iter().any(binds),
                syn::Pat::Paren(pp) => binds(&pp.pat),
                _ => false,
            }
        }
        if scrut.effects && m.arms.iter().any(|a| binds(&a.pat)) {
            let t = self.fresh("scrutinee");
            self.emit_let(format!("let {t} = {};", scrut.code), &scrut);
            scrut = Val::new(t, scrut.ty);
        }
        if matches!(&sty, Ty::Tuple(_) | Ty::Option(_)) || matches!(&sty, Ty::Struct(d) if d.is_tuple()) {
            return self.match_tuple(m, want, scrut, sty);
        }
        if !self.is_int(&sty) && !matches!(sty, Ty::Enum(_)) {
            return Err(Error::unsupported(
                m.expr.span(),
                &format!("`match` on `{sty}`"),
                "match on i32/u32 values and #[rt_enum]s, or use if/else",
            ));
        }
        let mut cases = Vec::new();
        let mut result_ty: Option<Ty> = None;
        let mut has_default = false;
        let t = self.tmp();
        let mut values = Vec::new();
        // A `break` in an arm leaves the enclosing loop in Rust, the `switch`
        // in WGSL: it sets this flag, tested after the `switch`.
        let in_loop = self.loop_depth > 0;
        if in_loop {
            let flag = self.fresh("brk");
            self.breaks.push(Some((flag, false)));
        }
        let arms =
            self.match_arms(m, want, &sty, &scrut, &t, &mut cases, &mut result_ty, &mut has_default, &mut values);
        let flag = if in_loop {
            match self.breaks.pop() {
                Some(Some((flag, true))) => Some(flag),
                _ => None,
            }
        } else {
            None
        };
        arms?;
        if !has_default && matches!(sty, Ty::Enum(_)) && !cases.is_empty() {
            // Every variant listed (Rust checks it): the last arm is WGSL's
            // default too, so every path through the `switch` runs an arm.
            let last = cases.pop().unwrap();
            let (head, body) = last.split_once(": {").unwrap_or((&last, ""));
            cases.push(format!("{head}, default: {{{body}"));
        } else if !has_default {
            // WGSL needs a default; Rust's exhaustiveness check guarantees
            // it is unreachable.
            cases.push("default: {}".to_string());
        }
        if let Some(rt) = &result_ty {
            self.emit(format!("var {t}: {};", rt.wgsl()));
        }
        if let Some(f) = &flag {
            self.emit(format!("var {f} = false;"));
        }
        let text = format!("switch {} {{\n{}}}", scrut.code, indent(&cases.join("\n")));
        let text = self.mark(m.span(), &text);
        self.emit(text);
        if let Some(f) = &flag {
            let brk = self.break_text();
            self.emit(format!("if {f} {{\n{}}}", indent(&brk)));
        }
        Ok(match result_ty {
            Some(rt) => Val::new(t, rt),
            None => Val::new("", Ty::Unit),
        })
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn match_arms(
        &mut self,
        m: &syn::ExprMatch,
        want: Option<&Ty>,
        sty: &Ty,
        scrut: &Val,
        t: &str,
        cases: &mut Vec<String>,
        result_ty: &mut Option<Ty>,
        has_default: &mut bool,
        values: &mut Vec<Span>,
    ) -> Result<()> {
        for arm in &m.arms {
            if let Some((if_token, _)) = &arm.guard {
                return Err(Error::unsupported(if_token.span, "a match guard", "use if/else inside the arm"));
            }
            let mut labels = Vec::new();
            let mut binding = None;
            self.match_pattern(&arm.pat, sty, &mut labels, &mut binding)?;
            self.scopes.push(Vec::new());
            self.blocks.push(Block::default());
            if let Some(b) = &binding {
                let w = self.fresh(b);
                self.emit_let(format!("let {w} = {};", scrut.code), scrut);
                self.bind(b, Local { wgsl: w, ty: sty.clone(), var: false });
            }
            let want_arm = result_ty.clone().or(want.cloned());
            let r = self.expr(&arm.body, want_arm.as_ref());
            let mut lines = self.blocks.pop().unwrap().lines;
            self.scopes.pop();
            let v = r?;
            let vty = self.resolved(&v.ty);
            if !matches!(vty, Ty::Unit | Ty::Never) {
                match result_ty {
                    Some(rt) => {
                        let v = self.coerce(v.clone(), rt, arm.body.span())?;
                        lines.push(format!("{t} = {};", v.code));
                    }
                    None => {
                        *result_ty = Some(vty.clone());
                        lines.push(format!("{t} = {};", v.code));
                    }
                }
                values.push(arm.body.span());
            }
            let head = if labels.is_empty() {
                *has_default = true;
                "default".to_string()
            } else {
                format!("case {}", labels.join(", "))
            };
            cases.push(format!("{head}: {{\n{}}}", indent(&lines.join("\n"))));
        }
        Ok(())
    }

    pub(super) fn match_pattern(
        &mut self,
        p: &syn::Pat,
        sty: &Ty,
        labels: &mut Vec<String>,
        binding: &mut Option<String>,
    ) -> Result<()> {
        match p {
            syn::Pat::Wild(_) => Ok(()),
            // A name that resolves to a constant is a constant pattern, as
            // in Rust (`EXCEPTION_USER => ...`), not a binding.
            syn::Pat::Ident(pi)
                if pi.subpat.is_none() && pi.by_ref.is_none() && self.is_const_name(&pi.ident.to_string()) =>
            {
                let v = self.path_expr(&syn::parse_quote!(#pi))?;
                let v = self.coerce(v, sty, pi.span())?;
                labels.push(v.code);
                Ok(())
            }
            syn::Pat::Path(pp) => {
                let v = self.path_expr(pp)?;
                let v = self.coerce(v, sty, pp.span())?;
                labels.push(v.code);
                Ok(())
            }
            syn::Pat::Ident(pi) if pi.subpat.is_none() && pi.by_ref.is_none() && pi.mutability.is_none() => {
                *binding = Some(pi.ident.to_string());
                Ok(())
            }
            syn::Pat::Lit(l) => {
                // syn folds the minus of a `-1 =>` pattern into the literal.
                let e = match &l.lit {
                    syn::Lit::Int(i) if i.base10_digits().starts_with('-') => {
                        let pos = syn::LitInt::new(&format!("{}{}", &i.base10_digits()[1..], i.suffix()), i.span());
                        syn::parse_quote_spanned!(i.span()=> -#pos)
                    }
                    _ => Expr::Lit(l.clone()),
                };
                let v = self.expr(&e, Some(sty))?;
                let v = self.coerce(v, sty, l.span())?;
                labels.push(v.code);
                Ok(())
            }
            syn::Pat::Or(o) => {
                for c in &o.cases {
                    self.match_pattern(c, sty, labels, binding)?;
                }
                Ok(())
            }
            syn::Pat::Paren(pp) => self.match_pattern(&pp.pat, sty, labels, binding),
            syn::Pat::Range(r) => {
                Err(Error::unsupported(r.span(), "a range pattern", "list the values or use if/else"))
            }
            other => Err(Error::unsupported(other.span(), "this pattern", "match integer literals and `_`")),
        }
    }

    /// Whether `name` names a constant: a function-local `const`, an
    /// `#[rt_const]` or one of rt-std's.
    pub(super) fn is_const_name(&self, name: &str) -> bool {
        match self.lookup(name) {
            Some(l) => self.local_consts.contains(&l.wgsl),
            None => self.m.consts.contains_key(name) || kinds::constant(name).is_some(),
        }
    }
}
