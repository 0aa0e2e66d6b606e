//! Plain `const` items (no `#[rt_const]`) that a program, helper or impl
//! names, found in its own module.
//!
//! The macros see only the item they are attached to; the chain (see
//! `expand::chain`) hands them what other rt items declare, and a plain
//! `const` declares nothing. So the macro reads the source file it was
//! invoked from (`proc_macro::Span::local_file`, set by `rt-macros` through
//! [`with_source`]), finds the module that declares the item, and takes the
//! plain constants of that module that the item names (and that those
//! name) as definitions of its own, beside what the chain collects; their
//! errors are the item's, and name the constant. The CPU copy names the
//! constant as Rust does.
//!
//! Only the declaring module's own `const` items are seen, as Rust sees
//! them without a `use`: one imported from elsewhere, or one where the
//! file cannot be read (an item a `macro_rules!` writes, an IDE's
//! expansion) still needs `#[rt_const]`, which its error says. Rustc
//! re-expands a file's macros when the file changes, so the constants
//! read are never stale.

use crate::deps::{self, Dep, DepKind};
use proc_macro2::TokenStream;
use quote::quote;
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

thread_local! {
    /// The file of the item being expanded.
    static SOURCE: RefCell<Option<PathBuf>> = const { RefCell::new(None) };
}

/// Runs `f` (a macro's expansion) with `file` as the source file of the
/// item it expands.
pub fn with_source<R>(file: Option<PathBuf>, f: impl FnOnce() -> R) -> R {
    let before = SOURCE.with(|s| s.replace(file));
    let r = f();
    SOURCE.with(|s| *s.borrow_mut() = before);
    r
}

/// Which item a macro expands, to find its module by.
pub enum Owner<'a> {
    /// A function (a program or helper) or `#[rt_const]` of this name.
    Named(&'a str),
    /// An impl block for the type of this name.
    Impl(&'a str),
}

/// Takes out of `deps` the constants that are plain `const` items of the
/// module declaring `owner` (and the plain constants they name in turn,
/// whose other dependencies join `deps`): their definitions, for the
/// chain to start with, and the dependencies left.
pub fn take(owner: Owner<'_>, deps: Vec<Dep>) -> (TokenStream, Vec<Dep>) {
    if !deps.iter().any(|d| d.kind == DepKind::Value) {
        return (TokenStream::new(), deps);
    }
    let Some(file) = SOURCE.with(|s| s.borrow().clone()).and_then(|p| parsed(&p)) else {
        return (TokenStream::new(), deps);
    };
    let mut modules = Vec::new();
    declaring_modules(&file.items, &owner, &mut modules);
    let [items] = modules[..] else { return (TokenStream::new(), deps) };
    let plain: HashMap<String, &syn::ItemConst> = items
        .iter()
        .filter_map(|it| match it {
            syn::Item::Const(c) if !c.attrs.iter().any(is_rt_attribute) => Some((c.ident.to_string(), c)),
            _ => None,
        })
        .collect();
    let mut taken: Vec<syn::ItemConst> = Vec::new();
    let mut left: Vec<Dep> = Vec::new();
    let mut todo = deps;
    todo.reverse();
    while let Some(d) = todo.pop() {
        let found = match (&d.kind, d.path.get_ident()) {
            (DepKind::Value, Some(i)) => plain.get(&i.to_string()),
            _ => None,
        };
        match found {
            Some(c) if !taken.iter().any(|t| t.ident == c.ident) => {
                let mut c = (*c).clone();
                c.attrs.clear();
                todo.extend(deps::of_const(&c).into_iter().rev());
                taken.push(c);
            }
            Some(_) => {}
            None => {
                let key = |p: &syn::Path| quote!(#p).to_string();
                if !left.iter().any(|l| key(&l.path) == key(&d.path)) {
                    left.push(d);
                }
            }
        }
    }
    // Marked, so that the lowering reports their errors with the entry's
    // (no macro of their own reports them).
    let defs = taken.iter().map(|c| quote!(constant { #[rt_plain_const] #c })).collect();
    (defs, left)
}

/// Whether `c` is a plain constant [`take`] found (its mark).
pub fn is_plain(c: &syn::ItemConst) -> bool {
    c.attrs.iter().any(|a| a.path().is_ident("rt_plain_const"))
}

/// `path` parsed; `None` where it cannot be read or parsed. (Not kept
/// between expansions: a tree parsed in one holds the compiler's handles
/// of that one.)
fn parsed(path: &Path) -> Option<syn::File> {
    let text = std::fs::read_to_string(path).ok()?;
    syn::parse_file(&text).ok()
}

/// The item lists of the modules (the file's own, and inline `mod`s in
/// it) that declare `owner` with an rt attribute.
fn declaring_modules<'f>(items: &'f [syn::Item], owner: &Owner<'_>, out: &mut Vec<&'f [syn::Item]>) {
    let declares = items.iter().any(|it| match (it, owner) {
        (syn::Item::Fn(f), Owner::Named(name)) => f.sig.ident == name && f.attrs.iter().any(is_rt_attribute),
        (syn::Item::Const(c), Owner::Named(name)) => c.ident == name && c.attrs.iter().any(is_rt_attribute),
        (syn::Item::Impl(i), Owner::Impl(name)) => {
            crate::methods::self_name(i).as_deref() == Some(*name) && i.attrs.iter().any(is_rt_attribute)
        }
        _ => false,
    });
    if declares {
        out.push(items);
    }
    for it in items {
        if let syn::Item::Mod(m) = it
            && let Some((_, inner)) = &m.content
        {
            declaring_modules(inner, owner, out);
        }
    }
}

/// Whether `a` is one of the project's attributes (`#[rt_program(..)]`,
/// `#[rt_const]`, ...).
fn is_rt_attribute(a: &syn::Attribute) -> bool {
    a.path().segments.last().is_some_and(|s| s.ident.to_string().starts_with("rt_"))
}
