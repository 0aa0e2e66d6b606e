//! Places and assignment: what `=`, the compound assignments and `&mut`
//! arguments write to (locals, fields, elements, buffer elements through
//! pointers), and how.

use super::*;

impl FnLowerer<'_> {
    /// What `e` names as the target of an assignment or a `&mut`, its
    /// type noted in the typed form.
    pub(super) fn place(&mut self, e: &Expr) -> Result<Place> {
        let place = self.place_inner(e)?;
        let ty = match &place {
            Place::Wgsl(v) => v.ty.clone(),
            Place::Buffer { ty, .. } => ty.clone(),
        };
        self.expr_types.insert(crate::typed::address(e), ty);
        Ok(place)
    }

    fn place_inner(&mut self, e: &Expr) -> Result<Place> {
        match e {
            Expr::Paren(p) => self.place(&p.expr),
            Expr::Group(g) => self.place(&g.expr),
            Expr::Path(p) if p.path.segments.len() == 1 => self.local_place(p),
            Expr::MethodCall(m) if m.method == "col_mut" => match self.col_mut_place(m)? {
                Some(p) => Ok(p),
                None => Err(Error::new(m.span(), "cannot assign to this expression")),
            },
            Expr::Unary(u)
                if matches!(u.op, UnOp::Deref(_))
                    && matches!(strip_parens(&u.expr), Expr::MethodCall(m) if m.method == "col_mut") =>
            {
                self.place(&u.expr)
            }
            Expr::Unary(u) if matches!(u.op, UnOp::Deref(_)) => {
                let v = self.expr(&u.expr, None)?;
                match v.ty {
                    Ty::Ref(true, t) => Ok(Place::Wgsl(Val::new(format!("(*{})", v.code), *t).with_effects(v.effects))),
                    t => Err(Error::new(u.span(), format!("cannot assign through `{t}`"))),
                }
            }
            Expr::Field(f) => self.field_place(f),
            Expr::Index(i) => self.index_place(i),
            other => Err(Error::new(other.span(), "cannot assign to this expression")),
        }
    }

    /// A local variable as a place: a `let mut` one only.
    fn local_place(&mut self, p: &syn::ExprPath) -> Result<Place> {
        let name = p.path.segments[0].ident.to_string();
        match self.lookup(&name).cloned() {
            Some(Local { wgsl, .. }) if wgsl == POISONED => Err(Error::silent(p.span())),
            Some(Local { wgsl, ty, var: true }) => Ok(Place::Wgsl(Val::new(self.mark(p.span(), &wgsl), ty))),
            Some(Local { ty: Ty::Ref(..), .. }) => Err(Error::new(
                p.span(),
                format!("cannot assign to the reference `{name}`: assign through it with `*{name} = ...`"),
            )),
            Some(_) => Err(Error::new(p.span(), format!("cannot assign twice to immutable variable `{name}`"))),
            None => Err(Error::new(p.span(), format!("cannot find variable `{name}`"))),
        }
    }

    /// `base.field` as a place, in a local or in a buffer element.
    fn field_place(&mut self, f: &syn::ExprField) -> Result<Place> {
        let name = match &f.member {
            syn::Member::Named(n) => n.to_string(),
            syn::Member::Unnamed(i) => i.index.to_string(),
        };
        // Fields of reference parameters are places through the pointer.
        let base = match self.ref_base(&f.base) {
            Some((code, ty)) => {
                self.expr_types.insert(crate::typed::address(&f.base), Ty::Ref(true, Box::new(ty.clone())));
                Place::Wgsl(Val::new(code, ty))
            }
            None => self.place(&f.base)?,
        };
        match base {
            Place::Wgsl(v) => Ok(Place::Wgsl(self.field_of(v, &name, f.member.span())?)),
            Place::Buffer { buf, kind, elem, index, path, ty, effects } => {
                let v = self.field_of(Val::new("e", ty), &name, f.member.span())?;
                let path = format!("{path}{}", &v.code[1..]);
                Ok(Place::Buffer { buf, kind, elem, index, path, ty: v.ty, effects })
            }
        }
    }

    /// `base[index]` as a place: a writable buffer's element, or an element
    /// of an array or a vector (in a local or a buffer element).
    fn index_place(&mut self, i: &syn::ExprIndex) -> Result<Place> {
        let base_val = self.expr(&i.expr, None)?;
        if let Ty::Buffer(kind, elem) = self.resolved(&self.deref(base_val.clone()).ty) {
            return self.buffer_element_place(i, base_val, kind, *elem);
        }
        self.reject_id_and_sampler_elements(i, &base_val)?;
        let base = self.place(&i.expr)?;
        let idx = self.int_index(&i.index)?;
        let element = |code: String, ty: Ty, effects: bool| {
            Place::Wgsl(Val::new(format!("{code}[{}]", idx.code), ty).with_effects(effects || idx.effects))
        };
        match base {
            Place::Wgsl(Val { code, ty: Ty::Array(elem, _), effects, .. }) => Ok(element(code, *elem, effects)),
            Place::Wgsl(Val { code, ty: Ty::Vec(_, s), effects, .. }) => Ok(element(code, Ty::Scalar(s), effects)),
            Place::Buffer { buf, kind, elem, index, path, ty: Ty::Array(e, _), effects } => {
                let path = format!("{path}[{}]", idx.code);
                Ok(Place::Buffer { buf, kind, elem, index, path, ty: *e, effects: effects || idx.effects })
            }
            _ => Err(Error::new(i.expr.span(), "cannot index into this value")),
        }
    }

    /// `buf[index]` of the buffer `buf` (its element type `elem`) as a
    /// place: the index evaluated once, into a `let`; an error where the
    /// buffer is read-only.
    fn buffer_element_place(&mut self, i: &syn::ExprIndex, buf: Val, kind: BufferKind, elem: Ty) -> Result<Place> {
        if !kind.writable {
            return Err(Error::new(
                i.expr.span(),
                format!(
                    "cannot write to a read-only `{}`: declare the variable as `{}`",
                    kind.rust_name(),
                    BufferKind { writable: true, ..kind }.rust_name()
                ),
            ));
        }
        let index = self.buffer_index(kind, &i.index)?;
        let t = self.tmp();
        self.emit_let(format!("let {t} = {};", index.code), &index);
        let buf = self.deref(buf);
        Ok(Place::Buffer { buf, kind, elem: elem.clone(), index: t, path: String::new(), ty: elem, effects: false })
    }

    /// The error for an element assigned through a bindless buffer id or
    /// a sampler (each says how to write instead), where `base` is one.
    fn reject_id_and_sampler_elements(&self, i: &syn::ExprIndex, base: &Val) -> Result<()> {
        if let Ty::BufferId(writable, elem) = self.resolved(&self.deref(base.clone()).ty) {
            let ty = Ty::BufferId(writable, elem.clone());
            let how = if writable {
                "write the element with `.store(i, v)`".to_string()
            } else {
                format!("it is read-only; write through an `RwBindlessBuffer<{elem}>` with `.store(i, v)`")
            };
            return Err(Error::new(i.expr.span(), format!("cannot assign to an element through `{ty}`: {how}")));
        }
        if let t @ (Ty::SamplerId(_) | Ty::Sampler | Ty::Sampler3d | Ty::SamplerCube) =
            self.resolved(&self.deref(base.clone()).ty)
        {
            return Err(Error::new(
                i.expr.span(),
                format!(
                    "cannot assign to texels through `{t}`: textures are read-only in ray programs \
                     (write into an `RwBuffer<Vec4>` instead)"
                ),
            ));
        }
        Ok(())
    }

    /// glam's methods that change a matrix or a bool vector in place and
    /// return nothing (`builtins::in_place_method`), `m.set_row(i, v)` and
    /// `mask.set(i, b)`: assignments to the receiver's place, the index and
    /// the value evaluated once, the index clamped to the last row or
    /// component as indexing is (glam panics there; the CPU copy clamps
    /// through `rt_std::arith::GpuMut`). `None` where the call is not one
    /// of them; `col_mut`, a place, is lowered by [`Self::place`].
    pub(super) fn in_place_method(&mut self, m: &syn::ExprMethodCall, name: &str) -> Result<Option<Val>> {
        let Some(t) = self.in_place_receiver(&m.receiver, name)? else { return Ok(None) };
        let Some((params, ret)) = builtins::in_place_method(&t, name) else { return Ok(None) };
        let span = m.method.span();
        if ret != Ty::Unit {
            return Err(Error::new(
                span,
                format!("`{t}::{name}` gives a place to write: `*m.{name}(i) = v` (read a column with `m.col(i)`)"),
            ));
        }
        if m.args.len() != params.len() {
            return Err(Error::new(
                span,
                format!("`{t}::{name}` takes {} arguments, found {}", params.len(), m.args.len()),
            ));
        }
        let n = match &t {
            Ty::Mat(n) | Ty::Vec(n, _) => *n,
            _ => unreachable!("in_place_method's receivers"),
        };
        let value_ty = params[1].clone();
        let idx = self.int_index(&m.args[0])?;
        let value = self.expr(&m.args[1], Some(&value_ty))?;
        let value = self.deref(value);
        let value = self.coerce(value, &value_ty, m.args[1].span())?;
        let (i, v) = (self.fresh("row"), self.fresh("value"));
        self.emit(format!("let {i} = min(u32({}), {}u);", idx.code, n - 1));
        self.emit(format!("let {v} = {};", value.code));
        let (ri, rv) = (format!("__rt_index_{i}"), format!("__rt_value_{v}"));
        self.bind(&ri, Local { wgsl: i, ty: Ty::Scalar(Scalar::Usize), var: false });
        self.bind(&rv, Local { wgsl: v.clone(), ty: value_ty, var: false });
        let recv = &m.receiver;
        let index = syn::Ident::new(&ri, span);
        if name == "set" {
            let left: Expr = syn::parse_quote_spanned!(span=> #recv[#index]);
            self.assign(&left, None, Val::new(v, Ty::Scalar(Scalar::Bool)), span)?;
        } else {
            for (c, axis) in ["x_axis", "y_axis", "z_axis", "w_axis"].iter().take(n as usize).enumerate() {
                let axis = syn::Ident::new(axis, span);
                let left: Expr = syn::parse_quote_spanned!(span=> #recv.#axis[#index]);
                let part = Val::new(format!("{v}.{}", ["x", "y", "z", "w"][c]), Ty::Scalar(Scalar::F32));
                self.assign(&left, None, part, span)?;
            }
        }
        Ok(Some(Val::new("", Ty::Unit)))
    }

    /// The receiver's type (through a `&mut` parameter) where some glam
    /// type has an in-place method `name`.
    fn in_place_receiver(&mut self, recv: &Expr, name: &str) -> Result<Option<Ty>> {
        if !matches!(name, "set_row" | "set" | "col_mut") {
            return Ok(None);
        }
        let Some(t) = self.peek_type(recv)? else { return Ok(None) };
        Ok(Some(match self.resolved(&t) {
            Ty::Ref(_, t) => self.resolved(&t),
            t => t,
        }))
    }

    /// `m.col_mut(i)` as a place: the column, `i` clamped to the last one.
    fn col_mut_place(&mut self, m: &syn::ExprMethodCall) -> Result<Option<Place>> {
        let Some(t @ Ty::Mat(n)) = self.in_place_receiver(&m.receiver, "col_mut")? else { return Ok(None) };
        if m.method != "col_mut" {
            return Ok(None);
        }
        if m.args.len() != 1 {
            return Err(Error::new(
                m.method.span(),
                format!("`{t}::col_mut` takes 1 argument, found {}", m.args.len()),
            ));
        }
        let base = match self.ref_base(&m.receiver) {
            Some((code, ty)) => Place::Wgsl(Val::new(code, ty)),
            None => self.place(&m.receiver)?,
        };
        let idx = self.int_index(&m.args[0])?;
        let col = format!("min(u32({}), {}u)", idx.code, n - 1);
        match base {
            Place::Wgsl(v) => {
                let effects = v.effects || idx.effects;
                Ok(Some(Place::Wgsl(Val::new(format!("{}[{col}]", v.code), Ty::vec(n)).with_effects(effects))))
            }
            Place::Buffer { buf, kind, elem, index, path, effects, .. } => Ok(Some(Place::Buffer {
                buf,
                kind,
                elem,
                index,
                path: format!("{path}[{col}]"),
                ty: Ty::vec(n),
                effects: effects || idx.effects,
            })),
        }
    }

    /// `prd` where `prd: &mut T` is a parameter: the pointer's target.
    pub(super) fn ref_base(&mut self, e: &Expr) -> Option<(String, Ty)> {
        self.ref_param(e).map(|(ptr, ty)| (format!("(*{ptr})"), ty))
    }

    /// `prd` where `prd: &mut T` is a parameter: the pointer.
    fn ref_param(&self, e: &Expr) -> Option<(String, Ty)> {
        if let Expr::Path(p) = e
            && p.path.segments.len() == 1
            && let Some(Local { wgsl, ty: Ty::Ref(true, t), .. }) = self.lookup(&p.path.segments[0].ident.to_string())
        {
            return Some((wgsl.clone(), (**t).clone()));
        }
        None
    }

    pub(super) fn assign(&mut self, left: &Expr, op: Option<&BinOp>, value: Val, vspan: Span) -> Result<()> {
        // Rust evaluates the value first, then the place's indices: if those
        // need statements, the value is read before them.
        let mut value = value;
        let at = self.here();
        let place = self.place(left)?;
        self.spill(at, &mut [&mut value]);
        let pty = match &place {
            Place::Wgsl(Val { ty: t, .. }) | Place::Buffer { ty: t, .. } => t.clone(),
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
                let effects = value.effects;
                let reads = value.reads;
                // `x <<= n` needs a u32 amount; `v <<= n` and `v &= n` a vector.
                match (base_op, self.resolved(&pty)) {
                    (BinOp::Shl(_) | BinOp::Shr(_), Ty::Vec(n, _)) => {
                        let amount = match vty {
                            Ty::Vec(_, Scalar::U32) => value.code,
                            Ty::Scalar(Scalar::I32) => format!("vec{n}<u32>(u32({}))", value.code),
                            _ => format!("vec{n}<u32>({})", value.code),
                        };
                        Val::new(self.mask_amount(amount, Some(n)), Ty::Vec(n, Scalar::U32))
                            .with_effects(effects)
                            .with_reads(reads)
                    }
                    (BinOp::BitAnd(_) | BinOp::BitOr(_) | BinOp::BitXor(_), Ty::Vec(n, s))
                        if !matches!(vty, Ty::Vec(..)) =>
                    {
                        Val::new(format!("vec{n}<{}>({})", s.wgsl(), value.code), Ty::Vec(n, s))
                            .with_effects(effects)
                            .with_reads(reads)
                    }
                    (BinOp::Shl(_) | BinOp::Shr(_), Ty::Scalar(_) | Ty::IntVar(_)) => {
                        let amount = if matches!(vty, Ty::Scalar(Scalar::U32 | Scalar::Usize)) {
                            value.code
                        } else {
                            format!("u32({})", value.code)
                        };
                        Val::new(self.mask_amount(amount, None), U32).with_effects(effects).with_reads(reads)
                    }
                    _ => value,
                }
            }
        };
        // Float `%=` has no WGSL compound form with Rust's meaning: assign
        // `rt_fmod(place, value)` (see `binary_op`). Nor has `bool ^=`
        // (WGSL has no `^` on bools or bool vectors): assign `place != value`.
        let float_rem = matches!(op, Some(BinOp::RemAssign(_))) && self.resolved(&pty).scalar() == Some(Scalar::F32);
        let bool_xor = matches!(op, Some(BinOp::BitXorAssign(_))) && self.resolved(&pty).scalar() == Some(Scalar::Bool);
        let mut sym = op.map(op_symbol).unwrap_or("=");
        let mut value = value;
        // The local a buffer element is read into, changed in and stored
        // back from (named here: `%=` and `^=` read it in the value).
        let elem_local = match &place {
            Place::Buffer { path, .. } if !(path.is_empty() && op.is_none()) => Some(self.tmp()),
            _ => None,
        };
        if float_rem || bool_xor {
            sym = "=";
            let (place_code, effects) = match &place {
                Place::Wgsl(v) => (v.code.clone(), v.effects),
                Place::Buffer { path, effects, .. } => (format!("{}{path}", elem_local.as_ref().unwrap()), *effects),
            };
            if effects {
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
            Place::Wgsl(v) => format!("{} {sym} {};", v.code, value.code),
            Place::Buffer { buf, kind, elem, index, path, .. } => {
                let load = self.m.accessors.borrow_mut().buffer_load(kind.dims, &elem);
                let store = self.m.accessors.borrow_mut().buffer_store(kind.dims, &elem);
                match elem_local {
                    None => format!("{store}({}, {index}, {});", buf.code, value.code),
                    Some(t) => format!(
                        "var {t} = {load}({b}, {index});\n{t}{path} {sym} {};\n{store}({b}, {index}, {t});",
                        value.code,
                        b = buf.code
                    ),
                }
            }
        };
        let line = self.mark(left.span().join(vspan).unwrap_or(left.span()), &line);
        self.emit(line);
        Ok(())
    }

    /// A `&mut place` argument (or a `&mut T` parameter passed on): the WGSL
    /// pointer expression and the pointee type.
    pub(super) fn mut_ref_arg(&mut self, e: &Expr) -> Result<(String, Ty)> {
        let (ptr, ty) = self.mut_ref_arg_inner(e)?;
        self.expr_types.insert(crate::typed::address(e), Ty::Ref(true, Box::new(ty.clone())));
        Ok((ptr, ty))
    }

    fn mut_ref_arg_inner(&mut self, e: &Expr) -> Result<(String, Ty)> {
        match e {
            Expr::Reference(r) if r.mutability.is_some() => {
                if let Some(ptr) = self.ref_param(&r.expr) {
                    // `&mut *prd` or `&mut prd` where prd is `&mut T`.
                    self.expr_types.insert(crate::typed::address(&r.expr), Ty::Ref(true, Box::new(ptr.1.clone())));
                    return Ok(ptr);
                }
                let inner = match &*r.expr {
                    Expr::Unary(u) if matches!(u.op, UnOp::Deref(_)) => {
                        if let Some(ptr) = self.ref_param(&u.expr) {
                            return Ok(ptr);
                        }
                        &r.expr
                    }
                    _ => &r.expr,
                };
                let whole = is_local(inner);
                match self.place(inner)? {
                    Place::Wgsl(Val { code, ty, .. }) => {
                        // WGSL passes pointers to whole variables only: a
                        // field or element goes through a temporary that is
                        // written back after the call.
                        if whole {
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
}

/// Whether a place expression names a local itself (not a field, an
/// element or through a pointer).
fn is_local(e: &Expr) -> bool {
    match e {
        Expr::Paren(p) => is_local(&p.expr),
        Expr::Group(g) => is_local(&g.expr),
        Expr::Path(p) => p.path.segments.len() == 1,
        _ => false,
    }
}

fn paren(code: &str) -> String {
    if code.chars().all(|c| c.is_alphanumeric() || c == '_' || (c as u32) < 8) {
        code.to_string()
    } else {
        format!("({code})")
    }
}
