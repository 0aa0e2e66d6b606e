//! The CPU copy of a program or helper with the GPU's integer semantics.
//!
//! rustc panics on integer overflow (debug builds), division by zero and
//! out-of-range indices; the megakernel defines each (`rt_std::arith`).
//! The function rustc compiles for the CPU backend is the user's own, with
//! its operators and indexing rewritten into calls of `rt_std::arith`,
//! which do what WGSL does. Each call carries the span of the operator it
//! replaces, so rustc's errors still point at the user's code.
//!
//! Rewritten: `+ - * / % << >>` and their compound assignments, unary `-`
//! (but not of a literal: `-2147483648i32` stays a literal), indexing
//! (`a[i]` reads through `arith::at`, a written place through
//! `arith::at_mut`), and the methods whose Rust (std or glam) versions
//! panic where WGSL answers (`gpu_method`): `abs` (of `i32::MIN`),
//! `clamp` (with `lo > hi`), the dividing methods (a zero divisor) and the
//! sums and products of integer vectors (`dot`, `element_sum`, `cross`,
//! ..., which overflow), and `Option`'s `unwrap` and `expect`, which
//! raise `EXCEPTION_PANIC` where Rust would panic (`arith::unwrap`). A method call `x.dot(y)` becomes
//! `arith::Gpu(x).dot(y)`, its path form `IVec3::dot(a, b)` becomes
//! `arith::Gpu::<IVec3>(a).dot(b)`: the macro does not know `x`'s type,
//! so Rust's method lookup picks `Gpu`'s own method where the type is an
//! integer one and the value's own method (through `Deref`) for any other
//! type, a user's struct included.
//! Bitwise operators, comparisons and casts already agree and are left as
//! written (a bitwise compound assignment only has its right side
//! evaluated first, as the arithmetic ones: its place may be an `at_mut`
//! borrow), as is everything inside macro invocations and `const` items.
//!
//! A function that names a scalar type the subset refuses (`u64`, `f64`,
//! `u8`, ...: [`names_refused_scalar`]) or takes an `impl Trait` is left
//! as written: the lowering refuses it with its own message, and
//! `rt_std::arith`, which has no such types, would only add rustc's errors
//! about its traits after it. A generic function is left as written too:
//! its bounds name std's operator traits, not `rt_std::arith`'s, so its
//! CPU copy keeps Rust's operators (an instance at an integer type that
//! overflows panics in a debug build where WGSL wraps; at float and
//! vector types the two agree).

use proc_macro2::Span;
use syn::spanned::Spanned;
use syn::visit_mut::{self, VisitMut};
use syn::{BinOp, Expr, UnOp};

/// Rewrites `f`'s body in place.
pub fn rewrite_fn(f: &mut syn::ItemFn) {
    let impl_trait =
        f.sig.inputs.iter().any(|a| matches!(a, syn::FnArg::Typed(pt) if matches!(&*pt.ty, syn::Type::ImplTrait(_))));
    if names_refused_scalar(f) || !f.sig.generics.params.is_empty() || impl_trait {
        return;
    }
    // `&mut` parameters (`m: &mut Mat3`, `&mut self`): an in-place method's
    // receiver is reborrowed through them (`&mut *m`), not borrowed again.
    let ref_params = f
        .sig
        .inputs
        .iter()
        .filter_map(|a| match a {
            syn::FnArg::Typed(pt) => match (&*pt.pat, &*pt.ty) {
                (syn::Pat::Ident(i), syn::Type::Reference(r)) if r.mutability.is_some() => Some(i.ident.to_string()),
                _ => None,
            },
            syn::FnArg::Receiver(r) if r.reference.is_some() && r.mutability.is_some() => Some("self".to_string()),
            _ => None,
        })
        .collect();
    Rewriter { ref_params }.visit_block_mut(&mut f.block);
    // The rewrite wraps index reads in parentheses and keeps the user's own
    // around what became call arguments.
    f.attrs.push(syn::parse_quote!(#[allow(unused_parens)]));
}

struct Rewriter {
    ref_params: Vec<String>,
}

/// The `rt_std::arith` function for a binary operator, and whether it is
/// the compound-assignment form.
fn arith_fn(op: &BinOp) -> Option<(&'static str, bool)> {
    Some(match op {
        BinOp::Add(_) => ("add", false),
        BinOp::Sub(_) => ("sub", false),
        BinOp::Mul(_) => ("mul", false),
        BinOp::Div(_) => ("div", false),
        BinOp::Rem(_) => ("rem", false),
        BinOp::Shl(_) => ("shl", false),
        BinOp::Shr(_) => ("shr", false),
        BinOp::AddAssign(_) => ("add_assign", true),
        BinOp::SubAssign(_) => ("sub_assign", true),
        BinOp::MulAssign(_) => ("mul_assign", true),
        BinOp::DivAssign(_) => ("div_assign", true),
        BinOp::RemAssign(_) => ("rem_assign", true),
        BinOp::ShlAssign(_) => ("shl_assign", true),
        BinOp::ShrAssign(_) => ("shr_assign", true),
        _ => return None,
    })
}

/// A method called with `args` arguments (after the receiver) whose Rust
/// version panics where the GPU answers: `rt_std::arith::Gpu` has it for
/// the integer types (and the clamps of floats).
fn gpu_method(name: &str, args: usize) -> bool {
    matches!(
        (name, args),
        (
            "abs"
                | "element_sum"
                | "element_product"
                | "length_squared"
                | "isqrt"
                | "ilog2"
                | "ilog10"
                | "next_power_of_two",
            0
        ) | ("clamp", 2)
            | ("test", 1)
            | (
                "div_euclid"
                    | "rem_euclid"
                    | "wrapping_div"
                    | "saturating_div"
                    | "dot"
                    | "dot_into_vec"
                    | "cross"
                    | "distance_squared"
                    | "manhattan_distance"
                    | "perp_dot"
                    | "rotate"
                    | "pow"
                    | "ilog"
                    | "div_ceil"
                    | "next_multiple_of"
                    | "wrapping_rem"
                    | "wrapping_div_euclid"
                    | "wrapping_rem_euclid"
                    | "overflowing_div"
                    | "overflowing_rem"
                    | "overflowing_div_euclid"
                    | "overflowing_rem_euclid",
                1
            )
    )
}

/// A method that changes its receiver in place (`&mut self`; `col_mut`
/// gives a place) and panics
/// where the GPU clamps: `rt_std::arith::GpuMut` has it for glam's types.
fn gpu_mut_method(name: &str, args: usize) -> bool {
    matches!((name, args), ("set_row" | "set", 2) | ("col_mut", 1))
}

/// `Mat2::from_mat3_minor`, `Mat3::from_mat4_minor`: the type's path and
/// the function's name.
fn gpu_assoc_fn(func: &Expr) -> Option<(syn::Path, syn::Ident)> {
    let (owner, name) = split_path(func)?;
    matches!(name.to_string().as_str(), "from_mat3_minor" | "from_mat4_minor").then_some((owner, name))
}

/// `A::B::f` as a path: `A::B` and `f` (none for a one-segment path or a
/// qualified `<T as U>::f`).
fn split_path(func: &Expr) -> Option<(syn::Path, syn::Ident)> {
    let Expr::Path(p) = func else { return None };
    if p.qself.is_some() || p.path.segments.len() < 2 {
        return None;
    }
    let mut owner = p.path.clone();
    let last = owner.segments.pop()?.into_value().ident;
    // (`pop` leaves the trailing `::` punctuation.)
    owner.segments.pop_punct();
    Some((owner, last))
}

/// `T::dot` called with `args` arguments (the receiver first), `T` a type
/// (a capitalised name or a primitive, not a module: `math::dot` is a
/// function): the type's path and the method's name.
fn path_gpu_method(func: &Expr, args: usize) -> Option<(syn::Path, syn::Ident)> {
    let (owner, name) = split_path(func)?;
    if args == 0 || !gpu_method(&name.to_string(), args - 1) {
        return None;
    }
    let ty = owner.segments.last()?.ident.to_string();
    let is_type =
        ty.starts_with(|c: char| c.is_ascii_uppercase()) || matches!(ty.as_str(), "i32" | "u32" | "f32" | "usize");
    is_type.then_some((owner, name))
}

/// `unwrap()` and `expect(msg)`, which `rt_std::arith::unwrap` and
/// `expect` stand for.
pub fn unwrap_method(name: &str, args: usize) -> bool {
    matches!((name, args), ("unwrap", 0) | ("expect", 1))
}

fn is_assign(op: &BinOp) -> bool {
    matches!(op, BinOp::BitAndAssign(_) | BinOp::BitOrAssign(_) | BinOp::BitXorAssign(_))
}

fn path(name: &str, span: Span) -> syn::Path {
    let ident = syn::Ident::new(name, span);
    syn::parse_quote_spanned!(span=> ::rt_std::arith::#ident)
}

impl Rewriter {
    /// `e` in a place that is written or borrowed mutably.
    fn place(&mut self, e: &mut Expr) {
        match e {
            Expr::Index(i) => {
                self.place(&mut i.expr);
                self.visit_expr_mut(&mut i.index);
                let span = i.bracket_token.span.join();
                let (base, index) = (&i.expr, &i.index);
                let f = path("at_mut", span);
                *e = syn::parse_quote_spanned!(span=> (*#f(&mut #base, #index)));
            }
            Expr::Field(f) => self.place(&mut f.base),
            Expr::Paren(p) => self.place(&mut p.expr),
            _ => self.visit_expr_mut(e),
        }
    }
}

impl VisitMut for Rewriter {
    fn visit_expr_mut(&mut self, e: &mut Expr) {
        match e {
            Expr::Assign(a) => {
                self.place(&mut a.left);
                self.visit_expr_mut(&mut a.right);
            }
            Expr::Binary(b) if arith_fn(&b.op).is_some() => {
                let (name, compound) = arith_fn(&b.op).unwrap();
                let span = b.op.span();
                let f = path(name, span);
                if compound {
                    self.place(&mut b.left);
                    self.visit_expr_mut(&mut b.right);
                    let (l, r) = (&b.left, &b.right);
                    // The right side first, then the borrow: Rust's order
                    // for primitive types, and `x += x * 2` borrows cleanly.
                    *e = syn::parse_quote_spanned!(span=> { let __rt_rhs = #r; #f(&mut #l, __rt_rhs) });
                } else {
                    self.visit_expr_mut(&mut b.left);
                    self.visit_expr_mut(&mut b.right);
                    let (l, r) = (&b.left, &b.right);
                    *e = syn::parse_quote_spanned!(span=> #f(#l, #r));
                }
            }
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
                if matches!(&*u.expr, Expr::Lit(_)) {
                    return;
                }
                self.visit_expr_mut(&mut u.expr);
                let span = u.op.span();
                let f = path("neg", span);
                let x = &u.expr;
                *e = syn::parse_quote_spanned!(span=> #f(#x));
            }
            Expr::Binary(b) if is_assign(&b.op) => {
                // `&=`, `|=`, `^=`: the left side is a place all the same,
                // and, as for the arithmetic ones, the right side is
                // evaluated first: `a[0] &= a[1]` would otherwise borrow
                // `a` through `at_mut` while the right side reads it.
                self.place(&mut b.left);
                self.visit_expr_mut(&mut b.right);
                let span = b.op.span();
                let (l, op, r) = (&b.left, &b.op, &b.right);
                *e = syn::parse_quote_spanned!(span=> { let __rt_rhs = #r; #l #op __rt_rhs });
            }
            Expr::Reference(r) if r.mutability.is_some() => self.place(&mut r.expr),
            Expr::Index(i) => {
                self.visit_expr_mut(&mut i.expr);
                self.visit_expr_mut(&mut i.index);
                let span = i.bracket_token.span.join();
                let (base, index) = (&i.expr, &i.index);
                let f = path("at", span);
                *e = syn::parse_quote_spanned!(span=> (*#f(&#base, #index)));
            }
            Expr::MethodCall(m) if gpu_mut_method(&m.method.to_string(), m.args.len()) => {
                // The receiver is a place written through (`ms[i].set_row(..)`
                // indexes with `at_mut`).
                self.place(&mut m.receiver);
                for a in m.args.iter_mut() {
                    self.visit_expr_mut(a);
                }
                let span = m.method.span();
                let gpu = path("GpuMut", span);
                let (method, turbofish, args) = (&m.method, &m.turbofish, &m.args);
                let recv = match &*m.receiver {
                    Expr::Path(p) if p.path.get_ident().is_some_and(|i| self.ref_params.contains(&i.to_string())) => {
                        quote::quote!(&mut *#p)
                    }
                    r => quote::quote!(&mut #r),
                };
                *e = syn::parse_quote_spanned!(span=> #gpu(#recv).#method #turbofish(#args));
            }
            // `o.unwrap()`, `o.expect("why")`: `Option`'s (the only type
            // in ray programs with them), raising rather than panicking.
            Expr::MethodCall(m) if unwrap_method(&m.method.to_string(), m.args.len()) => {
                visit_mut::visit_expr_method_call_mut(self, m);
                let span = m.method.span();
                let f = path(&m.method.to_string(), span);
                let (recv, args) = (&m.receiver, &m.args);
                *e = syn::parse_quote_spanned!(span=> #f(#recv, #args));
            }
            Expr::MethodCall(m) if gpu_method(&m.method.to_string(), m.args.len()) => {
                visit_mut::visit_expr_method_call_mut(self, m);
                let span = m.method.span();
                let gpu = path("Gpu", span);
                let (recv, method, turbofish, args) = (&m.receiver, &m.method, &m.turbofish, &m.args);
                *e = syn::parse_quote_spanned!(span=> #gpu(#recv).#method #turbofish(#args));
            }
            // `Mat2::from_mat3_minor(m, i, j)`: glam's associated function
            // that panics past the last row or column, through `Gpu`'s.
            Expr::Call(c) if gpu_assoc_fn(&c.func).is_some() => {
                visit_mut::visit_expr_call_mut(self, c);
                let (owner, name) = gpu_assoc_fn(&c.func).unwrap();
                let span = name.span();
                let gpu = path("Gpu", span);
                let args = &c.args;
                *e = syn::parse_quote_spanned!(span=> #gpu::<#owner>::#name(#args));
            }
            Expr::Call(c) if path_gpu_method(&c.func, c.args.len()).is_some() => {
                visit_mut::visit_expr_call_mut(self, c);
                let (owner, name) = path_gpu_method(&c.func, c.args.len()).unwrap();
                let span = name.span();
                let gpu = path("Gpu", span);
                let mut args = c.args.clone().into_iter();
                let Some(first) = args.next() else { return };
                // `Mat3::abs(&m)`: the receiver by value (lookup borrows it
                // again); a `&mut` receiver is a method that writes, which
                // no `Gpu` method is.
                let first = match first {
                    Expr::Reference(r) if r.mutability.is_none() => *r.expr,
                    Expr::Reference(_) => return,
                    f => f,
                };
                let rest: syn::punctuated::Punctuated<Expr, syn::Token![,]> = args.collect();
                *e = syn::parse_quote_spanned!(span=> #gpu::<#owner>(#first).#name(#rest));
            }
            _ => visit_mut::visit_expr_mut(self, e),
        }
    }

    fn visit_macro_mut(&mut self, m: &mut syn::Macro) {
        if m.path.is_ident("debug_assert") {
            // `debug_assert!(cond)`: rt-std's, which raises where Rust's
            // would panic (`arith::debug_assert_failed`), its condition
            // rewritten.
            let parser = syn::punctuated::Punctuated::<Expr, syn::Token![,]>::parse_terminated;
            if let Ok(mut args) = syn::parse::Parser::parse2(parser, m.tokens.clone()) {
                if let Some(cond) = args.first_mut() {
                    self.visit_expr_mut(cond);
                }
                let span = m.path.span();
                m.path = syn::parse_quote_spanned!(span=> ::rt_std::__rt_debug_assert);
                m.tokens = quote::ToTokens::to_token_stream(&args);
            }
            return;
        }
        // `rt_printf!("...", args)`: the arguments are expressions.
        if m.path.segments.last().is_none_or(|s| s.ident != "rt_printf") {
            return;
        }
        let parser = syn::punctuated::Punctuated::<Expr, syn::Token![,]>::parse_terminated;
        if let Ok(mut args) = syn::parse::Parser::parse2(parser, m.tokens.clone()) {
            for a in args.iter_mut().skip(1) {
                self.visit_expr_mut(a);
            }
            m.tokens = quote::ToTokens::to_token_stream(&args);
        }
    }

    fn visit_item_mut(&mut self, _: &mut syn::Item) {
        // Nested items (`const`, `fn`) keep their own meaning: a `const`
        // must stay evaluable by rustc.
    }

    fn visit_type_mut(&mut self, _: &mut syn::Type) {
        // Array lengths in types are constant expressions.
    }

    fn visit_expr_repeat_mut(&mut self, r: &mut syn::ExprRepeat) {
        // `[x; N]`: the length is a constant expression.
        self.visit_expr_mut(&mut r.expr);
    }
}

/// Whether `f` names a refused scalar type, as a type or a literal's
/// suffix, anywhere in its signature or body.
pub fn names_refused_scalar(f: &syn::ItemFn) -> bool {
    struct Find(bool);
    impl<'ast> syn::visit::Visit<'ast> for Find {
        fn visit_type_path(&mut self, t: &'ast syn::TypePath) {
            if t.qself.is_none() && t.path.segments.len() == 1 {
                self.0 |= crate::types::REFUSED_SCALARS.iter().any(|s| t.path.segments[0].ident == s);
            }
            syn::visit::visit_type_path(self, t);
        }
        fn visit_lit(&mut self, l: &'ast syn::Lit) {
            let suffix = match l {
                syn::Lit::Int(i) => i.suffix(),
                syn::Lit::Float(f) => f.suffix(),
                _ => "",
            };
            self.0 |= crate::types::REFUSED_SCALARS.contains(&suffix);
        }
    }
    let mut find = Find(false);
    syn::visit::Visit::visit_item_fn(&mut find, f);
    find.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::ToTokens;

    fn rewritten(src: &str) -> String {
        let mut f: syn::ItemFn = syn::parse_str(src).unwrap();
        rewrite_fn(&mut f);
        f.block.to_token_stream().to_string()
    }

    #[test]
    fn operators_and_indices_become_arith_calls() {
        let got = rewritten("fn f() { let h = (i + seed) * 7u32; arr[k as usize] = -x; y -= arr[1]; let n = -1i32; }");
        assert_eq!(
            got,
            "{ let h = :: rt_std :: arith :: mul ((:: rt_std :: arith :: add (i , seed)) , 7u32) ; \
             (* :: rt_std :: arith :: at_mut (& mut arr , k as usize)) = :: rt_std :: arith :: neg (x) ; \
             { let __rt_rhs = (* :: rt_std :: arith :: at (& arr , 1)) ; :: rt_std :: arith :: sub_assign (& mut y , __rt_rhs) } ; \
             let n = - 1i32 ; }"
        );
    }

    #[test]
    fn functions_the_lowering_refuses_by_type_are_left_as_written() {
        for src in [
            "fn f(x: u32) -> u32 { let h: u64 = x as u64 * 3; (h >> 1) as u32 }",
            "fn f(x: f32) -> f32 { x * 2.0f64 as f32 }",
            "fn f<T: Copy + core::ops::Add<Output = T>>(x: T) -> T { x + x }",
        ] {
            let f: syn::ItemFn = syn::parse_str(src).unwrap();
            assert_eq!(rewritten(src), f.block.to_token_stream().to_string(), "{src}");
        }
        // A name that only contains one is rewritten.
        assert!(rewritten("fn f(u64s: u32) -> u32 { u64s + 1 }").contains("arith :: add"));
    }

    #[test]
    fn every_refused_scalar_has_the_lowerings_advice() {
        for s in crate::types::REFUSED_SCALARS {
            assert!(crate::types::unsupported_type_advice(s).is_some(), "{s}");
        }
    }

    #[test]
    fn bitwise_compound_assignments_evaluate_the_right_side_first() {
        let got = rewritten("fn f() { a[0] &= a[1]; x |= 3; }");
        assert_eq!(
            got,
            "{ { let __rt_rhs = (* :: rt_std :: arith :: at (& a , 1)) ; \
             (* :: rt_std :: arith :: at_mut (& mut a , 0)) &= __rt_rhs } ; \
             { let __rt_rhs = 3 ; x |= __rt_rhs } ; }"
        );
    }

    #[test]
    fn panicking_methods_are_called_through_gpu_keeping_the_type() {
        let got = rewritten(
            "fn f() { let a = x.div_euclid(y); let b = i32::rem_euclid(7, 0); let c = v.element_sum(); \
             let d = Mat3::abs(&m); let e = math::dot(p, q); let f = u.dot(w, z); let g = s.clamp(lo, hi); }",
        );
        assert_eq!(
            got,
            "{ let a = :: rt_std :: arith :: Gpu (x) . div_euclid (y) ; \
             let b = :: rt_std :: arith :: Gpu :: < i32 > (7) . rem_euclid (0) ; \
             let c = :: rt_std :: arith :: Gpu (v) . element_sum () ; \
             let d = :: rt_std :: arith :: Gpu :: < Mat3 > (m) . abs () ; \
             let e = math :: dot (p , q) ; let f = u . dot (w , z) ; \
             let g = :: rt_std :: arith :: Gpu (s) . clamp (lo , hi) ; }"
        );
    }

    #[test]
    fn in_place_methods_are_called_through_gpu_mut() {
        let got = rewritten(
            "fn f(r: &mut Mat3, v: Vec3) { m.set_row(1, v); r.set_row(0, v); p.mask.set(2, true); ms[k].set_row(0, v); *m.col_mut(1) = v; }",
        );
        assert_eq!(
            got,
            "{ :: rt_std :: arith :: GpuMut (& mut m) . set_row (1 , v) ; \
             :: rt_std :: arith :: GpuMut (& mut * r) . set_row (0 , v) ; \
             :: rt_std :: arith :: GpuMut (& mut p . mask) . set (2 , true) ; \
             :: rt_std :: arith :: GpuMut (& mut (* :: rt_std :: arith :: at_mut (& mut ms , k))) . set_row (0 , v) ; \
             * :: rt_std :: arith :: GpuMut (& mut m) . col_mut (1) = v ; }"
        );
    }

    #[test]
    fn constants_and_macros_are_left_alone() {
        let got = rewritten(
            "fn f() { const N: usize = 2 + 2; let a = [0u32; 2 * 2]; other!(a + b); rt_printf!(\"{}\", a + b); }",
        );
        assert_eq!(
            got,
            "{ const N : usize = 2 + 2 ; let a = [0u32 ; 2 * 2] ; other ! (a + b) ; \
             rt_printf ! (\"{}\" , :: rt_std :: arith :: add (a , b)) ; }"
        );
    }
}
