//! Intrinsic calls, typed and lowered from their rows in the contract
//! (`rt-abi`): who may call each, the calls the rows lower alone, and the
//! `Form::Special` ones lowered here by hand (`rt_trace`,
//! `rt_report_intersection`).

use super::*;

impl FnLowerer<'_> {
    pub(super) fn use_intrinsic(&mut self, name: &'static str, span: Span) -> Result<()> {
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

    pub(super) fn intrinsic_call(&mut self, name: &str, args: &[&Expr], span: Span) -> Result<Option<Val>> {
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
                        let code = format!("rt_report_intersection_{}({}, {wgsl})", t.mangle(), a[0].code);
                        Ok(Some(Val::new(code, BOOL).with_effects(true)))
                    }
                    _ => Ok(Some(Val::new(format!("rt_report_intersection({})", a[0].code), BOOL).with_effects(true))),
                }
            }
            "rt_trace" | "rt_trace_with" | "rt_trace_at" => {
                let n = match name {
                    "rt_trace" => 3,
                    "rt_trace_with" => 5,
                    _ => 6,
                };
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
                let (flags, mask, time) = match n {
                    5 => {
                        let fm = self.args_typed(&args[3..], &[U32, U32], span, name)?;
                        (fm[0].code.clone(), fm[1].code.clone(), None)
                    }
                    6 => {
                        let fmt = self.args_typed(&args[3..], &[U32, U32, F32], span, name)?;
                        (fmt[0].code.clone(), fmt[1].code.clone(), Some(fmt[2].code.clone()))
                    }
                    _ => ("0u".to_string(), "255u".to_string(), None),
                };
                // The time travels beside the trace call (whose form every
                // trace shares): the runtime's trace takes it and puts it
                // back to 0.
                if let Some(time) = time {
                    let line = self.mark(span, &format!("rt_set_trace_time({time});"));
                    self.emit(line);
                }
                self.traced.push(pty.clone());
                self.m.trace_types.borrow_mut().insert(pty.wgsl(), pty.clone());
                if self.resume.is_some() {
                    self.trace_site(&pty.mangle(), [&obj[0].code, &ray[0].code, &flags, &mask], &prd, span)?;
                    return Ok(Some(Val::new("", Ty::Unit)));
                }
                let site = text::site(&text::Site::Trace(pty.mangle()));
                let line = format!(
                    "rt_trace_{}{site}({}, {}, {prd}, {flags}, {mask});",
                    pty.mangle(),
                    obj[0].code,
                    ray[0].code
                );
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
    pub(super) fn contract_call(&mut self, name: &str, f: &kinds::WgslFn, args: &[&Expr], span: Span) -> Result<Val> {
        if f.params.is_empty() && !args.is_empty() {
            return Err(Error::new(span, format!("`{name}` takes no arguments")));
        }
        let params: Option<Vec<Ty>> = f.params.iter().map(|(_, t)| abi_ty(*t)).collect();
        let (Some(params), Some(ret)) = (params, abi_ty(f.ret)) else {
            return Err(Error::new(span, format!("`{name}`: its contract row passes a handle by value")));
        };
        let a = self.args_typed(args, &params, span, name)?;
        let call = format!("{}({})", f.name, codes(&a).join(", "));
        match f.ret {
            kinds::AbiTy::Unit => {
                let line = self.mark(span, &format!("{call};"));
                self.emit(line);
                Ok(Val::new("", Ty::Unit))
            }
            // `rt_potential_intersection` may accept a hit, which a later
            // operand would see.
            _ => Ok(Val::new(call, ret)
                .with_effects(any_effects(&a) || name == "rt_potential_intersection")
                .with_reads(any_reads(&a))),
        }
    }
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
        A::UVec3 => Ty::Vec(3, Scalar::U32),
        A::Vec2 => Ty::vec(2),
        A::Vec3 => Ty::vec(3),
        A::Vec4 => Ty::vec(4),
        A::Mat4 => Ty::Mat(4),
        A::Ray => Ty::Ray,
        A::TransformKind => Ty::TransformKind,
        A::Buffer | A::Sampler | A::Sampler3d => return None,
    })
}
