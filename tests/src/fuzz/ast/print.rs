//! The AST printed as the Rust source of an `#[rt_program(ray_generation)]`
//! with its `#[rt_struct]`s, `#[rt_impl]`s and `#[rt_function]`s.

use super::*;
use std::fmt::Write;

/// The lane-wise variant's items (see [`Program::lanes_source`]).
const LANES_ITEMS: &str = "
#[rt_payload]
pub struct FuzzHit {
    pub acc: u32,
}

#[rt_function]
pub fn fuzz_ray(lane: u32, acc: u32, k: u32) -> Ray {
    let h = (lane * 2654435761u32) ^ (acc * 40503u32) ^ (k * 977u32);
    let x = (h % 61u32) as f32 / 30.0 - 1.0;
    let y = ((h / 61u32) % 59u32) as f32 / 29.0 - 1.0;
    Ray::new(vec3(0.0, 0.0, 3.0), vec3(x, y, -1.5).normalize(), 0, 1e-3, 1e9)
}

#[rt_program(closest_hit)]
pub fn fuzz_hit(prd: &mut FuzzHit) {
    prd.acc = prd.acc * 31u32 + primitive_index() + 1u32 + (t_hit() * 64.0) as u32 * 4099u32;
}

#[rt_program(miss)]
pub fn fuzz_miss(prd: &mut FuzzHit) {
    prd.acc = prd.acc * 31u32 + 7u32;
}
";

impl Program {
    /// Words of a value of type `t` in the runtime's packed layout.
    pub fn words(&self, t: &Ty) -> u32 {
        match t {
            Ty::S(_) => 1,
            Ty::V(n, _) => *n as u32,
            Ty::Struct(i) => self.structs[*i].fields.iter().map(|(_, f)| self.words(f)).sum(),
            Ty::Arr(e, n) => self.words(e) * n,
        }
    }

    /// The program as a Rust source file.
    pub fn source(&self) -> String {
        self.source_with(false)
    }

    /// The source of the lane-wise variant (`generate::lanes`), which the
    /// CPU backend runs: each input read from a buffer of one value per
    /// launch index (`#[var] fuzz_in_<name>: RwBuffer<T>`, a `bool` as a
    /// `u32`), so that every launch index of one launch has inputs of its
    /// own, as the wgpu harness gives them; and the items its traces use:
    /// the payload `FuzzHit` (a hash of what its rays hit), `fuzz_ray`
    /// (a ray from the launch index, the hash and the trace's number), a
    /// closest-hit and a miss program, and the variables `fuzz_top` (the
    /// scene) and `fuzz_rays` (each launch index's hash after each trace).
    pub fn lanes_source(&self) -> String {
        self.source_with(true)
    }

    fn source_with(&self, inputs_in_buffers: bool) -> String {
        let mut s = String::from("use rt_std::prelude::*;\n");
        s.push_str("\n#[rt_enum]\npub enum FuzzKind {\n    Alpha,\n    Beta = 5,\n    Gamma,\n}\n");
        s.push_str(
            "\n#[rt_function]\npub fn fuzz_pick<T: Copy>(second: bool, a: T, b: T) -> T {\n    if second { b } else { a }\n}\n",
        );
        // Given a closure: inlined where it is called, its local kept
        // apart from the closure's captures.
        s.push_str(
            "\n#[rt_function]\npub fn fuzz_apply<T: Copy, F: Fn(T) -> T>(f: F, a: T) -> T {\n    let fz_r = f(a);\n    fz_r\n}\n",
        );
        let forms: Vec<(usize, MethodForm)> =
            self.helpers.iter().filter_map(|h| h.method.map(|m| (m.of, m.form))).collect();
        let ops: Vec<&str> = forms
            .iter()
            .filter_map(|(_, f)| match f {
                MethodForm::Operator(op) => Some(op.rust().trim_end_matches("<f32>")),
                _ => None,
            })
            .collect();
        if !ops.is_empty() {
            let mut ops = ops;
            ops.sort();
            ops.dedup();
            let _ = writeln!(s, "use core::ops::{{{}}};", ops.join(", "));
        }
        self.trait_declaration(&mut s);
        for (i, d) in self.structs.iter().enumerate() {
            let mut impls: Vec<String> = Vec::new();
            if forms.contains(&(i, MethodForm::Inherent)) {
                impls.push("impl".into());
            }
            if forms.contains(&(i, MethodForm::Trait)) {
                impls.push("impl FuzzOps".into());
            }
            for (of, f) in &forms {
                if let (true, MethodForm::Operator(op)) = (*of == i, f) {
                    impls.push(format!("impl {}", op.rust()));
                }
            }
            if impls.is_empty() {
                s.push_str("\n#[rt_struct]\npub struct ");
            } else {
                let _ = write!(s, "\n#[rt_struct({})]\npub struct ", impls.join(", "));
            }
            s.push_str(&d.name);
            s.push_str(" {\n");
            for (n, t) in &d.fields {
                let _ = writeln!(s, "    pub {n}: {},", t.rust(self));
            }
            s.push_str("}\n");
        }
        for h in self.helpers.iter().filter(|h| h.method.is_none()) {
            let ret = h.ret.as_ref().map(|t| format!(" -> {}", t.rust(self))).unwrap_or_default();
            let _ = write!(s, "\n#[rt_function]\npub fn {}({}){ret} ", h.name, self.params(h).join(", "));
            self.block(&mut s, &h.body, 0);
            s.push('\n');
        }
        self.impl_blocks(&mut s);
        let mut params: Vec<String> = Vec::new();
        let mut reads = String::new();
        if inputs_in_buffers {
            s.push_str(LANES_ITEMS);
            params.push("#[var] fuzz_top: Object".into());
            params.push("#[var] mut fuzz_rays: RwBuffer<u32>".into());
            reads.push_str("    let mut fuzz_prd = FuzzHit { acc: 0u32 };\n");
        }
        for (n, t) in &self.inputs {
            if !inputs_in_buffers {
                params.push(format!("#[var] {n}: {}", t.rust(self)));
                continue;
            }
            let (elem, read) = match t {
                Ty::S(Scalar::Bool) => ("u32".to_string(), " != 0"),
                _ => (t.rust(self), ""),
            };
            params.push(format!("#[var] fuzz_in_{n}: RwBuffer<{elem}>"));
            let _ = writeln!(reads, "    let {n} = fuzz_in_{n}[launch_index().x]{read};");
        }
        params.extend(self.outputs.iter().map(|(n, t)| format!("#[var] mut {n}: RwBuffer<{}>", t.rust(self))));
        let _ =
            write!(s, "\n#[rt_program(ray_generation)]\npub fn {}(\n    {},\n) ", self.name, params.join(",\n    "));
        let mut body = String::new();
        self.block(&mut body, &self.body, 0);
        s.push_str("{\n");
        s.push_str(&reads);
        s.push_str(&body[2..]);
        s.push('\n');
        s
    }

    pub(super) fn block(&self, s: &mut String, b: &Block, depth: usize) {
        s.push_str("{\n");
        for st in &b.stmts {
            self.stmt(s, st, depth + 1);
        }
        if let Some(t) = &b.tail {
            indent(s, depth + 1);
            s.push_str(&self.expr(t));
            s.push('\n');
        }
        indent(s, depth);
        s.push('}');
    }

    fn stmt(&self, s: &mut String, st: &Stmt, depth: usize) {
        indent(s, depth);
        match st {
            Stmt::Let { name, mutable, ty, annotate, init } => {
                let m = if *mutable { "mut " } else { "" };
                let t = if *annotate { format!(": {}", ty.rust(self)) } else { String::new() };
                let _ = writeln!(s, "let {m}{name}{t} = {};", self.expr(init));
            }
            Stmt::Assign(p, op, v) => {
                let sym = op.map(|o| format!("{}=", o.symbol())).unwrap_or_else(|| "=".into());
                let _ = writeln!(s, "{} {sym} {};", self.place(p), self.expr(v));
            }
            Stmt::If(c, t, e) => {
                self.if_chain(s, c, t, e.as_ref(), depth);
                s.push('\n');
            }
            Stmt::For { var, ty, start, end, inclusive, body } => {
                let range = if *inclusive { "..=" } else { ".." };
                let _ = write!(s, "for {var} in {start}{}{range}{} ", ty.rust(), self.expr(end));
                self.block(s, body, depth);
                s.push('\n');
            }
            Stmt::Each { var, index, array, by_ref, rev, body } => {
                let a = self.expr(array);
                let rev = if *rev { ".rev()" } else { "" };
                let _ = match index {
                    Some((raw, _)) => write!(s, "for ({raw}, &{var}) in ({a}).iter().enumerate(){rev} "),
                    None if *by_ref => write!(s, "for &{var} in ({a}).iter(){rev} "),
                    None if rev.is_empty() => write!(s, "for {var} in {a} "),
                    None => write!(s, "for {var} in ({a}).into_iter(){rev} "),
                };
                self.block(s, body, depth);
                s.push('\n');
            }
            Stmt::While(c, body) => {
                let _ = write!(s, "while {} ", self.expr(c));
                self.block(s, body, depth);
                s.push('\n');
            }
            Stmt::Loop(body) => {
                s.push_str("loop ");
                self.block(s, body, depth);
                s.push('\n');
            }
            Stmt::Labelled(n, inner) => {
                let mut text = String::new();
                self.stmt(&mut text, inner, depth);
                let _ = write!(s, "'fz_l{n}: {}", text.trim_start());
            }
            Stmt::BreakTo(n) => {
                let _ = writeln!(s, "break 'fz_l{n};");
            }
            Stmt::Break => s.push_str("break;\n"),
            Stmt::Continue => s.push_str("continue;\n"),
            Stmt::Match(e, arms) => {
                self.match_text(s, e, arms, depth);
                s.push('\n');
            }
            Stmt::Store { buf, index, value, form } => {
                let b = &self.outputs[*buf].0;
                let (i, v) = (self.expr(index), self.expr(value));
                let _ = match form {
                    StoreForm::Method => writeln!(s, "{b}.store({i}, {v});"),
                    StoreForm::Index => writeln!(s, "{b}[{i}] = {v};"),
                    StoreForm::Compound(op) => writeln!(s, "{b}[{i}] {}= {v};", op.symbol()),
                };
            }
            Stmt::Expr(e) => {
                let _ = writeln!(s, "{};", self.expr(e));
            }
            Stmt::Return(e) => {
                let _ = match e {
                    Some(e) => writeln!(s, "return {};", self.expr(e)),
                    None => writeln!(s, "return;"),
                };
            }
            Stmt::Trace(k) => {
                // (The variant's items: see `source_with`.)
                let _ =
                    writeln!(s, "rt_trace(fuzz_top, fuzz_ray(launch_index().x, fuzz_prd.acc, {k}u32), &mut fuzz_prd);");
                indent(s, depth);
                let _ = writeln!(s, "fuzz_rays[launch_index().x] = fuzz_prd.acc;");
            }
        }
    }

    fn if_chain(&self, s: &mut String, c: &Expr, t: &Block, e: Option<&Block>, depth: usize) {
        let _ = write!(s, "if {} ", self.expr(c));
        self.block(s, t, depth);
        if let Some(e) = e {
            s.push_str(" else ");
            // `else if` for an else block that is a single `if` statement.
            if let ([Stmt::If(c2, t2, e2)], None) = (e.stmts.as_slice(), &e.tail) {
                self.if_chain(s, c2, t2, e2.as_ref(), depth);
            } else {
                self.block(s, e, depth);
            }
        }
    }

    fn match_text(&self, s: &mut String, e: &Expr, arms: &[Arm], depth: usize) {
        let _ = writeln!(s, "match {} {{", self.expr(e));
        for a in arms {
            indent(s, depth + 1);
            let pat = if a.pats.is_empty() {
                a.bind.clone().unwrap_or_else(|| "_".into())
            } else {
                a.pats.iter().map(|p| lit_text(&Lit { v: *p, suffix: false })).collect::<Vec<_>>().join(" | ")
            };
            let _ = write!(s, "{pat} => ");
            self.block(s, &a.body, depth + 1);
            s.push('\n');
        }
        indent(s, depth);
        s.push('}');
    }

    fn place(&self, p: &Place) -> String {
        match p {
            Place::Var(n) => n.clone(),
            Place::Deref(n) => format!("*{n}"),
            Place::Field(b, f, _) => match &**b {
                Place::Deref(n) => format!("(*{n}).{f}"),
                _ => format!("{}.{f}", self.place(b)),
            },
            Place::Index(b, i) => format!("{}[{}]", self.place(b), index_text(self, i)),
        }
    }

    /// An expression as Rust text. Operators, casts and `if`/`match`
    /// expressions are parenthesised, so precedence never matters.
    pub fn expr(&self, e: &Expr) -> String {
        match e {
            Expr::Lit(l) => lit_text(l),
            Expr::Var(n) => n.clone(),
            Expr::Deref(n) => format!("(*{n})"),
            Expr::LaunchX => "launch_index().x".into(),
            Expr::Field(b, f, _) => format!("{}.{f}", self.receiver(b)),
            Expr::Index(b, i) => format!("{}[{}]", self.receiver(b), index_text(self, i)),
            Expr::Unary(op, x) => {
                let sym = if *op == UnOp::Neg { "-" } else { "!" };
                format!("({sym}{})", self.receiver(x))
            }
            Expr::Bin(op, a, b) => format!("({} {} {})", self.expr(a), op.symbol(), self.expr(b)),
            Expr::Cast(x, s) => format!("({} as {})", self.receiver(x), s.rust()),
            Expr::Method(r, m, args) => format!("{}.{m}({})", self.receiver(r), self.args(args)),
            Expr::Path(t, f, args) => format!("{t}::{f}({})", self.args(args)),
            Expr::Free(f, args) => format!("{f}({})", self.args(args)),
            Expr::Const(t, n) if t.is_empty() => n.to_string(),
            Expr::Const(t, n) => format!("{t}::{n}"),
            Expr::Call(h, args) => {
                let a: Vec<String> = args
                    .iter()
                    .map(|a| match a {
                        Arg::Val(e) => self.expr(e),
                        Arg::MutRef(n) if self.is_ref_param(n) => n.clone(),
                        Arg::MutRef(n) => format!("&mut {n}"),
                    })
                    .collect();
                let Some(helper) = self.helpers.get(*h) else { return format!("missing_helper({})", a.join(", ")) };
                match helper.method {
                    None => format!("{}({})", helper.name, a.join(", ")),
                    Some(Method { form: MethodForm::Operator(op), ufcs, .. }) => match &args[0] {
                        Arg::Val(e) if ufcs => format!("{}.{}({})", self.receiver(e), op.method(), a[1]),
                        _ => format!("({} {} {})", a[0], op.token(), a[1]),
                    },
                    Some(m) => {
                        let ty = &self.structs[m.of].name;
                        let (recv, rest) = (a[0].clone(), &a[1..]);
                        if m.ufcs {
                            let recv = match (m.receiver, &args[0]) {
                                (Receiver::Ref, Arg::Val(e)) => format!("&{}", self.receiver(e)),
                                _ => recv,
                            };
                            let all: Vec<String> = std::iter::once(recv).chain(rest.iter().cloned()).collect();
                            format!("{ty}::{}({})", helper.name, all.join(", "))
                        } else {
                            let recv = match &args[0] {
                                Arg::Val(e) => self.receiver(e),
                                Arg::MutRef(n) => n.clone(),
                            };
                            format!("{recv}.{}({})", helper.name, rest.join(", "))
                        }
                    }
                }
            }
            Expr::StructLit(i, fields) => {
                let d = &self.structs[*i];
                let f: Vec<String> =
                    fields.iter().map(|(k, v)| format!("{}: {}", d.fields[*k].0, self.expr(v))).collect();
                format!("{} {{ {} }}", d.name, f.join(", "))
            }
            Expr::ArrayLit(xs) => format!("[{}]", self.args(xs)),
            Expr::ArrayRepeat(x, n) => format!("[{}; {n}]", self.expr(x)),
            Expr::If(c, t, e) => {
                let mut s = String::from("(");
                self.if_chain(&mut s, c, t, Some(e), 1);
                s.push(')');
                s
            }
            Expr::Match(x, arms) => {
                let mut s = String::from("(");
                self.match_text(&mut s, x, arms, 1);
                s.push(')');
                s
            }
            Expr::BufLoad(b, i, method) => {
                let b = &self.outputs[*b].0;
                if *method { format!("{b}.load({})", self.expr(i)) } else { format!("{b}[{}]", self.expr(i)) }
            }
            Expr::TupleField(xs, k) => format!("({},).{k}", self.args(xs)),
            Expr::Pick(xs, k) => format!("fuzz_pick({}, {})", *k == 1, self.args(xs)),
            Expr::Sugar(sugar, xs) => self.sugar(sugar, xs),
            Expr::EnumRound(x) => format!(
                "(match (match ({}) % 3 {{ 0 => FuzzKind::Alpha, 1 => FuzzKind::Beta, _ => FuzzKind::Gamma }}) \
                 {{ FuzzKind::Alpha => 10u32, FuzzKind::Beta => FuzzKind::Beta as u32, FuzzKind::Gamma => 7u32 }})",
                self.expr(x)
            ),
        }
    }

    /// What [`Expr::Sugar`] prints (see [`Sugar`]).
    fn sugar(&self, sugar: &Sugar, xs: &[Expr]) -> String {
        match sugar {
            Sugar::Closure { op, ty, given, id } => {
                let closure = format!("|fz_a{id}: {}| (fz_a{id} {} {})", ty.rust(self), op.symbol(), self.expr(&xs[1]));
                let arg = self.expr(&xs[0]);
                if *given {
                    format!("fuzz_apply({closure}, {arg})")
                } else {
                    format!("{{ let fz_f{id} = {closure}; fz_f{id}({arg}) }}")
                }
            }
            Sugar::Option { form, id } => {
                let (c, v, f) = (self.expr(&xs[0]), self.expr(&xs[1]), self.expr(&xs[2]));
                let made = format!("(if {c} {{ Some({v}) }} else {{ None }})");
                match form {
                    0 => format!("{made}.unwrap_or({f})"),
                    1 => format!("(match {made} {{ Some(fz_o{id}) => fz_o{id}, None => {f} }})"),
                    2 => format!("(if let Some(fz_o{id}) = {made} {{ fz_o{id} }} else {{ {f} }})"),
                    _ => format!("Some({v}).filter(|_| {c}).unwrap_or_else(|| {f})"),
                }
            }
            Sugar::Fold { op, ty, rev, sum, id } => {
                let elems = format!("[{}].iter(){}", self.args(&xs[1..]), if *rev { ".rev()" } else { "" });
                if *sum {
                    format!("{elems}.sum::<{}>()", ty.rust(self))
                } else {
                    format!(
                        "{elems}.fold({}, |fz_acc{id}: {}, fz_v{id}| (fz_acc{id} {} *fz_v{id}))",
                        self.expr(&xs[0]),
                        ty.rust(self),
                        op.symbol()
                    )
                }
            }
        }
    }

    /// `&mut` parameters are named `state*` (see the generator), or are a
    /// method's `&mut self`.
    fn is_ref_param(&self, n: &str) -> bool {
        n.starts_with("state") || n == "self"
    }

    /// An expression in receiver position (`x.f()`, `x.y`, `x[i]`, `-x`):
    /// literals are suffixed and parenthesised, since `2.0.sqrt()` is
    /// ambiguous in Rust.
    fn receiver(&self, e: &Expr) -> String {
        match e {
            Expr::Lit(l) => format!("({})", lit_text(&Lit { v: l.v, suffix: true })),
            Expr::StructLit(..) => format!("({})", self.expr(e)),
            _ => self.expr(e),
        }
    }

    fn args(&self, xs: &[Expr]) -> String {
        xs.iter().map(|x| self.expr(x)).collect::<Vec<_>>().join(", ")
    }
}

fn index_text(p: &Program, i: &Expr) -> String {
    match i {
        Expr::Lit(Lit { v: LitV::U32(k), .. }) => k.to_string(),
        Expr::Lit(Lit { v: LitV::I32(k), .. }) => k.to_string(),
        _ => format!("{} as usize", p.receiver(i)),
    }
}

fn indent(s: &mut String, depth: usize) {
    for _ in 0..depth {
        s.push_str("    ");
    }
}

pub fn lit_text(l: &Lit) -> String {
    match l.v {
        LitV::Bool(b) => b.to_string(),
        LitV::I32(i) => {
            let t = if l.suffix { format!("{i}i32") } else { i.to_string() };
            if i < 0 { format!("({t})") } else { t }
        }
        LitV::U32(u) => {
            // Large values in hex, as hash constants are written.
            let t = if u > 0xffff && u % 7 == 0 { format!("{u:#x}") } else { u.to_string() };
            if l.suffix { format!("{t}u32") } else { t }
        }
        LitV::F32(f) => {
            let mut t = format!("{f:?}");
            if !t.contains(['.', 'e']) {
                t.push_str(".0");
            }
            if l.suffix {
                t.push_str("f32");
            }
            if f.is_sign_negative() { format!("({t})") } else { t }
        }
    }
}
