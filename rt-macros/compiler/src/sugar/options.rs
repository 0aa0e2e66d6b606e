//! `Option`'s methods that take closures, as the `match` each means, the
//! closure inlined in its arm (so it never escapes):
//!
//! ```text
//! o.map(|x| b)             match o { Some(x) => Some(b), None => None }
//! o.and_then(|x| b)        match o { Some(x) => b, None => None }
//! o.filter(|x| b)          match o { Some(v) => if b[x := v] { Some(v) } else { None }, None => None }
//! o.unwrap_or_else(|| d)   match o { Some(v) => v, None => d }
//! o.or_else(|| d)          match o { Some(v) => Some(v), None => d }
//! o.is_some_and(|x| b)     match o { Some(x) => b, None => false }
//! o.is_none_or(|x| b)      match o { Some(x) => b, None => true }
//! o.map_or(d, |x| b)       { let o' = o; let d' = d; match o' { Some(x) => b, None => d' } }
//! o.map_or_else(|| d, |x| b)  match o { Some(x) => b, None => d }
//! ```
//!
//! The reductions of iterator chains that return an `Option` (`.min()`,
//! `.max()`, `.position(..)`, `.find(..)`) are loops that end in
//! `if found { Some(..) } else { None }`.
//!
//! The receiver is not known to be an `Option` here: a method of these
//! names whose receiver is an iterator chain is `iterators.rs`'s; any other
//! receiver is wrapped in a marker method, `rt_sugar_option_<name>()`,
//! which the lowering takes off an `Option` and, on any other type,
//! reports as the method the user wrote (glam's `Vec3::map`, say).

use super::Rewriter;
use super::iterators::{ChainLoop, inline};
use syn::{Expr, parse_quote_spanned};

/// Whether `p` is the path `None` or `Option::None` (the lowering's test
/// too).
pub(crate) fn is_none_path(p: &syn::Path) -> bool {
    variant_path(p, "None")
}

/// Whether `p` is the path `Some` or `Option::Some`.
pub(crate) fn is_some_path(p: &syn::Path) -> bool {
    variant_path(p, "Some")
}

fn variant_path(p: &syn::Path, name: &str) -> bool {
    let segs: Vec<String> = p.segments.iter().map(|s| s.ident.to_string()).collect();
    let segs: Vec<&str> = segs.iter().map(String::as_str).collect();
    matches!(segs.as_slice(), [n] | ["Option", n] | ["std" | "core", "option", "Option", n] if *n == name)
}

impl Rewriter {
    /// `o.map(|x| ..)` and the others above as a `match`; `None` for any
    /// other method call, or one whose closures cannot be inlined.
    pub(super) fn option_closure(&mut self, m: &syn::ExprMethodCall) -> Option<Expr> {
        let name = m.method.to_string();
        let args: Vec<&Expr> = m.args.iter().collect();
        let closure = |e: &Expr| match e {
            Expr::Closure(c) => Some(c.clone()),
            _ => None,
        };
        let known = matches!(
            (name.as_str(), args.len()),
            ("map" | "and_then" | "filter" | "unwrap_or_else" | "or_else" | "is_some_and" | "is_none_or", 1)
                | ("map_or" | "map_or_else", 2)
        );
        if !known || closure(args[args.len() - 1]).is_none() || self.is_chain(&m.receiver) {
            return None;
        }
        let span = m.method.span();
        // The receiver through a marker the lowering takes off an `Option`
        // and reports as the method it stands for on any other type.
        let marker = syn::Ident::new(&format!("rt_sugar_option_{name}"), span);
        let receiver = &m.receiver;
        let recv: Expr = parse_quote_spanned!(span=> #receiver.#marker());
        let v = self.fresh("some", span);
        let value: Expr = parse_quote_spanned!(span=> #v);
        let f = closure(args[args.len() - 1])?;
        let (some, none): (Expr, Expr) = match name.as_str() {
            "map" => {
                let b = inline(&f, vec![value])?;
                (parse_quote_spanned!(span=> Some(#b)), parse_quote_spanned!(span=> None))
            }
            "and_then" => (inline(&f, vec![value])?, parse_quote_spanned!(span=> None)),
            "filter" => {
                let b = inline(&f, vec![value])?;
                (parse_quote_spanned!(span=> if #b { Some(#v) } else { None }), parse_quote_spanned!(span=> None))
            }
            "unwrap_or_else" => (value, inline(&f, vec![])?),
            "or_else" => (parse_quote_spanned!(span=> Some(#v)), inline(&f, vec![])?),
            "is_some_and" => (inline(&f, vec![value])?, parse_quote_spanned!(span=> false)),
            "is_none_or" => (inline(&f, vec![value])?, parse_quote_spanned!(span=> true)),
            "map_or_else" => (inline(&f, vec![value])?, inline(&closure(args[0])?, vec![])?),
            "map_or" => {
                // Rust evaluates the receiver, then the default, then matches.
                let (o, d) = (self.fresh("opt", span), self.fresh("default", span));
                let b = inline(&f, vec![value])?;
                let default = args[0];
                return Some(parse_quote_spanned! {span=>
                    {
                        let #o = #recv;
                        let #d = #default;
                        match #o {
                            Some(#v) => #b,
                            None => #d,
                        }
                    }
                });
            }
            _ => return None,
        };
        Some(parse_quote_spanned! {span=>
            match #recv {
                Some(#v) => #some,
                None => #none,
            }
        })
    }
}

impl Rewriter {
    /// The reductions of an iterator chain that return an `Option`:
    /// `.min()`, `.max()` (of integers: Rust's `Ord`), `.position(..)`
    /// (counting the elements that pass the chain's filters) and
    /// `.find(..)`, as a loop; `None` for any other call, or a chain whose
    /// element cannot be read again (`find` after a `map` or `filter`).
    pub(super) fn option_reduction(&mut self, m: &syn::ExprMethodCall) -> Option<Expr> {
        let name = m.method.to_string();
        let args: Vec<&Expr> = m.args.iter().collect();
        let test = match (name.as_str(), args.as_slice()) {
            ("min" | "max", []) => None,
            ("position" | "find", [Expr::Closure(c)]) => Some(c.clone()),
            _ => return None,
        };
        let span = m.method.span();
        let (k, value) = (self.fresh("k", span), self.fresh("v", span));
        let ChainLoop { setup, count, mut body, element } = self.chain_loop(&m.receiver, &k, &value)?;
        let (found, best, passed) = (self.fresh("found", span), self.fresh("best", span), self.fresh("n", span));
        let (init, result): (Expr, Expr) = match name.as_str() {
            "min" | "max" => {
                // Equal integers are the same value: the first or the last
                // of them is the same answer.
                let better: Expr = if name == "min" {
                    parse_quote_spanned!(span=> #value < #best)
                } else {
                    parse_quote_spanned!(span=> #value >= #best)
                };
                body.push(parse_quote_spanned! {span=> if !#found || #better { #best = #value; } });
                body.push(parse_quote_spanned! {span=> #found = true; });
                (parse_quote_spanned!(span=> 0), parse_quote_spanned!(span=> #best))
            }
            "position" => {
                let t = inline(test.as_ref()?, vec![parse_quote_spanned!(span=> #value)])?;
                body.push(parse_quote_spanned! {span=> if #t { #found = true; #best = #passed; break; } });
                body.push(parse_quote_spanned! {span=> #passed += 1usize; });
                (parse_quote_spanned!(span=> 0usize), parse_quote_spanned!(span=> #best))
            }
            "find" => {
                let element = element?;
                let t = inline(test.as_ref()?, vec![parse_quote_spanned!(span=> #value)])?;
                body.push(parse_quote_spanned! {span=> if #t { #found = true; #best = #k; break; } });
                (parse_quote_spanned!(span=> 0), element(parse_quote_spanned!(span=> #best)))
            }
            _ => return None,
        };
        Some(parse_quote_spanned! {span=>
            {
                #(#setup)*
                let mut #found = false;
                let mut #best = #init;
                let mut #passed = 0usize;
                for #k in 0..#count {
                    #(#body)*
                }
                if #found { Some(#result) } else { None }
            }
        })
    }
}

impl Rewriter {
    /// `if c { None } else { e }` as `if !(c) { e } else { None }`: the
    /// lowering types an `if`'s second branch by its first, so the `None`
    /// takes `e`'s type, as rustc infers it from either branch. (The
    /// condition runs once either way, and the branches are the same.)
    pub(super) fn none_first(&mut self, i: &syn::ExprIf) -> Option<Expr> {
        let [syn::Stmt::Expr(Expr::Path(p), None)] = i.then_branch.stmts.as_slice() else { return None };
        let (_, otherwise) = i.else_branch.as_ref()?;
        // (An `if let` is a `match` by now: `if_let` comes first.)
        if p.qself.is_some() || !is_none_path(&p.path) {
            return None;
        }
        let span = i.if_token.span;
        let cond = &i.cond;
        let first: syn::Block = match &**otherwise {
            Expr::Block(b) if b.label.is_none() => b.block.clone(),
            other => parse_quote_spanned!(span=> { #other }),
        };
        let none = &p.path;
        Some(parse_quote_spanned!(span=> if !(#cond) #first else { #none }))
    }
}
