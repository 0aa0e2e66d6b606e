//! Iterator loops and reductions over ranges and fixed arrays, as counted
//! loops: `for x in arr`, `.iter()`, `.rev()`, `.step_by(n)`,
//! `.enumerate()`, `.zip(..)`, `.map(..)`, `.filter(..)`, and `.sum()`,
//! `.product()`, `.fold(..)`, `.any(..)`, `.all(..)`, `.count()` at the end
//! of a chain. Closures passed to the adaptors are inlined where they are
//! called, so they never escape.
//!
//! A chain is a [`Seq`]: statements that set it up, how many elements it
//! has, and element `k` as an expression of a counter `k`; each adaptor
//! makes a new `Seq` of the one before (`rev` reads element `n - 1 - k`,
//! `step_by(s)` element `k * s`, `enumerate` pairs `k` with element `k`).
//! A `filter` cannot be counted ahead, so it comes after every adaptor
//! that reorders or numbers the elements (its test is a `continue` in the
//! loop), followed only by `map`s and `filter`s.

use super::Rewriter;
use proc_macro2::Span;
use syn::spanned::Spanned;
use syn::{Expr, parse_quote_spanned};

/// Element `k` of a sequence, as an expression of the counter `k`.
pub(super) type Element = Box<dyn Fn(Expr) -> Expr>;

/// What runs on an element after the counted part of a chain: a `filter`
/// test, or a `map` after one.
enum After {
    Filter(syn::ExprClosure),
    Map(syn::ExprClosure),
}

/// A chain's counted loop ([`Rewriter::chain_loop`]).
pub(super) struct ChainLoop {
    pub setup: Vec<syn::Stmt>,
    pub count: Expr,
    /// Sets the value to element `k`, or `continue`s past a filtered one.
    pub body: Vec<syn::Stmt>,
    /// Element `k` as an expression, where nothing follows the counted part.
    pub element: Option<Element>,
}

/// A chain as a counted sequence (see the module's doc).
struct Seq {
    setup: Vec<syn::Stmt>,
    count: Expr,
    element: Element,
    after: Vec<After>,
    /// A range's own integers, no adaptor between: a sum starts at `0`.
    integers: bool,
    /// An array's elements (at least one: WGSL has no empty array): a sum
    /// starts at the first.
    nonempty: bool,
}

impl Rewriter {
    /// `for PAT in CHAIN BODY` as a counted loop; `None` for a plain range
    /// (the lowering's own loop) or what is not a chain.
    pub(super) fn for_loop(&mut self, f: &syn::ExprForLoop) -> Option<Expr> {
        if is_range(&f.expr) {
            return None;
        }
        let span = f.for_token.span;
        let seq = self.chain(&f.expr, true)?;
        let k = self.fresh("k", span);
        let value = self.fresh("v", span);
        let mut body = self.element_stmts(&seq, &k, &value);
        let pat = without_refs(&f.pat);
        body.push(parse_quote_spanned! {span=> let #pat = #value; });
        body.extend(f.body.stmts.iter().cloned());
        let Seq { setup, count, .. } = seq;
        let label = &f.label;
        Some(parse_quote_spanned! {span=>
            {
                #(#setup)*
                #label for #k in 0..#count {
                    #(#body)*
                }
            }
        })
    }

    /// `CHAIN.sum()` and the other reductions as a loop in a block; `None`
    /// for any other method call.
    pub(super) fn reduction(&mut self, m: &syn::ExprMethodCall) -> Option<Expr> {
        let name = m.method.to_string();
        if !matches!(name.as_str(), "sum" | "product" | "fold" | "any" | "all" | "count") {
            return None;
        }
        let span = m.method.span();
        let seq = self.chain(&m.receiver, false)?;
        let k = self.fresh("k", span);
        let value = self.fresh("v", span);
        let acc = self.fresh("acc", span);
        let args: Vec<&Expr> = m.args.iter().collect();
        let (init, step, first): (Expr, Vec<syn::Stmt>, bool) = match (name.as_str(), args.as_slice()) {
            ("sum" | "product", []) => {
                let sum = name == "sum";
                let op: syn::BinOp =
                    if sum { parse_quote_spanned!(span=> +=) } else { parse_quote_spanned!(span=> *=) };
                let step = vec![parse_quote_spanned! {span=> #acc #op #value; }];
                if let Some(init) = m.turbofish.as_ref().and_then(|t| identity(t, sum)) {
                    (init, step, false)
                } else if seq.integers {
                    let init: Expr = if sum { parse_quote_spanned!(span=> 0) } else { parse_quote_spanned!(span=> 1) };
                    (init, step, false)
                } else if seq.nonempty && seq.after.is_empty() {
                    ((seq.element)(parse_quote_spanned!(span=> 0)), step, true)
                } else {
                    return None;
                }
            }
            ("fold", [init, f]) => {
                let Expr::Closure(c) = f else { return None };
                let folded = inline(c, vec![parse_quote_spanned!(span=> #acc), parse_quote_spanned!(span=> #value)])?;
                ((*init).clone(), vec![parse_quote_spanned! {span=> #acc = #folded; }], false)
            }
            ("any" | "all", [f]) => {
                let Expr::Closure(c) = f else { return None };
                let test = inline(c, vec![parse_quote_spanned!(span=> #value)])?;
                let step = if name == "any" {
                    parse_quote_spanned! {span=> if #test { #acc = true; break; } }
                } else {
                    parse_quote_spanned! {span=> if !(#test) { #acc = false; break; } }
                };
                let init: Expr =
                    if name == "any" { parse_quote_spanned!(span=> false) } else { parse_quote_spanned!(span=> true) };
                (init, vec![step], false)
            }
            ("count", []) => {
                (parse_quote_spanned!(span=> 0usize), vec![parse_quote_spanned! {span=> #acc += 1usize; }], false)
            }
            _ => return None,
        };
        let mut body = self.element_stmts(&seq, &k, &value);
        body.extend(step);
        let Seq { setup, count, .. } = seq;
        let start: Expr = if first { parse_quote_spanned!(span=> 1) } else { parse_quote_spanned!(span=> 0) };
        Some(parse_quote_spanned! {span=>
            {
                #(#setup)*
                let mut #acc = #init;
                for #k in #start..#count {
                    #(#body)*
                }
                #acc
            }
        })
    }

    /// The statements that set `value` to element `k`, with the filters'
    /// `continue`s and the maps after them.
    fn element_stmts(&mut self, seq: &Seq, k: &syn::Ident, value: &syn::Ident) -> Vec<syn::Stmt> {
        let span = k.span();
        let first = (seq.element)(parse_quote_spanned!(span=> #k));
        let mut stmts: Vec<syn::Stmt> = vec![parse_quote_spanned! {span=> let #value = #first; }];
        for a in &seq.after {
            match a {
                After::Filter(c) => {
                    // `inline` succeeded when the chain was read.
                    if let Some(test) = inline(c, vec![parse_quote_spanned!(span=> #value)]) {
                        stmts.push(parse_quote_spanned! {span=> if !(#test) { continue; } });
                    }
                }
                After::Map(c) => {
                    if let Some(mapped) = inline(c, vec![parse_quote_spanned!(span=> #value)]) {
                        stmts.push(parse_quote_spanned! {span=> let #value = #mapped; });
                    }
                }
            }
        }
        stmts
    }

    /// Whether `e` is an iterator chain this file takes (not a bare array).
    pub(super) fn is_chain(&mut self, e: &Expr) -> bool {
        self.chain(e, false).is_some()
    }

    /// The counted loop over the chain `e`, for the reductions other files
    /// write (`options.rs`): its setup, its count, the statements that set
    /// `value` to element `k` (or `continue` past a filtered one), and
    /// element `k` itself where no filter or map comes after the counted
    /// part.
    pub(super) fn chain_loop(&mut self, e: &Expr, k: &syn::Ident, value: &syn::Ident) -> Option<ChainLoop> {
        let seq = self.chain(e, false)?;
        let body = self.element_stmts(&seq, k, value);
        let Seq { setup, count, element, after, .. } = seq;
        let element = after.is_empty().then_some(element);
        Some(ChainLoop { setup, count, body, element })
    }

    /// The sequence `e` yields, if it is a chain: a range, an array
    /// (`arr`, `&arr`, `arr.iter()`; a bare expression only where `for`
    /// takes it, `bare`), and adaptors after it.
    fn chain(&mut self, e: &Expr, bare: bool) -> Option<Seq> {
        let e = unparen(e);
        let span = e.span();
        if let Expr::Range(r) = e {
            return self.range(r);
        }
        if let Expr::Reference(r) = e
            && r.mutability.is_none()
        {
            return Some(self.array(&r.expr));
        }
        let Expr::MethodCall(m) = e else { return bare.then(|| self.array(e)) };
        let args: Vec<&Expr> = m.args.iter().collect();
        let name = m.method.to_string();
        if matches!(name.as_str(), "iter" | "into_iter") && args.is_empty() {
            let inner = unparen(&m.receiver);
            return match inner {
                Expr::Range(r) => self.range(r),
                _ => Some(self.array(inner)),
            };
        }
        if matches!(name.as_str(), "copied" | "cloned") && args.is_empty() {
            return self.chain(&m.receiver, false);
        }
        let mut seq = self.chain(&m.receiver, false)?;
        let nonempty = seq.nonempty && matches!(name.as_str(), "rev" | "step_by" | "enumerate" | "map");
        let reorders = matches!(name.as_str(), "rev" | "step_by" | "enumerate" | "zip");
        if reorders && !seq.after.is_empty() {
            // After a `filter`, elements cannot be counted ahead.
            return None;
        }
        match (name.as_str(), args.as_slice()) {
            ("rev", []) => {
                let n = self.fresh("n", span);
                let count = seq.count.clone();
                seq.setup.push(parse_quote_spanned! {span=> let #n = #count; });
                seq.count = parse_quote_spanned!(span=> #n);
                let inner = seq.element;
                seq.element = Box::new(move |k| inner(parse_quote_spanned!(span=> (#n - 1 - #k))));
            }
            ("step_by", [step]) => {
                let (n, s, stepped) = (self.fresh("n", span), self.fresh("step", span), self.fresh("n", span));
                let count = seq.count.clone();
                seq.setup.push(parse_quote_spanned! {span=> let #n = #count; });
                seq.setup.push(parse_quote_spanned! {span=> let #s = #step; });
                seq.setup.push(parse_quote_spanned! {span=>
                    let #stepped = if #n == 0 { 0 } else { (#n - 1) / #s + 1 };
                });
                seq.count = parse_quote_spanned!(span=> #stepped);
                let inner = seq.element;
                seq.element = Box::new(move |k| inner(parse_quote_spanned!(span=> (#k * #s))));
            }
            ("enumerate", []) => {
                let inner = seq.element;
                seq.element = Box::new(move |k| {
                    let e = inner(k.clone());
                    parse_quote_spanned!(span=> ((#k as usize), #e))
                });
            }
            ("zip", [other]) => {
                let other = self.chain(other, true)?;
                if !other.after.is_empty() {
                    return None;
                }
                let (a, b) = (seq.count.clone(), other.count.clone());
                seq.nonempty = seq.nonempty && other.nonempty;
                seq.setup.extend(other.setup);
                seq.count = parse_quote_spanned!(span=> (#a).min(#b));
                let (left, right) = (seq.element, other.element);
                seq.element = Box::new(move |k| {
                    let (l, r) = (left(k.clone()), right(k));
                    parse_quote_spanned!(span=> (#l, #r))
                });
            }
            ("map", [Expr::Closure(c)]) if inlinable(c, 1) => {
                if seq.after.is_empty() {
                    let (inner, c) = (seq.element, c.clone());
                    seq.element = Box::new(move |k| inline(&c, vec![inner(k)]).expect("inlined above"));
                } else {
                    seq.after.push(After::Map(c.clone()));
                }
            }
            ("filter", [Expr::Closure(c)]) if inlinable(c, 1) => {
                seq.after.push(After::Filter(c.clone()));
            }
            _ => return None,
        }
        seq.integers = false;
        seq.nonempty = if name == "zip" { seq.nonempty } else { nonempty };
        Some(seq)
    }

    /// `a..b` or `a..=b`, both bounds given, as a sequence.
    fn range(&mut self, r: &syn::ExprRange) -> Option<Seq> {
        let (Some(a), Some(b)) = (&r.start, &r.end) else { return None };
        let span = r.span();
        let (s, e) = (self.fresh("start", span), self.fresh("end", span));
        let count: Expr = match r.limits {
            syn::RangeLimits::HalfOpen(_) => parse_quote_spanned!(span=> if #s < #e { #e - #s } else { 0 }),
            syn::RangeLimits::Closed(_) => parse_quote_spanned!(span=> if #s <= #e { #e - #s + 1 } else { 0 }),
        };
        let n = self.fresh("n", span);
        Some(Seq {
            setup: vec![
                parse_quote_spanned! {span=> let #s = #a; },
                parse_quote_spanned! {span=> let #e = #b; },
                parse_quote_spanned! {span=> let #n = #count; },
            ],
            count: parse_quote_spanned!(span=> #n),
            element: Box::new(move |k| parse_quote_spanned!(span=> (#s + #k))),
            after: Vec::new(),
            integers: true,
            nonempty: false,
        })
    }

    /// A fixed array's elements, the array evaluated once (a copy, as
    /// iterating an array by value copies it).
    fn array(&mut self, e: &Expr) -> Seq {
        let span = e.span();
        let a = self.fresh("array", span);
        Seq {
            setup: vec![parse_quote_spanned! {span=> let #a = #e; }],
            count: parse_quote_spanned!(span=> #a.len()),
            element: Box::new(move |k| parse_quote_spanned!(span=> #a[#k])),
            after: Vec::new(),
            integers: false,
            nonempty: true,
        }
    }
}

/// The closure `c` applied to `args`: its parameters bound to them in a
/// block, its body the block's value. `None` where it cannot be inlined:
/// another number of arguments, or a `return` (which would leave the
/// enclosing function).
pub(super) fn inline(c: &syn::ExprClosure, args: Vec<Expr>) -> Option<Expr> {
    if !inlinable(c, args.len()) {
        return None;
    }
    let span = c.or1_token.span;
    let binds: Vec<syn::Stmt> = c
        .inputs
        .iter()
        .zip(args)
        .map(|(p, a)| {
            let p = without_refs(p);
            parse_quote_spanned! {span=> let #p = #a; }
        })
        .collect();
    // Built as a tree, not from tokens: a body that starts with a block
    // (`{ .. } * s`, an inlined call first) would read as a statement.
    let mut stmts = binds;
    stmts.push(syn::Stmt::Expr((*c.body).clone(), None));
    Some(Expr::Block(syn::ExprBlock {
        attrs: Vec::new(),
        label: None,
        block: syn::Block { brace_token: syn::token::Brace(span), stmts },
    }))
}

/// Whether `c` can be inlined with `arity` arguments (see [`inline`]).
fn inlinable(c: &syn::ExprClosure, arity: usize) -> bool {
    c.inputs.len() == arity && !has_return(&c.body)
}

/// `e` without the parentheses around it.
pub(super) fn unparen(e: &Expr) -> &Expr {
    match e {
        Expr::Paren(p) => unparen(&p.expr),
        e => e,
    }
}

fn is_range(e: &Expr) -> bool {
    matches!(unparen(e), Expr::Range(_))
}

/// `pat` with its reference patterns and reference types taken off
/// (`&x` is `x`, `x: &f32` is `x: f32`): elements are values here, and
/// `*x` of a value is the value (see the lowering's `*`).
pub(super) fn without_refs(pat: &syn::Pat) -> syn::Pat {
    struct Strip;
    impl syn::visit_mut::VisitMut for Strip {
        fn visit_pat_mut(&mut self, p: &mut syn::Pat) {
            if let syn::Pat::Reference(r) = p {
                *p = (*r.pat).clone();
            }
            syn::visit_mut::visit_pat_mut(self, p);
        }
        fn visit_type_mut(&mut self, t: &mut syn::Type) {
            if let syn::Type::Reference(r) = t {
                *t = (*r.elem).clone();
            }
            syn::visit_mut::visit_type_mut(self, t);
        }
    }
    let mut p = pat.clone();
    syn::visit_mut::VisitMut::visit_pat_mut(&mut Strip, &mut p);
    p
}

/// Whether `e` has a `return` outside any closure inside it.
fn has_return(e: &Expr) -> bool {
    let mut f = FirstReturn(None);
    syn::visit::Visit::visit_expr(&mut f, e);
    f.0.is_some()
}

/// A visit that finds the first `return` outside the closures it meets
/// (their `return`s leave them): its span.
pub(super) struct FirstReturn(pub(super) Option<proc_macro2::Span>);

impl<'a> syn::visit::Visit<'a> for FirstReturn {
    fn visit_expr_return(&mut self, r: &'a syn::ExprReturn) {
        self.0 = self.0.or(Some(syn::spanned::Spanned::span(r)));
    }
    fn visit_expr_closure(&mut self, _: &'a syn::ExprClosure) {}
}

/// The start of `sum::<T>()` (`sum`) or `product::<T>()` for the scalar or
/// vector type `T`: what Rust's `Sum` and `Product` start from (`-0.0` for
/// a float sum, so that a sum of negative zeros is one).
fn identity(t: &syn::AngleBracketedGenericArguments, sum: bool) -> Option<Expr> {
    let Some(syn::GenericArgument::Type(syn::Type::Path(p))) = t.args.first() else { return None };
    let name = p.path.segments.last()?.ident.to_string();
    let span: Span = p.span();
    let scalar = |zero: &str, one: &str| -> Option<Expr> { syn::parse_str(if sum { zero } else { one }).ok() };
    let e = match name.as_str() {
        "f32" => scalar("-0.0f32", "1.0f32")?,
        "i32" => scalar("0i32", "1i32")?,
        "u32" => scalar("0u32", "1u32")?,
        "usize" => scalar("0usize", "1usize")?,
        v if v.starts_with("Vec") || v.starts_with("IVec") || v.starts_with("UVec") => {
            let ty = syn::Ident::new(v, span);
            if sum { parse_quote_spanned!(span=> #ty::ZERO) } else { parse_quote_spanned!(span=> #ty::ONE) }
        }
        _ => return None,
    };
    Some(e)
}
