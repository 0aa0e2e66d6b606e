//! Bindless buffer ids, `BindlessBuffer<T>` and `RwBindlessBuffer<T>`:
//! reads and writes through an id (`ids.load(i)`, `ids[i]`, `ids.len()`,
//! `ids.store(i, v)`) lowered to the id accessors (`rt_idload_<T>`, ...),
//! which check the id against the launch's buffer table before the bounds
//! check; and ids made in a program, `BindlessBuffer::NONE`,
//! `BindlessBuffer::from_id(id)` and `BindlessBuffer::default()`, their
//! element type from the turbofish or the place they go.

use super::*;
use crate::types::bindless_name;

impl FnLowerer<'_> {
    /// `ids.name(args)` on a bindless id of elements `elem`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn bindless_method(
        &mut self,
        recv: Val,
        writable: bool,
        elem: &Ty,
        name: &str,
        args: &[&Expr],
        name_span: Span,
        span: Span,
    ) -> Result<Val> {
        let ty = Ty::BufferId(writable, Box::new(elem.clone()));
        if name != "id" && name != "read_only" {
            self.check_bindless_caller(name_span)?;
        }
        let want_args = |n: usize| -> Result<()> {
            if args.len() != n {
                Err(Error::new(name_span, format!("`{ty}::{name}` takes {n} argument(s), found {}", args.len())))
            } else {
                Ok(())
            }
        };
        match name {
            "len" | "is_empty" => {
                want_args(0)?;
                let f = self.m.accessors.borrow_mut().bindless_len(writable, elem);
                let len = format!("{f}({})", recv.code);
                let (code, t) = if name == "len" { (len, U32) } else { (format!("({len} == 0u)"), BOOL) };
                Ok(Val::new(code, t).with_effects(true).with_reads(true))
            }
            "id" => {
                want_args(0)?;
                Ok(Val::new(recv.code.clone(), U32).with_effects(recv.effects).with_reads(recv.reads))
            }
            "load" => {
                want_args(1)?;
                self.bindless_load(recv, writable, elem, args[0])
            }
            "read_only" if writable => {
                want_args(0)?;
                Ok(Val::new(recv.code.clone(), Ty::BufferId(false, Box::new(elem.clone())))
                    .with_effects(recv.effects)
                    .with_reads(recv.reads))
            }
            "store" if writable => {
                want_args(2)?;
                let mut idx = self.buffer_index(BufferKind { dims: 1, writable }, args[0])?;
                let at = self.here();
                let v = self.expr(args[1], Some(elem))?;
                let v = self.deref(v);
                let v = self.coerce(v, elem, args[1].span())?;
                self.spill(at, &mut [&mut idx]);
                let f = self.m.accessors.borrow_mut().bindless_store(elem);
                let line = self.mark(span, &format!("{f}({}, {}, {});", recv.code, idx.code, v.code));
                self.emit(line);
                Ok(Val::new("", Ty::Unit))
            }
            "store" => Err(Error::new(
                name_span,
                format!(
                    "cannot store through a read-only `{ty}`: take an `RwBindlessBuffer<{elem}>` (`Context::rw_buffer_id`)"
                ),
            )),
            _ => Err(Error::new(
                name_span,
                format!(
                    "no method `{name}` on `{ty}` in ray programs (it has load, len, is_empty, id{}, and indexing `ids[i]`)",
                    if writable { ", store, read_only" } else { "" }
                ),
            )),
        }
    }

    /// A bounding-box program runs at build time, outside any launch and
    /// its buffer table: it reads no buffer through an id.
    fn check_bindless_caller(&self, span: Span) -> Result<()> {
        if self.kind() == Some(Kind::BoundingBox) {
            return Err(Error::new(
                span,
                "a bounding_box program cannot read buffers through bindless ids: it runs at build time, \
                 outside any launch; take the buffer as a `Buffer<T>` variable",
            ));
        }
        Ok(())
    }

    /// `ids.load(i)` and `ids[i]`.
    pub(super) fn bindless_load(&mut self, recv: Val, writable: bool, elem: &Ty, index: &Expr) -> Result<Val> {
        self.check_bindless_caller(index.span())?;
        let idx = self.buffer_index(BufferKind { dims: 1, writable }, index)?;
        let f = self.m.accessors.borrow_mut().bindless_load(writable, elem);
        let effects = recv.effects || idx.effects;
        Ok(Val::new(format!("{f}({}, {})", recv.code, idx.code), elem.clone()).with_effects(effects).with_reads(true))
    }
}

/// Whether `path` names an item of a bindless id type
/// (`BindlessBuffer::NONE`, `RwBindlessBuffer::<T>::from_id`,
/// `BindlessSampler::<Sampler2d>::default`).
pub(super) fn is_bindless_item(path: &syn::Path) -> bool {
    let owner = path.segments[0].ident.to_string();
    path.segments.len() == 2
        && (crate::types::bindless_kind(&owner).is_some() || owner == crate::types::BINDLESS_SAMPLER)
}

impl FnLowerer<'_> {
    /// `BindlessBuffer::NONE`, `::default()` or `::from_id(id)` (`args` for
    /// a call), of the element type the turbofish names or else the one
    /// `want` has.
    pub(super) fn bindless_item(
        &mut self,
        path: &syn::Path,
        args: Option<&[&Expr]>,
        want: Option<&Ty>,
        span: Span,
    ) -> Result<Val> {
        let (owner, item) = (&path.segments[0], &path.segments[1]);
        let owner_name = owner.ident.to_string();
        let writable = owner_name == bindless_name(true);
        let sampler = owner_name == crate::types::BINDLESS_SAMPLER;
        let (what, example) = if sampler { ("sampler", "Sampler2d") } else { ("element", "Vec3") };
        let name = item.ident.to_string();
        if !item.arguments.is_none() {
            return Err(Error::unsupported(
                item.arguments.span(),
                "generic arguments here",
                &format!("write `{owner_name}::<T>::..`"),
            ));
        }
        let ty = if owner.arguments.is_none() {
            match want {
                Some(t @ Ty::BufferId(w, _)) if *w == writable && !sampler => t.clone(),
                Some(t @ Ty::SamplerId(_)) if sampler => t.clone(),
                _ => {
                    let call = if args.is_some() { format!("{name}(..)") } else { name.clone() };
                    return Err(Error::new(
                        owner.ident.span(),
                        format!(
                            "the {what} type of `{owner_name}::{call}` is not known here: name it \
                             (`{owner_name}::<{example}>::{call}`) or bind it first \
                             (`let b: {owner_name}<{example}> = {owner_name}::{call};`)"
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
                let a = self.args_typed(args, &[U32], span, &format!("{owner_name}::from_id"))?;
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
