//! Values of generic structs built in a function: literals (`Pair { a:
//! 1.0, b: 2.0 }`, `Pair::<f32> { .. }`), tuple-struct calls (`Wrap(1.0,
//! 2.0)`, `Wrap::<f32>(..)`) and `Pair::default()`. The instance built:
//! its arguments from the turbofish, else the type the value is wanted
//! at, else the fields' values (see `lower/generic_structs.rs`).

use super::*;
use crate::lower::generics::{self, GenericArg, Param, ParamKind};
use std::collections::HashMap;

impl FnLowerer<'_> {
    /// The instance of the generic struct `name` the literal `s` builds,
    /// where `name` is one.
    pub(super) fn generic_struct_lit_type(
        &mut self,
        s: &syn::ExprStruct,
        name: &str,
        want: Option<&Ty>,
    ) -> Option<Result<Ty>> {
        self.m.generic_structs.params(name)?;
        let template = self.m.generic_structs.templates[name].clone();
        let last = s.path.segments.last().expect("a path has a segment");
        let mut fields = Vec::new();
        for fv in &s.fields {
            let syn::Member::Named(n) = &fv.member else { continue };
            if let Some(f) = template.fields.iter().find(|f| f.ident.as_ref() == Some(n)) {
                fields.push((&f.ty, &fv.expr));
            }
        }
        let how = format!("`{name}::<..> {{ .. }}`");
        Some(self.generic_struct_instance(name, last, want, &fields, s.path.span(), &how))
    }

    /// The instance of the generic tuple struct the call `Wrap(..)` or
    /// `Wrap::<f32>(..)` builds, where `path` names one that no local
    /// shadows.
    pub(super) fn generic_tuple_struct_type(
        &mut self,
        path: &syn::Path,
        args: &[&Expr],
        want: Option<&Ty>,
    ) -> Option<Result<Ty>> {
        let [seg] = path.segments.iter().collect::<Vec<_>>()[..] else { return None };
        let name = seg.ident.to_string();
        let template = self.m.generic_structs.templates.get(&name)?.clone();
        if !matches!(template.fields, syn::Fields::Unnamed(_)) || self.lookup(&name).is_some() {
            return None;
        }
        let fields: Vec<(&syn::Type, &Expr)> =
            template.fields.iter().map(|f| &f.ty).zip(args.iter().copied()).collect();
        let how = format!("`{name}::<..>(..)`");
        Some(self.generic_struct_instance(&name, seg, want, &fields, path.span(), &how))
    }

    /// `Pair::default()` or `Pair::<f32>::default()` of the generic struct
    /// `owner` (the path's segment before `default`): the instance's zero
    /// value, which is what its derived `Default` gives where every field's
    /// default is zero.
    pub(super) fn generic_struct_default(
        &mut self,
        owner: &syn::PathSegment,
        want: Option<&Ty>,
        span: Span,
    ) -> Result<Val> {
        let name = owner.ident.to_string();
        let how = format!("`{name}::<..>::default()`");
        let ty = self.generic_struct_instance(&name, owner, want, &[], span, &how)?;
        self.default_of(ty, span)
    }

    /// The zero value of the struct `ty` as its `Default`, or the error
    /// where a field's default is not zero.
    pub(super) fn default_of(&mut self, ty: Ty, span: Span) -> Result<Val> {
        if !options::zero_is_default(&ty) {
            return Err(Error::unsupported(
                span,
                &format!("`{ty}::default()`"),
                &format!(
                    "the WGSL default of `{ty}` is all zeros, and the `Default` of one of its fields is not (an enum's \
                     first variant, a matrix's identity): build the value with a literal"
                ),
            ));
        }
        Ok(Val::new(format!("{}()", ty.wgsl()), ty))
    }

    /// The instance of the generic struct `name` that `seg` names (with
    /// its turbofish, if any) and whose `fields` (each the template's
    /// type and the value given for it) are as given, wanted at `want`;
    /// `how` says how to give the arguments.
    fn generic_struct_instance(
        &mut self,
        name: &str,
        seg: &syn::PathSegment,
        want: Option<&Ty>,
        fields: &[(&syn::Type, &Expr)],
        span: Span,
        how: &str,
    ) -> Result<Ty> {
        let params = self.m.generic_structs.params(name).expect("a generic struct");
        if !seg.arguments.is_none() {
            // `Pair::<f32> { .. }`: the type as written.
            let mut seg = seg.clone();
            if let syn::PathArguments::AngleBracketed(a) = &mut seg.arguments {
                a.colon2_token = None;
            }
            let ty: syn::Type = syn::Type::Path(syn::TypePath { qself: None, path: syn::Path::from(seg) });
            return self.m.resolve_type(&ty);
        }
        if let Some(w) = want
            && let Ty::Struct(d) = self.resolved(w)
            && d.generic.as_ref().is_some_and(|(g, _)| g == name)
        {
            return Ok(Ty::Struct(d));
        }
        let ps: Vec<Param> = params.iter().map(|p| Param { name: p.clone(), kind: ParamKind::Type }).collect();
        let mut binds: HashMap<String, (GenericArg, bool)> = HashMap::new();
        for (fty, e) in fields {
            if !generics::mentions(fty, &ps) {
                continue;
            }
            let Some(t) = self.peek_type(e)? else { continue };
            let mut literal = false;
            let t = self.probed_arg(&t, &mut literal);
            generics::bind(fty, &t, &ps, &mut binds, literal);
        }
        let mut args = Vec::new();
        for p in &params {
            match binds.remove(p) {
                Some((GenericArg::Type(t), _)) => args.push(t),
                _ => {
                    let from = if fields.is_empty() { "" } else { " from the fields" };
                    return Err(Error::new(
                        span,
                        format!(
                            "cannot infer the type parameter `{p}` of `{name}`{from}: give it, as in {how}, or the \
                             type of the binding"
                        ),
                    ));
                }
            }
        }
        match self.m.user_type(name, Some(&args), span) {
            Some(t) => t,
            None => unreachable!("`{name}` is a generic struct"),
        }
    }
}
