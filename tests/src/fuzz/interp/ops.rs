//! Operators: scalar and vector binary operators, shift amounts, casts.

use super::*;

/// A binary operator on scalars (both sides of one type, except shifts).
pub(super) fn scalar_bin(op: BinOp, a: &V, b: &V) -> R<V> {
    use BinOp::*;
    Ok(match (a, b) {
        (V::F(..), V::F(..)) => {
            let (x, y) = (a.f(), b.f());
            match op {
                Add => fv(fadd(x, y, false))?,
                Sub => fv(fsub(x, y, false))?,
                Mul => fv(fmul(x, y, false))?,
                Div => fv(fdiv(x, y))?,
                Rem => fv(frem(x, y))?,
                Eq | Ne | Lt | Le | Gt | Ge => fcmp(op, x, y),
                _ => panic!("{op:?} on f32"),
            }
        }
        (V::I(x, u), _) if matches!(op, Shl | Shr) => {
            let (s, su) = shift_amount(b);
            let r = if op == Shl { x.wrapping_shl(s) } else { x.wrapping_shr(s) };
            V::I(r, *u || su)
        }
        (V::U(x, u), _) if matches!(op, Shl | Shr) => {
            let (s, su) = shift_amount(b);
            let r = if op == Shl { x.wrapping_shl(s) } else { x.wrapping_shr(s) };
            V::U(r, *u || su)
        }
        (V::I(x, xu), V::I(y, yu)) => {
            let u = *xu || *yu;
            let (x, y) = (*x, *y);
            match op {
                Add => V::I(x.wrapping_add(y), u),
                Sub => V::I(x.wrapping_sub(y), u),
                Mul => V::I(x.wrapping_mul(y), u),
                // `rt_std::arith`: `x / 0` is `x`, `x % 0` is 0, `MIN / -1`
                // wraps.
                Div | Rem if y == 0 => V::I(if op == Div { x } else { 0 }, u),
                Div => V::I(x.wrapping_div(y), u),
                Rem => V::I(x.wrapping_rem(y), u),
                BitAnd => V::I(x & y, u),
                BitOr => V::I(x | y, u),
                BitXor => V::I(x ^ y, u),
                Eq => V::B(x == y, u),
                Ne => V::B(x != y, u),
                Lt => V::B(x < y, u),
                Le => V::B(x <= y, u),
                Gt => V::B(x > y, u),
                Ge => V::B(x >= y, u),
                _ => panic!("{op:?} on i32"),
            }
        }
        (V::U(x, xu), V::U(y, yu)) => {
            let u = *xu || *yu;
            let (x, y) = (*x, *y);
            match op {
                Add => V::U(x.wrapping_add(y), u),
                Sub => V::U(x.wrapping_sub(y), u),
                Mul => V::U(x.wrapping_mul(y), u),
                Div | Rem if y == 0 => V::U(if op == Div { x } else { 0 }, u),
                Div => V::U(x / y, u),
                Rem => V::U(x % y, u),
                BitAnd => V::U(x & y, u),
                BitOr => V::U(x | y, u),
                BitXor => V::U(x ^ y, u),
                Eq => V::B(x == y, u),
                Ne => V::B(x != y, u),
                Lt => V::B(x < y, u),
                Le => V::B(x <= y, u),
                Gt => V::B(x > y, u),
                Ge => V::B(x >= y, u),
                _ => panic!("{op:?} on u32"),
            }
        }
        (V::B(x, xu), V::B(y, yu)) => {
            let u = *xu || *yu;
            match op {
                BitAnd | And => V::B(*x & *y, u),
                BitOr | Or => V::B(*x | *y, u),
                BitXor | Ne => V::B(*x ^ *y, u),
                Eq => V::B(x == y, u),
                _ => panic!("{op:?} on bool"),
            }
        }
        _ => panic!("{op:?} on {a:?} and {b:?}"),
    })
}

fn shift_amount(b: &V) -> (u32, bool) {
    match b {
        V::I(s, u) => (*s as u32, *u),
        V::U(s, u) => (*s, *u),
        other => panic!("shift by {other:?}"),
    }
}

/// `a op b` on scalars or vectors (glam's operators are component-wise;
/// vector `==` compares all components).
pub(super) fn bin(op: BinOp, a: &V, b: &V) -> R<V> {
    match (op, a, b) {
        (BinOp::Eq | BinOp::Ne, V::Vec(x), V::Vec(y)) => {
            // Three-valued: a certain difference decides.
            let mut any_diff = false;
            let mut unc = false;
            for (p, q) in x.iter().zip(y) {
                match scalar_bin(BinOp::Ne, p, q)? {
                    V::B(true, false) => any_diff = true,
                    V::B(_, true) => unc = true,
                    _ => {}
                }
            }
            let ne = if any_diff { (true, false) } else { (false, unc) };
            Ok(V::B(if op == BinOp::Ne { ne.0 } else { !ne.0 }, ne.1))
        }
        // glam's `Vec4` is SIMD (SSE2 here, NEON, wasm) and its `%` is
        // `x - floor(x / y) * y`, unlike `f32`'s `%` (`Vec2`, `Vec3`).
        (BinOp::Rem, V::Vec(x), _) if x.len() == 4 && matches!(x[0], V::F(..)) => zip(a, b, &mut |p, q| {
            let (x, y) = (p.f(), q.f());
            let n = fstep(fdiv(x, y)?, f32::floor)?;
            fv(fsub(x, fmul(n, y, false)?, false))
        }),
        (BinOp::Rem, _, V::Vec(y)) if y.len() == 4 && matches!(y[0], V::F(..)) => {
            bin(op, &V::Vec(vec![a.clone(); 4]), b)
        }
        _ => zip(a, b, &mut |p, q| scalar_bin(op, p, q)),
    }
}

/// `as` between scalars (component-wise for glam's `as_*vecN`).
pub(super) fn cast(v: &V, to: Scalar) -> R<V> {
    map1(v, &mut |s| {
        Ok(match (s, to) {
            (V::F(f, e), Scalar::I32) => f2i((*f, *e), true),
            (V::F(f, e), Scalar::U32) => f2i((*f, *e), false),
            (V::F(f, e), Scalar::F32) => V::F(*f, *e),
            (V::I(i, u), Scalar::F32) => i2f(*i as f64, *u)?,
            (V::U(i, u), Scalar::F32) => i2f(*i as f64, *u)?,
            (V::I(i, u), Scalar::I32) => V::I(*i, *u),
            (V::I(i, u), Scalar::U32) => V::U(*i as u32, *u),
            (V::U(i, u), Scalar::I32) => V::I(*i as i32, *u),
            (V::U(i, u), Scalar::U32) => V::U(*i, *u),
            (V::B(b, u), Scalar::I32) => V::I(*b as i32, *u),
            (V::B(b, u), Scalar::U32) => V::U(*b as u32, *u),
            (v, s) => panic!("cast {v:?} as {s:?}"),
        })
    })
}

pub(super) fn loose_bin(op: BinOp, x: &V, y: &V) -> R<V> {
    match (x, y) {
        (V::F(..), V::F(..)) => match op {
            BinOp::Add => fv(fadd(x.f(), y.f(), true)),
            BinOp::Mul => fv(fmul(x.f(), y.f(), true)),
            _ => unreachable!(),
        },
        _ => scalar_bin(op, x, y),
    }
}
