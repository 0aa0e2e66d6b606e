//! Literals of generic structs (`Pair { a: 1.0, b: 2.0 }`,
//! `Pair::<f32> { .. }`): the instance built, its arguments from the
//! turbofish, else the type the literal is wanted at, else the fields'
//! values (see `lower/generic_structs.rs`).

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
        let params = self.m.generic_structs.params(name)?;
        Some(self.generic_struct_args(s, name, &params, want))
    }

    fn generic_struct_args(
        &mut self,
        s: &syn::ExprStruct,
        name: &str,
        params: &[String],
        want: Option<&Ty>,
    ) -> Result<Ty> {
        let last = s.path.segments.last().expect("a path has a segment");
        if !last.arguments.is_none() {
            // `Pair::<f32> { .. }`: the type as written.
            let mut seg = last.clone();
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
        let template = self.m.generic_structs.templates[name].clone();
        let ps: Vec<Param> = params.iter().map(|p| Param { name: p.clone(), kind: ParamKind::Type }).collect();
        let mut binds: HashMap<String, (GenericArg, bool)> = HashMap::new();
        for fv in &s.fields {
            let syn::Member::Named(n) = &fv.member else { continue };
            let Some(f) = template.fields.iter().find(|f| f.ident.as_ref() == Some(n)) else { continue };
            if !generics::mentions(&f.ty, &ps) {
                continue;
            }
            let Some(t) = self.peek_type(&fv.expr)? else { continue };
            let mut literal = false;
            let t = self.probed_arg(&t, &mut literal);
            generics::bind(&f.ty, &t, &ps, &mut binds, literal);
        }
        let mut args = Vec::new();
        for p in params {
            match binds.remove(p) {
                Some((GenericArg::Type(t), _)) => args.push(t),
                _ => {
                    return Err(Error::new(
                        s.path.span(),
                        format!(
                            "cannot infer the type parameter `{p}` of `{name}` from the fields: give it, as in \
                             `{name}::<..> {{ .. }}`, or the type of the binding"
                        ),
                    ));
                }
            }
        }
        match self.m.user_type(name, Some(&args), s.path.span()) {
            Some(t) => t,
            None => unreachable!("`{name}` is a generic struct"),
        }
    }
}
