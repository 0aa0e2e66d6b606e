//! `matches!`, and the `match` arms a WGSL `switch` cannot take (range
//! patterns `1..=9`, guards `x if x > 2`) as an `if` chain over the
//! scrutinee, evaluated once.
//!
//! Each arm's pattern becomes a condition on the scrutinee: a literal or a
//! constant is `==`, a range compares both ends, `|` is `||`, `_` and a
//! binding are true (the binding is a `let` in the arm and in its guard),
//! a tuple's elements each their own, `Some(p)` the flag and `p` on the
//! value, `None` the flag's absence.
//! The last arm is the final `else`: rustc checks the match on the CPU copy,
//! so the arms are exhaustive and the last one takes what the others left.

use super::Rewriter;
use syn::spanned::Spanned;
use syn::{Expr, parse_quote_spanned};

impl Rewriter {
    /// `matches!(e, PAT)` or `matches!(e, PAT if guard)` as a `match`.
    pub(super) fn matches_macro(&mut self, m: &syn::Macro) -> Option<Expr> {
        if !m.path.is_ident("matches") {
            return None;
        }
        let span = m.path.span();
        let args = m.parse_body_with(MatchesArgs::parse).ok()?;
        let MatchesArgs { scrutinee, pat, guard } = args;
        let guard = guard.map(|g| quote::quote!(if #g));
        Some(parse_quote_spanned! {span=>
            match #scrutinee {
                #pat #guard => true,
                _ => false,
            }
        })
    }

    /// A `match` with a range pattern or a guard, as an `if` chain; `None`
    /// for one the lowering takes as it is, or a pattern this cannot test.
    pub(super) fn match_chain(&mut self, m: &syn::ExprMatch) -> Option<Expr> {
        let needs = m.arms.iter().any(|a| a.guard.is_some() || has_range(&a.pat));
        if !needs || m.arms.is_empty() {
            return None;
        }
        let span = m.match_token.span;
        let scrutinee = self.fresh("match", span);
        let on: Expr = parse_quote_spanned!(span=> #scrutinee);
        let mut chain: Option<Expr> = None;
        for (i, arm) in m.arms.iter().enumerate().rev() {
            let mut binds = Vec::new();
            let cond = condition(&arm.pat, &on, &mut binds)?;
            let body = &arm.body;
            let value: Expr = parse_quote_spanned! {span=> { #(#binds)* #body } };
            chain = Some(match chain {
                // The last arm: what no other arm took.
                None if i + 1 == m.arms.len() => value,
                None => return None,
                Some(rest) => {
                    let test: Expr = match &arm.guard {
                        Some((_, g)) => parse_quote_spanned!(span=> (#cond) && { #(#binds)* #g }),
                        None => cond,
                    };
                    parse_quote_spanned!(span=> if #test #value else { #rest })
                }
            });
        }
        let scrutinee_expr = &m.expr;
        let chain = chain?;
        Some(parse_quote_spanned! {span=>
            {
                let #scrutinee = #scrutinee_expr;
                #chain
            }
        })
    }
}

/// `matches!`'s arguments: an expression, a pattern, maybe a guard.
struct MatchesArgs {
    scrutinee: Expr,
    pat: syn::Pat,
    guard: Option<Expr>,
}

impl MatchesArgs {
    fn parse(input: syn::parse::ParseStream) -> syn::Result<Self> {
        let scrutinee: Expr = input.parse()?;
        input.parse::<syn::Token![,]>()?;
        let pat = syn::Pat::parse_multi_with_leading_vert(input)?;
        let guard = if input.peek(syn::Token![if]) {
            input.parse::<syn::Token![if]>()?;
            Some(input.parse()?)
        } else {
            None
        };
        if input.peek(syn::Token![,]) {
            input.parse::<syn::Token![,]>()?;
        }
        Ok(MatchesArgs { scrutinee, pat, guard })
    }
}

fn has_range(p: &syn::Pat) -> bool {
    match p {
        syn::Pat::Range(_) => true,
        syn::Pat::Or(o) => o.cases.iter().any(has_range),
        syn::Pat::Paren(p) => has_range(&p.pat),
        syn::Pat::Tuple(t) => t.elems.iter().any(has_range),
        syn::Pat::Ident(p) => p.subpat.as_ref().is_some_and(|(_, p)| has_range(p)),
        syn::Pat::TupleStruct(t) => t.elems.iter().any(has_range),
        _ => false,
    }
}

/// The test that `pat` matches `on`, with the `let`s of its bindings
/// pushed on `binds`; `None` for a pattern this does not test (a struct,
/// a variant with fields other than `Some`), which stays a `match` for the
/// lowering to take or refuse.
fn condition(pat: &syn::Pat, on: &Expr, binds: &mut Vec<syn::Stmt>) -> Option<Expr> {
    let span = pat.span();
    Some(match pat {
        syn::Pat::Wild(_) => parse_quote_spanned!(span=> true),
        // `Option`'s patterns: the value is read only once the flag is
        // tested (`rt_sugar_value` is the lowering's read of it).
        syn::Pat::Ident(pi) if pi.ident == "None" && pi.subpat.is_none() => parse_quote_spanned!(span=> #on.is_none()),
        syn::Pat::TupleStruct(ts) if ts.path.is_ident("Some") && ts.elems.len() == 1 => {
            let value: Expr = parse_quote_spanned!(span=> #on.rt_sugar_value());
            let inner = condition(&ts.elems[0], &value, binds)?;
            parse_quote_spanned!(span=> (#on.is_some() && #inner))
        }
        syn::Pat::Tuple(t) => {
            let mut all = Vec::new();
            for (i, p) in t.elems.iter().enumerate() {
                let k = syn::Index::from(i);
                let elem: Expr = parse_quote_spanned!(span=> #on.#k);
                all.push(condition(p, &elem, binds)?);
            }
            parse_quote_spanned!(span=> (true #(&& #all)*))
        }
        syn::Pat::Lit(l) => parse_quote_spanned!(span=> #on == #l),
        syn::Pat::Path(p) => parse_quote_spanned!(span=> #on == #p),
        // `k @ 1..=9`: the binding, and the pattern's test.
        syn::Pat::Ident(pi) if pi.by_ref.is_none() && pi.subpat.is_some() => {
            let (id, (_, sub)) = (&pi.ident, pi.subpat.as_ref()?);
            binds.push(parse_quote_spanned! {span=> let #id = #on; });
            condition(sub, on, binds)?
        }
        syn::Pat::Ident(pi) if pi.subpat.is_none() && pi.by_ref.is_none() => {
            let name = pi.ident.to_string();
            if name.chars().next().is_some_and(|c| c.is_ascii_uppercase()) {
                // A constant in a pattern compares (a capitalised binding
                // would be a constant's misspelling).
                let id = &pi.ident;
                parse_quote_spanned!(span=> #on == #id)
            } else {
                let id = &pi.ident;
                binds.push(parse_quote_spanned! {span=> let #id = #on; });
                parse_quote_spanned!(span=> true)
            }
        }
        syn::Pat::Range(r) => {
            let low = r.start.as_ref().map(|s| -> Expr { parse_quote_spanned!(span=> #on >= #s) });
            let high = r.end.as_ref().map(|e| -> Expr {
                match r.limits {
                    syn::RangeLimits::HalfOpen(_) => parse_quote_spanned!(span=> #on < #e),
                    syn::RangeLimits::Closed(_) => parse_quote_spanned!(span=> #on <= #e),
                }
            });
            match (low, high) {
                (Some(l), Some(h)) => parse_quote_spanned!(span=> (#l && #h)),
                (Some(c), None) | (None, Some(c)) => c,
                (None, None) => parse_quote_spanned!(span=> true),
            }
        }
        syn::Pat::Or(o) => {
            let mut cases = Vec::new();
            for c in &o.cases {
                let mut inner = Vec::new();
                cases.push(condition(c, on, &mut inner)?);
                if !inner.is_empty() {
                    // A binding in one case of `|`: the lowering's `match`
                    // takes what it can.
                    return None;
                }
            }
            parse_quote_spanned!(span=> (#(#cases)||*))
        }
        syn::Pat::Paren(p) => condition(&p.pat, on, binds)?,
        _ => return None,
    })
}
