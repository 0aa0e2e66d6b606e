//! `Option<T>`: a WGSL struct of a flag and a value (`Ty::Option`'s
//! spelling, declared once per module as a tuple is), `some` and `value`,
//! the value's zero when `None`.
//!
//! `Some(x)`; `None`, typed by what its place wants (a `let`'s annotation, a
//! parameter, the other branch of an `if` or `match`, `None::<T>`, and for
//! `let o = None;` the first use of `o` after it that fixes its type, as
//! rustc infers it: an `Option` assigned to it, `o` passed where an
//! `Option` of a known type is wanted (a parameter, the result, a field),
//! compared with one, or given a value by `unwrap_or`:
//! [`FnLowerer::none_local_type`]); the
//! methods that take no closure (`is_some`, `is_none`, `unwrap_or`,
//! `unwrap_or_default`, `or`, `xor`, and `copied`/`cloned`, which change
//! nothing where elements are values). `unwrap` and `expect` of a `None`
//! raise `EXCEPTION_PANIC` and give the zero value, on every backend (the
//! CPU copy calls `rt_std::arith::unwrap`). Patterns `Some(p)` and `None` are taken
//! where tuple patterns are (`tuples.rs`); the methods that take closures
//! (`map`, `and_then`, `filter`, `unwrap_or_else`, `is_some_and`,
//! `map_or`, ...) are `match`es by the time the lowering sees them
//! (`sugar/options.rs`).

use super::*;

pub(super) use crate::sugar::{is_none_path, is_some_path};

/// Whether `t`'s WGSL zero value is its Rust `Default` (an enum's default
/// is its first variant, whose discriminant may be another number; a
/// matrix's is the identity).
pub(super) fn zero_is_default(t: &Ty) -> bool {
    match t {
        Ty::Scalar(_) | Ty::Vec(..) => true,
        Ty::Tuple(ts) => ts.iter().all(zero_is_default),
        Ty::Array(t, _) => zero_is_default(t),
        Ty::Struct(s) => s.fields.iter().all(|(_, t)| zero_is_default(t)),
        _ => false,
    }
}

impl FnLowerer<'_> {
    /// `Some(x)`: the value, then the struct with its flag set.
    pub(super) fn option_some(&mut self, c: &syn::ExprCall, want: Option<&Ty>) -> Result<Val> {
        let [arg] = c.args.iter().collect::<Vec<_>>()[..] else {
            return Err(Error::new(c.span(), "`Some` takes one value: `Some(x)`"));
        };
        let inner = match want.map(|w| self.resolved(w)) {
            // Not a `None` local's still unknown type (`o == Some(x)`).
            Some(Ty::Option(t)) if *t != Ty::Never => Some(*t),
            _ => None,
        };
        let v = self.expr(arg, inner.as_ref())?;
        let v = self.deref(v);
        let v = match &inner {
            Some(t) => self.coerce(v, t, arg.span())?,
            None => v,
        };
        let ety = self.resolved(&v.ty);
        if !matches!(ety, Ty::IntVar(_) | Ty::Scalar(_) | Ty::Option(_)) && !ety.is_plain_data() {
            return Err(Error::unsupported(
                arg.span(),
                &format!("`Option<{ety}>`"),
                "an `Option` holds a plain value (a scalar, vector, matrix, array, struct, enum or tuple); keep handles and references apart and pass a flag beside them",
            ));
        }
        let ty = Ty::Option(Box::new(ety));
        self.note_tuple(&ty);
        Ok(Val::new(format!("{}(true, {})", ty.wgsl(), v.code), ty).with_effects(v.effects).with_reads(v.reads))
    }

    /// `None` (or `None::<T>`): the struct's zero value, of the type its
    /// place wants.
    pub(super) fn option_none(&mut self, p: &syn::ExprPath, want: Option<&Ty>) -> Result<Val> {
        let last = p.path.segments.last().unwrap();
        let ty = match &last.arguments {
            syn::PathArguments::AngleBracketed(a) if a.args.len() == 1 => match &a.args[0] {
                syn::GenericArgument::Type(t) => {
                    let t = self.resolve_type(&syn::parse_quote_spanned!(t.span()=> Option<#t>))?;
                    if let Some(w) = want {
                        let v = Val::new("", t.clone());
                        self.coerce(v, w, p.span())?;
                    }
                    t
                }
                other => return Err(Error::new(other.span(), "`None` takes a type: `None::<f32>`")),
            },
            syn::PathArguments::None => match want.map(|w| self.resolved(w)) {
                Some(t @ Ty::Option(_)) => t,
                Some(other) if other.is_value() => {
                    return Err(Error::new(p.span(), format!("mismatched types: expected `{other}`, found `Option`")));
                }
                _ => {
                    return Err(Error::new(
                        p.span(),
                        "the type of this `None` is not known here: annotate the binding (`let o: Option<f32> = None;`) or write `None::<f32>`",
                    ));
                }
            },
            other => return Err(Error::new(other.span(), "`None` takes one type: `None::<f32>`")),
        };
        self.note_tuple(&ty);
        Ok(Val::new(format!("{}()", ty.wgsl()), ty))
    }

    /// `o.name(args)` on an `Option<T>`.
    pub(super) fn option_method(
        &mut self,
        recv: Val,
        inner: &Ty,
        name: &str,
        args: &[&Expr],
        name_span: Span,
    ) -> Result<Val> {
        let opt = Ty::Option(Box::new(inner.clone()));
        let arity = match name {
            "is_some" | "is_none" | "rt_sugar_value" | "unwrap_or_default" | "copied" | "cloned" => 0,
            "unwrap_or" | "or" | "xor" => 1,
            "unwrap" | "expect" => return self.option_unwrap(recv, inner, name, args, name_span),
            _ => {
                return Err(Error::new(
                    name_span,
                    format!(
                        "no method `{name}` on `{opt}` in ray programs: programs call `is_some`, `is_none`, `unwrap_or`, `unwrap_or_else`, `unwrap_or_default`, `copied`, `map`, `map_or`, `and_then`, `filter`, `is_some_and`, `or`, `xor`, or `match` on `Some(x)` / `None`"
                    ),
                ));
            }
        };
        if args.len() != arity {
            return Err(Error::new(
                name_span,
                format!("`Option::{name}` takes {arity} argument(s), found {}", args.len()),
            ));
        }
        let (effects, reads) = (recv.effects, recv.reads);
        match name {
            // `arr.iter().min().copied()`: elements are values here.
            "copied" | "cloned" => return Ok(recv),
            "is_some" => {
                return Ok(Val::new(format!("{}.some", recv.code), BOOL).with_effects(effects).with_reads(reads));
            }
            "is_none" => {
                return Ok(Val::new(format!("!({}.some)", recv.code), BOOL).with_effects(effects).with_reads(reads));
            }
            // The value of an option a pattern has tested (`sugar/`'s
            // conditions); not a name user code reaches.
            "rt_sugar_value" => {
                return Ok(Val::new(format!("{}.value", recv.code), inner.clone())
                    .with_effects(effects)
                    .with_reads(reads));
            }
            "unwrap_or_default" if !zero_is_default(inner) => {
                return Err(Error::unsupported(
                    name_span,
                    &format!("`unwrap_or_default` on `{opt}`"),
                    "the default of an enum (its first variant) or a matrix (the identity) is not the zero WGSL has; write `unwrap_or(..)` with the value",
                ));
            }
            "unwrap_or_default" => {
                return Ok(Val::new(format!("{}.value", recv.code), inner.clone())
                    .with_effects(effects)
                    .with_reads(reads));
            }
            _ => {}
        }
        // The receiver once, then the argument (Rust evaluates both).
        let o = self.fresh("opt");
        self.emit_let(format!("let {o} = {};", recv.code), &recv);
        let t = self.tmp();
        match name {
            "unwrap_or" | "or" | "xor" => {
                let want = if name == "unwrap_or" { inner.clone() } else { opt.clone() };
                let d = self.expr(args[0], Some(&want))?;
                let d = self.deref(d);
                // `o.unwrap_or(x)` of a `None` local whose type is probed: `x`'s.
                let found = if name == "unwrap_or" { Ty::Option(Box::new(d.ty.clone())) } else { d.ty.clone() };
                self.note_none_use(&recv, &found);
                let d = self.coerce(d, &want, args[0].span())?;
                let pick = match name {
                    "unwrap_or" => format!("if {o}.some {{\n    {t} = {o}.value;\n}}"),
                    "or" => format!("if {o}.some {{\n    {t} = {o};\n}}"),
                    _ => format!(
                        "if {o}.some && {t}.some {{\n    {t} = {}();\n}} else if {o}.some {{\n    {t} = {o};\n}}",
                        opt.wgsl()
                    ),
                };
                self.emit(format!("var {t}: {} = {};", want.wgsl(), d.code));
                self.emit(pick);
                Ok(Val::new(t, want))
            }
            _ => unreachable!("the arities above"),
        }
    }

    /// The conditions a pattern puts on the option `code` of type `ty`
    /// (`Some(p)`, `None`, a name), for `tuples.rs`'s `if` chains.
    pub(super) fn option_pattern(
        &mut self,
        p: &syn::Pat,
        code: &str,
        ty: &Ty,
        conds: &mut Vec<String>,
        names: &mut Vec<(String, String, Ty)>,
    ) -> Result<()> {
        let Ty::Option(inner) = self.resolved(ty) else {
            return Err(Error::new(p.span(), format!("mismatched types: expected `Option`, found `{ty}`")));
        };
        match p {
            syn::Pat::TupleStruct(ts) if is_some_path(&ts.path) && ts.elems.len() == 1 => {
                conds.push(format!("{code}.some"));
                // `Some(&m)` of an iterator's element: elements are values.
                let elem = match &ts.elems[0] {
                    syn::Pat::Reference(r) => &*r.pat,
                    p => p,
                };
                self.element_pattern(elem, &format!("{code}.value"), &inner, conds, names)
            }
            syn::Pat::Ident(pi) if pi.ident == "None" && pi.subpat.is_none() && self.lookup("None").is_none() => {
                conds.push(format!("!{code}.some"));
                Ok(())
            }
            syn::Pat::Path(pp) if pp.qself.is_none() && is_none_path(&pp.path) => {
                conds.push(format!("!{code}.some"));
                Ok(())
            }
            syn::Pat::Ident(pi) if pi.by_ref.is_none() && pi.subpat.is_none() && pi.mutability.is_none() => {
                names.push((pi.ident.to_string(), code.to_string(), self.resolved(ty)));
                Ok(())
            }
            other => Err(Error::unsupported(
                other.span(),
                "this pattern for an `Option`",
                "match `Some(p)`, `None`, `_` or a name (without `mut`: copy it into a `let mut` in the arm)",
            )),
        }
    }
}

impl FnLowerer<'_> {
    /// `a == b`, `a != b` of two `Option`s (`o == None`, `o == Some(x)`):
    /// equal where both are `None`, or both `Some` of equal values.
    pub(super) fn option_equality(&mut self, op: &BinOp, o: Operands, inner: &Ty) -> Result<Val> {
        let Operands { l, r, span, .. } = o;
        let mut vals = [l, r];
        self.once(&mut vals);
        let [l, r] = vals;
        let lv = Val::new(format!("{}.value", l.code), inner.clone());
        let rv = Val::new(format!("{}.value", r.code), inner.clone());
        let eq = self.binary_op(&BinOp::Eq(Default::default()), lv, rv, span)?;
        let code = format!("(({l}.some == {r}.some) && (!{l}.some || {}))", eq.code, l = l.code, r = r.code);
        let code = if matches!(op, BinOp::Ne(_)) { format!("!{code}") } else { code };
        Ok(Val::new(code, BOOL).with_effects(l.effects || r.effects).with_reads(l.reads || r.reads))
    }
}

impl FnLowerer<'_> {
    /// `o.unwrap()`, `o.expect("why")`: the value; a `None` raises
    /// `EXCEPTION_PANIC` (Rust's panic) and gives the zero value it holds.
    fn option_unwrap(&mut self, recv: Val, inner: &Ty, name: &str, args: &[&Expr], span: Span) -> Result<Val> {
        match (name, args) {
            ("unwrap", []) => {}
            ("expect", [Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(_), .. })]) => {}
            ("expect", _) => {
                return Err(Error::new(span, "`expect` takes its message as a string literal: `o.expect(\"why\")`"));
            }
            _ => return Err(Error::new(span, format!("`{name}` takes no arguments"))),
        }
        if let Some(kind) = self.kind()
            && kinds::intrinsic("rt_throw").is_some_and(|i| !i.callers.allows(kind))
        {
            return Err(Error::new(
                span,
                format!(
                    "`{name}` raises an exception where the `Option` is `None`, which {} cannot: use `unwrap_or(..)` or `match`",
                    kind.a_program()
                ),
            ));
        }
        let t = self.fresh("unwrap");
        let opt = Ty::Option(Box::new(inner.clone()));
        self.emit_let(format!("let {t} = {};", recv.code), &recv);
        let rust = format!("__rt_unwrap_{t}");
        self.bind(&rust, Local { wgsl: t.clone(), ty: opt, var: false });
        let ident = syn::Ident::new(&rust, span);
        let check: Expr = syn::parse_quote_spanned!(span=> if !#ident.is_some() { rt_throw(EXCEPTION_PANIC); });
        self.expr(&check, None)?;
        Ok(Val::new(format!("{t}.value"), inner.clone()).with_reads(recv.reads))
    }
}

/// A `let o = None;` whose type the statements after it are probed for.
pub(super) struct NoneProbe {
    /// The local's Rust name.
    name: String,
    /// Its WGSL name in the probe: a value read from it has this code
    /// (its markers stripped).
    wgsl: String,
    /// The type the first use that fixes it gives.
    found: Option<Ty>,
}

impl FnLowerer<'_> {
    /// The type of `let o = None;` (no type written, `None` without a
    /// turbofish): that the first use of `o` in `rest` (the statements
    /// after it in its block) that fixes it gives, found by lowering them
    /// as a probe (nothing emitted, no error kept): an `Option` assigned to
    /// `o` ([`FnLowerer::note_none_probe`]), or `o` read where an `Option`
    /// of a known type is wanted ([`FnLowerer::note_none_use`]), the
    /// block's tail where the block is wanted at `want`.
    pub(super) fn none_local_type(&mut self, l: &syn::Local, rest: &[Stmt], want: Option<&Ty>) -> Option<Ty> {
        let syn::Pat::Ident(pi) = &l.pat else { return None };
        let init = l.init.as_ref()?;
        let bare_none = matches!(&*init.expr, Expr::Path(p) if p.qself.is_none() && p.path.is_ident("None"));
        if init.diverge.is_some() || !bare_none || self.lookup("None").is_some() {
            return None;
        }
        // Unknown until assigned: an `Option` of `!`. Inside another's
        // probe, such a local stays unknown (its assignments are skipped):
        // probes do not nest.
        let unknown = Ty::Option(Box::new(Ty::Never));
        if self.none_probe.is_some() {
            return Some(unknown);
        }
        let name = pi.ident.to_string();
        let saved = self.snapshot();
        self.scopes.push(Vec::new());
        let wgsl = self.fresh(&name);
        self.bind(&name, Local { wgsl: wgsl.clone(), ty: unknown, var: true });
        self.none_probe = Some(NoneProbe { name, wgsl, found: None });
        for (j, s) in rest.iter().enumerate() {
            if let Stmt::Local(l) = s {
                self.let_type_hint = self.none_local_type(l, &rest[j + 1..], want);
            }
            let failed = match s {
                Stmt::Expr(e, None) if j + 1 == rest.len() => match self.expr(e, want) {
                    Ok(v) => {
                        if let Some(w) = want {
                            self.note_none_use(&v, w);
                        }
                        false
                    }
                    Err(_) => true,
                },
                _ => self.stmt(s).is_err(),
            };
            if failed || self.none_probe.as_ref().is_some_and(|p| p.found.is_some()) {
                break;
            }
        }
        let found = self.none_probe.take().and_then(|p| p.found);
        // The probe's inference variables go with it: an integer still
        // open there is open again (`count = Some(3)`, its type from a
        // later use, as rustc's).
        let found = found.map(|t| self.resolved(&t));
        let live = saved.ivars.len();
        self.restore(saved, false);
        found.map(|t| self.reopen_ivars(&t, live))
    }

    /// `t` with each integer inference variable numbered `live` or above
    /// (a probe's) replaced by a fresh one.
    fn reopen_ivars(&mut self, t: &Ty, live: usize) -> Ty {
        match t {
            Ty::IntVar(v) if *v as usize >= live => Ty::IntVar(self.new_ivar()),
            Ty::Option(e) => Ty::Option(Box::new(self.reopen_ivars(e, live))),
            Ty::Array(e, n) => Ty::Array(Box::new(self.reopen_ivars(e, live)), *n),
            Ty::Tuple(ts) => Ty::Tuple(ts.iter().map(|t| self.reopen_ivars(t, live)).collect()),
            other => other.clone(),
        }
    }

    /// During [`FnLowerer::none_local_type`]'s probe, `o = value` where
    /// `o` is a local of a type still unknown: the value's type noted where
    /// `o` is the local probed (and the value an `Option` of a known type);
    /// whether the assignment is to be skipped (`o` unknown).
    pub(super) fn note_none_probe(&mut self, left: &Expr, value: &Val) -> bool {
        let Some(NoneProbe { name, found, .. }) = &self.none_probe else { return false };
        let Expr::Path(p) = strip_parens(left) else { return false };
        let unknown = Ty::Option(Box::new(Ty::Never));
        let Some(target) = p.path.get_ident().map(|i| i.to_string()) else { return false };
        if !self.lookup(&target).is_some_and(|l| l.ty == unknown) {
            return false;
        }
        if target == *name
            && found.is_none()
            && let Ty::Option(inner) = self.resolved(&value.ty)
            && *inner != Ty::Never
        {
            self.none_probe.as_mut().unwrap().found = Some(Ty::Option(inner));
        }
        true
    }

    /// During [`FnLowerer::none_local_type`]'s probe, `v` used where a
    /// value of type `want` is (a parameter, the result, a field, the
    /// other side of `==`, an `Option` of `unwrap_or`'s value): `want`
    /// noted where `v` is read from the local probed and `want` is an
    /// `Option` of a known type.
    pub(super) fn note_none_use(&mut self, v: &Val, want: &Ty) {
        let Some(probe) = &self.none_probe else { return };
        if probe.found.is_some() || text::strip(&v.code) != probe.wgsl {
            return;
        }
        if let Ty::Option(inner) = self.resolved(want)
            && *inner != Ty::Never
        {
            self.none_probe.as_mut().unwrap().found = Some(Ty::Option(inner));
        }
    }
}
