//! Calls: methods of builtin types (rows of `builtins`), `Type::f(...)`
//! constructors and UFCS, glam's free functions, `#[rt_function]`
//! helpers (their intrinsics, traces and `&mut` writebacks), and the
//! methods and associated functions of `#[rt_impl]`s, which are helpers
//! whose first parameter is the receiver (see `methods`).

use super::*;

/// The `#[rt_impl]` method a method call names.
enum UserMethod {
    Plain(HelperSig),
    /// A generic method and its key (`Type::name`).
    Generic(std::rc::Rc<syn::ItemFn>, String),
}

impl FnLowerer<'_> {
    pub(super) fn method_call(&mut self, m: &syn::ExprMethodCall, want: Option<&Ty>) -> Result<Val> {
        let name = m.method.to_string();
        let args: Vec<&Expr> = m.args.iter().collect();
        match self.user_method(&m.receiver, &name)? {
            Some(UserMethod::Generic(g, key)) => return self.generic_method_call(&g, &key, m, want),
            Some(UserMethod::Plain(_)) | None if m.turbofish.is_some() => {
                return Err(Error::unsupported(
                    m.turbofish.span(),
                    "generic arguments on a method that is not generic",
                    "only generic #[rt_function]s and generic #[rt_impl] methods take them",
                ));
            }
            Some(UserMethod::Plain(sig)) => return self.user_method_call(&sig, &m.receiver, &args, m.span()),
            None => {}
        }
        if let Some(v) = self.operator_by_name(m, want)? {
            return Ok(v);
        }
        if let Some(v) = self.in_place_method(m, &name)? {
            return Ok(v);
        }
        let recv = self.expr(&m.receiver, None)?;
        let recv = self.deref(recv);
        self.method(recv, &name, &args, m.method.span(), m.span())
    }

    /// The `#[rt_impl]` method `recv.name(..)` calls, if the receiver is a
    /// user type with one of that name. The receiver's type is probed
    /// first only where some method has that name.
    fn user_method(&mut self, recv: &Expr, name: &str) -> Result<Option<UserMethod>> {
        let suffix = format!("::{name}");
        let named = |k: &String| k.ends_with(&suffix);
        if !self.m.helpers.keys().any(named) && !self.m.failed.iter().any(named) && !self.m.generics.keys().any(named) {
            return Ok(None);
        }
        let ty = match self.peek_type(recv)? {
            Some(t) => self.resolved(&t),
            None => return Ok(None),
        };
        let owner = match &ty {
            Ty::Struct(d) => d.impl_name().to_string(),
            Ty::Enum(e) => e.name.clone(),
            _ => return Ok(None),
        };
        let key = crate::methods::member_key(&owner, name);
        if self.m.failed.contains(&key) {
            return Err(Error::silent(recv.span()));
        }
        if let Some(g) = self.m.generics.get(&key) {
            return Ok(Some(UserMethod::Generic(g.clone(), key)));
        }
        Ok(self.m.helpers.get(&key).cloned().map(UserMethod::Plain))
    }

    /// `recv.name(args)` of an `#[rt_impl]` method: a helper call with the
    /// receiver first, borrowed as the method takes it (`&mut self` a
    /// pointer to the place, or to a temporary holding a value that is not
    /// one).
    pub(super) fn user_method_call(&mut self, sig: &HelperSig, recv: &Expr, args: &[&Expr], span: Span) -> Result<Val> {
        if !sig.has_receiver {
            let (ty, name) = sig.name.split_once("::").unwrap_or(("", &sig.name));
            return Err(Error::new(
                span,
                format!("`{name}` is an associated function of `{ty}`, not a method: call it as `{ty}::{name}(..)`"),
            ));
        }
        self.method_calls.push((sig.name.clone(), span));
        let receiver: Expr = match sig.params.first() {
            Some(Ty::Ref(true, _)) => {
                let place = match strip_parens(recv) {
                    Expr::Path(_) | Expr::Field(_) | Expr::Index(_) | Expr::Unary(_) => recv.clone(),
                    other => {
                        // `Sphere::new(..).grow(2.0)`: a temporary, as in Rust.
                        let v = self.expr(other, None)?;
                        let v = self.deref(v);
                        let t = self.fresh("recv");
                        self.emit(format!("var {t} = {};", v.code));
                        let rust = format!("__rt_recv_{t}");
                        self.bind(&rust, Local { wgsl: t, ty: v.ty, var: true });
                        let ident = syn::Ident::new(&rust, other.span());
                        syn::parse_quote_spanned!(other.span()=> #ident)
                    }
                };
                syn::parse_quote_spanned!(recv.span()=> &mut #place)
            }
            _ => recv.clone(),
        };
        let mut all: Vec<&Expr> = vec![&receiver];
        all.extend_from_slice(args);
        self.helper_call(sig, &all, span)
    }

    /// Lowers `recv.name(args)`.
    pub(super) fn method(&mut self, recv: Val, name: &str, args: &[&Expr], name_span: Span, span: Span) -> Result<Val> {
        // `sugar/options.rs`'s marker: the receiver itself if an `Option`,
        // the method the user wrote on anything else.
        let name = match name.strip_prefix("rt_sugar_option_") {
            Some(_) if matches!(self.resolved(&recv.ty), Ty::Option(_)) => return Ok(recv),
            Some(written) => written,
            None => name,
        };
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
            // A fixed array's length: a constant (`usize`, as in Rust).
            Ty::Array(_, n) if name == "len" && args.is_empty() => {
                return Ok(Val::new(format!("{n}u"), Ty::Scalar(Scalar::Usize)).with_effects(recv.effects));
            }
            Ty::Buffer(kind, elem) => return self.buffer_method(recv, *kind, elem, name, args, name_span, span),
            Ty::Sampler => return self.sampler_method(recv, name, args, name_span, span),
            Ty::Sampler3d => return self.sampler3d_method(recv, name, args, name_span),
            Ty::SamplerCube => return self.sampler_cube_method(recv, name, args, name_span),
            Ty::Callable(sig) => return self.callable_call(recv, sig, name, args, name_span, span),
            Ty::BufferId(w, elem) => return self.bindless_method(recv, *w, elem, name, args, name_span, span),
            Ty::SamplerId(shape) => return self.sampler_id_method(recv, shape, name, args, name_span, span),
            Ty::Option(inner) => return self.option_method(recv, inner, name, args, name_span),
            _ => {}
        }
        let sig = builtins::method_sig(&rt, name).ok_or_else(|| {
            let hint = match &rt {
                Ty::Struct(_) | Ty::Enum(_) => format!(
                    ": the methods programs call are declared in an `#[rt_impl] impl {rt}` block, \
                     with the type declared `(impl)` (as in `#[rt_struct(impl)]`), or in an \
                     `#[rt_impl] impl Trait for {rt}`, with the type declared `(impl Trait)`"
                ),
                _ => builtins::method_hint(&rt, name),
            };
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
        self.builtin_call(&rt, name, sig, vec![recv], args)
    }

    /// A row of `builtins` applied: `vals` the operands already lowered
    /// (a method's receiver, none for an associated function), then
    /// `args` for the rest of `sig.params`.
    fn builtin_call(
        &mut self,
        rt: &Ty,
        name: &str,
        sig: builtins::MethodSig,
        mut vals: Vec<Val>,
        args: &[&Expr],
    ) -> Result<Val> {
        let params = &sig.params[sig.params.len() - args.len()..];
        for (&a, p) in args.iter().zip(params) {
            // glam takes some operands by reference: `m.mul_mat3(&n)`.
            let a = match a {
                Expr::Reference(r) if r.mutability.is_none() => &*r.expr,
                a => a,
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
            "wrapping_add"
                | "wrapping_sub"
                | "wrapping_mul"
                | "dot"
                | "element_sum"
                | "element_product"
                | "saturating_add"
                | "saturating_sub"
                | "saturating_mul"
                | "length_squared"
                | "distance_squared"
                | "manhattan_distance"
                | "chebyshev_distance"
                | "cross"
                | "perp_dot"
                | "rotate"
        );
        if wraps
            && !vals.is_empty()
            && (self.is_int(rt) || matches!(rt, Ty::Vec(_, s) if s.is_int()))
            && vals.iter().all(|v| self.is_const_code(&v.code))
        {
            vals[0] = self.at_run_time(vals[0].clone());
        }
        // A lowering that repeats an operand (`(x - trunc(x))`) must not
        // repeat its side effects: evaluate such operands (and, to keep
        // Rust's left-to-right order, effectful ones before them) once, first.
        // Which operands a row repeats is learnt from the row's own lowering,
        // applied to a probe per operand.
        let probe: Vec<String> = (0..vals.len()).map(|i| format!("\u{6}{i}\u{6}")).collect();
        let shape = (sig.lower)(&probe);
        let last_repeated = (0..vals.len()).rev().find(|&i| shape.matches(&probe[i]).count() > 1 && vals[i].effects);
        if let Some(last) = last_repeated {
            self.once(&mut vals[..=last]);
        }
        // And a repeated operand that is more than a name or a field
        // (`a.cross(b.cross(c))` would repeat `b.cross(c)`'s text six
        // times, and nesting multiplies it) into a `let` too: every operand
        // is valid where the call ends (the loop above spilled them), so
        // there.
        if self.in_function {
            for (i, v) in vals.iter_mut().enumerate() {
                if shape.matches(&probe[i]).count() > 1 && !is_atom(&v.code) {
                    let t = self.tmp();
                    self.emit_let(format!("let {t} = {};", v.code), v);
                    *v = Val::new(t, v.ty.clone()).with_reads(v.reads);
                }
            }
        }
        for (name, text) in sig.support {
            self.m.accessors.borrow_mut().functions.entry(name.to_string()).or_insert_with(|| text.to_string());
        }
        self.m.note_tuples(&sig.ret);
        let effects = any_effects(&vals);
        let reads = any_reads(&vals);
        Ok(Val::new((sig.lower)(&codes(&vals)), sig.ret).with_effects(effects).with_reads(reads))
    }

    /// Evaluates the operands with effects into `let`s, in order.
    pub(super) fn once(&mut self, vals: &mut [Val]) {
        for v in vals {
            if v.effects {
                let t = self.tmp();
                self.emit_let(format!("let {t} = {};", v.code), v);
                *v = Val::new(t, v.ty.clone());
            }
        }
    }

    /// A call that builds a value of a built-in or declared item rather
    /// than calling a function: a callable or bindless id, `Some(..)`, a
    /// tuple struct.
    fn item_call(
        &mut self,
        c: &syn::ExprCall,
        path: &syn::Path,
        args: &[&Expr],
        want: Option<&Ty>,
    ) -> Option<Result<Val>> {
        if callables::is_callable_item(path) {
            return Some(self.callable_item(path, Some(args), want, c.span()));
        }
        if bindless::is_bindless_item(path) {
            return Some(self.bindless_item(path, Some(args), want, c.span()));
        }
        if options::is_some_path(path) && self.lookup("Some").is_none() {
            return Some(self.option_some(c, want));
        }
        let ty = match self.generic_tuple_struct_type(path, args, want) {
            Some(Ok(t)) => t,
            Some(Err(e)) => return Some(Err(e)),
            None => self.tuple_struct_named(path)?,
        };
        Some(self.tuple_struct_lit(&ty, args, c.span()))
    }

    pub(super) fn call(&mut self, c: &syn::ExprCall, want: Option<&Ty>) -> Result<Val> {
        let path = match &*c.func {
            Expr::Path(p) if p.qself.is_none() => &p.path,
            other => {
                return Err(Error::unsupported(other.span(), "calling this expression", "call a function by name"));
            }
        };
        let args: Vec<&Expr> = c.args.iter().collect();
        if let Some(v) = self.item_call(c, path, &args, want) {
            return v;
        }
        let segs: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
        let name = segs.last().unwrap().clone();
        let span = c.span();
        let of_type = segs.len() >= 2 && segs[segs.len() - 2].starts_with(|c: char| c.is_ascii_uppercase());
        // A generic helper, or a generic method by path
        // (`Disc::scaled::<f32>(&d, 2.0)`).
        let key = if of_type { crate::methods::member_key(&segs[segs.len() - 2], &name) } else { name.clone() };
        if (of_type || self.lookup(&name).is_none())
            && let Some(g) = self.m.generics.get(&key).cloned()
        {
            return self.generic_call(&g, &key, path, &args, want, span);
        }
        // `Pair::default()`, `Pair::<f32>::default()` of a generic struct
        // whose impl declares no `default` of its own.
        if let [owner, f] = &path.segments.iter().collect::<Vec<_>>()[..]
            && f.ident == "default"
            && f.arguments.is_none()
            && args.is_empty()
            && self.m.generic_structs.params(&owner.ident.to_string()).is_some()
        {
            return self.generic_struct_default(owner, want, span);
        }
        if let Some(seg) = path.segments.iter().find(|s| !s.arguments.is_none()) {
            return Err(Error::unsupported(
                seg.arguments.span(),
                "generic arguments",
                "only generic #[rt_function]s take them",
            ));
        }

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
        if segs.len() >= 2
            && let Some(v) = self.type_path_call(path, &segs, &args, span)?
        {
            return Ok(v);
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

    /// `Type::function(...)`: constructors and UFCS methods of builtin
    /// types, and an `#[rt_impl]`'s associated functions. `None` where
    /// the owner is none of these.
    fn type_path_call(&mut self, path: &syn::Path, segs: &[String], args: &[&Expr], span: Span) -> Result<Option<Val>> {
        let name = segs.last().unwrap();
        let name_span = path.segments.last().unwrap().ident.span();
        let owner = segs[segs.len() - 2].as_str();
        if let Some(advice) = crate::types::unsupported_type_advice(owner) {
            let owner_span = path.segments[segs.len() - 2].ident.span();
            return Err(Error::unsupported(owner_span, &format!("the type `{owner}`"), advice));
        }
        if let Some(ty) = crate::types::builtin_type(owner) {
            if let Some(v) = self.constructor(&ty, name, args, span)? {
                return Ok(Some(v));
            }
            if name == "default" && args.is_empty() {
                return Ok(Some(Val::new(builtins::zero_value(&ty), ty)));
            }
            // UFCS: `f32::max(a, b)` is `a.max(b)`.
            if let Some((first, rest)) = args.split_first() {
                let recv = self.expr(first, Some(&ty))?;
                let recv = self.deref(recv);
                let recv = self.coerce(recv, &ty, first.span())?;
                return self.method(recv, name, rest, name_span, span).map(Some);
            }
        }
        // `Sphere::new(..)`, `Sphere::area(&s)`: an `#[rt_impl]`'s.
        let key = crate::methods::member_key(owner, name);
        if let Some(sig) = self.m.helpers.get(&key) {
            let sig = sig.clone();
            return self.helper_call(&sig, args, span).map(Some);
        }
        if self.m.failed.contains(&key) {
            return Err(Error::silent(path.span()));
        }
        if let Some(d) = self.m.structs.get(owner)
            && name == "default"
            && args.is_empty()
        {
            let ty = Ty::Struct(d.clone());
            return Ok(Some(Val::new(format!("{}()", ty.wgsl()), ty)));
        }
        if self.m.structs.contains_key(owner) {
            let at = path.segments.last().map_or(path.span(), |s| s.ident.span());
            return Err(Error::new(
                at,
                format!(
                    "no associated function `{name}` on `{owner}` in ray programs: declare it in an \
                     `#[rt_impl] impl {owner}` block (and the struct with `(impl)`)"
                ),
            ));
        }
        Ok(None)
    }

    pub(super) fn args_typed(&mut self, args: &[&Expr], params: &[Ty], span: Span, what: &str) -> Result<Vec<Val>> {
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
        Ok(out)
    }

    pub(super) fn constructor(&mut self, ty: &Ty, name: &str, args: &[&Expr], span: Span) -> Result<Option<Val>> {
        if let Some(sig) = builtins::assoc_fn(ty, name) {
            if args.len() != sig.params.len() {
                let n = sig.params.len();
                return Err(Error::new(
                    span,
                    format!("`{ty}::{name}` takes {n} argument{}, found {}", if n == 1 { "" } else { "s" }, args.len()),
                ));
            }
            return self.builtin_call(ty, name, sig, Vec::new(), args).map(Some);
        }
        match (ty, name) {
            (Ty::Ray, "new") => {
                let params = [Ty::vec(3), Ty::vec(3), U32, F32, F32];
                let a = self.args_typed(args, &params, span, "Ray::new")?;
                Ok(Some(
                    Val::new(format!("RtRay({})", codes(&a).join(", ")), Ty::Ray)
                        .with_effects(any_effects(&a))
                        .with_reads(any_reads(&a)),
                ))
            }
            (Ty::Aabb, "new") => {
                let a = self.args_typed(args, &[Ty::vec(3), Ty::vec(3)], span, "Aabb::new")?;
                Ok(Some(
                    Val::new(format!("RtAabb({})", codes(&a).join(", ")), Ty::Aabb)
                        .with_effects(any_effects(&a))
                        .with_reads(any_reads(&a)),
                ))
            }
            _ => Ok(None),
        }
    }

    pub(super) fn free_builtin(
        &mut self,
        name: &str,
        args: &[&Expr],
        span: Span,
        want: Option<&Ty>,
    ) -> Result<Option<Val>> {
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
            "bvec2" => Some(Ty::Vec(2, Scalar::Bool)),
            "bvec3" => Some(Ty::Vec(3, Scalar::Bool)),
            "bvec4" => Some(Ty::Vec(4, Scalar::Bool)),
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
                let code = format!("select({zero}, {one}, {} >= {})", a[1].code, a[0].code);
                return Ok(Some(Val::new(code, ret).with_effects(any_effects(&a)).with_reads(any_reads(&a))));
            }
            if f == "mix" {
                // rt-std's formula (see `builtins::lerp_formula`); `t` is
                // used twice: once evaluated.
                if a[2].effects {
                    self.once(&mut a);
                }
                let code = builtins::lerp_formula(&a[0].code, &a[1].code, &a[2].code);
                return Ok(Some(Val::new(code, ret).with_effects(any_effects(&a)).with_reads(any_reads(&a))));
            }
            return Ok(Some(
                Val::new(format!("{f}({})", codes(&a).join(", ")), ret)
                    .with_effects(any_effects(&a))
                    .with_reads(any_reads(&a)),
            ));
        }
        self.intrinsic_call(name, args, span)
    }

    pub(super) fn helper_call(&mut self, sig: &HelperSig, args: &[&Expr], span: Span) -> Result<Val> {
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
        self.finish_helper_call(sig, vals, start, span)
    }

    /// A helper call of arguments already lowered (in order, from the
    /// statement index `start`): the intrinsics and traces it brings, the
    /// call, and the `&mut` writebacks after it.
    pub(super) fn finish_helper_call(
        &mut self,
        sig: &HelperSig,
        vals: Vec<Val>,
        start: usize,
        span: Span,
    ) -> Result<Val> {
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
        let site = text::site(&text::Site::Call(sig.wgsl_name.clone()));
        let code = format!("{}{site}({})", sig.wgsl_name, codes.join(", "));
        let writebacks = std::mem::take(&mut self.writebacks);
        if matches!(sig.ret, Ty::Unit) {
            let line = self.mark(span, &format!("{code};"));
            self.emit(line);
            writebacks.into_iter().for_each(|w| self.emit(w));
            Ok(Val::new("", Ty::Unit))
        } else if writebacks.is_empty() {
            // A helper may write through its `&mut` parameters and to buffers.
            Ok(Val::new(code, sig.ret.clone()).with_effects(true))
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

/// Whether lowered code is a name, a literal or a field of one (markers
/// aside): cheap to repeat.
fn is_atom(code: &str) -> bool {
    code.chars().all(|c| c.is_alphanumeric() || c == '_' || c == '.' || (c as u32) < 8)
}
