//! Statements: `let` (locals), `const` items, expression statements and
//! `rt_printf!`.

use super::*;

impl FnLowerer<'_> {
    pub(super) fn stmt(&mut self, s: &Stmt) -> Result<()> {
        match s {
            Stmt::Local(l) => {
                let before = self.errors.0.len();
                let r = self.local(l);
                if let Err(e) = r {
                    // Later uses of the names are silent errors, not "cannot
                    // find value"; and a `let` whose initialiser already
                    // reported an error reports nothing more.
                    self.poison_pattern(&l.pat);
                    return Err(if self.errors.0.len() > before { Error::silent(e.span) } else { e });
                }
                Ok(())
            }
            Stmt::Item(syn::Item::Const(c)) => {
                let ty = self.resolve_type(&c.ty)?;
                let v = self.expr(&c.expr, Some(&ty))?;
                let v = self.coerce(v, &ty, c.expr.span())?;
                let name = self.fresh(&c.ident.to_string());
                // Infinity and NaN are run-time values in WGSL (rt-abi's
                // `f32_wgsl`): a constant holding one is a `let`.
                let run_time = v.code.contains(rt_abi::wgsl::F32_FROM_BITS);
                let keyword = if run_time { "let" } else { "const" };
                let line = format!("{keyword} {name}: {} = {};", ty.wgsl(), v.code);
                let line = self.mark(c.span(), &line);
                if self.hoisting() {
                    self.hoist_const(line);
                } else {
                    self.emit(line);
                }
                if !run_time {
                    self.local_consts.insert(name.clone());
                }
                self.bind(&c.ident.to_string(), Local { wgsl: name, ty, var: false });
                Ok(())
            }
            // `sugar` takes every other one out to stand beside the
            // function; this one's name is a helper's of the program.
            Stmt::Item(syn::Item::Fn(f)) => Err(Error::new(
                f.sig.ident.span(),
                format!(
                    "a function declared in a body has the name of another function of this program (`{}`); WGSL has \
                     one namespace of functions: rename it",
                    f.sig.ident
                ),
            )),
            Stmt::Item(other) => {
                Err(Error::unsupported(other.span(), "this item inside a function", "move it out of the function"))
            }
            Stmt::Macro(m) => self.macro_stmt(&m.mac),
            Stmt::Expr(e, _) => {
                let v = self.expr(e, None)?;
                if !matches!(self.resolved(&v.ty), Ty::Unit | Ty::Never) && !v.code.is_empty() {
                    let line = format!("_ = {};", v.code);
                    self.emit(line);
                }
                Ok(())
            }
        }
    }

    pub(super) fn local(&mut self, l: &syn::Local) -> Result<()> {
        let hint = self.let_type_hint.take();
        let (pat, annot) = match &l.pat {
            syn::Pat::Type(pt) => (&*pt.pat, Some(self.resolve_type(&pt.ty)?)),
            p => (p, hint),
        };
        let (name, mutable) = match pat {
            syn::Pat::Ident(pi) => {
                if pi.by_ref.is_some() {
                    return Err(Error::unsupported(pi.span(), "a `ref` binding", "bind by value"));
                }
                if pi.subpat.is_some() {
                    return Err(Error::unsupported(pi.span(), "a `@` pattern", "bind a plain name"));
                }
                (pi.ident.to_string(), pi.mutability.is_some())
            }
            syn::Pat::Wild(_) => ("_".to_string(), false),
            syn::Pat::Tuple(_) | syn::Pat::TupleStruct(_) => {
                let Some(init) = &l.init else {
                    return Err(Error::new(pat.span(), "a tuple pattern needs a value: `let (a, b) = ...;`"));
                };
                if let Some((_, d)) = &init.diverge {
                    return Err(Error::unsupported(d.span(), "`let ... else`", "use if/else"));
                }
                return self.let_tuple(pat, annot.as_ref(), &init.expr, l.span());
            }
            other => return Err(Error::unsupported(other.span(), "this pattern", "bind a plain name")),
        };
        if let Some(a) = annot.as_ref()
            && matches!(a, Ty::Ref(..))
        {
            return Err(Error::unsupported(
                l.pat.span(),
                "a reference local",
                "copy the value (`let x = *r;`) or pass `&mut` directly to a call",
            ));
        }
        let init = match &l.init {
            Some(init) => {
                if let Some((_, d)) = &init.diverge {
                    return Err(Error::unsupported(d.span(), "`let ... else`", "use if/else"));
                }
                if let Expr::Reference(r) = &*init.expr {
                    return Err(Error::unsupported(
                        r.and_token.span,
                        "a reference in a local",
                        "bind the value itself (`let r = x;`) and pass `&mut x` directly to the call that needs it",
                    ));
                }
                let v = self.expr(&init.expr, annot.as_ref())?;
                let v = match &annot {
                    Some(a) => self.coerce(v, a, init.expr.span())?,
                    None => v,
                };
                if matches!(v.ty, Ty::Ref(..)) && name != "_" {
                    return Err(Error::unsupported(
                        init.expr.span(),
                        "a reference local",
                        "copy the value (`let x = *r;`) or pass `&mut` directly to a call",
                    ));
                }
                let silenced_ref = name == "_" && matches!(v.ty, Ty::Ref(..));
                if !v.ty.is_value() && !silenced_ref {
                    return Err(Error::new(init.expr.span(), format!("cannot bind a value of type `{}`", v.ty)));
                }
                Some(v)
            }
            None => None,
        };
        if name == "_" {
            // `let _ = attr;` silences an unused reference parameter: it
            // reads nothing, so it emits nothing.
            if let Some(v) = init
                && (v.effects || !matches!(v.ty, Ty::Ref(..)))
            {
                let v = self.deref(v);
                self.emit(format!("_ = {};", v.code));
            }
            return Ok(());
        }
        let ty = match (&annot, &init) {
            (Some(a), _) => a.clone(),
            (None, Some(v)) => v.ty.clone(),
            (None, None) => {
                return Err(Error::new(
                    l.pat.span(),
                    format!(
                        "`{name}` needs a type annotation or an initial value (e.g. `let {name}: f32;` or `let {name} = 0.0;`)"
                    ),
                ));
            }
        };
        let var = mutable || init.is_none() || matches!(ty, Ty::Array(..) | Ty::Mat(_));
        let wname = self.fresh(&name);
        self.declare_local(&wname, mutable, ty.clone(), init, l.span());
        self.bind(&name, Local { wgsl: wname, ty, var });
        Ok(())
    }

    /// Declares the WGSL local `wname` (already fresh) of type `ty`: a `var`
    /// when `mutable`, deferred, or an array or matrix (which may be
    /// indexed dynamically, as WGSL allows only on `var`s); else a `let`.
    pub(super) fn declare_local(&mut self, wname: &str, mutable: bool, ty: Ty, init: Option<Val>, span: Span) {
        let var = mutable || init.is_none() || matches!(ty, Ty::Array(..) | Ty::Mat(_));
        if self.hoisting() {
            self.hoisted_let(wname, &ty, init.as_ref());
            return;
        }
        let (line, writes) = match (&init, var) {
            (Some(v), true) => (format!("var {wname}: {} = {};", ty.wgsl(), v.code), true),
            (Some(v), false) => (format!("let {wname}: {} = {};", ty.wgsl(), v.code), v.effects),
            (None, _) => (format!("var {wname}: {};", ty.wgsl()), true),
        };
        let line = self.mark(span, &line);
        self.blocks.last_mut().unwrap().push(line, writes);
    }

    pub(super) fn macro_stmt(&mut self, mac: &syn::Macro) -> Result<()> {
        let name = mac.path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
        if name == "debug_assert" && mac.path.is_ident("debug_assert") {
            return self.debug_assert(mac);
        }
        if name != "rt_printf" {
            return Err(unsupported_macro(mac, &name));
        }
        self.use_intrinsic("rt_printf", mac.span())?;
        let args = mac.parse_body_with(syn::punctuated::Punctuated::<Expr, syn::Token![,]>::parse_terminated)?;
        let mut it = args.iter();
        let fmt = match it.next() {
            Some(Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. })) => s.value(),
            Some(other) => {
                return Err(Error::new(other.span(), "rt_printf! takes a string literal as its first argument"));
            }
            None => return Err(Error::new(mac.span(), "rt_printf! needs a format string")),
        };
        let holes = count_placeholders(&fmt).map_err(|m| Error::new(mac.span(), m))?;
        let rest: Vec<&Expr> = it.collect();
        if holes != rest.len() {
            return Err(Error::new(
                mac.span(),
                format!("rt_printf! format has {holes} `{{}}` placeholders but {} arguments", rest.len()),
            ));
        }
        let mut words = Vec::new();
        let mut types = Vec::new();
        for a in rest {
            let v = self.expr(a, None)?;
            let v = self.deref(v);
            let ty = self.resolved(&v.ty);
            let ty = if let Ty::IntVar(x) = ty {
                self.ivars[x as usize].1 = Some(Scalar::I32);
                I32
            } else {
                ty
            };
            let comps: Vec<(String, Scalar)> = match &ty {
                Ty::Scalar(s) => vec![(v.code.clone(), *s)],
                Ty::Vec(n, s) => (0..*n).map(|i| (format!("{}[{i}]", v.code), *s)).collect(),
                other => {
                    return Err(Error::new(
                        a.span(),
                        format!("rt_printf! can print scalars and vectors, not `{other}`"),
                    ));
                }
            };
            let t = self.tmp();
            self.emit_let(format!("let {t} = {};", v.code), &v);
            for (i, (_, s)) in comps.iter().enumerate() {
                let c = if matches!(ty, Ty::Vec(..)) { format!("{t}[{i}]") } else { t.clone() };
                words.push(match s {
                    Scalar::F32 | Scalar::I32 => format!("bitcast<u32>({c})"),
                    Scalar::Bool => format!("select(0u, 1u, {c})"),
                    _ => c,
                });
            }
            types.push(ty.wgsl());
        }
        let id = self.m.printf_id(&fmt, &types);
        let mut body = Vec::new();
        for w in &words {
            body.push(format!("rt_printf_word({w});"));
        }
        let line = format!("if rt_printf_begin({id}u, {}u) {{\n{}}}", words.len(), indent(&body.join("\n")));
        let line = self.mark(mac.span(), &line);
        self.emit(line);
        Ok(())
    }
}

impl FnLowerer<'_> {
    /// `debug_assert!(cond)`, `debug_assert!(cond, "why")`: with debug
    /// assertions on, a false `cond` raises `EXCEPTION_PANIC` (as the CPU
    /// copy's `rt_std::__rt_debug_assert!` does) and the program goes on;
    /// off, nothing, `cond` not evaluated (it is checked all the same, in
    /// the lowering with them on).
    fn debug_assert(&mut self, mac: &syn::Macro) -> Result<()> {
        let args = mac.parse_body_with(syn::punctuated::Punctuated::<Expr, syn::Token![,]>::parse_terminated)?;
        let cond = match (args.len(), args.iter().nth(1)) {
            (1, _) | (2, Some(Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(_), .. }))) => &args[0],
            (0, _) => return Err(Error::new(mac.span(), "`debug_assert!` needs a condition")),
            (_, Some(msg)) => {
                return Err(Error::unsupported(
                    msg.span(),
                    "a formatted `debug_assert!` message",
                    "write the message as one string literal: `debug_assert!(cond, \"why\")` (the GPU has no \
                     strings; the exception's record says where)",
                ));
            }
            _ => unreachable!("two or more arguments have a second"),
        };
        if let Some(kind) = self.kind()
            && kinds::intrinsic("rt_throw").is_some_and(|i| !i.callers.allows(kind))
        {
            return Err(Error::new(
                mac.path.span(),
                format!(
                    "`debug_assert!` raises an exception where its condition is false, which {} cannot: \
                     check the condition and handle it in the program",
                    kind.a_program()
                ),
            ));
        }
        if !self.m.debug_assertions {
            return Ok(());
        }
        let span = mac.path.span();
        let check: Expr = syn::parse_quote_spanned!(span=> if !(#cond) { rt_throw(EXCEPTION_PANIC); });
        self.expr(&check, None)?;
        Ok(())
    }
}

fn unsupported_macro(mac: &syn::Macro, name: &str) -> Error {
    let instead = match name {
        "println" | "print" | "eprintln" | "eprint" | "dbg" => "use `rt_printf!`",
        "panic" | "assert" | "assert_eq" | "assert_ne" | "unreachable" | "todo" | "unimplemented" => {
            "raise an exception with `rt_throw(code)`"
        }
        "vec" => "use a fixed-size array",
        _ => "only `rt_printf!` is available",
    };
    Error::unsupported(mac.path.span(), &format!("the macro `{name}!`"), instead)
}

/// Counts `{}` placeholders; `{{` and `}}` are escapes.
pub fn count_placeholders(fmt: &str) -> std::result::Result<usize, String> {
    let mut n = 0;
    let mut chars = fmt.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '{' if chars.peek() == Some(&'{') => {
                chars.next();
            }
            '{' => {
                let mut spec = String::new();
                for d in chars.by_ref() {
                    if d == '}' {
                        break;
                    }
                    spec.push(d);
                }
                if !spec.is_empty() {
                    return Err(format!("rt_printf! supports only plain `{{}}` placeholders, found `{{{spec}}}`"));
                }
                n += 1;
            }
            '}' if chars.peek() == Some(&'}') => {
                chars.next();
            }
            _ => {}
        }
    }
    Ok(n)
}
