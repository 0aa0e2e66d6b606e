//! The generated programs: a small typed AST of the subset, printed as Rust
//! source (what the compiler lowers) and evaluated by [`super::interp`].
//!
//! The AST is typed by construction (the generator only builds well-typed
//! trees), so it carries just what printing and evaluation need: literals
//! know their type, casts their target, calls their callee.
//!
//! The tree is here; `print` writes it as Rust source (`impls` its
//! methods' `#[rt_impl]` blocks and the trait), `walk` asks what an
//! expression or block does, and `rename` gives a method's body its
//! receiver.

mod impls;
mod print;
mod rename;
mod walk;

pub use print::lit_text;

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
    /// `fuzz_pick(k == 1, a, b)`: the generic helper every program
    /// declares, at the elements' type (both evaluated in order, one
    /// returned).
    Pick(Vec<Expr>, usize),
    /// An `i32`/`u32` through the `#[rt_enum] FuzzKind` every program
    /// declares: `x % 3` picks a variant (0: `Alpha`, 1: `Beta`, else
    /// `Gamma`), an exhaustive `match` on it gives 10, `Beta as u32` (5) or 7.
    EnumRound(Box<Expr>),
    /// Rust that means another expression of this AST ([`Sugar::meaning`],
    /// which the interpreter evaluates), printed as the construct: a
    /// closure, an `Option`, an iterator's fold. Its operands have no
    /// effects and call no helper (the printed form may evaluate them in
    /// another order than the meaning, or once more).
    Sugar(Sugar, Vec<Expr>),
}

/// The constructs [`Expr::Sugar`] prints; `id` makes the names they bind
/// (`fz_a3`) unique in the program.
#[derive(Clone, Debug)]
pub enum Sugar {
    /// `{ let fz_f3 = |fz_a3: T| fz_a3 op (xs[1]); fz_f3(xs[0]) }`, or
    /// where `given` the closure given to the generic helper `fuzz_apply`
    /// every program declares, `fuzz_apply(|fz_a3: T| fz_a3 op (xs[1]),
    /// xs[0])`: `xs[0] op xs[1]`.
    Closure { op: BinOp, ty: Ty, given: bool, id: u32 },
    /// `xs[1]` where `xs[0]`, else `xs[2]`, through an `Option`: `form` 0
    /// `(if c { Some(v) } else { None }).unwrap_or(f)`, 1 a `match` on it,
    /// 2 `if let Some(..) = it { .. } else { f }`, 3
    /// `Some(v).filter(|_| c).unwrap_or_else(|| f)`.
    Option { form: u8, id: u32 },
    /// `[xs[1..]].iter().fold(xs[0], |fz_acc3, fz_v3| fz_acc3 op *fz_v3)`,
    /// `.rev()` before the fold where `rev`: the elements folded from the
    /// left (from the right where `rev`). With `sum` (f32, `Add`, `xs[0]`
    /// zero, not printed): `[..].iter().sum::<f32>()`.
    Fold { op: BinOp, ty: Ty, rev: bool, sum: bool, id: u32 },
}

impl Sugar {
    /// The expression of the core AST that `Expr::Sugar(self, xs)` means.
    pub fn meaning(&self, xs: &[Expr]) -> Expr {
        let value = |e: &Expr| Box::new(Block { stmts: Vec::new(), tail: Some(e.clone()) });
        match self {
            Sugar::Closure { op, .. } => Expr::Bin(*op, Box::new(xs[0].clone()), Box::new(xs[1].clone())),
            Sugar::Option { .. } => Expr::If(Box::new(xs[0].clone()), value(&xs[1]), value(&xs[2])),
            Sugar::Fold { op, rev, .. } => {
                let mut elems: Vec<&Expr> = xs[1..].iter().collect();
                if *rev {
                    elems.reverse();
                }
                elems.into_iter().fold(xs[0].clone(), |acc, e| Expr::Bin(*op, Box::new(acc), Box::new(e.clone())))
            }
        }
    }

    /// The operands of the value's own type (those a reduction may put in
    /// its place).
    pub fn same_typed<'a>(&self, xs: &'a [Expr]) -> &'a [Expr] {
        match self {
            Sugar::Closure { .. } | Sugar::Fold { .. } => xs,
            Sugar::Option { .. } => &xs[1..],
        }
    }
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
    /// A loop over a fixed array's elements, `var` each in turn: `for var
    /// in array` (by value), `for &var in array.iter()` (`by_ref`), each
    /// `.rev()` when `rev`; with `index`, `for (raw, &var) in
    /// array.iter().enumerate()` (then `.rev()`), the body starting `let
    /// index = raw as u32;`.
    Each {
        var: String,
        index: Option<(String, String)>,
        array: Expr,
        by_ref: bool,
        rev: bool,
        body: Block,
    },
    While(Expr, Block),
    Loop(Block),
    /// A loop statement (`For`, `Each`, `While`, `Loop`) labelled
    /// `'fz_l<n>`, which a `BreakTo(n)` inside a loop inside it leaves.
    Labelled(u32, Box<Stmt>),
    /// `break 'fz_l<n>;`
    BreakTo(u32),
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
    /// A trace, numbered within the program, of the lane-wise variant
    /// (`generate::lanes`): it changes only the variant's own payload and
    /// ray buffer, so the interpreter runs it as a no-op.
    Trace(u32),
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

/// A helper printed as a method of struct `of`: its first parameter (of
/// that struct's type) is the receiver, named `self` in the printed body.
/// The interpreter calls it as the helper it is.
#[derive(Clone, Copy, Debug)]
pub struct Method {
    pub of: usize,
    pub receiver: Receiver,
    /// Calls are printed `Struct::name(receiver, ..)` rather than
    /// `receiver.name(..)`; an operator's, `a.add(b)` rather than `(a + b)`.
    pub ufcs: bool,
    pub form: MethodForm,
}

/// Which `#[rt_impl]` block a method is printed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MethodForm {
    /// The struct's inherent block.
    Inherent,
    /// The struct's impl of the `#[rt_trait] FuzzOps` every program with
    /// such a method declares (the trait lists the method's signature).
    Trait,
    /// An operator trait's impl: the helper takes the struct by value and
    /// a right operand, returns the struct, and calls print as `(a op b)`.
    Operator(OpTrait),
}

/// The operator traits the fuzzer implements for its structs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpTrait {
    /// `impl Add for S`.
    Add,
    /// `impl Sub for S`.
    Sub,
    /// `impl Mul for S`.
    Mul,
    /// `impl Mul<f32> for S`, beside `Mul`.
    MulF32,
}

impl OpTrait {
    pub const ALL: [OpTrait; 4] = [OpTrait::Add, OpTrait::Sub, OpTrait::Mul, OpTrait::MulF32];

    /// The trait as the struct's attribute and the impl name it.
    pub fn rust(self) -> &'static str {
        match self {
            OpTrait::Add => "Add",
            OpTrait::Sub => "Sub",
            OpTrait::Mul => "Mul",
            OpTrait::MulF32 => "Mul<f32>",
        }
    }

    /// The trait's method.
    pub fn method(self) -> &'static str {
        match self {
            OpTrait::Add => "add",
            OpTrait::Sub => "sub",
            OpTrait::Mul | OpTrait::MulF32 => "mul",
        }
    }

    /// The operator's token.
    pub fn token(self) -> &'static str {
        match self {
            OpTrait::Add => "+",
            OpTrait::Sub => "-",
            OpTrait::Mul | OpTrait::MulF32 => "*",
        }
    }

    /// Whether the right operand is an `f32` (else the struct itself).
    pub fn scalar_rhs(self) -> bool {
        self == OpTrait::MulF32
    }
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
