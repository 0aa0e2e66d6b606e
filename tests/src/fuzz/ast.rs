//! The generated programs: a small typed AST of the subset, printed as Rust
//! source (what the compiler lowers) and evaluated by [`super::interp`].
//!
//! The AST is typed by construction (the generator only builds well-typed
//! trees), so it carries just what printing and evaluation need: literals
//! know their type, casts their target, calls their callee.

use std::fmt::Write;

/// A scalar type of the subset.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Scalar {
    Bool,
    I32,
    U32,
    F32,
}

impl Scalar {
    pub fn rust(self) -> &'static str {
        match self {
            Scalar::Bool => "bool",
            Scalar::I32 => "i32",
            Scalar::U32 => "u32",
            Scalar::F32 => "f32",
        }
    }

    /// The prefix of glam's vector type names (`Vec3`, `IVec3`, `UVec3`).
    pub fn vec_prefix(self) -> &'static str {
        match self {
            Scalar::I32 => "I",
            Scalar::U32 => "U",
            _ => "",
        }
    }

    pub fn is_int(self) -> bool {
        matches!(self, Scalar::I32 | Scalar::U32)
    }
}

/// A type of the subset. Vectors have 2 to 4 `f32`, `i32` or `u32`
/// components; structs are the program's `#[rt_struct]`s by index; arrays
/// are locals only.
#[derive(Clone, PartialEq, Eq, Debug, Hash)]
pub enum Ty {
    S(Scalar),
    V(u8, Scalar),
    Struct(usize),
    Arr(Box<Ty>, u32),
}

pub const F32: Ty = Ty::S(Scalar::F32);
pub const I32: Ty = Ty::S(Scalar::I32);
pub const U32: Ty = Ty::S(Scalar::U32);
pub const BOOL: Ty = Ty::S(Scalar::Bool);

impl Ty {
    pub fn scalar(&self) -> Option<Scalar> {
        match self {
            Ty::S(s) | Ty::V(_, s) => Some(*s),
            _ => None,
        }
    }

    /// The glam name of a vector type (`IVec3`).
    pub fn vec_name(n: u8, s: Scalar) -> String {
        format!("{}Vec{n}", s.vec_prefix())
    }

    /// The type a glam type name or scalar name denotes.
    pub fn from_name(name: &str) -> Option<Ty> {
        Some(match name {
            "f32" => F32,
            "i32" => I32,
            "u32" => U32,
            "bool" => BOOL,
            _ => {
                let (s, rest) = match name.as_bytes().first()? {
                    b'I' => (Scalar::I32, &name[1..]),
                    b'U' => (Scalar::U32, &name[1..]),
                    // (`BVec4A`: `Vec4`'s mask, four bools all the same.)
                    b'B' => (Scalar::Bool, name[1..].trim_end_matches('A')),
                    _ => (Scalar::F32, name),
                };
                let n: u8 = rest.strip_prefix("Vec")?.parse().ok()?;
                if !(2..=4).contains(&n) {
                    return None;
                }
                Ty::V(n, s)
            }
        })
    }

    pub fn rust(&self, p: &Program) -> String {
        match self {
            Ty::S(s) => s.rust().to_string(),
            Ty::V(n, s) => Ty::vec_name(*n, *s),
            Ty::Struct(i) => p.structs[*i].name.clone(),
            Ty::Arr(e, n) => format!("[{}; {n}]", e.rust(p)),
        }
    }
}

/// A literal: its value and whether it is printed with its type suffix
/// (unsuffixed ones take their type from the context, in Rust as in the
/// compiler).
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct Lit {
    pub v: LitV,
    pub suffix: bool,
}

#[derive(Clone, Copy, PartialEq, Debug)]
pub enum LitV {
    Bool(bool),
    I32(i32),
    U32(u32),
    F32(f32),
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum UnOp {
    Neg,
    Not,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    BitAnd,
    BitOr,
    BitXor,
    Shl,
    Shr,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    And,
    Or,
}

impl BinOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Rem => "%",
            BinOp::BitAnd => "&",
            BinOp::BitOr => "|",
            BinOp::BitXor => "^",
            BinOp::Shl => "<<",
            BinOp::Shr => ">>",
            BinOp::Eq => "==",
            BinOp::Ne => "!=",
            BinOp::Lt => "<",
            BinOp::Le => "<=",
            BinOp::Gt => ">",
            BinOp::Ge => ">=",
            BinOp::And => "&&",
            BinOp::Or => "||",
        }
    }
}

/// An argument of a helper call.
#[derive(Clone, Debug)]
pub enum Arg {
    Val(Expr),
    /// `&mut name` (a mutable local), or `name` itself where `name` is a
    /// `&mut` parameter passed on.
    MutRef(String),
}

#[derive(Clone, Debug)]
pub enum Expr {
    Lit(Lit),
    Var(String),
    /// `*name`, reading a `&mut` parameter.
    Deref(String),
    /// `launch_index().x`.
    LaunchX,
    /// A struct field or vector component by name, with its index.
    Field(Box<Expr>, String, usize),
    /// `base[index]` on an array or vector; the index is a `u32` or `i32`
    /// expression in range, printed `as usize` (a literal is printed bare).
    Index(Box<Expr>, Box<Expr>),
    Unary(UnOp, Box<Expr>),
    Bin(BinOp, Box<Expr>, Box<Expr>),
    Cast(Box<Expr>, Scalar),
    Method(Box<Expr>, &'static str, Vec<Expr>),
    /// `Type::function(args)`: constructors and UFCS calls.
    Path(&'static str, &'static str, Vec<Expr>),
    /// `function(args)`: glam's `vec3(..)`, rt-std's `mix` etc.
    Free(&'static str, Vec<Expr>),
    /// `Type::NAME`, or a bare `NAME` (`PI`) when the type is empty.
    Const(&'static str, &'static str),
    /// A helper call, by helper index.
    Call(usize, Vec<Arg>),
    /// A struct literal: struct index, `(field index, value)` in print order.
    StructLit(usize, Vec<(usize, Expr)>),
    ArrayLit(Vec<Expr>),
    ArrayRepeat(Box<Expr>, u32),
    If(Box<Expr>, Box<Block>, Box<Block>),
    Match(Box<Expr>, Vec<Arm>),
    /// A load from an output buffer: buffer index, element index, and
    /// whether it is written `buf.load(i)` (else `buf[i]`).
    BufLoad(usize, Box<Expr>, bool),
    /// `(a, b).k`: a tuple literal, its elements evaluated in order, one
    /// read.
    TupleField(Vec<Expr>, usize),
    /// An `i32`/`u32` through the `#[rt_enum] FuzzKind` every program
    /// declares: `x % 3` picks a variant (0: `Alpha`, 1: `Beta`, else
    /// `Gamma`), an exhaustive `match` on it gives 10, `Beta as u32` (5) or 7.
    EnumRound(Box<Expr>),
}

/// A `match` arm: literal patterns joined with `|` (none: a catch-all,
/// `_` or a binding).
#[derive(Clone, Debug)]
pub struct Arm {
    pub pats: Vec<LitV>,
    pub bind: Option<String>,
    pub body: Block,
}

#[derive(Clone, Debug, Default)]
pub struct Block {
    pub stmts: Vec<Stmt>,
    pub tail: Option<Expr>,
}

#[derive(Clone, Debug)]
pub enum Place {
    Var(String),
    Deref(String),
    Field(Box<Place>, String, usize),
    Index(Box<Place>, Expr),
}

#[derive(Clone, Copy, Debug)]
pub enum StoreForm {
    /// `buf.store(i, v)`.
    Method,
    /// `buf[i] = v`.
    Index,
    /// `buf[i] op= v`.
    Compound(BinOp),
}

#[derive(Clone, Debug)]
pub enum Stmt {
    Let {
        name: String,
        mutable: bool,
        ty: Ty,
        annotate: bool,
        init: Expr,
    },
    /// `place = value` or `place op= value`.
    Assign(Place, Option<BinOp>, Expr),
    If(Expr, Block, Option<Block>),
    /// `for var in start..end` (`..=` when inclusive); `start` is a suffixed
    /// literal, `end` any expression of the same type.
    For {
        var: String,
        ty: Scalar,
        start: i64,
        end: Expr,
        inclusive: bool,
        body: Block,
    },
    While(Expr, Block),
    Loop(Block),
    Break,
    Continue,
    Match(Expr, Vec<Arm>),
    Store {
        buf: usize,
        index: Expr,
        value: Expr,
        form: StoreForm,
    },
    /// An expression statement (a helper call whose value is dropped).
    Expr(Expr),
    Return(Option<Expr>),
}

/// A helper's parameter: a value, or a `&mut` of a type.
#[derive(Clone, Debug)]
pub enum Param {
    Val(String, Ty),
    MutRef(String, Ty),
}

#[derive(Clone, Debug)]
pub struct Helper {
    pub name: String,
    pub params: Vec<Param>,
    pub ret: Option<Ty>,
    pub body: Block,
    /// Printed as a method of a struct rather than a free function.
    pub method: Option<Method>,
}

/// A helper printed as a method in the `#[rt_impl]` block of struct `of`:
/// its first parameter (of that struct's type) is the receiver, named
/// `self` in the printed body. The interpreter calls it as the helper it
/// is.
#[derive(Clone, Copy, Debug)]
pub struct Method {
    pub of: usize,
    pub receiver: Receiver,
    /// Calls are printed `Struct::name(receiver, ..)` rather than
    /// `receiver.name(..)`.
    pub ufcs: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Receiver {
    /// `self`, from a value parameter.
    Value,
    /// `&self`, from a value parameter (read as `(*self)`).
    Ref,
    /// `&mut self`, from the `&mut` parameter.
    MutRef,
}

#[derive(Clone, Debug)]
pub struct StructDef {
    pub name: String,
    pub fields: Vec<(String, Ty)>,
}

/// One generated `#[rt_program(ray_generation)]` with its items.
#[derive(Clone, Debug)]
pub struct Program {
    pub name: String,
    pub structs: Vec<StructDef>,
    pub helpers: Vec<Helper>,
    /// Plain-data `#[var]` inputs.
    pub inputs: Vec<(String, Ty)>,
    /// `#[var] mut name: RwBuffer<T>` outputs, after the inputs.
    pub outputs: Vec<(String, Ty)>,
    /// Elements of each output buffer per launch index.
    pub slots: u32,
    pub body: Block,
}

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
        let mut s = String::from("use rt_std::prelude::*;\n");
        s.push_str("\n#[rt_enum]\npub enum FuzzKind {\n    Alpha,\n    Beta = 5,\n    Gamma,\n}\n");
        for (i, d) in self.structs.iter().enumerate() {
            let has_impl = self.helpers.iter().any(|h| h.method.is_some_and(|m| m.of == i));
            s.push_str(if has_impl { "\n#[rt_struct(impl)]\npub struct " } else { "\n#[rt_struct]\npub struct " });
            s.push_str(&d.name);
            s.push_str(" {\n");
            for (n, t) in &d.fields {
                let _ = writeln!(s, "    pub {n}: {},", t.rust(self));
            }
            s.push_str("}\n");
        }
        let params = |h: &Helper| -> Vec<String> {
            h.params
                .iter()
                .map(|p| match p {
                    Param::Val(n, t) => format!("{n}: {}", t.rust(self)),
                    Param::MutRef(n, t) => format!("{n}: &mut {}", t.rust(self)),
                })
                .collect()
        };
        for h in self.helpers.iter().filter(|h| h.method.is_none()) {
            let ret = h.ret.as_ref().map(|t| format!(" -> {}", t.rust(self))).unwrap_or_default();
            let _ = write!(s, "\n#[rt_function]\npub fn {}({}){ret} ", h.name, params(h).join(", "));
            self.block(&mut s, &h.body, 0);
            s.push('\n');
        }
        for (i, d) in self.structs.iter().enumerate() {
            let methods: Vec<&Helper> = self.helpers.iter().filter(|h| h.method.is_some_and(|m| m.of == i)).collect();
            if methods.is_empty() {
                continue;
            }
            let _ = writeln!(s, "\n#[rt_impl]\nimpl {} {{", d.name);
            for h in methods {
                let m = h.method.unwrap();
                let mut ps = params(h);
                let (first, body) = match &h.params[0] {
                    Param::Val(n, _) | Param::MutRef(n, _) => (n.clone(), h.body.clone()),
                };
                ps[0] = match m.receiver {
                    Receiver::Value => "self".into(),
                    Receiver::Ref => "&self".into(),
                    Receiver::MutRef => "&mut self".into(),
                };
                let mut body = body;
                rename::block(&mut body, &first, m.receiver == Receiver::Ref);
                let ret = h.ret.as_ref().map(|t| format!(" -> {}", t.rust(self))).unwrap_or_default();
                let _ = write!(s, "    pub fn {}({}){ret} ", h.name, ps.join(", "));
                self.block(&mut s, &body, 1);
                s.push('\n');
            }
            s.push_str("}\n");
        }
        let mut params: Vec<String> =
            self.inputs.iter().map(|(n, t)| format!("#[var] {n}: {}", t.rust(self))).collect();
        params.extend(self.outputs.iter().map(|(n, t)| format!("#[var] mut {n}: RwBuffer<{}>", t.rust(self))));
        let _ =
            write!(s, "\n#[rt_program(ray_generation)]\npub fn {}(\n    {},\n) ", self.name, params.join(",\n    "));
        self.block(&mut s, &self.body, 0);
        s.push('\n');
        s
    }

    fn block(&self, s: &mut String, b: &Block, depth: usize) {
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
            Expr::EnumRound(x) => format!(
                "(match (match ({}) % 3 {{ 0 => FuzzKind::Alpha, 1 => FuzzKind::Beta, _ => FuzzKind::Gamma }}) \
                 {{ FuzzKind::Alpha => 10u32, FuzzKind::Beta => FuzzKind::Beta as u32, FuzzKind::Gamma => 7u32 }})",
                self.expr(x)
            ),
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

impl Expr {
    /// Whether evaluating the expression may change a variable or buffer
    /// of its context (a helper call with a `&mut` argument, or a block
    /// with assignments or stores).
    pub fn has_effects(&self, p: &Program) -> bool {
        let any = |xs: &[Expr]| xs.iter().any(|x| x.has_effects(p));
        match self {
            Expr::Lit(_) | Expr::Var(_) | Expr::Deref(_) | Expr::LaunchX | Expr::Const(..) => false,
            Expr::Field(b, ..)
            | Expr::Unary(_, b)
            | Expr::Cast(b, _)
            | Expr::ArrayRepeat(b, _)
            | Expr::EnumRound(b) => b.has_effects(p),
            Expr::TupleField(xs, _) => any(xs),
            Expr::Index(a, b) | Expr::Bin(_, a, b) => a.has_effects(p) || b.has_effects(p),
            Expr::Method(r, _, args) => r.has_effects(p) || any(args),
            Expr::Path(_, _, args) | Expr::Free(_, args) | Expr::ArrayLit(args) => any(args),
            Expr::Call(_, args) => args.iter().any(|a| match a {
                Arg::MutRef(_) => true,
                Arg::Val(e) => e.has_effects(p),
            }),
            Expr::StructLit(_, fields) => fields.iter().any(|(_, e)| e.has_effects(p)),
            Expr::If(c, t, e) => c.has_effects(p) || t.has_effects(p) || e.has_effects(p),
            Expr::Match(x, arms) => x.has_effects(p) || arms.iter().any(|a| a.body.has_effects(p)),
            Expr::BufLoad(_, i, _) => i.has_effects(p),
        }
    }
}

impl Block {
    /// See [`Expr::has_effects`].
    pub fn has_effects(&self, p: &Program) -> bool {
        self.stmts.iter().any(|s| match s {
            Stmt::Let { init, .. } => init.has_effects(p),
            Stmt::Expr(e) => e.has_effects(p),
            _ => true,
        }) || self.tail.as_ref().is_some_and(|t| t.has_effects(p))
    }
}

impl Expr {
    /// Calls `f` on this expression and every expression inside it (also
    /// inside the blocks of `if` and `match` values).
    pub fn visit(&self, f: &mut dyn FnMut(&Expr)) {
        f(self);
        match self {
            Expr::Lit(_) | Expr::Var(_) | Expr::Deref(_) | Expr::LaunchX | Expr::Const(..) => {}
            Expr::Field(x, ..)
            | Expr::Unary(_, x)
            | Expr::Cast(x, _)
            | Expr::ArrayRepeat(x, _)
            | Expr::EnumRound(x) => x.visit(f),
            Expr::TupleField(xs, _) => xs.iter().for_each(|a| a.visit(f)),
            Expr::Index(a, b) | Expr::Bin(_, a, b) => {
                a.visit(f);
                b.visit(f);
            }
            Expr::Method(r, _, args) => {
                r.visit(f);
                args.iter().for_each(|a| a.visit(f));
            }
            Expr::Path(_, _, args) | Expr::Free(_, args) | Expr::ArrayLit(args) => args.iter().for_each(|a| a.visit(f)),
            Expr::Call(_, args) => args.iter().for_each(|a| {
                if let Arg::Val(e) = a {
                    e.visit(f)
                }
            }),
            Expr::StructLit(_, fs) => fs.iter().for_each(|(_, e)| e.visit(f)),
            Expr::If(c, t, e) => {
                c.visit(f);
                t.visit(f);
                e.visit(f);
            }
            Expr::Match(x, arms) => {
                x.visit(f);
                arms.iter().for_each(|a| a.body.visit(f));
            }
            Expr::BufLoad(_, i, _) => i.visit(f),
        }
    }

    /// Whether the expression calls a helper.
    pub fn calls_helper(&self) -> bool {
        let mut found = false;
        self.visit(&mut |e| found |= matches!(e, Expr::Call(..)));
        found
    }
}

impl Block {
    /// [`Expr::visit`] over the block's expressions.
    pub fn visit(&self, f: &mut dyn FnMut(&Expr)) {
        for s in &self.stmts {
            match s {
                Stmt::Let { init: e, .. } | Stmt::Assign(_, _, e) | Stmt::Expr(e) | Stmt::Return(Some(e)) => e.visit(f),
                Stmt::If(c, t, e) => {
                    c.visit(f);
                    t.visit(f);
                    if let Some(e) = e {
                        e.visit(f);
                    }
                }
                Stmt::For { end, body, .. } => {
                    end.visit(f);
                    body.visit(f);
                }
                Stmt::While(c, body) => {
                    c.visit(f);
                    body.visit(f);
                }
                Stmt::Loop(body) => body.visit(f),
                Stmt::Match(e, arms) => {
                    e.visit(f);
                    arms.iter().for_each(|a| a.body.visit(f));
                }
                Stmt::Store { index, value, .. } => {
                    index.visit(f);
                    value.visit(f);
                }
                Stmt::Break | Stmt::Continue | Stmt::Return(None) => {}
            }
        }
        if let Some(t) = &self.tail {
            t.visit(f);
        }
    }
}

/// A method's body as printed: its receiver parameter renamed `self`
/// (read through `(*self)` for `&self`).
mod rename {
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
            Stmt::For { end, body, .. } => {
                expr(end, from, by_ref);
                block(body, from, by_ref);
            }
            Stmt::While(c, body) => {
                expr(c, from, by_ref);
                block(body, from, by_ref);
            }
            Stmt::Loop(body) => block(body, from, by_ref),
            Stmt::Match(e, arms) => {
                expr(e, from, by_ref);
                arms.iter_mut().for_each(|a| block(&mut a.body, from, by_ref));
            }
            Stmt::Store { index, value, .. } => {
                expr(index, from, by_ref);
                expr(value, from, by_ref);
            }
            Stmt::Expr(e) | Stmt::Return(Some(e)) => expr(e, from, by_ref),
            Stmt::Break | Stmt::Continue | Stmt::Return(None) => {}
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
            Expr::Field(b, ..)
            | Expr::Unary(_, b)
            | Expr::Cast(b, _)
            | Expr::ArrayRepeat(b, _)
            | Expr::EnumRound(b) => expr(b, from, by_ref),
            Expr::Index(a, b) | Expr::Bin(_, a, b) => {
                expr(a, from, by_ref);
                expr(b, from, by_ref);
            }
            Expr::Method(r, _, args) => {
                expr(r, from, by_ref);
                args.iter_mut().for_each(|a| expr(a, from, by_ref));
            }
            Expr::Path(_, _, xs) | Expr::Free(_, xs) | Expr::ArrayLit(xs) | Expr::TupleField(xs, _) => {
                xs.iter_mut().for_each(|a| expr(a, from, by_ref))
            }
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
}
