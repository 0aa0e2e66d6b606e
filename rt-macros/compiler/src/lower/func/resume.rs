//! The resumable form of a tracing program.
//!
//! WGSL has no recursion, so a megakernel cannot call a closest-hit program
//! from inside the traversal that a closest-hit program started. Cloning
//! everything per trace depth works, but a shader compiler inlines every
//! call: a program with two `rt_trace` calls at depth 7 becomes 2^7 copies
//! of the traversal (minutes of pipeline creation on Mesa). The resumable
//! form lets the linker run every program from one loop instead: a program
//! returns to the kernel at each `rt_trace` with the request in the
//! kernel's request slot, and the kernel calls it again when the traced
//! ray's programs are done, so each program and the traversal appear once
//! in the kernel whatever the depth.
//!
//! The transformation is structured (WGSL has no `goto`):
//! - every Rust local of a block that contains a trace is declared at the top
//!   of the function and saved to a per-depth frame
//!   (`rt_fr_<entry>_<local>[rt_d]`) when the program suspends, restored
//!   when it resumes;
//! - sites (`rt_trace` calls, and calls of helpers that trace, whose own
//!   resumable forms `<helper>_rs` suspend and resume the same way) are
//!   numbered 1, 2, ... in source order; the kernel's `rt_rs` is non-zero
//!   when it calls a function to resume it, and the function's local
//!   `rt_site` is 0 while running, or the site it suspended at (kept in the
//!   frame) while resuming;
//! - statements without a site run only when `rt_site == 0u`; a statement
//!   containing sites `lo..=hi` is entered when running or resuming at one of
//!   them: an `if` keeps its condition in a local (so a resumed branch is the
//!   one that suspended), so does a `match` its scrutinee (its arms become a
//!   `switch` over that local), a loop skips its exit test while resuming;
//! - a trace site stores the request
//!   (`rt_request_<P>(object, ray, payload, flags, mask)`), saves the frame
//!   with the site, sets `rt_rs = 1u` and returns; resumed there, it takes
//!   the traced payload back (`rt_result_<P>()`) and clears `rt_rs`; a
//!   helper-call site evaluates the arguments once (into frame locals),
//!   calls the helper's resumable form and, if that suspended (`rt_rs !=
//!   0u`), saves the frame with the site and returns too.
//!
//! Functions with a site where the form does not follow (in a condition or
//! a `match` scrutinee, in a `let`'s value or the returned value, a payload
//! that is a field) have no resumable form: the linker falls back to
//! per-depth clones for kernels that use them.
//! [`FnLowerer::function_resumable`] says why.

use super::*;

/// State of a resumable lowering.
#[derive(Default)]
pub struct Resume {
    /// `rt_fr_<entry>_`: the frame arrays' prefix.
    prefix: String,
    /// The last site number given.
    sites: u32,
    /// Locals declared at the top and kept in the frame: `(name, type)`.
    locals: Vec<(String, String)>,
    /// `const` items, moved to the top (they have no run-time effect).
    consts: Vec<String>,
    /// Set by a statement that lowers a trace call as a site.
    expect_site: bool,
    /// What the site just lowered does when resumed.
    resume_lines: Option<String>,
    /// The function's return type's zero value (`return T();` when
    /// suspending), empty for `()`.
    dummy: String,
    /// Rust names of the helpers that trace.
    tracing: HashSet<String>,
}

/// The line a site's frame save is written as until the function's locals
/// are all known.
const SAVE_FRAME: &str = "rt_save_frame_here;";

/// Counts sites: `rt_trace`/`rt_trace_with` calls and calls of helpers that
/// trace.
struct SiteCounter<'a> {
    n: u32,
    tracing: &'a HashSet<String>,
}

impl<'ast> syn::visit::Visit<'ast> for SiteCounter<'_> {
    fn visit_expr_call(&mut self, c: &'ast syn::ExprCall) {
        if let Expr::Path(p) = &*c.func
            && let Some(last) = p.path.segments.last()
        {
            let name = last.ident.to_string();
            if matches!(name.as_str(), "rt_trace" | "rt_trace_with" | "rt_trace_at") || self.tracing.contains(&name) {
                self.n += 1;
            }
        }
        syn::visit::visit_expr_call(self, c);
    }
}

/// Whether `s` is a statement of its own around one call of a helper that
/// traces (`let x = helper(..);`, `x = helper(..);`, `x op= helper(..);`,
/// `helper(..);`): the call is the site.
fn is_helper_site(s: &Stmt, tracing: &HashSet<String>) -> bool {
    match s {
        Stmt::Local(l) => {
            l.init.as_ref().is_some_and(|i| i.diverge.is_none() && tracing_call(&i.expr, tracing).is_some())
        }
        Stmt::Expr(Expr::Assign(a), _) => tracing_call(&a.right, tracing).is_some(),
        Stmt::Expr(Expr::Binary(b), _) => is_compound(&b.op) && tracing_call(&b.right, tracing).is_some(),
        Stmt::Expr(e, _) => tracing_call(e, tracing).is_some(),
        _ => false,
    }
}

/// The call of a helper that traces, when `e` is one.
fn tracing_call<'e>(e: &'e Expr, tracing: &HashSet<String>) -> Option<&'e syn::ExprCall> {
    match e {
        Expr::Call(c) => match &*c.func {
            Expr::Path(p) if p.path.segments.last().is_some_and(|s| tracing.contains(&s.ident.to_string())) => Some(c),
            _ => None,
        },
        Expr::Paren(p) => tracing_call(&p.expr, tracing),
        _ => None,
    }
}

fn not_resumable(span: Span, what: &str) -> Error {
    Error::new(span, format!("not resumable: {what}"))
}

impl FnLowerer<'_> {
    fn stmt_sites(&self, s: &Stmt) -> u32 {
        let tracing = &self.resume.as_ref().expect("resumable lowering").tracing;
        let mut c = SiteCounter { n: 0, tracing };
        syn::visit::Visit::visit_stmt(&mut c, s);
        c.n
    }

    fn expr_sites(&self, e: &Expr) -> u32 {
        let tracing = &self.resume.as_ref().expect("resumable lowering").tracing;
        let mut c = SiteCounter { n: 0, tracing };
        syn::visit::Visit::visit_expr(&mut c, e);
        c.n
    }

    /// Lowers a function that traces (a program, or a helper as
    /// `<name>_rs`) in its resumable form: private frame declarations
    /// followed by the function (same parameters as the plain form). An
    /// error means it has no resumable form.
    pub fn function_resumable(&mut self, wgsl_name: &str, params: &[LParam], body: &syn::Block) -> Result<String> {
        self.in_function = true;
        let tracing = self.m.helpers.values().filter(|h| !h.traced.is_empty()).map(|h| h.name.clone()).collect();
        let dummy = if matches!(self.ret, Ty::Unit) { String::new() } else { format!(" {}()", self.ret.wgsl()) };
        self.resume = Some(Resume { prefix: format!("rt_fr_{wgsl_name}_"), dummy, tracing, ..Resume::default() });
        let (sig, copies) = self.bind_params(params);
        let mut prologue = Vec::new();
        for (local, pname, ty) in copies {
            self.hoist_local(&local, &ty);
            prologue.push(format!("{local} = {pname};"));
        }
        let mut lines = Vec::new();
        if !prologue.is_empty() {
            lines.push(format!("if rt_site == 0u {{\n{}}}", indent(&prologue.join("\n"))));
        }
        let mut stmts: Vec<Stmt> = body.stmts.clone();
        let mut tail = None;
        if !matches!(self.ret, Ty::Unit)
            && let Some(Stmt::Expr(_, None)) = stmts.last()
        {
            let Some(Stmt::Expr(mut e, None)) = stmts.pop() else { unreachable!("matched above") };
            // A returned block with a trace (`{ rt_trace(..); prd.x }`):
            // its statements run as the function's last ones (nothing
            // follows them, so its scope ends where the function's does).
            while let Expr::Block(b) = &e
                && b.label.is_none()
                && self.expr_sites(&e) > 0
                && let Some((Stmt::Expr(inner, None), rest)) = b.block.stmts.split_last()
            {
                stmts.extend(rest.iter().cloned());
                e = inner.clone();
            }
            tail = Some(e);
        }
        let tail = tail.as_ref();
        self.scopes.push(Vec::new());
        let r = self.resumable_stmts(&stmts);
        let body_lines = match r {
            Ok(mut v) => match tail {
                Some(e) if self.expr_sites(e) > 0 => Err(not_resumable(e.span(), "a trace in the returned value")),
                Some(e) => {
                    let ret = self.ret.clone();
                    let r = self.buffered(|l| {
                        let x = l.expr(e, Some(&ret))?;
                        let x = l.deref(x);
                        l.coerce(x, &ret, e.span())
                    });
                    r.map(|(mut pre, x)| {
                        pre.push(format!("return {};", x.code));
                        v.push(format!("if rt_site == 0u {{\n{}}}", indent(&pre.join("\n"))));
                        v
                    })
                }
                None => Ok(v),
            },
            Err(e) => Err(e),
        };
        self.scopes.pop();
        lines.extend(body_lines?);
        if !matches!(self.ret, Ty::Unit) {
            // Every path returned above; WGSL wants a return at the end.
            lines.push(format!("return{};", self.resume.as_ref().unwrap().dummy));
        }
        if let Some(e) = self.errors.0.first() {
            return Err(not_resumable(e.span, &e.message));
        }
        let r = self.resume.as_ref().unwrap();
        let mut head: Vec<String> = r.consts.clone();
        let mut decls = format!("var<private> {}rt_site: array<u32, RT_DEPTHS>;\n", r.prefix);
        let mut restore = Vec::new();
        head.push("var rt_site: u32 = 0u;".to_string());
        for (name, ty) in &r.locals {
            head.push(format!("var {name}: {ty};"));
            decls.push_str(&format!("var<private> {}{name}: array<{ty}, RT_DEPTHS>;\n", r.prefix));
            restore.push(format!("{name} = {}{name}[rt_d];", r.prefix));
        }
        restore.push(format!("rt_site = {}rt_site[rt_d];", r.prefix));
        head.push(format!("if rt_rs != 0u {{\n{}}}", indent(&restore.join("\n"))));
        head.extend(lines);
        let ret_text = if matches!(self.ret, Ty::Unit) { String::new() } else { format!(" -> {}", self.ret.wgsl()) };
        Ok(format!("{decls}fn {wgsl_name}({}){ret_text} {{\n{}}}\n", sig.join(", "), indent(&head.join("\n"))))
    }

    /// Replaces each site's frame-save line of the finished (marker-free)
    /// text with the saves of every local.
    pub fn fill_frame_saves(&self, text: &str) -> String {
        let Some(r) = &self.resume else { return text.to_string() };
        let (prefix, locals) = (&r.prefix, &r.locals);
        let mut out = String::with_capacity(text.len());
        for line in text.lines() {
            if line.trim() == SAVE_FRAME {
                let pad = &line[..line.len() - line.trim_start().len()];
                for (name, _) in locals {
                    out.push_str(&format!("{pad}{prefix}{name}[rt_d] = {name};\n"));
                }
            } else {
                out.push_str(line);
                out.push('\n');
            }
        }
        out
    }

    /// Declares `name` at the top of the function and in the frame.
    fn hoist_local(&mut self, name: &str, ty: &Ty) {
        let r = self.resume.as_mut().expect("resumable lowering");
        r.locals.push((name.to_string(), ty.wgsl()));
    }

    /// Whether `let`s and `const`s of the statement being lowered go to the
    /// top of the function.
    pub(super) fn hoisting(&self) -> bool {
        self.hoist && self.resume.is_some()
    }

    pub(super) fn hoist_const(&mut self, line: String) {
        self.resume.as_mut().expect("resumable lowering").consts.push(line);
    }

    /// A `let` at the level of a block with a trace: declared at the top,
    /// assigned here.
    pub(super) fn hoisted_let(&mut self, wname: &str, ty: &Ty, init: Option<&Val>) {
        self.hoist_local(wname, ty);
        if let Some(v) = init {
            self.emit(format!("{wname} = {};", v.code));
        }
    }

    /// The resumable form of a trace call (`rt_trace_<P>(...)` in the plain
    /// form): `[object, ray, flags, mask]` and `ptr`, the payload's pointer
    /// expression.
    pub(super) fn trace_site(&mut self, mangled: &str, args: [&str; 4], ptr: &str, span: Span) -> Result<()> {
        let [obj, ray, flags, mask] = args;
        let r = self.resume.as_mut().expect("resumable lowering");
        if !r.expect_site {
            return Err(not_resumable(span, "this trace is not a statement of its own"));
        }
        r.expect_site = false;
        // `ptr` is what `mut_ref_arg` gave: `&local`, a pointer parameter,
        // or `&tmp` for a field (which has a writeback).
        let clean = text::strip(ptr);
        let payload = match clean.strip_prefix('&') {
            Some(name) if name.chars().all(|c| c.is_alphanumeric() || c == '_') => name.to_string(),
            None if clean.chars().all(|c| c.is_alphanumeric() || c == '_') => format!("(*{clean})"),
            _ => return Err(not_resumable(span, "the payload is not a local or the program's payload")),
        };
        if !self.writebacks.is_empty() {
            return Err(not_resumable(span, "the payload is a field"));
        }
        r.sites += 1;
        let site = r.sites;
        r.resume_lines = Some(format!(
            "if rt_site == {site}u {{\n    {payload} = rt_result_{mangled}();\n    rt_site = 0u;\n    rt_rs = 0u;\n}}"
        ));
        let suspend = self.suspend(site);
        let line = self.mark(span, &format!("rt_request_{mangled}({obj}, {ray}, {payload}, {flags}, {mask});"));
        self.emit(line);
        self.emit(suspend);
        Ok(())
    }

    /// Saves the frame with `site` and returns to the kernel.
    fn suspend(&self, site: u32) -> String {
        let r = self.resume.as_ref().expect("resumable lowering");
        format!("{SAVE_FRAME}\n{}rt_site[rt_d] = {site}u;\nrt_rs = 1u;\nreturn{};", r.prefix, r.dummy)
    }

    /// The resumable form of a call of a helper that traces: `codes` are
    /// the arguments, whose statements were emitted from `at` on. Returns
    /// the call's value.
    pub(super) fn helper_site(
        &mut self,
        sig: &HelperSig,
        mut codes: Vec<String>,
        at: usize,
        span: Span,
    ) -> Result<Val> {
        if !sig.resumable {
            return Err(not_resumable(span, &format!("`{}` has no resumable form", sig.name)));
        }
        let r = self.resume.as_mut().expect("resumable lowering");
        if !r.expect_site {
            return Err(not_resumable(span, &format!("the call of `{}` is not a statement of its own", sig.name)));
        }
        r.expect_site = false;
        if !self.writebacks.is_empty() {
            return Err(not_resumable(span, "a field passed as `&mut` to a helper that traces"));
        }
        r.sites += 1;
        let site = r.sites;
        // Arguments are evaluated once, into frame locals: resuming passes
        // the same values.
        let mut pre = self.blocks.last_mut().unwrap().split_off(at);
        for (code, ty) in codes.iter_mut().zip(&sig.params) {
            if matches!(ty, Ty::Ref(..)) {
                continue;
            }
            let a = self.fresh("arg");
            self.hoist_local(&a, ty);
            pre.push(format!("{a} = {code};"));
            *code = a;
        }
        if !pre.is_empty() {
            self.emit(format!("if rt_site == 0u {{\n{}}}", indent(&pre.join("\n"))));
        }
        let call = format!("{}_rs({})", sig.wgsl_name, codes.join(", "));
        let value = if matches!(sig.ret, Ty::Unit) {
            let line = self.mark(span, &format!("{call};"));
            self.emit(line);
            Val::new("", Ty::Unit)
        } else {
            let t = self.tmp();
            let line = self.mark(span, &format!("let {t} = {call};"));
            self.emit(line);
            Val::new(t, sig.ret.clone())
        };
        let suspend = self.suspend(site);
        self.emit(format!("if rt_rs != 0u {{\n{}}}", indent(&suspend)));
        self.emit("rt_site = 0u;".to_string());
        Ok(value)
    }

    fn sites_so_far(&self) -> u32 {
        self.resume.as_ref().map_or(0, |r| r.sites)
    }

    /// Lowers `f` into a fresh buffer; returns its lines.
    fn buffered<T>(&mut self, f: impl FnOnce(&mut Self) -> Result<T>) -> Result<(Vec<String>, T)> {
        self.blocks.push(Block::default());
        let r = f(self);
        let lines = self.blocks.pop().unwrap().lines;
        r.map(|v| (lines, v))
    }

    /// The statements of a block containing a trace, in a new scope.
    fn resumable_block(&mut self, stmts: &[Stmt]) -> Result<Vec<String>> {
        self.scopes.push(Vec::new());
        let r = self.resumable_stmts(stmts);
        self.scopes.pop();
        r
    }

    fn resumable_stmts(&mut self, stmts: &[Stmt]) -> Result<Vec<String>> {
        let mut out = Vec::new();
        let mut run: Vec<String> = Vec::new();
        let flush = |run: &mut Vec<String>, out: &mut Vec<String>| {
            if !run.is_empty() {
                out.push(format!("if rt_site == 0u {{\n{}}}", indent(&run.join("\n"))));
                run.clear();
            }
        };
        let mut expanded = Vec::with_capacity(stmts.len());
        for s in stmts {
            self.hoist_helper_calls(s, &mut expanded);
        }
        for s in &expanded {
            let n = self.stmt_sites(s);
            if n == 0 {
                let saved = std::mem::replace(&mut self.hoist, true);
                let r = self.buffered(|l| l.stmt(s));
                self.hoist = saved;
                let (lines, ()) = r?;
                run.extend(lines);
                continue;
            }
            flush(&mut run, &mut out);
            let lo = self.sites_so_far() + 1;
            let lines = self.resumable_stmt(s)?;
            let hi = self.sites_so_far();
            if hi + 1 != lo + n {
                return Err(not_resumable(s.span(), "a trace the resumable form does not reach"));
            }
            out.extend(lines);
        }
        flush(&mut run, &mut out);
        Ok(out)
    }

    /// Pushes `s` with each call of a helper that traces inside a larger
    /// expression (or an `if` condition) taken out first, into
    /// `let rt_call_<k> = helper(..);` before it: a statement of its own,
    /// which is a site. Like the compiler's other statements hoisted out of
    /// expressions, the call then runs before the operands left of it,
    /// which can only matter if those have effects; calls of helpers that
    /// take `&mut` stay where they are (and make the form fail).
    fn hoist_helper_calls(&mut self, s: &Stmt, out: &mut Vec<Stmt>) {
        struct Hoist<'a> {
            m: &'a ModuleCtx,
            tracing: &'a HashSet<String>,
            taken: Vec<Stmt>,
            next: usize,
        }
        impl syn::visit_mut::VisitMut for Hoist<'_> {
            fn visit_expr_mut(&mut self, e: &mut Expr) {
                match e {
                    // Not into nested statements: their blocks hoist their own.
                    Expr::Block(_)
                    | Expr::If(_)
                    | Expr::Loop(_)
                    | Expr::While(_)
                    | Expr::ForLoop(_)
                    | Expr::Match(_)
                    | Expr::Closure(_) => return,
                    _ => {}
                }
                syn::visit_mut::visit_expr_mut(self, e);
                let Some(c) = tracing_call(e, self.tracing) else { return };
                let name = match &*c.func {
                    Expr::Path(p) => p.path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default(),
                    _ => return,
                };
                if self.m.helpers.get(&name).is_none_or(|h| h.params.iter().any(|p| matches!(p, Ty::Ref(true, _)))) {
                    return;
                }
                let var = syn::Ident::new(&format!("rt_call_{}", self.next), c.span());
                self.next += 1;
                let call = e.clone();
                self.taken.push(syn::parse_quote_spanned!(call.span()=> let #var = #call;));
                *e = syn::parse_quote_spanned!(call.span()=> #var);
            }
        }
        let tracing = &self.resume.as_ref().expect("resumable lowering").tracing;
        if is_helper_site(s, tracing) || self.stmt_sites(s) == 0 {
            out.push(s.clone());
            return;
        }
        let mut h = Hoist { m: self.m, tracing, taken: Vec::new(), next: self.hoisted_calls };
        let mut s = s.clone();
        match &mut s {
            Stmt::Local(l) => {
                if let Some(init) = &mut l.init {
                    syn::visit_mut::VisitMut::visit_expr_mut(&mut h, &mut init.expr);
                }
            }
            Stmt::Expr(Expr::If(i), _) => syn::visit_mut::VisitMut::visit_expr_mut(&mut h, &mut i.cond),
            Stmt::Expr(e, _) => syn::visit_mut::VisitMut::visit_expr_mut(&mut h, e),
            _ => {}
        }
        let (taken, next) = (h.taken, h.next);
        self.hoisted_calls = next;
        out.extend(taken);
        out.push(s);
    }

    /// A statement containing sites.
    fn resumable_stmt(&mut self, s: &Stmt) -> Result<Vec<String>> {
        let lo = self.sites_so_far() + 1;
        let hi = self.sites_so_far() + self.stmt_sites(s);
        let guard = |lines: Vec<String>| -> Vec<String> {
            let cond = if lo == hi {
                format!("rt_site == 0u || rt_site == {lo}u")
            } else {
                format!("rt_site == 0u || (rt_site >= {lo}u && rt_site <= {hi}u)")
            };
            vec![format!("if {cond} {{\n{}}}", indent(&lines.join("\n")))]
        };
        if is_helper_site(s, &self.resume.as_ref().unwrap().tracing) {
            if hi != lo {
                return Err(not_resumable(s.span(), "several sites in one statement"));
            }
            self.resume.as_mut().unwrap().expect_site = true;
            let saved = std::mem::replace(&mut self.hoist, true);
            let r = self.buffered(|l| l.stmt(s));
            self.hoist = saved;
            let expected = std::mem::replace(&mut self.resume.as_mut().unwrap().expect_site, false);
            let (lines, ()) = r?;
            if expected {
                return Err(not_resumable(s.span(), "a helper call the resumable form does not reach"));
            }
            return Ok(guard(lines));
        }
        let e = match s {
            Stmt::Expr(e, _) => e,
            other => return Err(not_resumable(other.span(), "a site inside a `let` or a macro")),
        };
        match e {
            Expr::Paren(p) => self.resumable_stmt(&Stmt::Expr((*p.expr).clone(), None)),
            Expr::Call(_) => {
                self.resume.as_mut().unwrap().expect_site = true;
                let saved = std::mem::replace(&mut self.hoist, false);
                let r = self.buffered(|l| l.expr(e, None));
                self.hoist = saved;
                let r = r.and_then(|(lines, v)| {
                    if self.resume.as_ref().unwrap().expect_site || !matches!(v.ty, Ty::Unit) {
                        Err(not_resumable(e.span(), "a trace inside another call"))
                    } else {
                        Ok(lines)
                    }
                });
                self.resume.as_mut().unwrap().expect_site = false;
                let lines = r?;
                let resume = self.resume.as_mut().unwrap().resume_lines.take().unwrap_or_default();
                Ok(vec![format!("if rt_site == 0u {{\n{}}}", indent(&lines.join("\n"))), resume])
            }
            Expr::If(i) => {
                if self.expr_sites(&i.cond) > 0 {
                    return Err(not_resumable(i.cond.span(), "a trace in a condition"));
                }
                let (pre, cond) = self.buffered(|l| l.cond(&i.cond))?;
                let c = self.fresh("cond");
                self.hoist_local(&c, &BOOL);
                let mut run = pre;
                run.push(format!("{c} = {cond};"));
                let then = self.resumable_block(&i.then_branch.stmts)?;
                let mut body = format!("if {c} {{\n{}}}", indent(&then.join("\n")));
                match &i.else_branch {
                    None => {}
                    Some((_, e)) => {
                        let lines = match &**e {
                            Expr::Block(b) if b.label.is_none() => self.resumable_block(&b.block.stmts)?,
                            other => {
                                self.scopes.push(Vec::new());
                                let r = self.resumable_stmts(&[Stmt::Expr(other.clone(), None)]);
                                self.scopes.pop();
                                r?
                            }
                        };
                        body.push_str(&format!(" else {{\n{}}}", indent(&lines.join("\n"))));
                    }
                }
                let mut out = vec![format!("if rt_site == 0u {{\n{}}}", indent(&run.join("\n")))];
                out.extend(guard(vec![body]));
                Ok(out)
            }
            Expr::Block(b) if b.label.is_none() => {
                let lines = self.resumable_block(&b.block.stmts)?;
                Ok(guard(lines))
            }
            Expr::Loop(l) if l.label.is_none() => {
                let body = self.resumable_loop_body(&l.body.stmts, None)?;
                Ok(guard(vec![format!("loop {{\n{}}}", indent(&body.join("\n")))]))
            }
            Expr::While(w) if w.label.is_none() && !matches!(&*w.cond, Expr::Let(_)) => {
                if self.expr_sites(&w.cond) > 0 {
                    return Err(not_resumable(w.cond.span(), "a trace in a condition"));
                }
                let (mut pre, cond) = self.buffered(|l| l.cond(&w.cond))?;
                pre.push(format!("if !({cond}) {{\n    break;\n}}"));
                let head = format!("if rt_site == 0u {{\n{}}}", indent(&pre.join("\n")));
                let body = self.resumable_loop_body(&w.body.stmts, None)?;
                let mut all = vec![head];
                all.extend(body);
                Ok(guard(vec![format!("loop {{\n{}}}", indent(&all.join("\n")))]))
            }
            Expr::ForLoop(f) if f.label.is_none() => self.resumable_for(f, guard),
            Expr::Match(m) => self.resumable_match(m, guard),
            other => Err(not_resumable(other.span(), "a trace in this kind of statement")),
        }
    }

    /// A `match` statement with traces in its arms: the scrutinee is kept in
    /// a frame local, so a resumed `switch` enters the arm that suspended.
    fn resumable_match(
        &mut self,
        m: &syn::ExprMatch,
        guard: impl Fn(Vec<String>) -> Vec<String>,
    ) -> Result<Vec<String>> {
        if self.expr_sites(&m.expr) > 0 {
            return Err(not_resumable(m.expr.span(), "a trace in a `match` scrutinee"));
        }
        let (pre, scrut) = self.buffered(|l| {
            let v = l.expr(&m.expr, None)?;
            Ok(l.deref(v))
        })?;
        let sty = self.resolved(&scrut.ty);
        if !self.is_int(&sty) {
            return Err(not_resumable(m.expr.span(), "a `match` on a value that is not an integer"));
        }
        let sel = self.fresh("sel");
        self.hoist_local(&sel, &sty);
        let mut run = pre;
        run.push(format!("{sel} = {};", scrut.code));
        // A `break` in an arm leaves the enclosing loop in Rust, the
        // `switch` in WGSL: it sets this flag, tested after the `switch`.
        let in_loop = self.loop_depth > 0;
        if in_loop {
            let flag = self.fresh("brk");
            self.breaks.push(Some((flag, false)));
        }
        let arms = self.resumable_arms(m, &sty, &sel);
        let flag = match in_loop.then(|| self.breaks.pop()) {
            Some(Some(Some((flag, true)))) => Some(flag),
            _ => None,
        };
        let (mut cases, has_default) = arms?;
        if !has_default {
            // WGSL needs a default; Rust's exhaustiveness check makes it
            // unreachable.
            cases.push("default: {}".to_string());
        }
        let mut body = vec![format!("switch {sel} {{\n{}}}", indent(&cases.join("\n")))];
        if let Some(f) = &flag {
            self.hoist_local(f, &BOOL);
            run.push(format!("{f} = false;"));
            body.push(format!("if {f} {{\n    break;\n}}"));
        }
        let mut out = vec![format!("if rt_site == 0u {{\n{}}}", indent(&run.join("\n")))];
        out.extend(guard(body));
        Ok(out)
    }

    /// The cases of [`Self::resumable_match`]'s `switch`, arms bound to the
    /// scrutinee's local `sel`.
    /// The `switch` cases of a `match`'s arms, and whether one is the
    /// default.
    fn resumable_arms(&mut self, m: &syn::ExprMatch, sty: &Ty, sel: &str) -> Result<(Vec<String>, bool)> {
        let mut cases = Vec::new();
        let mut has_default = false;
        for arm in &m.arms {
            if let Some((if_token, _)) = &arm.guard {
                return Err(not_resumable(if_token.span, "a match guard"));
            }
            let mut labels = Vec::new();
            let mut binding = None;
            self.match_pattern(&arm.pat, sty, &mut labels, &mut binding)?;
            let stmts = match &*arm.body {
                Expr::Block(b) if b.label.is_none() => b.block.stmts.clone(),
                other => vec![Stmt::Expr(other.clone(), None)],
            };
            self.scopes.push(Vec::new());
            if let Some(b) = &binding {
                self.bind(b, Local { wgsl: sel.to_string(), ty: sty.clone(), var: false });
            }
            let r = self.resumable_block(&stmts);
            self.scopes.pop();
            let lines = r?;
            has_default |= labels.is_empty();
            let head = if labels.is_empty() { "default".to_string() } else { format!("case {}", labels.join(", ")) };
            cases.push(format!("{head}: {{\n{}}}", indent(&lines.join("\n"))));
        }
        Ok((cases, has_default))
    }

    /// A loop body with traces; `bind` binds the loop variable.
    fn resumable_loop_body(&mut self, stmts: &[Stmt], bind: Option<(&str, Local)>) -> Result<Vec<String>> {
        self.loop_depth += 1;
        self.breaks.push(None);
        self.scopes.push(Vec::new());
        if let Some((rust, local)) = bind {
            self.bind(rust, local);
        }
        let r = self.resumable_block(stmts);
        self.scopes.pop();
        self.breaks.pop();
        self.loop_depth -= 1;
        r
    }

    fn resumable_for(
        &mut self,
        f: &syn::ExprForLoop,
        guard: impl Fn(Vec<String>) -> Vec<String>,
    ) -> Result<Vec<String>> {
        let name = match &*f.pat {
            syn::Pat::Ident(pi) if pi.by_ref.is_none() && pi.subpat.is_none() => pi.ident.to_string(),
            syn::Pat::Wild(_) => "_".to_string(),
            other => return Err(not_resumable(other.span(), "this loop pattern")),
        };
        let range = match &*f.expr {
            Expr::Range(r) => r,
            Expr::Paren(p) => match &*p.expr {
                Expr::Range(r) => r,
                other => return Err(not_resumable(other.span(), "this loop")),
            },
            other => return Err(not_resumable(other.span(), "this loop")),
        };
        let (Some(start), Some(end)) = (&range.start, &range.end) else {
            return Err(not_resumable(range.span(), "an open range"));
        };
        if self.expr_sites(start) + self.expr_sites(end) > 0 {
            return Err(not_resumable(range.span(), "a trace in a range bound"));
        }
        let (pre, (s, e)) = self.buffered(|l| {
            let s = l.expr(start, None)?;
            let s = l.deref(s);
            let e = l.expr(end, Some(&s.ty))?;
            let e = l.deref(e);
            Ok((s, e))
        })?;
        if !self.is_int(&s.ty) || !self.unify(&s.ty, &e.ty) {
            return Err(not_resumable(range.span(), "a range without integer bounds of one type"));
        }
        let ty = self.resolved(&s.ty);
        let var = self.fresh(if name == "_" { "i" } else { &name });
        let last = self.fresh("end");
        self.hoist_local(&var, &ty);
        self.hoist_local(&last, &ty);
        let mut run = pre;
        run.push(format!("{var} = {};", s.code));
        run.push(format!("{last} = {};", e.code));
        let closed = matches!(range.limits, syn::RangeLimits::Closed(_));
        let cmp = if closed { "<=" } else { "<" };
        let head = format!("if rt_site == 0u {{\n    if !({var} {cmp} {last}) {{\n        break;\n    }}\n}}");
        let local = Local { wgsl: var.clone(), ty: ty.clone(), var: false };
        let body = self.resumable_loop_body(&f.body.stmts, Some((&name, local)))?;
        // `a..=b` stops after `b` without computing `b + 1` (which wraps at
        // the type's maximum).
        let continuing = if closed {
            let stop = self.fresh("last");
            format!("continuing {{\n    let {stop} = {var} == {last};\n    {var}++;\n    break if {stop};\n}}")
        } else {
            format!("continuing {{\n    {var}++;\n}}")
        };
        let mut all = vec![head];
        all.extend(body);
        all.push(continuing);
        let mut out = vec![format!("if rt_site == 0u {{\n{}}}", indent(&run.join("\n")))];
        out.extend(guard(vec![format!("loop {{\n{}}}", indent(&all.join("\n")))]));
        Ok(out)
    }
}
