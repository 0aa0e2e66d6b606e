//! Vector expressions and the names of glam's vector types,
//! constructors, casts and swizzles.

use super::*;

pub(super) const COMP: [&str; 4] = ["x", "y", "z", "w"];

pub(super) fn vec_name(n: u8, s: Scalar) -> &'static str {
    match (s, n) {
        (Scalar::F32, 2) => "Vec2",
        (Scalar::F32, 3) => "Vec3",
        (Scalar::F32, _) => "Vec4",
        (Scalar::I32, 2) => "IVec2",
        (Scalar::I32, 3) => "IVec3",
        (Scalar::I32, _) => "IVec4",
        (_, 2) => "UVec2",
        (_, 3) => "UVec3",
        _ => "UVec4",
    }
}

pub(super) fn vec_fn(n: u8, s: Scalar) -> &'static str {
    match (s, n) {
        (Scalar::F32, 2) => "vec2",
        (Scalar::F32, 3) => "vec3",
        (Scalar::F32, _) => "vec4",
        (Scalar::I32, 2) => "ivec2",
        (Scalar::I32, 3) => "ivec3",
        (Scalar::I32, _) => "ivec4",
        (_, 2) => "uvec2",
        (_, 3) => "uvec3",
        _ => "uvec4",
    }
}

fn as_vec(n: u8, s: Scalar) -> &'static str {
    match (s, n) {
        (Scalar::F32, 2) => "as_vec2",
        (Scalar::F32, 3) => "as_vec3",
        (Scalar::F32, _) => "as_vec4",
        (Scalar::I32, 2) => "as_ivec2",
        (Scalar::I32, 3) => "as_ivec3",
        (Scalar::I32, _) => "as_ivec4",
        (_, 2) => "as_uvec2",
        (_, 3) => "as_uvec3",
        _ => "as_uvec4",
    }
}

fn swizzle_name(idx: &[usize]) -> &'static str {
    // Leaked once per distinct swizzle; there are at most 4^2+4^3+4^4.
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static NAMES: OnceLock<Mutex<HashMap<Vec<usize>, &'static str>>> = OnceLock::new();
    let mut m = NAMES.get_or_init(Default::default).lock().unwrap();
    m.entry(idx.to_vec())
        .or_insert_with(|| Box::leak(idx.iter().map(|i| COMP[*i]).collect::<String>().into_boxed_str()))
}

impl Gen {
    /// A float vector type of the program, if any.
    pub(super) fn fvec(&mut self) -> Ty {
        let fs: Vec<Ty> = self.vecs.iter().filter(|t| t.scalar() == Some(Scalar::F32)).cloned().collect();
        if fs.is_empty() { Ty::V(self.r.range(2, 4) as u8, Scalar::F32) } else { self.r.pick(&fs) }
    }

    pub(super) fn ivec(&mut self, s: Scalar) -> Ty {
        let vs: Vec<Ty> = self.vecs.iter().filter(|t| t.scalar() == Some(s)).cloned().collect();
        if vs.is_empty() { Ty::V(self.r.range(2, 4) as u8, s) } else { self.r.pick(&vs) }
    }

    pub(super) fn fvec_expr(&mut self, n: u8, d: u32, typed: bool) -> Expr {
        let t = Ty::V(n, Scalar::F32);
        let d1 = d - 1;
        let name = vec_name(n, Scalar::F32);
        match self.r.below(100) {
            0..=9 => {
                let args: Vec<Expr> = (0..n).map(|_| self.expr(&F32, d1, true)).collect();
                match self.r.below(4) {
                    0 => Expr::Path(name, "new", args),
                    1 => Expr::Path(name, "splat", vec![self.expr(&F32, d1, true)]),
                    2 => Expr::Path(name, "from_array", vec![Expr::ArrayLit(args)]),
                    _ => Expr::Free(vec_fn(n, Scalar::F32), args),
                }
            }
            10..=29 => {
                let op = self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul]);
                let (a, c) = self.operands(&t, &t, d, false);
                bin(op, a, c)
            }
            30..=39 => {
                let op = self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Rem]);
                let a = self.expr(&t, d1, false);
                let c = if matches!(op, BinOp::Div | BinOp::Rem) {
                    self.divisor(&F32, d)
                } else {
                    self.expr(&F32, d1, false)
                };
                bin(op, a, c)
            }
            40..=43 => {
                // A scalar on the left: suffixed.
                let a = self.expr(&F32, d1, false);
                bin(BinOp::Mul, a, self.expr(&t, d1, false))
            }
            44..=46 => {
                let a = self.expr(&t, d1, false);
                let c = self.divisor(&t, d);
                bin(self.r.pick(&[BinOp::Div, BinOp::Rem]), a, c)
            }
            47..=49 => Expr::Unary(UnOp::Neg, b(self.expr(&t, d1, false))),
            50..=59 => {
                let x = self.expr(&t, d1, false);
                let m = self.r.pick(&["abs", "floor", "ceil", "round", "trunc", "fract", "fract_gl", "signum"]);
                method(x, m, vec![])
            }
            60..=66 => {
                let x = self.expr(&t, d1, false);
                match self.r.below(6) {
                    0 => method(method(x, "abs", vec![]), "sqrt", vec![]),
                    1 => {
                        let lo = Expr::Path(name, "splat", vec![lit(LitV::F32(-6.0), false)]);
                        let hi = Expr::Path(name, "splat", vec![lit(LitV::F32(6.0), false)]);
                        method(method(x, "clamp", vec![lo, hi]), "exp", vec![])
                    }
                    2 => method(bin(BinOp::Rem, x, lit(LitV::F32(3.0), true)), self.r.pick(&["sin", "cos"]), vec![]),
                    3 => {
                        let base = bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), true));
                        let y = self.expr(&F32, d1, false);
                        method(
                            base,
                            "powf",
                            vec![method(y, "clamp", vec![lit(LitV::F32(-3.0), false), lit(LitV::F32(3.0), false)])],
                        )
                    }
                    4 => method(x, "mul_add", vec![self.expr(&t, d1, true), self.expr(&t, d1, true)]),
                    _ => method(x, "normalize_or_zero", vec![]),
                }
            }
            67..=74 => {
                let x = self.expr(&t, d1, false);
                match self.r.below(4) {
                    0 => method(x, self.r.pick(&["min", "max"]), vec![self.expr(&t, d1, true)]),
                    1 => {
                        let lo = self.r.range(-6, 2) as f32 * 0.5;
                        let hi = lo + self.r.range(0, 6) as f32 * 0.5;
                        let lo = Expr::Path(name, "splat", vec![lit(LitV::F32(lo), true)]);
                        let hi = Expr::Path(name, "splat", vec![lit(LitV::F32(hi), true)]);
                        method(x, "clamp", vec![lo, hi])
                    }
                    2 => method(x, "lerp", vec![self.expr(&t, d1, true), self.expr(&F32, d1, true)]),
                    _ if n == 3 => method(x, "cross", vec![self.expr(&t, d1, true)]),
                    _ if self.r.chance(50) => {
                        let m = self.mask_expr(n, d1, true);
                        Expr::Path(name, "select", vec![m, x, self.expr(&t, d1, true)])
                    }
                    _ => method(x, "lerp", vec![self.expr(&t, d1, true), self.expr(&F32, d1, true)]),
                }
            }
            75..=81 => match self.r.below(4) {
                0 => Expr::Free("saturate", vec![self.expr(&t, d1, false)]),
                1 => Expr::Free("step", vec![self.expr(&t, d1, false), self.expr(&t, d1, false)]),
                2 => {
                    let lo = self.r.range(-4, 2) as f32;
                    let hi = lo + self.r.range(1, 4) as f32;
                    let x = self.expr(&t, d1, false);
                    let lo = Expr::Path(name, "splat", vec![lit(LitV::F32(lo), true)]);
                    let hi = Expr::Path(name, "splat", vec![lit(LitV::F32(hi), true)]);
                    Expr::Free("smoothstep", vec![lo, hi, x])
                }
                _ => {
                    let tt = if self.r.chance(50) { F32 } else { t.clone() };
                    Expr::Free(
                        "mix",
                        vec![self.expr(&t, d1, false), self.expr(&t, d1, false), self.expr(&tt, d1, false)],
                    )
                }
            },
            82..=91 => self.reshape(n, Scalar::F32, d1),
            92..=95 => {
                let s = self.r.pick(&[Scalar::I32, Scalar::U32]);
                let x = self.expr(&Ty::V(n, s), d1, false);
                method(x, as_vec(n, Scalar::F32), vec![])
            }
            _ => self.leaf(&t, typed),
        }
    }

    /// A vector of `n` `s`s made from another vector: a swizzle, `extend`
    /// or `truncate`.
    fn reshape(&mut self, n: u8, s: Scalar, d: u32) -> Expr {
        match self.r.below(4) {
            0 if n > 2 => {
                let x = self.expr(&Ty::V(n - 1, s), d, false);
                method(x, "extend", vec![self.expr(&Ty::S(s), d, true)])
            }
            1 if n < 4 => method(self.expr(&Ty::V(n + 1, s), d, false), "truncate", vec![]),
            _ => {
                let m = self.r.range(2, 4) as u8;
                let x = self.expr(&Ty::V(m, s), d, false);
                let idx: Vec<usize> = (0..n).map(|_| self.r.below(m as u64) as usize).collect();
                method(x, swizzle_name(&idx), vec![])
            }
        }
    }

    /// A bool vector of `n` components (`BVecN`, which is never stored:
    /// built and consumed in one expression): comparisons of two vectors
    /// (a float one now and then against `NaN`s, where every comparison
    /// but `cmpne` is false), `!`, `& | ^`, `new` and `splat`. Four
    /// components come in glam's two types: `BVec4A` (`float`: what `Vec4`'s
    /// comparisons give and its `select` takes) and `BVec4` (the integer
    /// vectors'), which Rust does not mix.
    pub(super) fn mask_expr(&mut self, n: u8, d: u32, float: bool) -> Expr {
        let d1 = d.saturating_sub(1);
        let bvec = match n {
            2 => "BVec2",
            3 => "BVec3",
            _ if float => "BVec4A",
            _ => "BVec4",
        };
        match self.r.below(10) {
            6 if d1 > 0 => Expr::Unary(UnOp::Not, b(self.mask_expr(n, d1, float))),
            7 if d1 > 0 => {
                let op = self.r.pick(&[BinOp::BitAnd, BinOp::BitOr, BinOp::BitXor]);
                bin(op, self.mask_expr(n, d1, float), self.mask_expr(n, d1, float))
            }
            8 => Expr::Path(bvec, "splat", vec![self.expr(&BOOL, d1, true)]),
            9 => Expr::Path(bvec, "new", (0..n).map(|_| self.expr(&BOOL, d1, true)).collect()),
            _ => {
                let s = match n {
                    4 if float => Scalar::F32,
                    4 => self.r.pick(&[Scalar::I32, Scalar::U32]),
                    _ => self.r.pick(&[Scalar::F32, Scalar::F32, Scalar::I32, Scalar::U32]),
                };
                let t = Ty::V(n, s);
                let m = self.r.pick(&["cmpeq", "cmpne", "cmplt", "cmple", "cmpgt", "cmpge"]);
                let (a, c) = (self.expr(&t, d1, false), self.expr(&t, d1, true));
                if s == Scalar::F32 && self.r.chance(20) {
                    let nan = Expr::Path(vec_name(n, s), "splat", vec![Expr::Const("f32", "NAN")]);
                    if self.r.chance(50) { method(nan, m, vec![c]) } else { method(a, m, vec![nan]) }
                } else {
                    method(a, m, vec![c])
                }
            }
        }
    }

    pub(super) fn ivec_expr(&mut self, n: u8, s: Scalar, d: u32, typed: bool) -> Expr {
        let t = Ty::V(n, s);
        let d1 = d - 1;
        let name = vec_name(n, s);
        match self.r.below(100) {
            0..=9 => {
                let args: Vec<Expr> = (0..n).map(|_| self.expr(&Ty::S(s), d1, true)).collect();
                match self.r.below(4) {
                    0 => Expr::Path(name, "new", args),
                    1 => Expr::Path(name, "splat", vec![self.expr(&Ty::S(s), d1, true)]),
                    2 => Expr::Path(name, "from_array", vec![Expr::ArrayLit(args)]),
                    _ => Expr::Free(vec_fn(n, s), args),
                }
            }
            10..=24 => {
                let op = self.r.pick(&[BinOp::Add, BinOp::Sub, BinOp::Mul]);
                if self.r.chance(70) {
                    let (a, c) = self.operands(&t, &t, d, false);
                    bin(op, a, c)
                } else {
                    let a = self.expr(&t, d1, false);
                    bin(op, a, self.expr(&Ty::S(s), d1, false))
                }
            }
            25..=29 => {
                // (glam's unsigned vectors have no `div_euclid`/`rem_euclid`.)
                let m = if s == Scalar::I32 {
                    self.r.pick(&[
                        "wrapping_add",
                        "wrapping_sub",
                        "wrapping_mul",
                        "div_euclid",
                        "rem_euclid",
                        "wrapping_div",
                        "saturating_div",
                    ])
                } else {
                    self.r.pick(&["wrapping_add", "wrapping_sub", "wrapping_mul", "wrapping_div", "saturating_div"])
                };
                let (x, y) = (self.expr(&t, d1, false), self.expr(&t, d1, true));
                if self.r.chance(25) { Expr::Path(name, m, vec![x, y]) } else { method(x, m, vec![y]) }
            }
            30..=36 => {
                let op = self.r.pick(&[BinOp::Div, BinOp::Rem]);
                let a = self.expr(&t, d1, false);
                let c = if self.r.chance(60) { self.divisor(&t, d) } else { self.divisor(&Ty::S(s), d) };
                bin(op, a, c)
            }
            37..=49 => {
                let op = self.r.pick(&[BinOp::BitAnd, BinOp::BitOr, BinOp::BitXor]);
                let a = self.expr(&t, d1, false);
                let c = if self.r.chance(60) { self.expr(&t, d1, true) } else { self.expr(&Ty::S(s), d1, false) };
                bin(op, a, c)
            }
            50..=57 => {
                let op = self.r.pick(&[BinOp::Shl, BinOp::Shr]);
                let a = self.expr(&t, d1, false);
                let c = self.shift_amount(&t, d);
                bin(op, a, c)
            }
            58..=62 => {
                let x = self.expr(&t, d1, false);
                if s == Scalar::I32 && self.r.chance(50) {
                    Expr::Unary(UnOp::Neg, b(x))
                } else {
                    Expr::Unary(UnOp::Not, b(x))
                }
            }
            63..=72 => {
                let x = self.expr(&t, d1, false);
                match self.r.below(5) {
                    0 if s == Scalar::I32 => method(x, self.r.pick(&["abs", "signum"]), vec![]),
                    2 if n == 3 => method(x, "cross", vec![self.expr(&t, d1, true)]),
                    3 => {
                        let m = self.mask_expr(n, d1, false);
                        Expr::Path(name, "select", vec![m, x, self.expr(&t, d1, true)])
                    }
                    1 => {
                        let lo = if s == Scalar::I32 { self.r.range(-20, 5) } else { self.r.range(0, 5) };
                        let hi = lo + self.r.range(0, 30);
                        let l = |v: i64| {
                            lit(if s == Scalar::I32 { LitV::I32(v as i32) } else { LitV::U32(v as u32) }, true)
                        };
                        method(
                            x,
                            "clamp",
                            vec![Expr::Path(name, "splat", vec![l(lo)]), Expr::Path(name, "splat", vec![l(hi)])],
                        )
                    }
                    _ => method(x, self.r.pick(&["min", "max"]), vec![self.expr(&t, d1, true)]),
                }
            }
            73..=84 => self.reshape(n, s, d1),
            85..=94 => {
                let from = self.r.pick(&[Scalar::F32, if s == Scalar::I32 { Scalar::U32 } else { Scalar::I32 }]);
                let x = self.expr(&Ty::V(n, from), d1, false);
                method(x, as_vec(n, s), vec![])
            }
            _ => self.leaf(&t, typed),
        }
    }
}
