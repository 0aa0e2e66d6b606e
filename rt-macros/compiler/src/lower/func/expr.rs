//! Expressions: the dispatch over syn's `Expr`, literals, paths (locals,
//! constants), fields, indexing, and struct and array literals.

use super::*;

impl FnLowerer<'_> {
    pub fn expr(&mut self, e: &Expr, want: Option<&Ty>) -> Result<Val> {
        let span = e.span();
        let v = self.expr_inner(e, want)?;
        self.expr_types.insert(crate::typed::address(e), v.ty.clone());
        let code = if v.code.is_empty() { v.code } else { self.mark(span, &v.code) };
        Ok(Val { code, ty: v.ty, effects: v.effects, reads: v.reads })
    }

    pub(super) fn expr_inner(&mut self, e: &Expr, want: Option<&Ty>) -> Result<Val> {
        match e {
            Expr::Lit(l) => self.literal(&l.lit, want),
            Expr::Paren(p) => {
                // Binary operators are always parenthesised; only a unary
                // operand needs the parentheses kept (`(-v).x`).
                let v = self.expr(&p.expr, want)?;
                if matches!(&*p.expr, Expr::Unary(_)) {
                    Ok(Val::new(format!("({})", v.code), v.ty).with_effects(v.effects).with_reads(v.reads))
                } else {
                    Ok(v)
                }
            }
            Expr::Group(g) => self.expr_inner(&g.expr, want),
            Expr::Path(p) if p.qself.is_none() && callables::is_callable_item(&p.path) => {
                self.callable_item(&p.path, None, want, p.span())
            }
            Expr::Path(p) if p.qself.is_none() && bindless::is_bindless_item(&p.path) => {
                self.bindless_item(&p.path, None, want, p.span())
            }
            Expr::Path(p) if p.qself.is_none() && options::is_none_path(&p.path) && self.lookup("None").is_none() => {
                self.option_none(p, want)
            }
            Expr::Path(p) => self.path_expr(p),
            Expr::Unary(u) => self.unary(u, want),
            Expr::Binary(b) => self.binary(b, want),
            Expr::Assign(a) => {
                let v = self.expr(&a.right, None)?;
                if self.note_none_probe(&a.left, &v) {
                    return Ok(Val::new("", Ty::Unit));
                }
                self.assign(&a.left, None, v, a.right.span())?;
                Ok(Val::new("", Ty::Unit))
            }
            Expr::Cast(c) => self.cast(c),
            Expr::Field(f) => self.field(f),
            Expr::Index(i) => self.index(i),
            Expr::MethodCall(m) => self.method_call(m, want),
            Expr::Call(c) => self.call(c, want),
            Expr::Struct(s) => self.struct_lit(s, want),
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
            Expr::Break(b) => self.break_expr(b),
            Expr::Continue(c) => self.continue_expr(c),
            Expr::Return(r) => self.return_expr(r),
            Expr::Match(m) => self.match_expr(m, want),
            Expr::Macro(m) => {
                self.macro_stmt(&m.mac)?;
                Ok(Val::new("", Ty::Unit))
            }
            Expr::Tuple(t) if t.elems.is_empty() => Ok(Val::new("", Ty::Unit)),
            Expr::Tuple(t) => self.tuple_lit(t, want),
            Expr::Closure(c) => Err(Error::unsupported(
                c.or1_token.span,
                "a closure that is not only called (stored, passed on, returned, or `move`)",
                "call it where it is bound or pass it to an iterator adaptor; a #[rt_function] helper can hold it",
            )),
            Expr::Reference(r) => Err(Error::unsupported(
                r.and_token.span,
                "a reference here",
                "references may only be passed directly as `&mut` call arguments (rt_trace, helpers)",
            )),
            Expr::Try(t) => {
                Err(Error::unsupported(t.question_token.span, "the `?` operator", "check the condition with if/else"))
            }
            Expr::Range(r) => Err(Error::unsupported(r.span(), "a range outside a `for` loop", "use `for i in a..b`")),
            Expr::Let(l) => Err(Error::unsupported(
                l.let_token.span,
                "a `let` inside a longer condition (`if let P = e && c`)",
                "put the rest of the condition in an `if` inside the `if let`",
            )),
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

    pub(super) fn literal(&mut self, lit: &syn::Lit, want: Option<&Ty>) -> Result<Val> {
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

    pub(super) fn path_expr(&mut self, p: &syn::ExprPath) -> Result<Val> {
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
                let reads = l.var || matches!(l.ty, Ty::Ref(true, _));
                return Ok(Val::new(l.wgsl.clone(), l.ty.clone()).with_reads(reads));
            }
        }
        let last = segs.last().unwrap().as_str();
        // Associated constants: `Vec3::ZERO`, `f32::MAX`, `Mat3::IDENTITY`.
        if segs.len() >= 2 {
            let owner = segs[segs.len() - 2].as_str();
            if let Some(v) = builtins::assoc_const(owner, last) {
                return Ok(v);
            }
            if owner == "TransformKind" {
                return transform_kind(last, p.span());
            }
            // `Finish::COUNT`: an enum's associated constant.
            let key = crate::methods::member_key(owner, last);
            if let Some(e) = self.m.enums.get(owner)
                && !self.m.consts.contains_key(&key)
                && !self.m.failed.contains(&key)
            {
                return match e.variant(last) {
                    Some(d) => Ok(Val::new(format!("{d}u"), Ty::Enum(e.clone()))),
                    None => {
                        let at = p.path.segments.last().map_or(p.span(), |s| s.ident.span());
                        Err(Error::new(at, format!("no variant `{last}` on enum `{owner}`")))
                    }
                };
            }
            // `Sphere::UNIT`: an `#[rt_impl]`'s associated constant.
            if let Some(c) = self.m.consts.get(&key) {
                return Ok(Val::new(c.wgsl_name.clone(), c.ty.clone()));
            }
            if self.m.failed.contains(owner) || self.m.failed.contains(&key) {
                return Err(Error::silent(p.span()));
            }
            if self.m.structs.contains_key(owner) {
                let at = p.path.segments.last().map_or(p.span(), |s| s.ident.span());
                return Err(Error::new(
                    at,
                    format!(
                        "no associated constant `{last}` on `{owner}` in ray programs: declare it in an \
                         `#[rt_impl] impl {owner}` block (and the struct with `(impl)`)"
                    ),
                ));
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

    pub(super) fn field(&mut self, f: &syn::ExprField) -> Result<Val> {
        if let (Expr::Tuple(t), syn::Member::Unnamed(i)) = (strip_parens(&f.base), &f.member)
            && (i.index as usize) < t.elems.len()
        {
            return self.tuple_lit_field(t, i.index as usize);
        }
        let base = self.expr(&f.base, None)?;
        let base = self.deref(base);
        let name = match &f.member {
            syn::Member::Named(n) => n.to_string(),
            syn::Member::Unnamed(i) => i.index.to_string(),
        };
        self.field_of(base, &name, f.member.span())
    }

    pub(super) fn field_of(&mut self, base: Val, name: &str, span: Span) -> Result<Val> {
        let t = self.resolved(&base.ty);
        match &t {
            Ty::Vec(n, s) => {
                let idx = "xyzw".find(name).filter(|i| name.len() == 1 && *i < *n as usize);
                match idx {
                    Some(_) => Ok(Val::new(format!("{}.{name}", base.code), Ty::Scalar(*s))
                        .with_effects(base.effects)
                        .with_reads(base.reads)),
                    None => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
                }
            }
            Ty::Mat(n) => {
                let axis = ["x_axis", "y_axis", "z_axis", "w_axis"].iter().position(|a| *a == name);
                match axis {
                    Some(i) if i < *n as usize => Ok(Val::new(format!("{}[{i}]", base.code), Ty::vec(*n))
                        .with_effects(base.effects)
                        .with_reads(base.reads)),
                    _ => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
                }
            }
            Ty::Struct(_) | Ty::Ray | Ty::Aabb => match t.fields().into_iter().find(|(n, _)| n == name) {
                Some((_, fty)) => {
                    let field = crate::lower::resolve::wgsl_field(name);
                    Ok(Val::new(format!("{}.{field}", base.code), fty)
                        .with_effects(base.effects)
                        .with_reads(base.reads))
                }
                None => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
            },
            Ty::Tuple(elems) => match name.parse::<usize>().ok().and_then(|i| elems.get(i).map(|e| (i, e))) {
                Some((i, ety)) => Ok(Val::new(format!("{}.f{i}", base.code), ety.clone())
                    .with_effects(base.effects)
                    .with_reads(base.reads)),
                None => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
            },
            _ if name.parse::<usize>().is_ok() => {
                Err(Error::new(span, format!("no field `{name}` on `{t}`: `.{name}` reads an element of a tuple")))
            }
            _ => Err(Error::new(span, format!("no field `{name}` on `{t}`"))),
        }
    }

    pub(super) fn index(&mut self, i: &syn::ExprIndex) -> Result<Val> {
        let base = self.expr(&i.expr, None)?;
        let base = self.deref(base);
        let at = self.here();
        let mut base = match self.user_index(base, &i.index, at, i.span())? {
            Ok(v) => return Ok(v),
            Err(base) => base,
        };
        match self.resolved(&base.ty) {
            Ty::Buffer(kind, elem) => {
                let idx = self.buffer_index(kind, &i.index)?;
                let f = self.m.accessors.borrow_mut().buffer_load(kind.dims, &elem);
                let effects = base.effects || idx.effects;
                Ok(Val::new(format!("{f}({}, {})", base.code, idx.code), *elem).with_effects(effects).with_reads(true))
            }
            Ty::BufferId(writable, elem) => self.bindless_load(base, writable, &elem, &i.index),
            Ty::Array(elem, _) => {
                let idx = self.int_index(&i.index)?;
                self.spill(at, &mut [&mut base]);
                let effects = base.effects || idx.effects;
                let reads = base.reads || idx.reads;
                Ok(Val::new(format!("{}[{}]", base.code, idx.code), *elem).with_effects(effects).with_reads(reads))
            }
            Ty::Vec(_, s) => {
                let idx = self.int_index(&i.index)?;
                self.spill(at, &mut [&mut base]);
                let effects = base.effects || idx.effects;
                let reads = base.reads || idx.reads;
                Ok(Val::new(format!("{}[{}]", base.code, idx.code), Ty::Scalar(s))
                    .with_effects(effects)
                    .with_reads(reads))
            }
            t @ (Ty::SamplerId(_) | Ty::Sampler | Ty::Sampler3d | Ty::SamplerCube) => Err(Error::new(
                i.expr.span(),
                format!("cannot index into a `{t}`: read a texel with `.fetch(texel)`, or sample it"),
            )),
            t => Err(Error::new(i.expr.span(), format!("cannot index into a value of type `{t}`"))),
        }
    }

    pub(super) fn int_index(&mut self, e: &Expr) -> Result<Val> {
        let v = self.expr(e, Some(&Ty::Scalar(Scalar::Usize)))?;
        let v = self.deref(v);
        if !self.is_int(&v.ty) {
            return Err(Error::new(e.span(), format!("an index must be an integer, found `{}`", self.resolved(&v.ty))));
        }
        self.unify(&v.ty, &Ty::Scalar(Scalar::Usize));
        Ok(v)
    }

    pub(super) fn struct_lit(&mut self, s: &syn::ExprStruct, want: Option<&Ty>) -> Result<Val> {
        let name = s.path.segments.last().unwrap().ident.to_string();
        let generic = self.generic_struct_lit_type(s, &name, want).transpose()?;
        let ty = match name.as_str() {
            _ if generic.is_some() => generic.unwrap(),
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
            if !in_order && v.effects {
                let t = self.tmp();
                self.emit_let(format!("let {t} = {};", v.code), &v);
                v = Val::new(t, v.ty);
            }
            done.push((idx, v));
        }
        // `..base`, evaluated after the fields as in Rust, once; the
        // fields not written come from it.
        let base = match &s.rest {
            None => None,
            Some(r) => {
                let at = self.here();
                let v = self.struct_base(r, &ty)?;
                self.spill(at, &mut done.iter_mut().map(|(_, v)| v).collect::<Vec<_>>());
                Some(v)
            }
        };
        let mut effects = done.iter().any(|(_, v)| v.effects);
        let mut reads = done.iter().any(|(_, v)| v.reads);
        for (idx, v) in done {
            given[idx] = Some(v.code);
        }
        if let Some(b) = base {
            effects |= b.effects;
            reads |= b.reads;
            for (i, (f, _)) in fields.iter().enumerate() {
                if given[i].is_none() {
                    given[i] = Some(self.field_of(b.clone(), f, s.span())?.code);
                }
            }
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
        Ok(Val::new(format!("{}({})", ty.wgsl(), args.join(", ")), ty).with_effects(effects).with_reads(reads))
    }

    /// The base of `S { .., ..base }`: `Default::default()` or
    /// `S::default()` as the zero value (what the `Default` the struct's
    /// attribute derives gives), anything else evaluated once into a
    /// local.
    fn struct_base(&mut self, r: &Expr, ty: &Ty) -> Result<Val> {
        if let Expr::Call(c) = strip_parens(r)
            && c.args.is_empty()
            && let Expr::Path(p) = &*c.func
            && let [owner, f] = p.path.segments.iter().map(|s| s.ident.to_string()).collect::<Vec<_>>().as_slice()
            && f == "default"
        {
            // An instance of a generic struct (`Pair<f32>`) is named bare
            // (`Pair::default()`, `Pair::<f32>::default()`), its
            // `Default` derived over its parameters' own.
            match ty {
                Ty::Struct(d) if d.generic.is_some() && owner == "Default" => {
                    return self.default_of(ty.clone(), r.span());
                }
                Ty::Struct(d) if d.generic.is_some() && owner == d.impl_name() => {
                    let v = self.expr(r, Some(ty))?;
                    return self.coerce(v, ty, r.span());
                }
                _ if owner == "Default" || *owner == ty.to_string() => {
                    return Ok(Val::new(format!("{}()", ty.wgsl()), ty.clone()));
                }
                _ => {}
            }
        }
        let v = self.expr(r, Some(ty))?;
        let v = self.deref(v);
        let v = self.coerce(v, ty, r.span())?;
        let t = self.tmp();
        self.emit_let(format!("let {t} = {};", v.code), &v);
        Ok(Val::new(t, v.ty).with_reads(v.reads))
    }

    pub(super) fn array_lit(&mut self, a: &syn::ExprArray, want: Option<&Ty>) -> Result<Val> {
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
        let effects = vals.iter().any(|v| v.effects);
        let reads = vals.iter().any(|v| v.reads);
        let codes: Vec<String> = vals.into_iter().map(|v| v.code).collect();
        let ty = Ty::Array(Box::new(elem_want.unwrap()), codes.len() as u32);
        Ok(Val::new(format!("{}({})", ty.wgsl(), codes.join(", ")), ty).with_effects(effects).with_reads(reads))
    }

    pub(super) fn repeat_lit(&mut self, r: &syn::ExprRepeat, want: Option<&Ty>) -> Result<Val> {
        let n = crate::lower::resolve::array_len(&r.len)?;
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
            v
        } else {
            let t = self.tmp();
            self.emit_let(format!("let {t} = {};", v.code), &v);
            Val::new(t, v.ty)
        };
        let parts = vec![value.code; n as usize];
        let code = format!("{}({})", ty.wgsl(), parts.join(", "));
        Ok(Val::new(code, ty).with_effects(value.effects).with_reads(value.reads))
    }
}

pub(super) fn strip_parens(e: &Expr) -> &Expr {
    match e {
        Expr::Paren(p) => strip_parens(&p.expr),
        Expr::Group(g) => strip_parens(&g.expr),
        e => e,
    }
}

fn transform_kind(name: &str, span: Span) -> Result<Val> {
    match name {
        "ObjectToWorld" => Ok(Val::new("0u", Ty::TransformKind)),
        "WorldToObject" => Ok(Val::new("1u", Ty::TransformKind)),
        _ => Err(Error::new(span, format!("no transform kind `{name}` (ObjectToWorld or WorldToObject)"))),
    }
}

fn check_int_range(value: u64, s: Scalar, span: Span) -> Result<()> {
    let max = if s == Scalar::I32 { i32::MAX as u64 } else { u32::MAX as u64 };
    if value > max {
        let hint = if s == Scalar::I32 { "; use `u32` for values up to 4294967295" } else { "" };
        return Err(Error::new(span, format!("literal out of range for `{}`: the largest is {max}{hint}", s.rust())));
    }
    Ok(())
}
