//! Calls through a callable id, `shade.call(n, l)`: the arguments checked
//! against the id's signature and passed to the signature's dispatch
//! function, whose stub the module's prelude declares and whose `switch`
//! the linker writes. And ids made in a program: `Callable::NONE`,
//! `Callable::from_id(id)` (an id read as a `u32`, from a buffer or
//! arithmetic), `Callable::default()`, their signature from the turbofish
//! (`Callable::<fn(u32) -> u32>::NONE`) or the place they go.

use super::*;
use crate::types::CallSig;
use std::rc::Rc;

impl FnLowerer<'_> {
    pub(super) fn callable_call(
        &mut self,
        recv: Val,
        sig: &Rc<CallSig>,
        name: &str,
        args: &[&Expr],
        name_span: Span,
        span: Span,
    ) -> Result<Val> {
        let ty = Ty::Callable(sig.clone());
        if name != "call" {
            return Err(Error::new(name_span, format!("no method `{name}` on `{ty}` in ray programs (it has `call`)")));
        }
        if self.kind() == Some(Kind::BoundingBox) {
            return Err(Error::new(
                name_span,
                "a bounding_box program cannot call callable programs: it runs at build time, outside any launch",
            ));
        }
        if args.len() != sig.params.len() {
            let n = sig.params.len();
            return Err(Error::new(
                name_span,
                format!("`{ty}` takes {n} argument{}, found {}", if n == 1 { "" } else { "s" }, args.len()),
            ));
        }
        let mut vals = vec![recv];
        for (a, p) in args.iter().zip(&sig.params) {
            let at = self.here();
            let v = self.expr(a, Some(p))?;
            let v = self.deref(v);
            let v = self.coerce(v, p, a.span())?;
            self.spill(at, &mut vals.iter_mut().collect::<Vec<_>>());
            vals.push(v);
        }
        let dispatch = sig.dispatch();
        self.m.call_types.borrow_mut().insert(dispatch.clone(), sig.clone());
        let site = text::site(&text::Site::Dispatch(dispatch.clone()));
        let code = format!("{dispatch}{site}({})", codes(&vals).join(", "));
        if matches!(sig.ret, Ty::Unit) {
            let line = self.mark(span, &format!("{code};"));
            self.emit(line);
            return Ok(Val::new("", Ty::Unit));
        }
        // A callable may write buffers and raise: its result is taken here,
        // in evaluation order.
        let t = self.tmp();
        let line = self.mark(span, &format!("let {t} = {code};"));
        self.emit(line);
        Ok(Val::new(t, sig.ret.clone()))
    }
}

/// Whether `path` names an item of `Callable` (`Callable::NONE`,
/// `Callable::<F>::from_id`).
pub(super) fn is_callable_item(path: &syn::Path) -> bool {
    path.segments.len() == 2 && path.segments[0].ident == "Callable"
}

impl FnLowerer<'_> {
    /// `Callable::NONE` or `Callable::from_id(id)` (`args` for a call), of
    /// the signature the turbofish names or else the one `want` is.
    pub(super) fn callable_item(
        &mut self,
        path: &syn::Path,
        args: Option<&[&Expr]>,
        want: Option<&Ty>,
        span: Span,
    ) -> Result<Val> {
        let (owner, item) = (&path.segments[0], &path.segments[1]);
        let name = item.ident.to_string();
        if !item.arguments.is_none() {
            return Err(Error::unsupported(
                item.arguments.span(),
                "generic arguments here",
                "write `Callable::<F>::..`",
            ));
        }
        let ty = if owner.arguments.is_none() {
            match want {
                Some(t @ Ty::Callable(_)) => t.clone(),
                _ => {
                    let call = if args.is_some() { format!("{name}(..)") } else { name.clone() };
                    return Err(Error::new(
                        owner.ident.span(),
                        format!(
                            "the signature of `Callable::{call}` is not known here: name it \
                             (`Callable::<fn(u32) -> u32>::{call}`) or bind it first \
                             (`let f: Callable<fn(u32) -> u32> = Callable::{call};`)"
                        ),
                    ));
                }
            }
        } else {
            let owner_type = syn::Type::Path(syn::TypePath { qself: None, path: syn::Path::from(owner.clone()) });
            self.resolve_type(&owner_type)?
        };
        match (name.as_str(), args) {
            ("NONE", None) => Ok(Val::new("0u", ty)),
            ("default", Some([])) => Ok(Val::new("0u", ty)),
            ("from_id", Some(args)) => {
                let a = self.args_typed(args, &[U32], span, "Callable::from_id")?;
                let v = &a[0];
                Ok(Val::new(v.code.clone(), ty).with_effects(v.effects).with_reads(v.reads))
            }
            _ => Err(Error::new(
                item.ident.span(),
                format!(
                    "no {} `{name}` on `{ty}` in ray programs (it has `NONE`, `from_id(id)` and `default()`)",
                    if args.is_some() { "associated function" } else { "associated constant" }
                ),
            )),
        }
    }
}
