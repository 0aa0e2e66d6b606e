//! Operators and casts: unary and binary operators with Rust's typing
//! rules (glam's vector and matrix forms included), `&&`/`||` with their
//! short circuit, float `%` as Rust's `fmod`, and `as`.

use super::*;

impl FnLowerer<'_> {
    pub(super) fn unary(&mut self, u: &syn::ExprUnary, want: Option<&Ty>) -> Result<Val> {
        if let Some(v) = self.user_unary(u)? {
            return Ok(v);
        }
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
                    Some(Scalar::F32) | Some(Scalar::I32) => {
                        Ok(Val::new(negate(&v.code), v.ty).with_effects(v.effects).with_reads(v.reads))
                    }
                    _ if matches!(t, Ty::IntVar(_)) => {
                        self.unify(&t, &I32);
                        Ok(Val::new(negate(&v.code), I32).with_effects(v.effects).with_reads(v.reads))
                    }
                    _ => Err(Error::new(u.span(), format!("cannot negate a value of type `{t}`"))),
                }
            }
            UnOp::Not(_) => {
                let v = self.expr(&u.expr, want)?;
                let v = self.deref(v);
                let t = self.resolved(&v.ty);
                if t == BOOL || matches!(t, Ty::Vec(_, Scalar::Bool)) {
                    Ok(Val::new(format!("!{}", v.code), t).with_effects(v.effects).with_reads(v.reads))
                } else if self.is_int(&t) || matches!(t, Ty::Vec(_, s) if s.is_int()) {
                    Ok(Val::new(format!("~{}", v.code), v.ty).with_effects(v.effects).with_reads(v.reads))
                } else {
                    Err(Error::new(u.span(), format!("cannot apply `!` to a value of type `{t}`")))
                }
            }
            UnOp::Deref(_) => {
                let v = self.expr(&u.expr, want)?;
                match v.ty {
                    Ty::Ref(..) => Ok(self.deref(v)),
                    // An element an iterator chain yields by reference is a
                    // value here (`sugar`); rustc checks the CPU copy's `*`.
                    _ => Ok(v),
                }
            }
            _ => Err(Error::unsupported(u.span(), "this operator", "use arithmetic, comparison and logic operators")),
        }
    }

    pub(super) fn binary(&mut self, b: &syn::ExprBinary, want: Option<&Ty>) -> Result<Val> {
        if is_compound(&b.op) {
            if let Some(v) = self.user_compound(b)? {
                return Ok(v);
            }
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
        let start = self.here();
        let l = self.expr(&b.left, lw.as_ref())?;
        let mut l = self.deref(l);
        let rw = match (&b.op, self.resolved(&l.ty)) {
            (BinOp::Shl(_) | BinOp::Shr(_), _) => None,
            (_, t @ (Ty::Scalar(_) | Ty::IntVar(_))) => Some(t),
            // `id == Callable::NONE`, `b == BindlessBuffer::default()`: the
            // id's type from the left.
            (BinOp::Eq(_) | BinOp::Ne(_), t @ (Ty::Callable(_) | Ty::BufferId(..) | Ty::SamplerId(_))) => Some(t),
            // `o == None`, `o != Some(x)`: the `Option`'s type from the left.
            (BinOp::Eq(_) | BinOp::Ne(_), t @ Ty::Option(_)) => Some(t),
            _ => None,
        };
        let at = self.here();
        let r = self.expr(&b.right, rw.as_ref())?;
        let r = self.deref(r);
        self.spill(at, &mut [&mut l]);
        let (l, r) = match self.user_binary(&b.op, l, r, start, b.op.span())? {
            Ok(v) => return Ok(v),
            Err(operands) => operands,
        };
        // Errors point at the operator, as rustc's do.
        self.binary_op(&b.op, l, r, b.op.span())
    }

    /// Types and lowers `l op r` (both already lowered).
    pub(super) fn binary_op(&mut self, op: &BinOp, l: Val, r: Val, span: Span) -> Result<Val> {
        let l = match op {
            BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Shl(_) | BinOp::Shr(_) => {
                self.const_int_op(op, l, &r)
            }
            _ => l,
        };
        let (lt, rt) = (self.resolved(&l.ty), self.resolved(&r.ty));
        let effects = l.effects || r.effects;
        let reads = l.reads || r.reads;
        let o = Operands { l, r, lt, rt, effects, reads, span };
        let sym = op_symbol(op);
        match op {
            BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Div(_) | BinOp::Rem(_) => self.arithmetic(op, o),
            BinOp::BitAnd(_) | BinOp::BitOr(_) | BinOp::BitXor(_) => self.bitwise(op, o),
            BinOp::Shl(_) | BinOp::Shr(_) if matches!(o.lt, Ty::Vec(_, s) if s.is_int()) => self.vector_shift(sym, o),
            BinOp::Shl(_) | BinOp::Shr(_) => self.scalar_shift(sym, o),
            BinOp::Eq(_) | BinOp::Ne(_) => self.equality(op, o),
            BinOp::Lt(_) | BinOp::Le(_) | BinOp::Gt(_) | BinOp::Ge(_) => self.comparison(sym, o),
            _ => Err(Error::unsupported(span, &format!("the `{sym}` operator"), "see the supported operators")),
        }
    }

    /// `+ - * / %`: scalars of one type, vectors with vectors or scalars
    /// of their element type, and glam's matrix products.
    fn arithmetic(&mut self, op: &BinOp, o: Operands) -> Result<Val> {
        let (lt, rt) = (&o.lt, &o.rt);
        let mul = matches!(op, BinOp::Mul(_));
        let ty = match (lt, rt) {
            (a, b) if (self.is_int(a) || *a == F32) && self.unify(a, b) => self.resolved(a),
            (Ty::Vec(n, s), Ty::Vec(m, t)) if n == m && s == t && *s != Scalar::Bool => lt.clone(),
            (Ty::Vec(_, s), b) if Some(*s) == b.scalar() && !matches!(b, Ty::Vec(..) | Ty::Mat(_)) => lt.clone(),
            (Ty::Vec(_, s), Ty::IntVar(_)) if s.is_int() => {
                self.unify(rt, &Ty::Scalar(*s));
                lt.clone()
            }
            (a, Ty::Vec(_, s)) if Some(*s) == a.scalar() && !matches!(a, Ty::Vec(..) | Ty::Mat(_)) => rt.clone(),
            (Ty::IntVar(_), Ty::Vec(_, s)) if s.is_int() => {
                self.unify(lt, &Ty::Scalar(*s));
                rt.clone()
            }
            (Ty::Mat(n), Ty::Mat(m)) if n == m && !matches!(op, BinOp::Div(_) | BinOp::Rem(_)) => lt.clone(),
            (Ty::Mat(n), Ty::Vec(m, Scalar::F32)) if mul && n == m => rt.clone(),
            (Ty::Mat(_), b) if mul && *b == F32 => lt.clone(),
            (a, Ty::Mat(_)) if mul && *a == F32 => rt.clone(),
            _ => return Err(o.mismatch(op)),
        };
        if matches!(op, BinOp::Rem(_)) && ty.scalar() == Some(Scalar::F32) {
            let Operands { l, r, lt, rt, .. } = o;
            return Ok(self.float_rem(l, &lt, r, &rt, ty));
        }
        Ok(o.infix(op_symbol(op), ty))
    }

    /// `& | ^`: logic on bools and bool vectors (`^` is `!=`), bitwise on
    /// integers and integer vectors, glam's vector with a scalar.
    fn bitwise(&mut self, op: &BinOp, o: Operands) -> Result<Val> {
        let sym = op_symbol(op);
        let lt = &o.lt;
        let ty = if *lt == BOOL && o.rt == BOOL {
            if matches!(op, BinOp::BitXor(_)) {
                return Ok(o.val(format!("({} != {})", o.l.code, o.r.code), BOOL));
            }
            BOOL
        } else if matches!(lt, Ty::Vec(_, Scalar::Bool)) && *lt == o.rt {
            // glam's `BVec` operators, per component (WGSL's `&`,
            // `|` on bool vectors; `^` is `!=`).
            if matches!(op, BinOp::BitXor(_)) {
                return Ok(o.val(format!("({} != {})", o.l.code, o.r.code), lt.clone()));
            }
            lt.clone()
        } else if self.is_int(lt) && self.unify(lt, &o.rt) {
            self.resolved(lt)
        } else if matches!(lt, Ty::Vec(_, s) if s.is_int()) && *lt == o.rt {
            lt.clone()
        } else if let Ty::Vec(n, s) = *lt
            && s.is_int()
            && self.unify(&o.rt, &Ty::Scalar(s))
        {
            // glam's `v & 1`: WGSL wants both sides the same type.
            let code = format!("({} {sym} vec{n}<{}>({}))", o.l.code, s.wgsl(), o.r.code);
            return Ok(o.val(code, lt.clone()));
        } else {
            return Err(o.mismatch(op));
        };
        Ok(o.infix(sym, ty))
    }

    /// `<<`, `>>` of an integer vector: glam shifts a vector by a scalar or
    /// by a vector of either signedness; WGSL wants a `vecN<u32>` amount.
    fn vector_shift(&mut self, sym: &str, o: Operands) -> Result<Val> {
        let Ty::Vec(n, _) = o.lt else { unreachable!() };
        let (r, rt) = (&o.r, &o.rt);
        let amount = match *rt {
            Ty::Vec(m, Scalar::U32) if m == n => r.code.clone(),
            Ty::Vec(m, t) if m == n && t.is_int() => format!("vec{n}<u32>({})", r.code),
            Ty::IntVar(_) if self.unify(rt, &U32) => format!("vec{n}<u32>({})", r.code),
            Ty::Scalar(Scalar::I32) => format!("vec{n}<u32>(u32({}))", r.code),
            Ty::Scalar(t) if t.is_int() => format!("vec{n}<u32>({})", r.code),
            _ => return Err(o.mismatch_of(sym)),
        };
        let amount = self.mask_amount(amount, Some(n));
        Ok(o.val(format!("({} {sym} {amount})", o.l.code), o.lt.clone()))
    }

    /// `<<`, `>>` of an integer scalar, by a `u32` amount.
    fn scalar_shift(&mut self, sym: &str, o: Operands) -> Result<Val> {
        if !self.is_int(&o.lt) || !self.is_int(&o.rt) {
            return Err(o.mismatch_of(sym));
        }
        let amount = match o.rt {
            Ty::IntVar(_) => {
                self.unify(&o.rt, &U32);
                o.r.code.clone()
            }
            Ty::Scalar(Scalar::U32) | Ty::Scalar(Scalar::Usize) => o.r.code.clone(),
            _ => format!("u32({})", o.r.code),
        };
        let amount = self.mask_amount(amount, None);
        Ok(o.val(format!("({} {sym} {amount})", o.l.code), o.lt.clone()))
    }

    /// `==`, `!=` of two values of one type; vectors compare whole.
    fn equality(&mut self, op: &BinOp, o: Operands) -> Result<Val> {
        let sym = op_symbol(op);
        let (l, r, lt) = (&o.l, &o.r, &o.lt);
        // `o == Some(x)` of a `None` local whose type is probed: the other side's.
        self.note_none_use(l, &o.rt);
        self.note_none_use(r, lt);
        if !self.unify(lt, &o.rt) || !lt.is_value() {
            return Err(o.mismatch(op));
        }
        if let Ty::Option(inner) = self.resolved(lt) {
            return self.option_equality(op, o, &inner);
        }
        // Rust's float `!=` is true where a NaN is (unordered); WGSL
        // implementations compare ordered: `!(a == b)` is Rust's.
        if matches!(op, BinOp::Ne(_)) && lt.scalar() == Some(Scalar::F32) {
            let eq = match lt {
                Ty::Vec(..) => format!("all({} == {})", l.code, r.code),
                _ => format!("({} == {})", l.code, r.code),
            };
            return Ok(o.val(format!("!{eq}"), BOOL));
        }
        match lt {
            Ty::Vec(..) => {
                let f = if matches!(op, BinOp::Eq(_)) { "all" } else { "any" };
                Ok(o.val(format!("{f}({} {sym} {})", l.code, r.code), BOOL))
            }
            t if matches!(t, Ty::Scalar(_) | Ty::IntVar(_)) || t.is_u32_word() => Ok(o.infix(sym, BOOL)),
            other => Err(Error::new(o.span, format!("`{sym}` on `{other}` is not supported: compare the fields"))),
        }
    }

    /// `< <= > >=` of two integers or two floats.
    fn comparison(&mut self, sym: &str, o: Operands) -> Result<Val> {
        let ok = (self.is_int(&o.lt) || o.lt == F32) && self.unify(&o.lt, &o.rt);
        if !ok {
            return Err(o.mismatch_of(sym));
        }
        Ok(o.infix(sym, BOOL))
    }

    /// Float `l % r` of type `ty`: Rust's `fmod`, not WGSL's
    /// `x - y * trunc(x / y)`.
    fn float_rem(&self, l: Val, lt: &Ty, r: Val, rt: &Ty, ty: Ty) -> Val {
        let mut fns = self.m.accessors.borrow_mut();
        if !matches!(ty, Ty::Vec(4, _)) {
            fns.functions.entry("rt_fmod".to_string()).or_insert_with(|| builtins::FMOD.to_string());
        }
        let code = match ty {
            Ty::Vec(n, _) => {
                // glam's `Vec4` is SIMD on every target with SIMD (SSE2,
                // NEON, wasm), and its `%` is `x - floor(x / y) * y`
                // there, not `f32`'s `%` per component as for `Vec2` and
                // `Vec3`.
                let (f, text) = if n == 4 { builtins::VEC4_REM } else { builtins::fmod_vec(n) };
                fns.functions.entry(f.to_string()).or_insert_with(|| text.to_string());
                let splat = |v: &Val, t: &Ty| match t {
                    Ty::Vec(..) => v.code.clone(),
                    _ => format!("vec{n}<f32>({})", v.code),
                };
                format!("{f}({}, {})", splat(&l, lt), splat(&r, rt))
            }
            _ => format!("rt_fmod({}, {})", l.code, r.code),
        };
        Val::new(code, ty).with_effects(l.effects || r.effects).with_reads(l.reads || r.reads)
    }

    pub(super) fn short_circuit(&mut self, b: &syn::ExprBinary) -> Result<Val> {
        let and = matches!(b.op, BinOp::And(_));
        let l = self.expr(&b.left, Some(&BOOL))?;
        let l = self.deref(l);
        let l = self.coerce(l, &BOOL, b.left.span())?;
        self.blocks.push(Block::default());
        let r = self.expr(&b.right, Some(&BOOL));
        let hoisted = self.blocks.pop().unwrap().lines;
        let r = r?;
        let r = self.deref(r);
        let r = self.coerce(r, &BOOL, b.right.span())?;
        let sym = if and { "&&" } else { "||" };
        if hoisted.is_empty() {
            let effects = l.effects || r.effects;
            let reads = l.reads || r.reads;
            return Ok(Val::new(format!("({} {sym} {})", l.code, r.code), BOOL)
                .with_effects(effects)
                .with_reads(reads));
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

    pub(super) fn cast(&mut self, c: &syn::ExprCast) -> Result<Val> {
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
            // `kind as u32`: the discriminant, as in Rust (which casts C-like
            // enums to integers only).
            Ty::Enum(_) if ts.is_int() => U32,
            Ty::Enum(e) => {
                return Err(Error::new(
                    c.span(),
                    format!("cannot cast enum `{}` as `{}`: cast it to an integer", e.name, ts.rust()),
                ));
            }
            Ty::IntVar(_) if ts != Scalar::Bool => {
                // `j as f32` leaves `j`'s type to its other uses, as rustc
                // does (`i32` where none decides): the conversion's text is
                // the same from `i32` and from `u32`.
                let code = format!("{}({})", ts.wgsl(), v.code);
                return Ok(Val::new(code, Ty::Scalar(ts)).with_effects(v.effects).with_reads(v.reads));
            }
            Ty::IntVar(_) => {
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
        let effects = v.effects;
        let reads = v.reads;
        let code = if fs == Scalar::F32 && ts.is_int() {
            // Saturating at the integer limits, as Rust's `as`.
            let (f, text) = builtins::float_to_int(1, ts == Scalar::I32);
            self.m.accessors.borrow_mut().functions.entry(f.to_string()).or_insert_with(|| text.to_string());
            format!("{f}({})", v.code)
        } else if fs.wgsl() == ts.wgsl() {
            v.code
        } else {
            format!("{}({})", ts.wgsl(), v.code)
        };
        Ok(Val::new(code, Ty::Scalar(ts)).with_effects(effects).with_reads(reads))
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

pub(super) fn is_compound(op: &BinOp) -> bool {
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

/// The two sides of a binary operator, lowered, with their resolved types.
pub(super) struct Operands {
    pub(super) l: Val,
    pub(super) r: Val,
    pub(super) lt: Ty,
    pub(super) rt: Ty,
    /// Whether either side has effects.
    pub(super) effects: bool,
    /// Whether either side reads state.
    pub(super) reads: bool,
    /// The operator's span, where errors point.
    pub(super) span: Span,
}

impl Operands {
    /// `code` of type `ty`, with the effects and reads of both sides.
    fn val(&self, code: String, ty: Ty) -> Val {
        Val::new(code, ty).with_effects(self.effects).with_reads(self.reads)
    }

    /// `(l sym r)` of type `ty`.
    fn infix(&self, sym: &str, ty: Ty) -> Val {
        self.val(format!("({} {sym} {})", self.l.code, self.r.code), ty)
    }

    /// The error for operands `op` does not apply to.
    fn mismatch(&self, op: &BinOp) -> Error {
        self.mismatch_of(op_symbol(op))
    }

    /// The error for operands the operator `sym` does not apply to, with
    /// a hint where both are numbers.
    fn mismatch_of(&self, sym: &str) -> Error {
        let (lt, rt) = (&self.lt, &self.rt);
        let numeric = |t: &Ty| matches!(t, Ty::Scalar(s) if *s != Scalar::Bool);
        let hint = if numeric(lt) && numeric(rt) {
            format!(": there are no implicit conversions; convert one side with `as {lt}` or `as {rt}`")
        } else {
            String::new()
        };
        Error::new(self.span, format!("cannot apply `{sym}` to `{lt}` and `{rt}`{hint}"))
    }
}

pub(super) fn compound_base(op: &BinOp) -> BinOp {
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

pub(super) fn op_symbol(op: &BinOp) -> &'static str {
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
