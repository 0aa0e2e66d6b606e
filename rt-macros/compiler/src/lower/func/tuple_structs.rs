//! Tuple structs (`#[rt_struct] struct Rgb(f32, f32, f32);`): a WGSL
//! struct whose fields are `f0`, `f1`, ... (`resolve::wgsl_field`), laid
//! out as a named struct with fields `0`, `1`, ... would be. `Rgb(a, b, c)`
//! builds one; `.0` reads a field (`expr.rs`'s `field_of`); `Rgb(r, g, b)`
//! destructures one in a `let` and in `match` arms (`tuples.rs`). A
//! generic tuple struct (`struct Wrap<T>(T, T);`) is built the same way
//! once its instance is known (`generic_structs.rs`), and its patterns
//! name it bare (`Wrap(a, b)`).

use super::*;

impl FnLowerer<'_> {
    /// The tuple struct a call's path names, if it names one.
    pub(super) fn tuple_struct_named(&self, path: &syn::Path) -> Option<Ty> {
        let name = path.get_ident()?.to_string();
        if self.lookup(&name).is_some() {
            return None;
        }
        let d = self.m.structs.get(&name)?;
        d.is_tuple().then(|| Ty::Struct(d.clone()))
    }

    /// `Rgb(a, b, c)`: the fields in order, then the constructor.
    pub(super) fn tuple_struct_lit(&mut self, ty: &Ty, args: &[&Expr], span: Span) -> Result<Val> {
        let fields = ty.fields();
        if args.len() != fields.len() {
            return Err(Error::new(span, format!("`{ty}` has {} fields, and this gives {}", fields.len(), args.len())));
        }
        let mut vals: Vec<Val> = Vec::new();
        for (a, (_, fty)) in args.iter().zip(&fields) {
            let at = self.here();
            let v = self.expr(a, Some(fty))?;
            let v = self.deref(v);
            let v = self.coerce(v, fty, a.span())?;
            self.spill(at, &mut vals.iter_mut().collect::<Vec<_>>());
            vals.push(v);
        }
        let effects = any_effects(&vals);
        let reads = any_reads(&vals);
        Ok(Val::new(format!("{}({})", ty.wgsl(), codes(&vals).join(", ")), ty.clone())
            .with_effects(effects)
            .with_reads(reads))
    }

    /// The fields a tuple-struct pattern `Rgb(p0, p1, ..)` matches against
    /// the value of type `ty`, each with its WGSL field and type; the error
    /// at a pattern of another struct or of another number of fields.
    pub(super) fn tuple_struct_fields(&self, ts: &syn::PatTupleStruct, ty: &Ty) -> Result<Vec<(String, Ty)>> {
        let named = ts.path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
        let ty = self.resolved(ty);
        let Ty::Struct(d) = &ty else {
            return Err(Error::new(ts.span(), format!("mismatched types: expected `{ty}`, found `{named}`")));
        };
        if d.impl_name() != named || !d.is_tuple() {
            return Err(Error::new(ts.path.span(), format!("mismatched types: expected `{ty}`, found `{named}`")));
        }
        if ts.elems.len() != d.fields.len() {
            return Err(Error::new(
                ts.span(),
                format!("`{named}` has {} fields, and this pattern has {}", d.fields.len(), ts.elems.len()),
            ));
        }
        Ok(d.fields.iter().map(|(n, t)| (crate::lower::resolve::wgsl_field(n), t.clone())).collect())
    }
}
