//! Type aliases: `#[rt_type] type Brdf = Vec3;` beside the items, and
//! `type Brdf = Vec3;` in a function's body. The lowering never sees an
//! alias: before it types anything, each use is replaced by the type the
//! alias stands for, its parameters substituted (`type Pairs<T> =
//! Pair<T>;` makes `Pairs<f32>` `Pair<f32>`), in types and before `::` or
//! `{` in expressions and patterns (`Brdf::ZERO`, `Brdf::new(..)`, `P {
//! .. }`), where rustc reads an alias too. The CPU copy is the code as
//! written.
//!
//! An alias declared in a block holds in that block, as Rust's items do
//! (its functions declared in the block see it too).

use crate::Item;
use crate::error::{Error, Errors};
use std::collections::HashMap;
use syn::spanned::Spanned;
use syn::visit_mut::VisitMut;

/// How deep aliases of aliases may go before the rewrite calls it a cycle
/// (rustc refuses a cycle too; this keeps the macro from looping on one).
const MAX_DEPTH: u32 = 32;

/// An alias's type parameters and the type it stands for.
#[derive(Clone)]
struct Alias {
    params: Vec<syn::Ident>,
    ty: syn::Type,
}

/// The shape an alias of ray programs has: type parameters only (a
/// lifetime or a const parameter is refused, naming what to write).
pub fn check(t: &syn::ItemType) -> Result<(), Error> {
    for p in &t.generics.params {
        match p {
            syn::GenericParam::Type(_) => {}
            syn::GenericParam::Lifetime(l) => {
                return Err(Error::unsupported(
                    l.span(),
                    "a lifetime parameter of a type alias",
                    "ray programs have no references; drop it",
                ));
            }
            syn::GenericParam::Const(c) => {
                return Err(Error::unsupported(
                    c.span(),
                    "a const parameter of a type alias",
                    "write the array type with its length where it is used",
                ));
            }
        }
    }
    Ok(())
}

/// Whether a unit has an alias to replace: among `deps`, or declared in
/// the body of its entry (`entry_body`, where the entry is a function) or
/// of a dependency. Where it has none, the common case, [`resolve`] and
/// its copies are not needed.
pub fn needed(entry_body: Option<&syn::Block>, deps: &[Item]) -> bool {
    deps.iter().any(|d| matches!(d, Item::Alias(_)) || has_local_alias(d))
        || entry_body.is_some_and(|b| {
            let mut f = FindAlias(false);
            syn::visit::Visit::visit_block(&mut f, b);
            f.0
        })
}

/// `item` (a unit's entry) and `deps` with every alias replaced by what it
/// stands for, and the aliases left out of `deps`.
pub fn resolve(mut item: Item, deps: &[Item]) -> Result<(Item, Vec<Item>), Errors> {
    let module: HashMap<String, Alias> = deps
        .iter()
        .filter_map(|d| match d {
            Item::Alias(t) => Some((
                t.ident.to_string(),
                Alias { params: t.generics.type_params().map(|p| p.ident.clone()).collect(), ty: (*t.ty).clone() },
            )),
            _ => None,
        })
        .collect();
    let mut r = Rewriter { scopes: vec![module], depth: 0, errors: Errors::default() };
    r.item(&mut item);
    let mut rewritten = Vec::new();
    for d in deps {
        if matches!(d, Item::Alias(_)) {
            continue;
        }
        let mut d = d.clone();
        r.item(&mut d);
        rewritten.push(d);
    }
    if !r.errors.is_empty() {
        return Err(r.errors);
    }
    Ok((item, rewritten))
}

/// Whether a function or method of `item` declares an alias in its body.
fn has_local_alias(item: &Item) -> bool {
    let mut f = FindAlias(false);
    match item {
        Item::Function(g) => syn::visit::Visit::visit_block(&mut f, &g.block),
        Item::Impl(i) => syn::visit::Visit::visit_item_impl(&mut f, i),
        Item::Trait(t) => syn::visit::Visit::visit_item_trait(&mut f, t),
        _ => {}
    }
    f.0
}

/// Whether a visit met a `type` item.
struct FindAlias(bool);

impl<'ast> syn::visit::Visit<'ast> for FindAlias {
    fn visit_item_type(&mut self, _: &'ast syn::ItemType) {
        self.0 = true;
    }
}

/// The rewrite: a stack of scopes, the module's aliases at the bottom and
/// each block's above it.
struct Rewriter {
    scopes: Vec<HashMap<String, Alias>>,
    depth: u32,
    errors: Errors,
}

impl Rewriter {
    fn item(&mut self, item: &mut Item) {
        match item {
            Item::Struct(s, _) => self.visit_item_struct_mut(s),
            Item::Function(f) => self.visit_item_fn_mut(f),
            Item::Const(c) => self.visit_item_const_mut(c),
            Item::Enum(e) => self.visit_item_enum_mut(e),
            Item::Impl(i) => self.visit_item_impl_mut(i),
            Item::Trait(t) => self.visit_item_trait_mut(t),
            Item::Alias(_) => {}
        }
    }

    fn lookup(&self, name: &syn::Ident) -> Option<&Alias> {
        let name = name.to_string();
        self.scopes.iter().rev().find_map(|s| s.get(&name))
    }

    /// The type `path` (an alias's name and arguments) stands for, or
    /// `None` where its last segment names no alias.
    fn expand(&mut self, path: &syn::Path) -> Option<syn::Type> {
        let last = path.segments.last()?;
        let alias = self.lookup(&last.ident)?.clone();
        let args: Vec<syn::Type> = match &last.arguments {
            syn::PathArguments::AngleBracketed(a) => a
                .args
                .iter()
                .filter_map(|g| match g {
                    syn::GenericArgument::Type(t) => Some(t.clone()),
                    _ => None,
                })
                .collect(),
            _ => Vec::new(),
        };
        if args.len() != alias.params.len() {
            self.errors.0.push(Error::new(
                last.span(),
                format!(
                    "the type alias `{}` takes {} type argument{}, and {} {} given",
                    last.ident,
                    alias.params.len(),
                    if alias.params.len() == 1 { "" } else { "s" },
                    args.len(),
                    if args.len() == 1 { "is" } else { "are" },
                ),
            ));
            return None;
        }
        let mut ty = alias.ty;
        if !args.is_empty() {
            let map: HashMap<String, syn::Type> = alias.params.iter().map(|p| p.to_string()).zip(args).collect();
            Substitute(&map).visit_type_mut(&mut ty);
        }
        Some(ty)
    }

    /// `ty` with the aliases in it (those the expansion brought) replaced,
    /// or an error at `span` when aliases of aliases go too deep.
    fn nested(&mut self, ty: &mut syn::Type, span: proc_macro2::Span) {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            self.errors.0.push(Error::new(span, "this type alias stands for itself, through other aliases"));
        } else {
            self.visit_type_mut(ty);
        }
        self.depth -= 1;
    }

    /// A path in an expression or a pattern whose owner (the segment before
    /// the last, or the whole path of a struct literal or pattern where
    /// `whole`) is an alias: the owner replaced by the type's path, its
    /// arguments as a turbofish.
    fn value_path(&mut self, path: &mut syn::Path, whole: bool) {
        let n = path.segments.len();
        let owner_len = if whole { n } else { n.saturating_sub(1) };
        if owner_len == 0 {
            return;
        }
        let owner = syn::Path {
            leading_colon: path.leading_colon,
            segments: path.segments.iter().take(owner_len).cloned().collect(),
        };
        let span = owner.span();
        let Some(mut ty) = self.expand(&owner) else { return };
        self.nested(&mut ty, span);
        let syn::Type::Path(tp) = ty else {
            self.errors.0.push(Error::unsupported(
                span,
                "an alias of this type before `::` or `{`",
                "name the type the alias stands for",
            ));
            return;
        };
        if tp.qself.is_some() {
            return;
        }
        let mut new = tp.path;
        for seg in new.segments.iter_mut() {
            if let syn::PathArguments::AngleBracketed(a) = &mut seg.arguments {
                a.colon2_token = Some(Default::default());
            }
        }
        for seg in path.segments.iter().skip(owner_len) {
            new.segments.push(seg.clone());
        }
        *path = new;
    }
}

impl VisitMut for Rewriter {
    fn visit_type_mut(&mut self, t: &mut syn::Type) {
        if let syn::Type::Path(p) = t
            && p.qself.is_none()
        {
            let span = p.span();
            if let Some(mut ty) = self.expand(&p.path) {
                self.nested(&mut ty, span);
                *t = ty;
                return;
            }
        }
        syn::visit_mut::visit_type_mut(self, t);
    }

    fn visit_block_mut(&mut self, b: &mut syn::Block) {
        let mut scope = HashMap::new();
        b.stmts.retain(|s| match s {
            syn::Stmt::Item(syn::Item::Type(t)) => {
                if let Err(e) = check(t) {
                    self.errors.0.push(e);
                }
                scope.insert(
                    t.ident.to_string(),
                    Alias { params: t.generics.type_params().map(|p| p.ident.clone()).collect(), ty: (*t.ty).clone() },
                );
                false
            }
            _ => true,
        });
        self.scopes.push(scope);
        syn::visit_mut::visit_block_mut(self, b);
        self.scopes.pop();
    }

    fn visit_expr_path_mut(&mut self, e: &mut syn::ExprPath) {
        if e.qself.is_none() {
            self.value_path(&mut e.path, false);
        }
        syn::visit_mut::visit_expr_path_mut(self, e);
    }

    fn visit_expr_struct_mut(&mut self, e: &mut syn::ExprStruct) {
        if e.qself.is_none() {
            self.value_path(&mut e.path, true);
        }
        syn::visit_mut::visit_expr_struct_mut(self, e);
    }

    fn visit_pat_struct_mut(&mut self, p: &mut syn::PatStruct) {
        if p.qself.is_none() {
            self.value_path(&mut p.path, true);
        }
        syn::visit_mut::visit_pat_struct_mut(self, p);
    }

    fn visit_pat_tuple_struct_mut(&mut self, p: &mut syn::PatTupleStruct) {
        // `K::Variant(..)`: never the alias alone (Rust has no tuple
        // constructor through an alias).
        if p.qself.is_none() {
            self.value_path(&mut p.path, false);
        }
        syn::visit_mut::visit_pat_tuple_struct_mut(self, p);
    }

    fn visit_item_impl_mut(&mut self, i: &mut syn::ItemImpl) {
        // The impl's own type and trait are its key (`methods`), as
        // written; what its items name is rewritten.
        for it in &mut i.items {
            self.visit_impl_item_mut(it);
        }
    }
}

/// Replaces an alias's type parameters by its arguments.
struct Substitute<'a>(&'a HashMap<String, syn::Type>);

impl VisitMut for Substitute<'_> {
    fn visit_type_mut(&mut self, t: &mut syn::Type) {
        if let syn::Type::Path(p) = t
            && p.qself.is_none()
            && p.path.segments.len() == 1
            && let Some(arg) = self.0.get(&p.path.segments[0].ident.to_string())
        {
            *t = arg.clone();
            return;
        }
        syn::visit_mut::visit_type_mut(self, t);
    }
}
