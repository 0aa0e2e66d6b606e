//! Lowers one Rust function body to WGSL, checking the subset's rules and
//! inferring types as it goes (one pass: every expression is typed when it
//! is lowered; unsuffixed integer literals get an inference variable that
//! later uses resolve, `i32` by default as in Rust).

use super::text::{self, indent, int_literal_placeholder, mark};
use super::value::{Place, Val, f32_literal};
use super::{HelperSig, ModuleCtx};
use crate::error::{Error, Errors, Result};
use crate::kinds::{self, Kind};
use crate::types::{BOOL, BufferKind, F32, I32, Scalar, Ty, U32};
use proc_macro2::Span;
use std::collections::HashSet;
use syn::spanned::Spanned;
use syn::{BinOp, Expr, Stmt, UnOp};

mod resume;

#[derive(Clone, Debug)]
struct Local {
    wgsl: String,
    ty: Ty,
    /// Declared with `var` (assignable, addressable).
    var: bool,
}

/// The WGSL name of a local whose `let` failed (see `poison_pattern`).
const POISONED: &str = "<poisoned>";

/// What the function being lowered is.
pub enum FnRole {
    Program(Kind),
    Helper,
}

pub struct FnLowerer<'m> {
    m: &'m ModuleCtx,
    role: FnRole,
    fn_name: String,
    scopes: Vec<Vec<(String, Local)>>,
    names: HashSet<String>,
    ivars: Vec<(u32, Option<Scalar>)>,
    blocks: Vec<Vec<String>>,
    ret: Ty,
    loop_depth: u32,
    /// Lowering a function body (not a constant's initialiser, which has no
    /// statements to emit into).
    in_function: bool,
    /// What a `break` leaves, innermost last: a loop (`None`), or a `match`
    /// arm, a WGSL `switch` case, where `break` would leave the `switch`
    /// only: `Some((flag, used))`, set the flag, leave the `switch`, and
    /// test the flag after it.
    breaks: Vec<Option<(String, bool)>>,
    /// WGSL names of function-local `const` items (patterns name them).
    local_consts: HashSet<String>,
    /// Intrinsics called (directly, or through helpers) with the call span.
    pub intrinsics: Vec<(&'static str, Span)>,
    /// Helpers called.
    pub calls: Vec<String>,
    /// Payload types passed to `rt_trace`.
    pub traced: Vec<Ty>,
    pub errors: Errors,
    /// Assignments that copy temporaries passed as `&mut` back to the field
    /// or element they stand for, emitted right after the call.
    writebacks: Vec<String>,
    /// Lowering the resumable form of a tracing program (see `resume`).
    resume: Option<resume::Resume>,
    /// Statements being lowered are directly in a block with a trace: their
    /// `let`s and `const`s go to the top of the function.
    hoist: bool,
    /// Calls taken out of expressions by the resumable form so far.
    hoisted_calls: usize,
}

/// A parameter as the lowering sees it.
pub struct LParam {
    pub rust: String,
    pub ty: Ty,
    pub mutable_binding: bool,
    pub span: Span,
}

impl<'m> FnLowerer<'m> {
    pub fn new(m: &'m ModuleCtx, role: FnRole, fn_name: &str, ret: Ty) -> Self {
        let mut names: HashSet<String> = HashSet::new();
        names.insert(fn_name.to_string());
        FnLowerer {
            m,
            role,
            fn_name: fn_name.to_string(),
            scopes: vec![Vec::new()],
            names,
            ivars: Vec::new(),
            blocks: vec![Vec::new()],
            ret,
            loop_depth: 0,
            in_function: false,
            breaks: Vec::new(),
            local_consts: HashSet::new(),
            intrinsics: Vec::new(),
            calls: Vec::new(),
            traced: Vec::new(),
            errors: Errors::default(),
            writebacks: Vec::new(),
            resume: None,
            hoist: false,
            hoisted_calls: 0,
        }
    }

    fn kind(&self) -> Option<Kind> {
        match self.role {
            FnRole::Program(k) => Some(k),
            FnRole::Helper => None,
        }
    }

    /// Lowers a whole function: returns the WGSL text (with markers and
    /// placeholders still in; `ModuleCtx::finish_function` resolves them).
    pub fn function(&mut self, wgsl_name: &str, params: &[LParam], body: &syn::Block) -> String {
        self.in_function = true;
        let (sig, copies) = self.bind_params(params);
        let prologue = copies.into_iter().map(|(local, pname, _)| format!("var {local} = {pname};"));
        self.blocks.last_mut().unwrap().extend(prologue);
        let ret = self.ret.clone();
        let tail = self.block_inner(&body.stmts, Some(&ret));
        match tail {
            Ok(Some(v)) => {
                if matches!(ret, Ty::Unit) {
                    if !matches!(v.ty, Ty::Unit | Ty::Never) {
                        self.emit(format!("_ = {};", v.code));
                    }
                } else if !matches!(v.ty, Ty::Never) {
                    match self.coerce(v, &ret, body_tail_span(body)) {
                        Ok(v) => self.emit(format!("return {};", v.code)),
                        Err(e) => self.errors.push(e),
                    }
                }
            }
            Ok(None) => {
                if !matches!(ret, Ty::Unit) && !ends_in_return(body) {
                    self.errors.push(Error::new(
                        body.brace_token.span.close(),
                        format!("this function must return a `{ret}` on every path"),
                    ));
                }
            }
            Err(e) => self.errors.push(e),
        }
        let lines = self.blocks.pop().unwrap();
        let ret_text = if matches!(ret, Ty::Unit) { String::new() } else { format!(" -> {}", ret.wgsl()) };
        format!("fn {wgsl_name}({}){ret_text} {{\n{}}}\n", sig.join(", "), indent(&lines.join("\n")))
    }

    /// Binds the parameters: the signature's entries, and for each
    /// `mut` value parameter `(local, parameter, type)`, the local the
    /// body uses instead (WGSL parameters are immutable).
    fn bind_params(&mut self, params: &[LParam]) -> (Vec<String>, Vec<(String, String, Ty)>) {
        let mut sig = Vec::new();
        let mut copies = Vec::new();
        for p in params {
            let pname = self.fresh(&p.rust);
            sig.push(format!("{pname}: {}", p.ty.wgsl()));
            if p.mutable_binding && !matches!(p.ty, Ty::Ref(..)) {
                let local = self.fresh(&p.rust);
                self.bind(&p.rust, Local { wgsl: local.clone(), ty: p.ty.clone(), var: true });
                copies.push((local, pname, p.ty.clone()));
            } else {
                self.bind(&p.rust, Local { wgsl: pname, ty: p.ty.clone(), var: false });
            }
        }
        (sig, copies)
    }

    /// Resolves an integer inference variable (default `i32`).
    pub fn resolve_var(&self, v: u32) -> Scalar {
        let root = self.find(v);
        self.ivars[root as usize].1.unwrap_or(Scalar::I32)
    }

    // ---- names and scopes ----

    fn fresh(&mut self, base: &str) -> String {
        let base = if super::is_reserved(base) || base.starts_with("rt") || base.starts_with("__") || base == "_" {
            format!("{base}_")
        } else {
            base.to_string()
        };
        let mut name = base.clone();
        let mut n = 1;
        while self.names.contains(&name) || self.m.global_names.contains(&name) {
            name = format!("{base}_{n}");
            n += 1;
        }
        self.names.insert(name.clone());
        name
    }

    fn bind(&mut self, rust: &str, local: Local) {
        self.scopes.last_mut().unwrap().push((rust.to_string(), local));
    }

    /// Binds the names of a pattern whose `let` failed: their uses are
    /// silent errors.
    fn poison_pattern(&mut self, pat: &syn::Pat) {
        struct Names(Vec<String>);
        impl<'ast> syn::visit::Visit<'ast> for Names {
            fn visit_pat_ident(&mut self, p: &'ast syn::PatIdent) {
                self.0.push(p.ident.to_string());
                syn::visit::visit_pat_ident(self, p);
            }
        }
        let mut names = Names(Vec::new());
        syn::visit::Visit::visit_pat(&mut names, pat);
        for n in names.0 {
            self.bind(&n, Local { wgsl: POISONED.to_string(), ty: Ty::Never, var: false });
        }
    }

    fn lookup(&self, rust: &str) -> Option<&Local> {
        self.scopes.iter().rev().flat_map(|s| s.iter().rev()).find(|(n, _)| n == rust).map(|(_, l)| l)
    }

    fn emit(&mut self, line: String) {
        self.blocks.last_mut().unwrap().push(line);
    }

    fn mark(&self, span: Span, text: &str) -> String {
        mark(self.m.span_id(span), text)
    }

    fn tmp(&mut self) -> String {
        self.fresh("tmp")
    }

    /// Lowers statements in a new scope and buffer; returns the lines and
    /// the tail value.
    fn sub_block(&mut self, stmts: &[Stmt], want: Option<&Ty>) -> Result<(Vec<String>, Option<Val>)> {
        self.blocks.push(Vec::new());
        self.scopes.push(Vec::new());
        let hoist = std::mem::replace(&mut self.hoist, false);
        let r = self.block_inner(stmts, want);
        self.hoist = hoist;
        self.scopes.pop();
        let lines = self.blocks.pop().unwrap();
        r.map(|v| (lines, v))
    }

    /// Lowers statements into the current buffer; errors in a statement are
    /// recorded and lowering goes on with the next one.
    fn block_inner(&mut self, stmts: &[Stmt], want: Option<&Ty>) -> Result<Option<Val>> {
        let mut tail = None;
        for (i, s) in stmts.iter().enumerate() {
            let last = i + 1 == stmts.len();
            match s {
                Stmt::Expr(e, None) if last => match self.expr(e, want) {
                    Ok(v) => tail = Some(v),
                    Err(err) => {
                        self.errors.push(err);
                        // Already reported: not also "must return a value".
                        tail = Some(Val::new("", Ty::Never));
                    }
                },
                _ => {
                    if let Err(err) = self.stmt(s) {
                        self.errors.push(err);
                    }
                    // `{ ...; return; }` has type `!` in Rust, like `{ return }`.
                    if last && matches!(s, Stmt::Expr(Expr::Return(_) | Expr::Break(_) | Expr::Continue(_), Some(_))) {
                        tail = Some(Val::new("", Ty::Never));
                    }
                }
            }
        }
        Ok(tail)
    }

    // ---- types ----

    fn find(&self, v: u32) -> u32 {
        let mut v = v;
        while self.ivars[v as usize].0 != v {
            v = self.ivars[v as usize].0;
        }
        v
    }

    fn new_ivar(&mut self) -> u32 {
        let id = self.ivars.len() as u32;
        self.ivars.push((id, None));
        id
    }

    /// The type with every resolved inference variable replaced.
    fn resolved(&self, t: &Ty) -> Ty {
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
            other => other.clone(),
        }
    }

    /// Makes `a` and `b` the same type if they can be; false otherwise.
    fn unify(&mut self, a: &Ty, b: &Ty) -> bool {
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
            _ => a == b,
        }
    }

    fn is_int(&self, t: &Ty) -> bool {
        match self.resolved(t) {
            Ty::IntVar(_) => true,
            Ty::Scalar(s) => s.is_int(),
            _ => false,
        }
    }

    fn coerce(&mut self, v: Val, want: &Ty, span: Span) -> Result<Val> {
        if self.unify(&v.ty, want) {
            Ok(Val { code: v.code, ty: self.resolved(want) })
        } else {
            Err(Error::new(
                span,
                format!("mismatched types: expected `{}`, found `{}`", self.resolved(want), self.resolved(&v.ty)),
            ))
        }
    }

    /// Reads through a reference parameter.
    fn deref(&self, v: Val) -> Val {
        match v.ty {
            Ty::Ref(true, t) => Val::new(format!("(*{})", v.code), *t),
            Ty::Ref(false, t) => Val::new(v.code, *t),
            _ => v,
        }
    }

    pub fn resolve_type(&self, ty: &syn::Type) -> Result<Ty> {
        self.m.resolve_type(ty)
    }

    // ---- statements ----

    fn stmt(&mut self, s: &Stmt) -> Result<()> {
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
                let line = format!("const {name}: {} = {};", ty.wgsl(), v.code);
                let line = self.mark(c.span(), &line);
                if self.hoisting() {
                    self.hoist_const(line);
                } else {
                    self.emit(line);
                }
                self.local_consts.insert(name.clone());
                self.bind(&c.ident.to_string(), Local { wgsl: name, ty, var: false });
                Ok(())
            }
            Stmt::Item(syn::Item::Fn(f)) => Err(Error::unsupported(
                f.sig.ident.span(),
                "a nested function",
                "declare it at module level with `#[rt_function]`",
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

    fn local(&mut self, l: &syn::Local) -> Result<()> {
        let (pat, annot) = match &l.pat {
            syn::Pat::Type(pt) => (&*pt.pat, Some(self.resolve_type(&pt.ty)?)),
            p => (p, None),
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
            syn::Pat::Tuple(t) => {
                return Err(Error::unsupported(
                    t.span(),
                    "a tuple pattern",
                    "use a struct and bind its fields one by one",
                ));
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
                if matches!(v.ty, Ty::Ref(..)) {
                    return Err(Error::unsupported(
                        init.expr.span(),
                        "a reference local",
                        "copy the value (`let x = *r;`) or pass `&mut` directly to a call",
                    ));
                }
                if !v.ty.is_value() {
                    return Err(Error::new(init.expr.span(), format!("cannot bind a value of type `{}`", v.ty)));
                }
                Some(v)
            }
            None => None,
        };
        if name == "_" {
            if let Some(v) = init {
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
        // Arrays and matrices may be indexed dynamically, which WGSL allows
        // only on `var`s; so are deferred initialisations.
        let var = mutable || init.is_none() || matches!(ty, Ty::Array(..) | Ty::Mat(_));
        let wname = self.fresh(&name);
        if self.hoisting() {
            self.hoisted_let(&wname, &ty, init.as_ref());
            self.bind(&name, Local { wgsl: wname, ty, var });
            return Ok(());
        }
        let line = match (&init, var) {
            (Some(v), true) => format!("var {wname}: {} = {};", ty.wgsl(), v.code),
            (Some(v), false) => format!("let {wname}: {} = {};", ty.wgsl(), v.code),
            (None, _) => format!("var {wname}: {};", ty.wgsl()),
        };
        let line = self.mark(l.span(), &line);
        self.emit(line);
        self.bind(&name, Local { wgsl: wname, ty, var });
        Ok(())
    }

    fn macro_stmt(&mut self, mac: &syn::Macro) -> Result<()> {
        let name = mac.path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
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
            self.emit(format!("let {t} = {};", v.code));
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

    // ---- intrinsics bookkeeping ----

    fn use_intrinsic(&mut self, name: &'static str, span: Span) -> Result<()> {
        if let Some(kind) = self.kind()
            && let Some(i) = kinds::intrinsic(name)
            && !i.callers.allows(kind)
        {
            return Err(Error::new(
                span,
                format!(
                    "`{name}` cannot be called from {} ({})",
                    kind.a_program(),
                    i.callers.doc_line().trim_end_matches('.').replace("Program kinds:", "allowed in:")
                ),
            ));
        }
        self.intrinsics.push((name, span));
        Ok(())
    }

    // ---- expressions ----

    pub fn expr(&mut self, e: &Expr, want: Option<&Ty>) -> Result<Val> {
        let span = e.span();
        let v = self.expr_inner(e, want)?;
        let code = if v.code.is_empty() { v.code } else { self.mark(span, &v.code) };
        Ok(Val { code, ty: v.ty })
    }

    fn expr_inner(&mut self, e: &Expr, want: Option<&Ty>) -> Result<Val> {
        match e {
            Expr::Lit(l) => self.literal(&l.lit, want),
            Expr::Paren(p) => {
                // Binary operators are always parenthesised; only a unary
                // operand needs the parentheses kept (`(-v).x`).
                let v = self.expr(&p.expr, want)?;
                if matches!(&*p.expr, Expr::Unary(_)) { Ok(Val::new(format!("({})", v.code), v.ty)) } else { Ok(v) }
            }
            Expr::Group(g) => self.expr_inner(&g.expr, want),
            Expr::Path(p) => self.path_expr(p),
            Expr::Unary(u) => self.unary(u, want),
            Expr::Binary(b) => self.binary(b, want),
            Expr::Assign(a) => {
                let v = self.expr(&a.right, None)?;
                self.assign(&a.left, None, v, a.right.span())?;
                Ok(Val::new("", Ty::Unit))
            }
            Expr::Cast(c) => self.cast(c),
            Expr::Field(f) => self.field(f),
            Expr::Index(i) => self.index(i),
            Expr::MethodCall(m) => self.method_call(m, want),
            Expr::Call(c) => self.call(c, want),
            Expr::Struct(s) => self.struct_lit(s),
            Expr::Array(a) => self.array_lit(a, want),
            Expr::Repeat(r) => self.repeat_lit(r, want),
            Expr::If(i) => self.if_expr(i, want),
            Expr::Block(b) => {
                if let Some(l) = &b.label {
                    return Err(Error::unsupported(l.span(), "a labeled block", "restructure with if/else"));
                }
                self.block_expr(&b.block.stmts, want, b.span())
            }
            Expr::Unsafe(u) => Err(Error::unsupported(u.unsafe_token.span, "`unsafe`", "ray programs are safe code")),
            Expr::While(w) => self.while_loop(w),
            Expr::Loop(l) => self.loop_expr(l),
            Expr::ForLoop(f) => self.for_loop(f),
            Expr::Break(b) => {
                if let Some(l) = &b.label {
                    return Err(Error::unsupported(
                        l.span(),
                        "a labeled `break`",
                        "WGSL has no labels; use a flag variable",
                    ));
                }
                if let Some(v) = &b.expr {
                    return Err(Error::unsupported(
                        v.span(),
                        "`break` with a value",
                        "assign to a variable before `break`",
                    ));
                }
                if self.loop_depth == 0 {
                    return Err(Error::new(b.span(), "`break` outside of a loop"));
                }
                let text = self.break_text();
                let line = self.mark(b.span(), &text);
                self.emit(line);
                Ok(Val::new("", Ty::Never))
            }
            Expr::Continue(c) => {
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
            Expr::Return(r) => {
                let ret = self.ret.clone();
                match &r.expr {
                    Some(v) => {
                        let val = self.expr(v, Some(&ret))?;
                        let val = self.coerce(val, &ret, v.span())?;
                        let line = if matches!(ret, Ty::Unit) {
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
            Expr::Match(m) => self.match_expr(m, want),
            Expr::Macro(m) => {
                self.macro_stmt(&m.mac)?;
                Ok(Val::new("", Ty::Unit))
            }
            Expr::Tuple(t) if t.elems.is_empty() => Ok(Val::new("", Ty::Unit)),
            Expr::Tuple(t) => Err(Error::unsupported(t.span(), "a tuple", "use a struct declared with #[rt_struct]")),
            Expr::Closure(c) => {
                Err(Error::unsupported(c.or1_token.span, "a closure", "write a #[rt_function] helper and call it"))
            }
            Expr::Reference(r) => Err(Error::unsupported(
                r.and_token.span,
                "a reference here",
                "references may only be passed directly as `&mut` call arguments (rt_trace, helpers)",
            )),
            Expr::Try(t) => {
                Err(Error::unsupported(t.question_token.span, "the `?` operator", "check the condition with if/else"))
            }
            Expr::Range(r) => Err(Error::unsupported(r.span(), "a range outside a `for` loop", "use `for i in a..b`")),
            Expr::Let(l) => {
                Err(Error::unsupported(l.let_token.span, "`if let` / `while let`", "compare values with if/else"))
            }
            Expr::Async(a) => Err(Error::unsupported(a.async_token.span, "`async`", "ray programs are synchronous")),
            Expr::Await(a) => Err(Error::unsupported(a.await_token.span, "`.await`", "ray programs are synchronous")),
            Expr::Yield(y) => {
                Err(Error::unsupported(y.yield_token.span, "`yield`", "ray programs are plain functions"))
            }
            Expr::TryBlock(t) => Err(Error::unsupported(t.try_token.span, "a `try` block", "use if/else")),
            other => {
                Err(Error::unsupported(other.span(), "this expression", "see rt_std's docs for the supported subset"))
            }
        }
    }

    fn literal(&mut self, lit: &syn::Lit, want: Option<&Ty>) -> Result<Val> {
        match lit {
            syn::Lit::Bool(b) => Ok(Val::new(b.value.to_string(), BOOL)),
            syn::Lit::Float(f) => {
                match f.suffix() {
                    "" | "f32" => {}
                    "f64" => return Err(Error::unsupported(f.span(), "an f64 literal", "use f32")),
                    s => return Err(Error::new(f.span(), format!("unknown literal suffix `{s}`"))),
                }
                let v: f32 = f.base10_parse()?;
                if let Some(w) = want
                    && self.is_int(w)
                {
                    return Err(Error::new(
                        f.span(),
                        format!("mismatched types: expected `{}`, found `f32`", self.resolved(w)),
                    ));
                }
                Ok(Val::new(f32_literal(v), F32))
            }
            syn::Lit::Int(i) => {
                let scalar = match i.suffix() {
                    "i32" => Some(Scalar::I32),
                    "u32" => Some(Scalar::U32),
                    "usize" => Some(Scalar::Usize),
                    "f32" => {
                        let v: f32 = i.base10_parse()?;
                        return Ok(Val::new(f32_literal(v), F32));
                    }
                    "" => None,
                    s @ ("i8" | "i16" | "i64" | "i128" | "u8" | "u16" | "u64" | "u128" | "isize" | "f64") => {
                        return Err(Error::unsupported(i.span(), &format!("a `{s}` literal"), "use i32, u32 or f32"));
                    }
                    s => return Err(Error::new(i.span(), format!("unknown literal suffix `{s}`"))),
                };
                let value: u64 = i.base10_parse()?;
                let want_scalar = want.map(|w| self.resolved(w));
                let scalar = scalar.or(match want_scalar {
                    Some(Ty::Scalar(s)) if s.is_int() => Some(s),
                    Some(Ty::Scalar(Scalar::F32)) => {
                        return Err(Error::new(
                            i.span(),
                            format!("mismatched types: expected `f32`, found integer (write `{value}.0`)"),
                        ));
                    }
                    _ => None,
                });
                match scalar {
                    Some(s) => {
                        check_int_range(value, s, i.span())?;
                        Ok(Val::new(format!("{value}{}", if s == Scalar::I32 { "i" } else { "u" }), Ty::Scalar(s)))
                    }
                    None => {
                        if value > u32::MAX as u64 {
                            return Err(Error::new(i.span(), "integer literal out of range for 32 bits"));
                        }
                        let v = self.new_ivar();
                        Ok(Val::new(int_literal_placeholder(v, &value.to_string()), Ty::IntVar(v)))
                    }
                }
            }
            other => Err(Error::unsupported(other.span(), "this literal", "use numbers and booleans")),
        }
    }

    fn path_expr(&mut self, p: &syn::ExprPath) -> Result<Val> {
        if p.qself.is_some() {
            return Err(Error::unsupported(p.span(), "a qualified path", "name the item directly"));
        }
        let segs: Vec<String> = p.path.segments.iter().map(|s| s.ident.to_string()).collect();
        if segs.len() == 1 {
            let name = &segs[0];
            if let Some(l) = self.lookup(name) {
                if l.wgsl == POISONED {
                    return Err(Error::silent(p.span()));
                }
                return Ok(Val::new(l.wgsl.clone(), l.ty.clone()));
            }
        }
        let last = segs.last().unwrap().as_str();
        // Associated constants: `Vec3::ZERO`, `f32::MAX`, `Mat3::IDENTITY`.
        if segs.len() >= 2 {
            let owner = segs[segs.len() - 2].as_str();
            if let Some(v) = super::builtins::assoc_const(owner, last) {
                return Ok(v);
            }
            if owner == "TransformKind" {
                return transform_kind(last, p.span());
            }
        }
        if (segs.len() == 1 || segs[segs.len() - 2] == "consts")
            && let Some((_, v)) = kinds::F32_CONSTS.iter().find(|(n, _)| *n == last)
        {
            return Ok(Val::new(f32_literal(*v), F32));
        }
        if let Some(v) = kinds::constant(last) {
            return Ok(Val::new(format!("{v}u"), U32));
        }
        if segs.len() == 1 && (last == "ObjectToWorld" || last == "WorldToObject") {
            return transform_kind(last, p.span());
        }
        if let Some(c) = self.m.consts.get(last) {
            return Ok(Val::new(c.wgsl_name.clone(), c.ty.clone()));
        }
        if self.m.helpers.contains_key(last) {
            return Err(Error::unsupported(p.span(), "a function used as a value", "call it"));
        }
        if self.m.failed.contains(last) {
            return Err(Error::silent(p.span()));
        }
        Err(Error::new(p.span(), format!("cannot find value `{}` in this ray program", segs.join("::"))))
    }

    fn unary(&mut self, u: &syn::ExprUnary, want: Option<&Ty>) -> Result<Val> {
        match u.op {
            UnOp::Neg(_) => {
                // `-2147483648` is not a valid WGSL i32 literal: fold it.
                if let Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }) = &*u.expr
                    && i.base10_digits() == "2147483648"
                {
                    return Ok(Val::new("i32(-2147483648)", I32));
                }
                let v = self.expr(&u.expr, want)?;
                let v = self.deref(v);
                let t = self.resolved(&v.ty);
                // `-(i32::MIN)` of a constant expression fails when WGSL
                // evaluates it at shader creation; it wraps at run time.
                let v = if t.scalar() == Some(Scalar::I32)
                    && self.is_const_code(&v.code)
                    && int_literal_value(&v.code).is_none_or(|x| x == i32::MIN as i64)
                {
                    self.at_run_time(v)
                } else {
                    v
                };
                match t.scalar() {
                    Some(Scalar::F32) | Some(Scalar::I32) => Ok(Val::new(negate(&v.code), v.ty)),
                    _ if matches!(t, Ty::IntVar(_)) => {
                        self.unify(&t, &I32);
                        Ok(Val::new(negate(&v.code), I32))
                    }
                    _ => Err(Error::new(u.span(), format!("cannot negate a value of type `{t}`"))),
                }
            }
            UnOp::Not(_) => {
                let v = self.expr(&u.expr, want)?;
                let v = self.deref(v);
                let t = self.resolved(&v.ty);
                if t == BOOL {
                    Ok(Val::new(format!("!{}", v.code), BOOL))
                } else if self.is_int(&t) || matches!(t, Ty::Vec(_, s) if s.is_int()) {
                    Ok(Val::new(format!("~{}", v.code), v.ty))
                } else {
                    Err(Error::new(u.span(), format!("cannot apply `!` to a value of type `{t}`")))
                }
            }
            UnOp::Deref(_) => {
                let v = self.expr(&u.expr, want)?;
                match v.ty {
                    Ty::Ref(..) => Ok(self.deref(v)),
                    t => Err(Error::new(u.span(), format!("type `{t}` cannot be dereferenced"))),
                }
            }
            _ => Err(Error::unsupported(u.span(), "this operator", "use arithmetic, comparison and logic operators")),
        }
    }

    fn binary(&mut self, b: &syn::ExprBinary, want: Option<&Ty>) -> Result<Val> {
        if is_compound(&b.op) {
            let v = self.expr(&b.right, None)?;
            let v = self.deref(v);
            self.assign(&b.left, Some(&b.op), v, b.right.span())?;
            return Ok(Val::new("", Ty::Unit));
        }
        if matches!(b.op, BinOp::And(_) | BinOp::Or(_)) {
            return self.short_circuit(b);
        }
        let want_scalar = want.and_then(|w| match self.resolved(w) {
            t @ Ty::Scalar(_) => Some(t),
            _ => None,
        });
        let arith = matches!(b.op, BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Div(_) | BinOp::Rem(_));
        let lw = if arith { want_scalar.clone() } else { None };
        let l = self.expr(&b.left, lw.as_ref())?;
        let mut l = self.deref(l);
        let rw = match (&b.op, self.resolved(&l.ty)) {
            (BinOp::Shl(_) | BinOp::Shr(_), _) => None,
            (_, t @ (Ty::Scalar(_) | Ty::IntVar(_))) => Some(t),
            _ => None,
        };
        let at = self.here();
        let r = self.expr(&b.right, rw.as_ref())?;
        let r = self.deref(r);
        self.spill(at, &mut [&mut l]);
        // Errors point at the operator, as rustc's do.
        self.binary_op(&b.op, l, r, b.op.span())
    }

    // ---- evaluation order and constant expressions ----

    /// The current position in the statements being emitted (see [`spill`]).
    ///
    /// [`spill`]: FnLowerer::spill
    fn here(&self) -> usize {
        self.blocks.last().map_or(0, |b| b.len())
    }

    /// Rust evaluates operands left to right; a later operand that needs
    /// statements (an `if` or `match` value, a block) has them emitted
    /// before the whole expression, where they could change what an earlier
    /// operand reads (`x + { x += 1; 1 }`, a helper call through `&mut`).
    /// If statements were emitted since `at`, the `earlier` operands that
    /// read mutable state are evaluated into temporaries at `at`, first.
    fn spill(&mut self, at: usize, earlier: &mut [&mut Val]) {
        // `let`s of effect-free values change nothing.
        let writes = self.blocks.last().unwrap()[at..]
            .iter()
            .any(|line| !text::strip(line).trim_start().starts_with("let ") || may_have_effects(line));
        if !writes {
            return;
        }
        let mut lets = Vec::new();
        for v in earlier.iter_mut() {
            if v.code.is_empty() || matches!(v.ty, Ty::Ref(..)) || !self.reads_state(&v.code) {
                continue;
            }
            let t = self.tmp();
            let kw = if matches!(self.resolved(&v.ty), Ty::Array(..) | Ty::Mat(_)) { "var" } else { "let" };
            lets.push(format!("{kw} {t} = {};", v.code));
            v.code = t;
        }
        let block = self.blocks.last_mut().unwrap();
        for (i, l) in lets.into_iter().enumerate() {
            block.insert(at + i, l);
        }
    }

    /// Whether lowered code reads something that statements can change:
    /// a `var` local, a pointer parameter, a buffer, or a call with effects.
    fn reads_state(&self, code: &str) -> bool {
        let mutable: HashSet<&str> = self
            .scopes
            .iter()
            .flatten()
            .filter(|(_, l)| l.var || matches!(l.ty, Ty::Ref(true, _)))
            .map(|(_, l)| l.wgsl.as_str())
            .collect();
        wgsl_idents(code).iter().any(|id| {
            mutable.contains(id.as_str())
                || id.starts_with("rt_bufload")
                || id.starts_with("rt_load")
                || may_have_effects(id)
        })
    }

    /// Whether lowered code is a WGSL const-expression (literals,
    /// operators, constructors, builtins, constants). WGSL evaluates those
    /// when the shader is created, with stricter rules than Rust's run-time
    /// semantics: integer overflow in `+ - * <<` and shift amounts of 32 or
    /// more are errors there, where they wrap or are masked at run time.
    fn is_const_code(&self, code: &str) -> bool {
        wgsl_idents(code).iter().all(|id| {
            super::is_reserved(id)
                || id == "true"
                || id == "false"
                || self.local_consts.contains(id)
                || self.m.consts.values().any(|c| c.wgsl_name == *id)
        })
    }

    /// `v` through a `let`, which WGSL evaluates at run time.
    fn at_run_time(&mut self, v: Val) -> Val {
        if !self.in_function {
            return v;
        }
        let t = self.tmp();
        self.emit(format!("let {t} = {};", v.code));
        Val::new(t, v.ty)
    }

    /// Integer `l op r` with both operands constant: run time, unless WGSL
    /// evaluates it at shader creation exactly as Rust does at run time
    /// (two literals, no overflow).
    fn const_int_op(&mut self, op: &BinOp, l: Val, r: &Val) -> Val {
        let ty = self.resolved(&l.ty);
        if !(self.is_int(&ty) || matches!(ty, Ty::Vec(_, s) if s.is_int()))
            || !self.is_const_code(&l.code)
            || !self.is_const_code(&r.code)
        {
            return l;
        }
        let scalar = match ty {
            Ty::Scalar(s) => Some(s),
            _ => None,
        };
        match (int_literal_value(&l.code), int_literal_value(&r.code)) {
            (Some(a), Some(b)) if matches!(ty, Ty::Scalar(_) | Ty::IntVar(_)) && !const_overflows(op, a, b, scalar) => {
                l
            }
            _ => self.at_run_time(l),
        }
    }

    /// A shift amount that is a const-expression other than a literal below
    /// 32, masked as WGSL masks run-time amounts (a constant 32 or more is
    /// an error in WGSL; Rust masks it in release builds, glam's vector
    /// shifts included).
    fn mask_amount(&self, amount: String, vector: Option<u8>) -> String {
        if !self.is_const_code(&amount) || literals_below_32(&amount) {
            return amount;
        }
        match vector {
            Some(n) => format!("({amount} & vec{n}<u32>(31u))"),
            None => format!("({amount} & 31u)"),
        }
    }

    /// Types and lowers `l op r` (both already lowered).
    fn binary_op(&mut self, op: &BinOp, l: Val, r: Val, span: Span) -> Result<Val> {
        let l = match op {
            BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Shl(_) | BinOp::Shr(_) => {
                self.const_int_op(op, l, &r)
            }
            _ => l,
        };
        let (lt, rt) = (self.resolved(&l.ty), self.resolved(&r.ty));
        let sym = op_symbol(op);
        let mismatch = |lt: &Ty, rt: &Ty| {
            let numeric = |t: &Ty| matches!(t, Ty::Scalar(s) if *s != Scalar::Bool);
            let hint = if numeric(lt) && numeric(rt) {
                format!(": there are no implicit conversions; convert one side with `as {lt}` or `as {rt}`")
            } else {
                String::new()
            };
            Error::new(span, format!("cannot apply `{sym}` to `{lt}` and `{rt}`{hint}"))
        };
        let ty = match op {
            BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Div(_) | BinOp::Rem(_) => {
                let mul = matches!(op, BinOp::Mul(_));
                match (&lt, &rt) {
                    (a, b) if (self.is_int(a) || *a == F32) && self.unify(a, b) => self.resolved(a),
                    (Ty::Vec(n, s), Ty::Vec(m, t)) if n == m && s == t && *s != Scalar::Bool => lt.clone(),
                    (Ty::Vec(_, s), b) if Some(*s) == b.scalar() && !matches!(b, Ty::Vec(..) | Ty::Mat(_)) => {
                        lt.clone()
                    }
                    (Ty::Vec(_, s), Ty::IntVar(_)) if s.is_int() => {
                        self.unify(&rt, &Ty::Scalar(*s));
                        lt.clone()
                    }
                    (a, Ty::Vec(_, s)) if Some(*s) == a.scalar() && !matches!(a, Ty::Vec(..) | Ty::Mat(_)) => {
                        rt.clone()
                    }
                    (Ty::IntVar(_), Ty::Vec(_, s)) if s.is_int() => {
                        self.unify(&lt, &Ty::Scalar(*s));
                        rt.clone()
                    }
                    (Ty::Mat(n), Ty::Mat(m)) if n == m && !matches!(op, BinOp::Div(_) | BinOp::Rem(_)) => lt.clone(),
                    (Ty::Mat(n), Ty::Vec(m, Scalar::F32)) if mul && n == m => rt.clone(),
                    (Ty::Mat(_), b) if mul && *b == F32 => lt.clone(),
                    (a, Ty::Mat(_)) if mul && *a == F32 => rt.clone(),
                    _ => return Err(mismatch(&lt, &rt)),
                }
            }
            BinOp::BitAnd(_) | BinOp::BitOr(_) | BinOp::BitXor(_) => {
                if lt == BOOL && rt == BOOL {
                    if matches!(op, BinOp::BitXor(_)) {
                        return Ok(Val::new(format!("({} != {})", l.code, r.code), BOOL));
                    }
                    BOOL
                } else if self.is_int(&lt) && self.unify(&lt, &rt) {
                    self.resolved(&lt)
                } else if matches!(lt, Ty::Vec(_, s) if s.is_int()) && lt == rt {
                    lt.clone()
                } else if let Ty::Vec(n, s) = lt
                    && s.is_int()
                    && self.unify(&rt, &Ty::Scalar(s))
                {
                    // glam's `v & 1`: WGSL wants both sides the same type.
                    return Ok(Val::new(format!("({} {sym} vec{n}<{}>({}))", l.code, s.wgsl(), r.code), lt));
                } else {
                    return Err(mismatch(&lt, &rt));
                }
            }
            BinOp::Shl(_) | BinOp::Shr(_) if matches!(lt, Ty::Vec(_, s) if s.is_int()) => {
                // glam shifts a vector by a scalar or by a vector of either
                // signedness; WGSL wants a `vecN<u32>` amount.
                let Ty::Vec(n, _) = lt else { unreachable!() };
                let amount = match rt {
                    Ty::Vec(m, Scalar::U32) if m == n => r.code.clone(),
                    Ty::Vec(m, t) if m == n && t.is_int() => format!("vec{n}<u32>({})", r.code),
                    Ty::IntVar(_) if self.unify(&rt, &U32) => format!("vec{n}<u32>({})", r.code),
                    Ty::Scalar(Scalar::I32) => format!("vec{n}<u32>(u32({}))", r.code),
                    Ty::Scalar(t) if t.is_int() => format!("vec{n}<u32>({})", r.code),
                    _ => return Err(mismatch(&lt, &rt)),
                };
                let amount = self.mask_amount(amount, Some(n));
                return Ok(Val::new(format!("({} {sym} {amount})", l.code), lt));
            }
            BinOp::Shl(_) | BinOp::Shr(_) => {
                if !self.is_int(&lt) || !self.is_int(&rt) {
                    return Err(mismatch(&lt, &rt));
                }
                let amount = match rt {
                    Ty::IntVar(_) => {
                        self.unify(&rt, &U32);
                        r.code.clone()
                    }
                    Ty::Scalar(Scalar::U32) | Ty::Scalar(Scalar::Usize) => r.code.clone(),
                    _ => format!("u32({})", r.code),
                };
                let amount = self.mask_amount(amount, None);
                return Ok(Val::new(format!("({} {sym} {amount})", l.code), lt));
            }
            BinOp::Eq(_) | BinOp::Ne(_) => {
                if !self.unify(&lt, &rt) || !lt.is_value() {
                    return Err(mismatch(&lt, &rt));
                }
                return Ok(match lt {
                    Ty::Vec(..) => {
                        let f = if matches!(op, BinOp::Eq(_)) { "all" } else { "any" };
                        Val::new(format!("{f}({} {sym} {})", l.code, r.code), BOOL)
                    }
                    Ty::Scalar(_) | Ty::IntVar(_) | Ty::Object | Ty::TransformKind => {
                        Val::new(format!("({} {sym} {})", l.code, r.code), BOOL)
                    }
                    other => {
                        return Err(Error::new(
                            span,
                            format!("`{sym}` on `{other}` is not supported: compare the fields"),
                        ));
                    }
                });
            }
            BinOp::Lt(_) | BinOp::Le(_) | BinOp::Gt(_) | BinOp::Ge(_) => {
                let ok = (self.is_int(&lt) || lt == F32) && self.unify(&lt, &rt);
                if !ok {
                    return Err(mismatch(&lt, &rt));
                }
                return Ok(Val::new(format!("({} {sym} {})", l.code, r.code), BOOL));
            }
            _ => return Err(Error::unsupported(span, &format!("the `{sym}` operator"), "see the supported operators")),
        };
        if matches!(op, BinOp::Rem(_)) && ty.scalar() == Some(Scalar::F32) {
            // Rust's `fmod`, not WGSL's `x - y * trunc(x / y)`.
            let mut fns = self.m.accessors.borrow_mut();
            if !matches!(ty, Ty::Vec(4, _)) {
                fns.functions.entry("rt_fmod".to_string()).or_insert_with(|| super::builtins::FMOD.to_string());
            }
            let code = match ty {
                Ty::Vec(n, _) => {
                    // glam's `Vec4` is SIMD on every target with SIMD (SSE2,
                    // NEON, wasm), and its `%` is `x - floor(x / y) * y`
                    // there, not `f32`'s `%` per component as for `Vec2` and
                    // `Vec3`.
                    let (f, text) = if n == 4 { super::builtins::VEC4_REM } else { super::builtins::fmod_vec(n) };
                    fns.functions.entry(f.to_string()).or_insert_with(|| text.to_string());
                    let splat = |v: &Val, t: &Ty| match t {
                        Ty::Vec(..) => v.code.clone(),
                        _ => format!("vec{n}<f32>({})", v.code),
                    };
                    format!("{f}({}, {})", splat(&l, &lt), splat(&r, &rt))
                }
                _ => format!("rt_fmod({}, {})", l.code, r.code),
            };
            return Ok(Val::new(code, ty));
        }
        Ok(Val::new(format!("({} {sym} {})", l.code, r.code), ty))
    }

    fn short_circuit(&mut self, b: &syn::ExprBinary) -> Result<Val> {
        let and = matches!(b.op, BinOp::And(_));
        let l = self.expr(&b.left, Some(&BOOL))?;
        let l = self.deref(l);
        let l = self.coerce(l, &BOOL, b.left.span())?;
        self.blocks.push(Vec::new());
        let r = self.expr(&b.right, Some(&BOOL));
        let hoisted = self.blocks.pop().unwrap();
        let r = r?;
        let r = self.deref(r);
        let r = self.coerce(r, &BOOL, b.right.span())?;
        let sym = if and { "&&" } else { "||" };
        if hoisted.is_empty() {
            return Ok(Val::new(format!("({} {sym} {})", l.code, r.code), BOOL));
        }
        // The right side needs statements: keep short-circuit order by hand.
        let t = self.tmp();
        self.emit(format!("var {t}: bool = {};", l.code));
        let cond = if and { t.clone() } else { format!("!{t}") };
        let mut body = hoisted;
        body.push(format!("{t} = {};", r.code));
        self.emit(format!("if {cond} {{\n{}}}", indent(&body.join("\n"))));
        Ok(Val::new(t, BOOL))
    }

    fn cast(&mut self, c: &syn::ExprCast) -> Result<Val> {
        let target = self.resolve_type(&c.ty)?;
        let v = self.expr(&c.expr, None)?;
        let v = self.deref(v);
        let from = self.resolved(&v.ty);
        let ts = match target {
            Ty::Scalar(s) => s,
            other => {
                return Err(Error::unsupported(
                    c.ty.span(),
                    &format!("`as {other}`"),
                    "`as` converts between scalars; for vectors use `as_vec3()`, `as_ivec3()`, `as_uvec3()`",
                ));
            }
        };
        let from = match from {
            Ty::IntVar(_) => {
                // `5 as f32`: the literal is an i32 as in Rust.
                self.unify(&from, &I32);
                I32
            }
            f => f,
        };
        let fs = match from {
            Ty::Scalar(s) => s,
            other => return Err(Error::new(c.expr.span(), format!("cannot cast `{other}` with `as`: only scalars"))),
        };
        if ts == Scalar::Bool && fs != Scalar::Bool {
            return Err(Error::new(
                c.span(),
                format!("cannot cast `{}` as `bool`: compare with zero instead", fs.rust()),
            ));
        }
        if fs == Scalar::Bool && ts == Scalar::F32 {
            return Err(Error::new(c.span(), "cannot cast `bool` as `f32`: cast to u32 first or use `select`"));
        }
        let code = if fs == Scalar::F32 && ts.is_int() {
            // Saturating at the integer limits, as Rust's `as`.
            let (f, text) = super::builtins::float_to_int(1, ts == Scalar::I32);
            self.m.accessors.borrow_mut().functions.entry(f.to_string()).or_insert_with(|| text.to_string());
            format!("{f}({})", v.code)
        } else if fs.wgsl() == ts.wgsl() {
            v.code
        } else {
            format!("{}({})", ts.wgsl(), v.code)
        };
        Ok(Val::new(code, Ty::Scalar(ts)))
    }

    fn field(&mut self, f: &syn::ExprField) -> Result<Val> {
        let base = self.expr(&f.base, None)?;
        let base = self.deref(base);
        let name = match &f.member {
            syn::Member::Named(n) => n.to_string(),
            syn::Member::Unnamed(i) => {
                return Err(Error::unsupported(i.span(), "a tuple field", "use a struct with named fields"));
            }
        };
        self.field_of(base, &name, f.member.span())
    }

    fn field_of(&mut self, base: Val, name: &str, span: Span) -> Result<Val> {
        let t = self.resolved(&base.ty);
        match &t {
            Ty::Vec(n, s) => {
                let idx = "xyzw".find(name).filter(|i| name.len() == 1 && *i < *n as usize);
                match idx {
                    Some(_) => Ok(Val::new(format!("{}.{name}", base.code), Ty::Scalar(*s))),
                    None => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
                }
            }
            Ty::Mat(n) => {
                let axis = ["x_axis", "y_axis", "z_axis", "w_axis"].iter().position(|a| *a == name);
                match axis {
                    Some(i) if i < *n as usize => Ok(Val::new(format!("{}[{i}]", base.code), Ty::vec(*n))),
                    _ => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
                }
            }
            Ty::Struct(_) | Ty::Ray | Ty::Aabb => match t.fields().into_iter().find(|(n, _)| n == name) {
                Some((_, fty)) => Ok(Val::new(format!("{}.{name}", base.code), fty)),
                None => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
            },
            _ => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
        }
    }

    fn index(&mut self, i: &syn::ExprIndex) -> Result<Val> {
        let base = self.expr(&i.expr, None)?;
        let mut base = self.deref(base);
        let at = self.here();
        match self.resolved(&base.ty) {
            Ty::Buffer(kind, elem) => {
                let idx = self.buffer_index(kind, &i.index)?;
                let f = self.m.accessors.borrow_mut().buffer_load(kind.dims, &elem);
                Ok(Val::new(format!("{f}({}, {})", base.code, idx), *elem))
            }
            Ty::Array(elem, _) => {
                let idx = self.int_index(&i.index)?;
                self.spill(at, &mut [&mut base]);
                Ok(Val::new(format!("{}[{idx}]", base.code), *elem))
            }
            Ty::Vec(_, s) => {
                let idx = self.int_index(&i.index)?;
                self.spill(at, &mut [&mut base]);
                Ok(Val::new(format!("{}[{idx}]", base.code), Ty::Scalar(s)))
            }
            t => Err(Error::new(i.expr.span(), format!("cannot index into a value of type `{t}`"))),
        }
    }

    fn int_index(&mut self, e: &Expr) -> Result<String> {
        let v = self.expr(e, Some(&Ty::Scalar(Scalar::Usize)))?;
        let v = self.deref(v);
        if !self.is_int(&v.ty) {
            return Err(Error::new(e.span(), format!("an index must be an integer, found `{}`", self.resolved(&v.ty))));
        }
        self.unify(&v.ty, &Ty::Scalar(Scalar::Usize));
        Ok(v.code)
    }

    fn buffer_index(&mut self, kind: BufferKind, e: &Expr) -> Result<String> {
        let want = if kind.dims == 2 { Ty::Vec(2, Scalar::U32) } else { U32 };
        let v = self.expr(e, Some(&want))?;
        let v = self.deref(v);
        Ok(self.coerce(v, &want, e.span())?.code)
    }

    // ---- places and assignment ----

    fn place(&mut self, e: &Expr) -> Result<Place> {
        match e {
            Expr::Paren(p) => self.place(&p.expr),
            Expr::Group(g) => self.place(&g.expr),
            Expr::Path(p) if p.path.segments.len() == 1 => {
                let name = p.path.segments[0].ident.to_string();
                match self.lookup(&name).cloned() {
                    Some(Local { wgsl, .. }) if wgsl == POISONED => Err(Error::silent(p.span())),
                    Some(Local { wgsl, ty, var: true }) => Ok(Place::Wgsl(self.mark(p.span(), &wgsl), ty)),
                    Some(Local { ty: Ty::Ref(..), .. }) => Err(Error::new(
                        p.span(),
                        format!("cannot assign to the reference `{name}`: assign through it with `*{name} = ...`"),
                    )),
                    Some(_) => Err(Error::new(p.span(), format!("cannot assign twice to immutable variable `{name}`"))),
                    None => Err(Error::new(p.span(), format!("cannot find variable `{name}`"))),
                }
            }
            Expr::Unary(u) if matches!(u.op, UnOp::Deref(_)) => {
                let v = self.expr(&u.expr, None)?;
                match v.ty {
                    Ty::Ref(true, t) => Ok(Place::Wgsl(format!("(*{})", v.code), *t)),
                    t => Err(Error::new(u.span(), format!("cannot assign through `{t}`"))),
                }
            }
            Expr::Field(f) => {
                let name = match &f.member {
                    syn::Member::Named(n) => n.to_string(),
                    syn::Member::Unnamed(i) => {
                        return Err(Error::unsupported(i.span(), "a tuple field", "use a struct with named fields"));
                    }
                };
                // Fields of reference parameters are places through the pointer.
                let base =
                    if let Some(r) = self.ref_base(&f.base) { Place::Wgsl(r.0, r.1) } else { self.place(&f.base)? };
                match base {
                    Place::Wgsl(code, ty) => {
                        let v = self.field_of(Val::new(code, ty), &name, f.member.span())?;
                        Ok(Place::Wgsl(v.code, v.ty))
                    }
                    Place::Buffer { buf, kind, elem, index, path, ty } => {
                        let v = self.field_of(Val::new("e", ty), &name, f.member.span())?;
                        let path = format!("{path}{}", &v.code[1..]);
                        Ok(Place::Buffer { buf, kind, elem, index, path, ty: v.ty })
                    }
                }
            }
            Expr::Index(i) => {
                let base_val = self.expr(&i.expr, None)?;
                if let Ty::Buffer(kind, elem) = self.resolved(&self.deref(base_val.clone()).ty) {
                    if !kind.writable {
                        return Err(Error::new(
                            i.expr.span(),
                            format!(
                                "cannot write to a read-only `{}`: declare the variable as `RwBuffer`/`RwBuffer2d`",
                                kind.rust_name()
                            ),
                        ));
                    }
                    let index = self.buffer_index(kind, &i.index)?;
                    let t = self.tmp();
                    self.emit(format!("let {t} = {index};"));
                    let buf = self.deref(base_val);
                    return Ok(Place::Buffer {
                        buf,
                        kind,
                        elem: (*elem).clone(),
                        index: t,
                        path: String::new(),
                        ty: *elem,
                    });
                }
                let base = self.place(&i.expr)?;
                let idx = self.int_index(&i.index)?;
                match base {
                    Place::Wgsl(code, Ty::Array(elem, _)) => Ok(Place::Wgsl(format!("{code}[{idx}]"), *elem)),
                    Place::Wgsl(code, Ty::Vec(_, s)) => Ok(Place::Wgsl(format!("{code}[{idx}]"), Ty::Scalar(s))),
                    Place::Buffer { buf, kind, elem, index, path, ty: Ty::Array(e, _) } => {
                        Ok(Place::Buffer { buf, kind, elem, index, path: format!("{path}[{idx}]"), ty: *e })
                    }
                    _ => Err(Error::new(i.expr.span(), "cannot index into this value")),
                }
            }
            other => Err(Error::new(other.span(), "cannot assign to this expression")),
        }
    }

    /// `prd` where `prd: &mut T` is a parameter: the pointer's target.
    fn ref_base(&mut self, e: &Expr) -> Option<(String, Ty)> {
        if let Expr::Path(p) = e
            && p.path.segments.len() == 1
            && let Some(Local { wgsl, ty: Ty::Ref(true, t), .. }) = self.lookup(&p.path.segments[0].ident.to_string())
        {
            return Some((format!("(*{wgsl})"), (**t).clone()));
        }
        None
    }

    fn assign(&mut self, left: &Expr, op: Option<&BinOp>, value: Val, vspan: Span) -> Result<()> {
        // Rust evaluates the value first, then the place's indices: if those
        // need statements, the value is read before them.
        let mut value = value;
        let at = self.here();
        let place = self.place(left)?;
        self.spill(at, &mut [&mut value]);
        let pty = match &place {
            Place::Wgsl(_, t) | Place::Buffer { ty: t, .. } => t.clone(),
        };
        let value = match op {
            None => self.coerce(value, &pty, vspan)?,
            Some(op) => {
                let base_op = compound_base(op);
                let cur = Val::new("x", pty.clone());
                let r = self.binary_op(&base_op, cur, value.clone(), vspan)?;
                if !self.unify(&r.ty, &pty) {
                    return Err(Error::new(
                        vspan,
                        format!("cannot apply `{}` to `{pty}` and `{}`", op_symbol(op), self.resolved(&value.ty)),
                    ));
                }
                let vty = self.resolved(&value.ty);
                // `x <<= n` needs a u32 amount; `v <<= n` and `v &= n` a vector.
                match (base_op, self.resolved(&pty)) {
                    (BinOp::Shl(_) | BinOp::Shr(_), Ty::Vec(n, _)) => {
                        let amount = match vty {
                            Ty::Vec(_, Scalar::U32) => value.code,
                            Ty::Scalar(Scalar::I32) => format!("vec{n}<u32>(u32({}))", value.code),
                            _ => format!("vec{n}<u32>({})", value.code),
                        };
                        Val::new(self.mask_amount(amount, Some(n)), Ty::Vec(n, Scalar::U32))
                    }
                    (BinOp::BitAnd(_) | BinOp::BitOr(_) | BinOp::BitXor(_), Ty::Vec(n, s))
                        if !matches!(vty, Ty::Vec(..)) =>
                    {
                        Val::new(format!("vec{n}<{}>({})", s.wgsl(), value.code), Ty::Vec(n, s))
                    }
                    (BinOp::Shl(_) | BinOp::Shr(_), Ty::Scalar(_) | Ty::IntVar(_)) => {
                        let amount = if matches!(vty, Ty::Scalar(Scalar::U32 | Scalar::Usize)) {
                            value.code
                        } else {
                            format!("u32({})", value.code)
                        };
                        Val::new(self.mask_amount(amount, None), U32)
                    }
                    _ => value,
                }
            }
        };
        // Float `%=` has no WGSL compound form with Rust's meaning: assign
        // `rt_fmod(place, value)` (see `binary_op`). Nor has `bool ^=`
        // (WGSL has no `^` on bool): assign `place != value`.
        let float_rem = matches!(op, Some(BinOp::RemAssign(_))) && self.resolved(&pty).scalar() == Some(Scalar::F32);
        let bool_xor = matches!(op, Some(BinOp::BitXorAssign(_))) && self.resolved(&pty) == BOOL;
        let mut sym = op.map(op_symbol).unwrap_or("=");
        let mut value = value;
        if float_rem || bool_xor {
            sym = "=";
            let place_code = match &place {
                Place::Wgsl(code, _) => code.clone(),
                Place::Buffer { path, .. } => format!("\u{7}{path}"),
            };
            if may_have_effects(&place_code) {
                return Err(Error::unsupported(
                    left.span(),
                    &format!("`{}` on a place whose index calls a helper", op_symbol(op.unwrap())),
                    "compute the index into a `let` first",
                ));
            }
            let cur = Val::new(place_code, pty.clone());
            value = self.binary_op(&compound_base(op.unwrap()), cur, value, vspan)?;
        }
        let line = match place {
            Place::Wgsl(code, _) => format!("{code} {sym} {};", value.code),
            Place::Buffer { buf, kind, elem, index, path, .. } => {
                let load = self.m.accessors.borrow_mut().buffer_load(kind.dims, &elem);
                let store = self.m.accessors.borrow_mut().buffer_store(kind.dims, &elem);
                if path.is_empty() && op.is_none() {
                    format!("{store}({}, {index}, {});", buf.code, value.code)
                } else {
                    let t = self.tmp();
                    format!(
                        "var {t} = {load}({b}, {index});\n{t}{path} {sym} {};\n{store}({b}, {index}, {t});",
                        value.code.replace('\u{7}', &t),
                        b = buf.code
                    )
                }
            }
        };
        let line = self.mark(left.span().join(vspan).unwrap_or(left.span()), &line);
        self.emit(line);
        Ok(())
    }

    // ---- control flow ----

    fn cond(&mut self, e: &Expr) -> Result<String> {
        let v = self.expr(e, Some(&BOOL))?;
        let v = self.deref(v);
        Ok(self.coerce(v, &BOOL, e.span())?.code)
    }

    fn if_expr(&mut self, i: &syn::ExprIf, want: Option<&Ty>) -> Result<Val> {
        if let Expr::Let(l) = &*i.cond {
            return Err(Error::unsupported(
                l.let_token.span,
                "`if let`",
                "compare the value in a plain `if` (`if x == 0`), or `match` on an integer",
            ));
        }
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
                    self.blocks.push(Vec::new());
                    self.scopes.push(Vec::new());
                    let r = self.expr(e, else_want.as_ref());
                    self.scopes.pop();
                    let lines = self.blocks.pop().unwrap();
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

    fn block_expr(&mut self, stmts: &[Stmt], want: Option<&Ty>, _span: Span) -> Result<Val> {
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
    fn break_text(&mut self) -> String {
        match self.breaks.last_mut() {
            Some(Some((flag, used))) => {
                *used = true;
                format!("{flag} = true;\nbreak;")
            }
            _ => "break;".to_string(),
        }
    }

    fn loop_body(&mut self, stmts: &[Stmt]) -> Result<Vec<String>> {
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

    fn while_loop(&mut self, w: &syn::ExprWhile) -> Result<Val> {
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
        self.blocks.push(Vec::new());
        let cond = self.cond(&w.cond);
        let hoisted = self.blocks.pop().unwrap();
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

    fn loop_expr(&mut self, l: &syn::ExprLoop) -> Result<Val> {
        if let Some(lb) = &l.label {
            return Err(Error::unsupported(lb.span(), "a labeled loop", "WGSL has no labels; use a flag variable"));
        }
        let body = self.loop_body(&l.body.stmts)?;
        let text = self.mark(l.span(), &format!("loop {{\n{}}}", indent(&body.join("\n"))));
        self.emit(text);
        // A `loop` without `break` never ends; either way it yields no value.
        Ok(Val::new("", Ty::Unit))
    }

    fn for_loop(&mut self, f: &syn::ExprForLoop) -> Result<Val> {
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
            self.emit(format!("let {t} = {};", e.code));
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

    fn match_expr(&mut self, m: &syn::ExprMatch, want: Option<&Ty>) -> Result<Val> {
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
        if may_have_effects(&scrut.code) && m.arms.iter().any(|a| binds(&a.pat)) {
            let t = self.fresh("scrutinee");
            self.emit(format!("let {t} = {};", scrut.code));
            scrut.code = t;
        }
        if !self.is_int(&sty) {
            return Err(Error::unsupported(
                m.expr.span(),
                &format!("`match` on `{sty}`"),
                "match on i32/u32 values, or use if/else",
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
        if !has_default {
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
    fn match_arms(
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
            self.blocks.push(Vec::new());
            if let Some(b) = &binding {
                let w = self.fresh(b);
                self.emit(format!("let {w} = {};", scrut.code));
                self.bind(b, Local { wgsl: w, ty: sty.clone(), var: false });
            }
            let want_arm = result_ty.clone().or(want.cloned());
            let r = self.expr(&arm.body, want_arm.as_ref());
            let mut lines = self.blocks.pop().unwrap();
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

    fn match_pattern(
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
    fn is_const_name(&self, name: &str) -> bool {
        match self.lookup(name) {
            Some(l) => self.local_consts.contains(&l.wgsl),
            None => self.m.consts.contains_key(name) || kinds::constant(name).is_some(),
        }
    }

    // ---- literals of compound types ----

    fn struct_lit(&mut self, s: &syn::ExprStruct) -> Result<Val> {
        if let Some(r) = &s.rest {
            return Err(Error::unsupported(r.span(), "struct update syntax (`..`)", "list every field"));
        }
        let name = s.path.segments.last().unwrap().ident.to_string();
        let ty = match name.as_str() {
            "Ray" => Ty::Ray,
            "Aabb" => Ty::Aabb,
            _ => match self.m.structs.get(&name) {
                Some(d) => Ty::Struct(d.clone()),
                None if self.m.failed.contains(&name) => return Err(Error::silent(s.path.span())),
                None => {
                    return Err(Error::new(
                        s.path.span(),
                        format!("cannot find struct `{name}`: declare it with #[rt_struct]"),
                    ));
                }
            },
        };
        let fields = ty.fields();
        let mut given: Vec<Option<String>> = vec![None; fields.len()];
        // WGSL evaluates constructor arguments in declaration order, Rust the
        // fields in source order: when they differ, effects run first.
        let source_order: Vec<Option<usize>> = s
            .fields
            .iter()
            .map(|fv| match &fv.member {
                syn::Member::Named(n) => fields.iter().position(|(f, _)| n == f),
                syn::Member::Unnamed(_) => None,
            })
            .collect();
        let in_order = source_order.windows(2).all(|w| w[0] < w[1]);
        let mut done: Vec<(usize, Val)> = Vec::new();
        for fv in &s.fields {
            let fname = match &fv.member {
                syn::Member::Named(n) => n.to_string(),
                syn::Member::Unnamed(i) => {
                    return Err(Error::unsupported(i.span(), "a tuple field", "use named fields"));
                }
            };
            let Some(idx) = fields.iter().position(|(n, _)| *n == fname) else {
                return Err(Error::new(fv.member.span(), format!("struct `{name}` has no field named `{fname}`")));
            };
            let fty = fields[idx].1.clone();
            let at = self.here();
            let v = self.expr(&fv.expr, Some(&fty))?;
            let v = self.deref(v);
            let mut v = self.coerce(v, &fty, fv.expr.span())?;
            self.spill(at, &mut done.iter_mut().map(|(_, v)| v).collect::<Vec<_>>());
            if !in_order && may_have_effects(&v.code) {
                let t = self.tmp();
                self.emit(format!("let {t} = {};", v.code));
                v.code = t;
            }
            done.push((idx, v));
        }
        for (idx, v) in done {
            given[idx] = Some(v.code);
        }
        let missing: Vec<&str> =
            fields.iter().zip(&given).filter(|(_, g)| g.is_none()).map(|((n, _), _)| n.as_str()).collect();
        if !missing.is_empty() {
            return Err(Error::new(
                s.span(),
                format!("missing fields {} in initializer of `{name}`", missing.join(", ")),
            ));
        }
        let args: Vec<String> = given.into_iter().map(|g| g.unwrap()).collect();
        Ok(Val::new(format!("{}({})", ty.wgsl(), args.join(", ")), ty))
    }

    fn array_lit(&mut self, a: &syn::ExprArray, want: Option<&Ty>) -> Result<Val> {
        if a.elems.is_empty() {
            return Err(Error::unsupported(a.span(), "an empty array", "arrays need at least one element"));
        }
        let mut elem_want = match want.map(|w| self.resolved(w)) {
            Some(Ty::Array(e, _)) => Some(*e),
            _ => None,
        };
        let mut vals: Vec<Val> = Vec::new();
        for e in &a.elems {
            let at = self.here();
            let v = self.expr(e, elem_want.as_ref())?;
            let v = self.deref(v);
            let v = match &elem_want {
                Some(w) => self.coerce(v, w, e.span())?,
                None => v,
            };
            self.spill(at, &mut vals.iter_mut().collect::<Vec<_>>());
            elem_want = Some(v.ty.clone());
            vals.push(v);
        }
        let codes: Vec<String> = vals.into_iter().map(|v| v.code).collect();
        let ty = Ty::Array(Box::new(elem_want.unwrap()), codes.len() as u32);
        Ok(Val::new(format!("{}({})", ty.wgsl(), codes.join(", ")), ty))
    }

    fn repeat_lit(&mut self, r: &syn::ExprRepeat, want: Option<&Ty>) -> Result<Val> {
        let n = const_len(&r.len)?;
        let elem_want = match want.map(|w| self.resolved(w)) {
            Some(Ty::Array(e, _)) => Some(*e),
            _ => None,
        };
        let v = self.expr(&r.expr, elem_want.as_ref())?;
        let v = self.deref(v);
        let v = match &elem_want {
            Some(w) => self.coerce(v, w, r.expr.span())?,
            None => v,
        };
        let ty = Ty::Array(Box::new(v.ty.clone()), n);
        let simple = matches!(&*r.expr, Expr::Lit(_) | Expr::Path(_));
        let value = if simple {
            v.code
        } else {
            let t = self.tmp();
            self.emit(format!("let {t} = {};", v.code));
            t
        };
        let parts = vec![value; n as usize];
        Ok(Val::new(format!("{}({})", ty.wgsl(), parts.join(", ")), ty))
    }

    // ---- calls ----

    fn method_call(&mut self, m: &syn::ExprMethodCall, _want: Option<&Ty>) -> Result<Val> {
        if let Some(t) = &m.turbofish {
            return Err(Error::unsupported(t.span(), "generic arguments", "ray programs are not generic"));
        }
        let recv = self.expr(&m.receiver, None)?;
        let recv = self.deref(recv);
        let name = m.method.to_string();
        let args: Vec<&Expr> = m.args.iter().collect();
        self.method(recv, &name, &args, m.method.span(), m.span())
    }

    /// Lowers `recv.name(args)`.
    fn method(&mut self, recv: Val, name: &str, args: &[&Expr], name_span: Span, span: Span) -> Result<Val> {
        let rt = self.resolved(&recv.ty);
        if let Ty::IntVar(_) = rt {
            // `3.max(x)`: the literal's type comes from the argument.
            // (Probed, not lowered: lowering twice would emit its statements twice.)
            if let Some(a) = args.first()
                && let Some(t @ Ty::Scalar(_)) = self.peek_type(a)?
            {
                self.unify(&rt, &t);
            }
        }
        let rt = self.resolved(&recv.ty);
        match &rt {
            Ty::Buffer(kind, elem) => return self.buffer_method(recv, *kind, elem, name, args, name_span, span),
            Ty::Sampler => return self.sampler_method(recv, name, args, name_span, span),
            _ => {}
        }
        let sig = super::builtins::method_sig(&rt, name).ok_or_else(|| {
            let hint = super::builtins::method_hint(&rt, name);
            Error::new(name_span, format!("no method `{name}` on `{rt}` in ray programs{hint}"))
        })?;
        if args.len() != sig.params.len() {
            let n = sig.params.len();
            let want = match n {
                0 => "no arguments".to_string(),
                _ => {
                    let tys: Vec<String> = sig.params.iter().map(|t| format!("`{t}`")).collect();
                    format!("{n} argument{} ({})", if n == 1 { "" } else { "s" }, tys.join(", "))
                }
            };
            return Err(Error::new(name_span, format!("`{rt}::{name}` takes {want}, found {}", args.len())));
        }
        let mut vals = vec![recv.clone()];
        for (a, p) in args.iter().zip(&sig.params) {
            // glam takes some operands by reference: `m.mul_mat3(&n)`.
            let a = match a {
                Expr::Reference(r) if r.mutability.is_none() => &*r.expr,
                a => *a,
            };
            let at = self.here();
            let v = self.expr(a, Some(p))?;
            let v = self.deref(v);
            let v = self.coerce(v, p, a.span())?;
            self.spill(at, &mut vals.iter_mut().collect::<Vec<_>>());
            vals.push(v);
        }
        // Integer arithmetic on constants only: at run time (see
        // `const_int_op`).
        let wraps = matches!(
            name,
            "wrapping_add" | "wrapping_sub" | "wrapping_mul" | "dot" | "element_sum" | "element_product"
        );
        if wraps
            && (self.is_int(&rt) || matches!(rt, Ty::Vec(_, s) if s.is_int()))
            && vals.iter().all(|v| self.is_const_code(&v.code))
        {
            vals[0] = self.at_run_time(vals[0].clone());
        }
        let mut codes: Vec<String> = vals.into_iter().map(|v| v.code).collect();
        // A lowering that repeats an operand (`(x - trunc(x))`) must not
        // repeat its side effects: evaluate such operands (and, to keep
        // Rust's left-to-right order, effectful ones before them) once, first.
        let probe: Vec<String> = (0..codes.len()).map(|i| format!("\u{6}{i}\u{6}")).collect();
        let shape = (sig.lower)(&probe);
        let last_repeated =
            (0..codes.len()).rev().find(|&i| shape.matches(&probe[i]).count() > 1 && may_have_effects(&codes[i]));
        if let Some(last) = last_repeated {
            for c in codes.iter_mut().take(last + 1) {
                if may_have_effects(c) {
                    let t = self.tmp();
                    self.emit(format!("let {t} = {c};"));
                    *c = t;
                }
            }
        }
        if let Some((name, text)) = sig.support {
            self.m.accessors.borrow_mut().functions.entry(name.to_string()).or_insert_with(|| text.to_string());
        }
        Ok(Val::new((sig.lower)(&codes), sig.ret))
    }

    #[allow(clippy::too_many_arguments)]
    fn buffer_method(
        &mut self,
        recv: Val,
        kind: BufferKind,
        elem: &Ty,
        name: &str,
        args: &[&Expr],
        name_span: Span,
        span: Span,
    ) -> Result<Val> {
        let want_args = |n: usize| -> Result<()> {
            if args.len() != n {
                Err(Error::new(
                    name_span,
                    format!("`{}::{name}` takes {n} argument(s), found {}", kind.rust_name(), args.len()),
                ))
            } else {
                Ok(())
            }
        };
        match (name, kind.dims) {
            ("len", 1) => {
                want_args(0)?;
                Ok(Val::new(format!("{}.len", recv.code), U32))
            }
            ("is_empty", 1) => {
                want_args(0)?;
                Ok(Val::new(format!("({}.len == 0u)", recv.code), BOOL))
            }
            ("size", 2) => {
                want_args(0)?;
                Ok(Val::new(format!("vec2<u32>({0}.width, {0}.height)", recv.code), Ty::Vec(2, Scalar::U32)))
            }
            ("load", _) => {
                want_args(1)?;
                let idx = self.buffer_index(kind, args[0])?;
                let f = self.m.accessors.borrow_mut().buffer_load(kind.dims, elem);
                Ok(Val::new(format!("{f}({}, {idx})", recv.code), elem.clone()))
            }
            ("store", _) => {
                want_args(2)?;
                if !kind.writable {
                    return Err(Error::new(
                        name_span,
                        format!(
                            "cannot store into a read-only `{}`: declare the variable as `RwBuffer`/`RwBuffer2d`",
                            kind.rust_name()
                        ),
                    ));
                }
                let idx = self.buffer_index(kind, args[0])?;
                let mut idx = Val::new(idx, U32);
                let at = self.here();
                let v = self.expr(args[1], Some(elem))?;
                let v = self.deref(v);
                let v = self.coerce(v, elem, args[1].span())?;
                self.spill(at, &mut [&mut idx]);
                let f = self.m.accessors.borrow_mut().buffer_store(kind.dims, elem);
                let line = self.mark(span, &format!("{f}({}, {}, {});", recv.code, idx.code, v.code));
                self.emit(line);
                Ok(Val::new("", Ty::Unit))
            }
            _ => Err(Error::new(
                name_span,
                format!(
                    "no method `{name}` on `{}<{elem}>` (it has load, store, {})",
                    kind.rust_name(),
                    if kind.dims == 2 { "size" } else { "len, is_empty" }
                ),
            )),
        }
    }

    fn sampler_method(&mut self, recv: Val, name: &str, args: &[&Expr], name_span: Span, _span: Span) -> Result<Val> {
        let (f, arg_ty, ret) = match name {
            "sample" => ("rt_tex_sample", Ty::vec(2), Ty::vec(4)),
            "fetch" => ("rt_tex_fetch", Ty::Vec(2, Scalar::U32), Ty::vec(4)),
            "size" => {
                if !args.is_empty() {
                    return Err(Error::new(name_span, "`Sampler2d::size` takes no arguments"));
                }
                return Ok(Val::new(format!("vec2<u32>({0}.width, {0}.height)", recv.code), Ty::Vec(2, Scalar::U32)));
            }
            _ => {
                return Err(Error::new(
                    name_span,
                    format!("no method `{name}` on `Sampler2d` (it has sample, fetch, size)"),
                ));
            }
        };
        if args.len() != 1 {
            return Err(Error::new(name_span, format!("`Sampler2d::{name}` takes 1 argument, found {}", args.len())));
        }
        let v = self.expr(args[0], Some(&arg_ty))?;
        let v = self.deref(v);
        let v = self.coerce(v, &arg_ty, args[0].span())?;
        Ok(Val::new(format!("{f}({}, {})", recv.code, v.code), ret))
    }

    fn call(&mut self, c: &syn::ExprCall, want: Option<&Ty>) -> Result<Val> {
        let path = match &*c.func {
            Expr::Path(p) if p.qself.is_none() => &p.path,
            other => {
                return Err(Error::unsupported(other.span(), "calling this expression", "call a function by name"));
            }
        };
        if let Some(seg) = path.segments.iter().find(|s| !s.arguments.is_none()) {
            return Err(Error::unsupported(seg.arguments.span(), "generic arguments", "ray programs are not generic"));
        }
        let segs: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
        let name = segs.last().unwrap().clone();
        let args: Vec<&Expr> = c.args.iter().collect();
        let span = c.span();
        let name_span = path.segments.last().unwrap().ident.span();

        if segs.len() == 1
            && let Some(l) = self.lookup(&name)
        {
            if l.wgsl == POISONED {
                return Err(Error::silent(path.span()));
            }
            return Err(Error::unsupported(
                path.span(),
                &format!("calling the local `{name}`"),
                "call a #[rt_function] helper by name",
            ));
        }
        // `Type::function(...)`: constructors and UFCS methods of builtin types.
        if segs.len() >= 2 {
            let owner = segs[segs.len() - 2].as_str();
            if let Some(advice) = crate::types::unsupported_type_advice(owner) {
                let owner_span = path.segments[segs.len() - 2].ident.span();
                return Err(Error::unsupported(owner_span, &format!("the type `{owner}`"), advice));
            }
            if let Some(ty) = crate::types::builtin_type(owner) {
                if let Some(v) = self.constructor(&ty, &name, &args, span)? {
                    return Ok(v);
                }
                if name == "default" && args.is_empty() {
                    return Ok(Val::new(super::builtins::zero_value(&ty), ty));
                }
                // UFCS: `f32::max(a, b)` is `a.max(b)`.
                if let Some((first, rest)) = args.split_first() {
                    let recv = self.expr(first, Some(&ty))?;
                    let recv = self.deref(recv);
                    let recv = self.coerce(recv, &ty, first.span())?;
                    return self.method(recv, &name, rest, name_span, span);
                }
            }
            if let Some(d) = self.m.structs.get(owner)
                && name == "default"
                && args.is_empty()
            {
                let ty = Ty::Struct(d.clone());
                return Ok(Val::new(format!("{}()", ty.wgsl()), ty));
            }
        }
        if let Some(v) = self.free_builtin(&name, &args, span, want)? {
            return Ok(v);
        }
        if let Some(sig) = self.m.helpers.get(&name) {
            return self.helper_call(sig, &args, span);
        }
        if name == self.fn_name {
            return Err(Error::unsupported(
                span,
                &format!("recursion (`{name}` calls itself)"),
                "WGSL has no recursion; rewrite it as a loop",
            ));
        }
        if self.m.failed.contains(&name) {
            // A helper whose own macro reports its mistake.
            return Err(Error::silent(path.span()));
        }
        Err(Error::new(
            path.span(),
            format!(
                "cannot find function `{}`: ray programs may call #[rt_function] helpers and rt-std items",
                segs.join("::")
            ),
        ))
    }

    fn args_typed(&mut self, args: &[&Expr], params: &[Ty], span: Span, what: &str) -> Result<Vec<String>> {
        if args.len() != params.len() {
            return Err(Error::new(span, format!("`{what}` takes {} argument(s), found {}", params.len(), args.len())));
        }
        let mut out: Vec<Val> = Vec::new();
        for (a, p) in args.iter().zip(params) {
            let at = self.here();
            let v = self.expr(a, Some(p))?;
            let v = self.deref(v);
            let v = self.coerce(v, p, a.span())?;
            self.spill(at, &mut out.iter_mut().collect::<Vec<_>>());
            out.push(v);
        }
        Ok(out.into_iter().map(|v| v.code).collect())
    }

    fn constructor(&mut self, ty: &Ty, name: &str, args: &[&Expr], span: Span) -> Result<Option<Val>> {
        let w = ty.wgsl();
        match (ty, name) {
            (Ty::Vec(n, s), "new") => {
                let params = vec![Ty::Scalar(*s); *n as usize];
                let a = self.args_typed(args, &params, span, &format!("{ty}::new"))?;
                Ok(Some(Val::new(format!("{w}({})", a.join(", ")), ty.clone())))
            }
            (Ty::Vec(_, s), "splat") => {
                let a = self.args_typed(args, &[Ty::Scalar(*s)], span, &format!("{ty}::splat"))?;
                Ok(Some(Val::new(format!("{w}({})", a[0]), ty.clone())))
            }
            (Ty::Mat(n), "from_cols") => {
                let params = vec![Ty::vec(*n); *n as usize];
                let a = self.args_typed(args, &params, span, &format!("{ty}::from_cols"))?;
                Ok(Some(Val::new(format!("{w}({})", a.join(", ")), ty.clone())))
            }
            (Ty::Mat(n), "from_diagonal") => {
                let a = self.args_typed(args, &[Ty::vec(*n)], span, &format!("{ty}::from_diagonal"))?;
                let t = self.tmp();
                self.emit(format!("let {t} = {};", a[0]));
                let cols: Vec<String> = (0..*n)
                    .map(|i| {
                        let comps: Vec<String> =
                            (0..*n).map(|j| if i == j { format!("{t}[{i}]") } else { "0.0".into() }).collect();
                        format!("vec{n}<f32>({})", comps.join(", "))
                    })
                    .collect();
                Ok(Some(Val::new(format!("{w}({})", cols.join(", ")), ty.clone())))
            }
            (Ty::Ray, "new") => {
                let params = [Ty::vec(3), Ty::vec(3), U32, F32, F32];
                let a = self.args_typed(args, &params, span, "Ray::new")?;
                Ok(Some(Val::new(format!("RtRay({})", a.join(", ")), Ty::Ray)))
            }
            (Ty::Aabb, "new") => {
                let a = self.args_typed(args, &[Ty::vec(3), Ty::vec(3)], span, "Aabb::new")?;
                Ok(Some(Val::new(format!("RtAabb({})", a.join(", ")), Ty::Aabb)))
            }
            _ => Ok(None),
        }
    }

    fn free_builtin(&mut self, name: &str, args: &[&Expr], span: Span, want: Option<&Ty>) -> Result<Option<Val>> {
        // glam's `vec3(x, y, z)` style constructors.
        let ctor = match name {
            "vec2" => Some(Ty::vec(2)),
            "vec3" => Some(Ty::vec(3)),
            "vec4" => Some(Ty::vec(4)),
            "ivec2" => Some(Ty::Vec(2, Scalar::I32)),
            "ivec3" => Some(Ty::Vec(3, Scalar::I32)),
            "ivec4" => Some(Ty::Vec(4, Scalar::I32)),
            "uvec2" => Some(Ty::Vec(2, Scalar::U32)),
            "uvec3" => Some(Ty::Vec(3, Scalar::U32)),
            "uvec4" => Some(Ty::Vec(4, Scalar::U32)),
            _ => None,
        };
        if let Some(ty) = ctor {
            return self.constructor(&ty, "new", args, span);
        }
        let v3 = Ty::vec(3);
        let simple = |s: &str, params: Vec<Ty>, ret: Ty| Some((s.to_string(), params, ret));
        let generic_ty = |this: &mut Self| -> Result<Ty> {
            // smoothstep/step/saturate/mix work on f32 and f32 vectors: take
            // the type from the last argument (or the expected type).
            let probe = args.last().map(|a| this.peek_type(a)).transpose()?.flatten();
            Ok(match probe.or(want.cloned()) {
                Some(t @ Ty::Vec(_, Scalar::F32)) => t,
                _ => F32,
            })
        };
        let call = match name {
            "reflect" => simple("reflect", vec![v3.clone(), v3.clone()], v3.clone()),
            "refract" => simple("refract", vec![v3.clone(), v3.clone(), F32], v3.clone()),
            "faceforward" => simple("faceForward", vec![v3.clone(), v3.clone(), v3.clone()], v3.clone()),
            "smoothstep" => {
                let t = generic_ty(self)?;
                simple("smoothstep", vec![t.clone(), t.clone(), t.clone()], t)
            }
            "step" => {
                let t = generic_ty(self)?;
                simple("step", vec![t.clone(), t.clone()], t)
            }
            "saturate" => {
                let t = generic_ty(self)?;
                simple("saturate", vec![t.clone()], t)
            }
            "mix" => {
                let a_ty = match args.first().map(|a| self.peek_type(a)).transpose()?.flatten().or(want.cloned()) {
                    Some(t @ Ty::Vec(_, Scalar::F32)) => t,
                    _ => F32,
                };
                let t_ty = match args.get(2).map(|a| self.peek_type(a)).transpose()?.flatten() {
                    Some(t @ Ty::Vec(_, Scalar::F32)) => t,
                    _ => F32,
                };
                simple("mix", vec![a_ty.clone(), a_ty.clone(), t_ty], a_ty)
            }
            _ => None,
        };
        if let Some((f, params, ret)) = call {
            let mut a = self.args_typed(args, &params, span, name)?;
            if f == "step" {
                // rt-std's definition, `x >= edge` selecting 1 or 0, rather
                // than WGSL's `step`: lavapipe folds a constant added to a
                // `step` at reduced precision (`step(e, x) - 0.001` loses the
                // low 8 bits of the result).
                let (zero, one) = match &ret {
                    Ty::Vec(..) => (format!("{}(0.0)", ret.wgsl()), format!("{}(1.0)", ret.wgsl())),
                    _ => ("0.0f".to_string(), "1.0f".to_string()),
                };
                return Ok(Some(Val::new(format!("select({zero}, {one}, {} >= {})", a[1], a[0]), ret)));
            }
            if f == "mix" {
                // rt-std's formula (see `builtins::lerp_formula`); `t` is
                // used twice: once evaluated.
                if may_have_effects(&a[2]) {
                    for c in a.iter_mut() {
                        if may_have_effects(c) {
                            let t = self.tmp();
                            self.emit(format!("let {t} = {c};"));
                            *c = t;
                        }
                    }
                }
                return Ok(Some(Val::new(super::builtins::lerp_formula(&a[0], &a[1], &a[2]), ret)));
            }
            return Ok(Some(Val::new(format!("{f}({})", a.join(", ")), ret)));
        }
        self.intrinsic_call(name, args, span)
    }

    /// The type an expression would have, without emitting anything (used to
    /// pick an overload). Only cheap, side-effect-free forms are probed.
    fn peek_type(&mut self, e: &Expr) -> Result<Option<Ty>> {
        let saved_blocks = self.blocks.len();
        self.blocks.push(Vec::new());
        let saved_intr = self.intrinsics.len();
        let saved_calls = self.calls.len();
        let saved_ivars = self.ivars.clone();
        let saved_errors = self.errors.0.len();
        let r = self.expr(e, None);
        self.blocks.truncate(saved_blocks);
        self.intrinsics.truncate(saved_intr);
        self.calls.truncate(saved_calls);
        self.ivars = saved_ivars;
        self.errors.0.truncate(saved_errors);
        Ok(r.ok().map(|v| self.deref(v).ty))
    }

    fn intrinsic_call(&mut self, name: &str, args: &[&Expr], span: Span) -> Result<Option<Val>> {
        let Some(intr) = kinds::intrinsic(name) else { return Ok(None) };
        self.use_intrinsic(intr.name, span)?;
        if intr.form != kinds::Form::Special
            && let Some(f) = intr.wgsl
        {
            return self.contract_call(name, &f, args, span).map(Some);
        }
        match name {
            "rt_report_intersection" => {
                let a = self.args_typed(args, &[U32], span, name)?;
                let attr = self.scopes[0].iter().find(|(_, l)| matches!(&l.ty, Ty::Ref(true, t) if matches!(&**t, Ty::Struct(s) if s.role == crate::StructRole::Attributes))).map(|(_, l)| l.clone());
                match attr {
                    Some(Local { wgsl, ty: Ty::Ref(_, t), .. }) => {
                        self.m.report_types.borrow_mut().insert(t.wgsl(), (*t).clone());
                        Ok(Some(Val::new(format!("rt_report_intersection_{}({}, {wgsl})", t.mangle(), a[0]), BOOL)))
                    }
                    _ => Ok(Some(Val::new(format!("rt_report_intersection({})", a[0]), BOOL))),
                }
            }
            "rt_trace" | "rt_trace_with" => {
                let n = if name == "rt_trace" { 3 } else { 5 };
                if args.len() != n {
                    return Err(Error::new(span, format!("`{name}` takes {n} arguments, found {}", args.len())));
                }
                let obj = self.args_typed(&args[..1], &[Ty::Object], span, name)?;
                let ray = self.args_typed(&args[1..2], &[Ty::Ray], span, name)?;
                let (prd, pty) = self.mut_ref_arg(args[2])?;
                match &pty {
                    Ty::Struct(s) if s.role == crate::StructRole::Payload => {}
                    other => {
                        return Err(Error::new(
                            args[2].span(),
                            format!("`rt_trace` needs a `&mut` to a #[rt_payload] struct, found `&mut {other}`"),
                        ));
                    }
                }
                let (flags, mask) = if n == 5 {
                    let fm = self.args_typed(&args[3..], &[U32, U32], span, name)?;
                    (fm[0].clone(), fm[1].clone())
                } else {
                    ("0u".to_string(), "255u".to_string())
                };
                self.traced.push(pty.clone());
                self.m.trace_types.borrow_mut().insert(pty.wgsl(), pty.clone());
                if self.resume.is_some() {
                    self.trace_site(&pty.mangle(), [&obj[0], &ray[0], &flags, &mask], &prd, span)?;
                    return Ok(Some(Val::new("", Ty::Unit)));
                }
                let line = format!("rt_trace_{}({}, {}, {prd}, {flags}, {mask});", pty.mangle(), obj[0], ray[0]);
                let line = self.mark(span, &line);
                self.emit(line);
                for w in std::mem::take(&mut self.writebacks) {
                    self.emit(w);
                }
                Ok(Some(Val::new("", Ty::Unit)))
            }
            _ => Ok(None),
        }
    }

    /// A call of an intrinsic the contract lowers by its row alone: the
    /// arguments checked against the row's parameters, then the runtime
    /// function called as a value, or as a statement of its own.
    fn contract_call(&mut self, name: &str, f: &kinds::WgslFn, args: &[&Expr], span: Span) -> Result<Val> {
        if f.params.is_empty() && !args.is_empty() {
            return Err(Error::new(span, format!("`{name}` takes no arguments")));
        }
        let params: Option<Vec<Ty>> = f.params.iter().map(|(_, t)| abi_ty(*t)).collect();
        let (Some(params), Some(ret)) = (params, abi_ty(f.ret)) else {
            return Err(Error::new(span, format!("`{name}`: its contract row passes a handle by value")));
        };
        let a = self.args_typed(args, &params, span, name)?;
        let call = format!("{}({})", f.name, a.join(", "));
        match f.ret {
            kinds::AbiTy::Unit => {
                let line = self.mark(span, &format!("{call};"));
                self.emit(line);
                Ok(Val::new("", Ty::Unit))
            }
            _ => Ok(Val::new(call, ret)),
        }
    }

    /// A `&mut place` argument (or a `&mut T` parameter passed on): the WGSL
    /// pointer expression and the pointee type.
    fn mut_ref_arg(&mut self, e: &Expr) -> Result<(String, Ty)> {
        match e {
            Expr::Reference(r) if r.mutability.is_some() => {
                if let Some((code, ty)) = self.ref_base(&r.expr) {
                    // `&mut *prd` or `&mut prd` where prd is `&mut T`.
                    return Ok((code.trim_start_matches("(*").trim_end_matches(')').to_string(), ty));
                }
                let inner = match &*r.expr {
                    Expr::Unary(u) if matches!(u.op, UnOp::Deref(_)) => {
                        if let Some((code, ty)) = self.ref_base(&u.expr) {
                            return Ok((code.trim_start_matches("(*").trim_end_matches(')').to_string(), ty));
                        }
                        &r.expr
                    }
                    _ => &r.expr,
                };
                match self.place(inner)? {
                    Place::Wgsl(code, ty) => {
                        // WGSL passes pointers to whole variables only: a
                        // field or element goes through a temporary that is
                        // written back after the call.
                        let clean = super::text::strip(&code);
                        if clean.chars().all(|c| c.is_alphanumeric() || c == '_') {
                            Ok((format!("&{}", paren(&code)), ty))
                        } else {
                            let t = self.tmp();
                            self.emit(format!("var {t}: {} = {code};", ty.wgsl()));
                            self.writebacks.push(format!("{code} = {t};"));
                            Ok((format!("&{t}"), ty))
                        }
                    }
                    Place::Buffer { .. } => Err(Error::unsupported(
                        r.span(),
                        "a reference into a buffer",
                        "copy the element into a local, pass `&mut local`, and store it back",
                    )),
                }
            }
            _ => {
                let v = self.expr(e, None)?;
                match v.ty {
                    Ty::Ref(true, t) => Ok((v.code, *t)),
                    t => Err(Error::new(e.span(), format!("expected a `&mut` argument, found `{t}` (write `&mut x`)"))),
                }
            }
        }
    }

    fn helper_call(&mut self, sig: &HelperSig, args: &[&Expr], span: Span) -> Result<Val> {
        if args.len() != sig.params.len() {
            return Err(Error::new(
                span,
                format!("`{}` takes {} argument(s), found {}", sig.name, sig.params.len(), args.len()),
            ));
        }
        if let Some(kind) = self.kind() {
            for intr in &sig.intrinsics {
                if let Some(i) = kinds::intrinsic(intr)
                    && !i.callers.allows(kind)
                {
                    return Err(Error::new(
                        span,
                        format!(
                            "`{}` calls `{intr}`, which cannot be called from {} ({})",
                            sig.name,
                            kind.a_program(),
                            i.callers.doc_line().trim_end_matches('.').replace("Program kinds:", "allowed in:")
                        ),
                    ));
                }
            }
        }
        // Arguments in order; a pointer argument is a place, never spilled
        // (its type stays `Ref`).
        let start = self.here();
        let mut vals: Vec<Val> = Vec::new();
        for (a, p) in args.iter().zip(&sig.params) {
            let at = self.here();
            let v = match p {
                Ty::Ref(true, inner) => {
                    let (code, ty) = self.mut_ref_arg(a)?;
                    if !self.unify(&ty, inner) {
                        return Err(Error::new(
                            a.span(),
                            format!("mismatched types: expected `&mut {inner}`, found `&mut {ty}`"),
                        ));
                    }
                    Val::new(code, p.clone())
                }
                Ty::Ref(false, inner) => {
                    let target = match a {
                        Expr::Reference(r) if r.mutability.is_none() => &*r.expr,
                        other => other,
                    };
                    let v = self.expr(target, Some(inner))?;
                    let v = self.deref(v);
                    self.coerce(v, inner, a.span())?
                }
                p => {
                    let v = self.expr(a, Some(p))?;
                    let v = self.deref(v);
                    self.coerce(v, p, a.span())?
                }
            };
            self.spill(at, &mut vals.iter_mut().collect::<Vec<_>>());
            vals.push(v);
        }
        let codes: Vec<String> = vals.into_iter().map(|v| v.code).collect();
        if self.resume.is_some() && !sig.traced.is_empty() {
            self.calls.push(sig.name.clone());
            self.traced.extend(sig.traced.iter().cloned());
            return self.helper_site(sig, codes, start, span);
        }
        for intr in &sig.intrinsics {
            if let Some(i) = kinds::intrinsic(intr) {
                self.intrinsics.push((i.name, span));
            }
        }
        self.traced.extend(sig.traced.iter().cloned());
        self.calls.push(sig.name.clone());
        let code = format!("{}({})", sig.wgsl_name, codes.join(", "));
        let writebacks = std::mem::take(&mut self.writebacks);
        if matches!(sig.ret, Ty::Unit) {
            let line = self.mark(span, &format!("{code};"));
            self.emit(line);
            writebacks.into_iter().for_each(|w| self.emit(w));
            Ok(Val::new("", Ty::Unit))
        } else if writebacks.is_empty() {
            Ok(Val::new(code, sig.ret.clone()))
        } else {
            // The result must be taken before the temporaries are copied back.
            let t = self.tmp();
            let line = self.mark(span, &format!("let {t} = {code};"));
            self.emit(line);
            writebacks.into_iter().for_each(|w| self.emit(w));
            Ok(Val::new(t, sig.ret.clone()))
        }
    }
}

/// `-code`; `- -x` must not become WGSL's `--` token.
fn negate(code: &str) -> String {
    let mut chars = code.chars();
    let mut first = None;
    while let Some(c) = chars.next() {
        match c {
            // A source-map marker: `\u{1}id\u{2}` opens, `\u{3}` closes.
            '\u{1}' => chars.by_ref().take_while(|&d| d != '\u{2}').for_each(drop),
            '\u{3}' => {}
            c => {
                first = Some(c);
                break;
            }
        }
    }
    if first == Some('-') { format!("-({code})") } else { format!("-{code}") }
}

/// The identifiers lowered code names (not members after `.`, not literal
/// suffixes), markers and placeholders skipped.
fn wgsl_idents(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut chars = code.chars().peekable();
    let mut prev = ' ';
    while let Some(c) = chars.next() {
        match c {
            '\u{1}' => {
                chars.by_ref().take_while(|&d| d != '\u{2}').for_each(drop);
                continue;
            }
            '\u{4}' => {
                chars.by_ref().take_while(|&d| d != '\u{5}').for_each(drop);
                prev = '0';
                continue;
            }
            '\u{3}' => continue,
            c if c.is_ascii_digit() => {
                while chars.peek().is_some_and(|d| d.is_ascii_alphanumeric() || *d == '_' || *d == '.') {
                    chars.next();
                }
            }
            c if c.is_ascii_alphabetic() || c == '_' => {
                let mut id = String::from(c);
                while let Some(&d) = chars.peek() {
                    if d.is_ascii_alphanumeric() || d == '_' {
                        id.push(d);
                        chars.next();
                    } else {
                        break;
                    }
                }
                if prev != '.' {
                    out.push(id);
                }
            }
            _ => {}
        }
        prev = c;
    }
    out
}

/// The value of lowered code that is one integer literal (`5u`, `-3i`, a
/// literal placeholder), markers aside.
fn int_literal_value(code: &str) -> Option<i64> {
    let mut text = String::new();
    let mut chars = code.chars();
    while let Some(c) = chars.next() {
        match c {
            '\u{1}' => chars.by_ref().take_while(|&d| d != '\u{2}').for_each(drop),
            '\u{3}' => {}
            '\u{4}' => {
                let body: String = chars.by_ref().take_while(|&d| d != '\u{5}').collect();
                text.push_str(body.strip_prefix('L')?.split_once(' ')?.1);
            }
            c => text.push(c),
        }
    }
    let text = text.trim_end_matches(['i', 'u']);
    let (neg, digits) = match text.strip_prefix('-') {
        Some(d) => (true, d),
        None => (false, text),
    };
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let v: i64 = digits.parse().ok()?;
    Some(if neg { -v } else { v })
}

/// Whether const code is only integer literals below 32, possibly in
/// vector constructors and conversions (`5u`, `vec2<u32>(1u, 2u)`).
fn literals_below_32(code: &str) -> bool {
    let text = text::strip(code).replace("<u32>", "").replace("<i32>", "");
    if text.contains(['+', '-', '*', '/', '%', '&', '|', '^', '~', '<', '>', '!', '.']) {
        return false;
    }
    // Constructors and conversions only, no functions (`reverseBits(5u)`).
    if wgsl_idents(&text).iter().any(|id| !matches!(id.as_str(), "vec2" | "vec3" | "vec4" | "u32" | "i32")) {
        return false;
    }
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|t| t.starts_with(|c: char| c.is_ascii_digit()))
        .all(|t| t.trim_end_matches(['i', 'u']).parse::<u32>().is_ok_and(|v| v < 32))
}

/// Whether WGSL's shader-creation evaluation of `a op b` fails (an
/// overflow, a shift of 32 or more) for the scalar type (`None`: not yet
/// inferred, either).
fn const_overflows(op: &BinOp, a: i64, b: i64, scalar: Option<Scalar>) -> bool {
    let fails = |signed: bool| -> bool {
        let (lo, hi) = if signed { (i32::MIN as i64, i32::MAX as i64) } else { (0, u32::MAX as i64) };
        let out = |v: i64| v < lo || v > hi;
        if out(a) || (!matches!(op, BinOp::Shl(_) | BinOp::Shr(_)) && out(b)) {
            return true;
        }
        match op {
            BinOp::Add(_) => out(a + b),
            BinOp::Sub(_) => out(a - b),
            BinOp::Mul(_) => out(a.saturating_mul(b)),
            BinOp::Shl(_) | BinOp::Shr(_) if !(0..32).contains(&b) => true,
            // The bits shifted out (and, signed, the sign) must not change.
            BinOp::Shl(_) => out(a << b),
            _ => false,
        }
    };
    match scalar {
        Some(Scalar::I32) => fails(true),
        Some(Scalar::U32 | Scalar::Usize) => fails(false),
        _ => fails(true) || fails(false),
    }
}

/// Whether evaluating lowered code may have side effects: only calls of
/// helpers (which may write through `&mut` parameters or to buffers) and
/// of the intersection-reporting intrinsics do.
fn may_have_effects(code: &str) -> bool {
    code.contains("rtf_") || code.contains("rt_report_intersection") || code.contains("rt_potential_intersection")
}

fn paren(code: &str) -> String {
    if code.chars().all(|c| c.is_alphanumeric() || c == '_' || (c as u32) < 8) {
        code.to_string()
    } else {
        format!("({code})")
    }
}

fn transform_kind(name: &str, span: Span) -> Result<Val> {
    match name {
        "ObjectToWorld" => Ok(Val::new("0u", Ty::TransformKind)),
        "WorldToObject" => Ok(Val::new("1u", Ty::TransformKind)),
        _ => Err(Error::new(span, format!("no transform kind `{name}` (ObjectToWorld or WorldToObject)"))),
    }
}

fn unsupported_macro(mac: &syn::Macro, name: &str) -> Error {
    let instead = match name {
        "println" | "print" | "eprintln" | "eprint" | "dbg" => "use `rt_printf!`",
        "panic" | "assert" | "assert_eq" | "assert_ne" | "debug_assert" | "unreachable" | "todo" | "unimplemented" => {
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

fn check_int_range(value: u64, s: Scalar, span: Span) -> Result<()> {
    let max = if s == Scalar::I32 { i32::MAX as u64 } else { u32::MAX as u64 };
    if value > max {
        let hint = if s == Scalar::I32 { "; use `u32` for values up to 4294967295" } else { "" };
        return Err(Error::new(span, format!("literal out of range for `{}`: the largest is {max}{hint}", s.rust())));
    }
    Ok(())
}

fn const_len(e: &Expr) -> Result<u32> {
    match e {
        Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }) => {
            let n: u32 = i.base10_parse()?;
            if n == 0 {
                return Err(Error::unsupported(i.span(), "a zero-length array", "arrays need at least one element"));
            }
            Ok(n)
        }
        other => Err(Error::unsupported(other.span(), "a non-literal array length", "write the length as a number")),
    }
}

pub fn array_len(e: &Expr) -> Result<u32> {
    const_len(e)
}

fn is_compound(op: &BinOp) -> bool {
    matches!(
        op,
        BinOp::AddAssign(_)
            | BinOp::SubAssign(_)
            | BinOp::MulAssign(_)
            | BinOp::DivAssign(_)
            | BinOp::RemAssign(_)
            | BinOp::BitAndAssign(_)
            | BinOp::BitOrAssign(_)
            | BinOp::BitXorAssign(_)
            | BinOp::ShlAssign(_)
            | BinOp::ShrAssign(_)
    )
}

fn compound_base(op: &BinOp) -> BinOp {
    use syn::token;
    let s = proc_macro2::Span::call_site();
    match op {
        BinOp::AddAssign(_) => BinOp::Add(token::Plus(s)),
        BinOp::SubAssign(_) => BinOp::Sub(token::Minus(s)),
        BinOp::MulAssign(_) => BinOp::Mul(token::Star(s)),
        BinOp::DivAssign(_) => BinOp::Div(token::Slash(s)),
        BinOp::RemAssign(_) => BinOp::Rem(token::Percent(s)),
        BinOp::BitAndAssign(_) => BinOp::BitAnd(token::And(s)),
        BinOp::BitOrAssign(_) => BinOp::BitOr(token::Or(s)),
        BinOp::BitXorAssign(_) => BinOp::BitXor(token::Caret(s)),
        BinOp::ShlAssign(_) => BinOp::Shl(token::Shl(s)),
        BinOp::ShrAssign(_) => BinOp::Shr(token::Shr(s)),
        other => *other,
    }
}

fn op_symbol(op: &BinOp) -> &'static str {
    match op {
        BinOp::Add(_) => "+",
        BinOp::Sub(_) => "-",
        BinOp::Mul(_) => "*",
        BinOp::Div(_) => "/",
        BinOp::Rem(_) => "%",
        BinOp::And(_) => "&&",
        BinOp::Or(_) => "||",
        BinOp::BitXor(_) => "^",
        BinOp::BitAnd(_) => "&",
        BinOp::BitOr(_) => "|",
        BinOp::Shl(_) => "<<",
        BinOp::Shr(_) => ">>",
        BinOp::Eq(_) => "==",
        BinOp::Lt(_) => "<",
        BinOp::Le(_) => "<=",
        BinOp::Ne(_) => "!=",
        BinOp::Ge(_) => ">=",
        BinOp::Gt(_) => ">",
        BinOp::AddAssign(_) => "+=",
        BinOp::SubAssign(_) => "-=",
        BinOp::MulAssign(_) => "*=",
        BinOp::DivAssign(_) => "/=",
        BinOp::RemAssign(_) => "%=",
        BinOp::BitXorAssign(_) => "^=",
        BinOp::BitAndAssign(_) => "&=",
        BinOp::BitOrAssign(_) => "|=",
        BinOp::ShlAssign(_) => "<<=",
        BinOp::ShrAssign(_) => ">>=",
        _ => "?",
    }
}

fn body_tail_span(b: &syn::Block) -> Span {
    b.stmts.last().map(|s| s.span()).unwrap_or(b.brace_token.span.join())
}

fn ends_in_return(b: &syn::Block) -> bool {
    fn diverges(e: &Expr) -> bool {
        match e {
            Expr::Return(_) => true,
            Expr::Loop(l) => !contains_break(&l.body.stmts),
            Expr::If(i) => match &i.else_branch {
                Some((_, e)) => block_diverges(&i.then_branch) && diverges(e),
                None => false,
            },
            Expr::Block(b) => block_diverges(&b.block),
            Expr::Match(m) => !m.arms.is_empty() && m.arms.iter().all(|a| diverges(&a.body)),
            _ => false,
        }
    }
    fn block_diverges(b: &syn::Block) -> bool {
        b.stmts.iter().any(|s| match s {
            Stmt::Expr(e, _) => diverges(e),
            _ => false,
        })
    }
    fn contains_break(stmts: &[Stmt]) -> bool {
        // Conservative: any `break` text inside the loop body.
        stmts.iter().any(|s| quote::quote!(#s).to_string().contains("break"))
    }
    block_diverges(b)
}

/// The compiler's type for a contract type (none for the handles, which
/// no intrinsic passes by value).
fn abi_ty(t: kinds::AbiTy) -> Option<Ty> {
    use kinds::AbiTy as A;
    Some(match t {
        A::Unit => Ty::Unit,
        A::Bool => BOOL,
        A::U32 => U32,
        A::F32 => F32,
        A::UVec2 => Ty::Vec(2, Scalar::U32),
        A::Vec2 => Ty::vec(2),
        A::Vec3 => Ty::vec(3),
        A::Vec4 => Ty::vec(4),
        A::Mat4 => Ty::Mat(4),
        A::Ray => Ty::Ray,
        A::TransformKind => Ty::TransformKind,
        A::Buffer | A::Sampler => return None,
    })
}
