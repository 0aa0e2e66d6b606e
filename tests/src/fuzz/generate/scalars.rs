//! Scalar expressions: `f32`, integers, `bool`.

use super::*;

impl Gen {
    pub(super) fn f32_expr(&mut self, d: u32, typed: bool) -> Expr {
        let d1 = d - 1;
        match self.r.below(100) {
            0..=29 => self.f32_arith(d, typed),
            30..=33 => Expr::Unary(UnOp::Neg, b(self.expr(&F32, d1, typed))),
            34..=49 => self.f32_plain_method(d1),
            50..=57 => self.f32_transcendental(d),
            58..=67 => self.f32_two_operand_method(d),
            68..=74 => {
                let s = self.r.pick(&[Scalar::I32, Scalar::U32]);
                Expr::Cast(b(self.expr(&Ty::S(s), d1, false)), Scalar::F32)
            }
            75..=84 => self.f32_of_vector(d1),
            85..=92 => self.f32_generic_math(d1),
            93..=96 if self.ret.is_none() && !self.no_buf => {
                let i = self.scratch_index();
                Expr::BufLoad(1, b(i), self.r.chance(50))
            }
            _ => self.leaf(&F32, typed),
        }
    }

    /// `a op b` of `+ - * / %`, the dividing ones by [`Gen::divisor`].
    fn f32_arith(&mut self, d: u32, typed: bool) -> Expr {
        let d1 = d - 1;
        let op = [BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Rem][self.r.weighted(&[4, 4, 4, 2, 1])];
        if matches!(op, BinOp::Div | BinOp::Rem) {
            let a = self.expr(&F32, d1, typed);
            let c = self.divisor(&F32, d);
            bin(op, a, c)
        } else {
            let (a, c) = self.operands(&F32, &F32, d, typed);
            bin(op, a, c)
        }
    }

    /// A one-operand method defined for every operand (`abs`, `floor`,
    /// `atan`, ...).
    fn f32_plain_method(&mut self, d1: u32) -> Expr {
        let x = self.expr(&F32, d1, false);
        let m = self.r.pick(&[
            "abs",
            "floor",
            "ceil",
            "trunc",
            "round",
            "fract",
            "signum",
            "atan",
            "to_radians",
            "to_degrees",
        ]);
        method(x, m, vec![])
    }

    /// `sqrt`, `exp`, `ln`, `sin`, `recip`, ... with their operands kept
    /// in the range where they are defined and accurate.
    fn f32_transcendental(&mut self, d: u32) -> Expr {
        let d1 = d - 1;
        let x = self.expr(&F32, d1, false);
        match self.r.below(6) {
            0 => method(method(x, "abs", vec![]), "sqrt", vec![]),
            1 => {
                let m = self.r.pick(&["exp", "exp2"]);
                method(method(x, "clamp", vec![lit(LitV::F32(-8.0), false), lit(LitV::F32(8.0), false)]), m, vec![])
            }
            2 => {
                let m = self.r.pick(&["ln", "log2"]);
                method(bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), false)), m, vec![])
            }
            3 | 4 => {
                let m = self.r.pick(&["sin", "cos"]);
                if self.r.chance(85) {
                    method(bin(BinOp::Rem, x, lit(LitV::F32(3.0), false)), m, vec![])
                } else {
                    method(x, m, vec![])
                }
            }
            _ => method(self.divisor(&F32, d), "recip", vec![]),
        }
    }

    /// `min`/`max`, `clamp`, `powi`, `powf`, `mul_add` and `f32::min`/`max`.
    fn f32_two_operand_method(&mut self, d: u32) -> Expr {
        let d1 = d - 1;
        let x = self.expr(&F32, d1, false);
        match self.r.below(6) {
            0 => method(x, self.r.pick(&["min", "max"]), vec![self.expr(&F32, d1, true)]),
            1 => {
                let lo = self.r.range(-8, 4) as f32 * 0.5;
                let hi = lo + self.r.range(0, 8) as f32 * 0.5;
                method(x, "clamp", vec![lit(LitV::F32(lo), true), lit(LitV::F32(hi), true)])
            }
            2 => {
                let n = self.r.range(-3, 4) as i32;
                let base =
                    if n < 0 { bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), false)) } else { x };
                method(base, "powi", vec![lit(LitV::I32(n), self.r.chance(30))])
            }
            3 => {
                let base = bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), false));
                let y = self.expr(&F32, d1, false);
                method(
                    base,
                    "powf",
                    vec![method(y, "clamp", vec![lit(LitV::F32(-3.0), false), lit(LitV::F32(3.0), false)])],
                )
            }
            4 => method(x, "mul_add", vec![self.expr(&F32, d1, true), self.expr(&F32, d1, true)]),
            _ => Expr::Path("f32", self.r.pick(&["min", "max"]), vec![x, self.expr(&F32, d1, true)]),
        }
    }

    /// A float vector reduced to an `f32`: `dot`, `length`, an element.
    fn f32_of_vector(&mut self, d1: u32) -> Expr {
        let vt = self.fvec();
        let v = self.expr(&vt, d1, false);
        let Ty::V(n, _) = vt else { unreachable!() };
        match self.r.below(9) {
            0 => method(v, "dot", vec![self.expr(&vt, d1, true)]),
            1 => method(v, "length", vec![]),
            2 => method(v, "length_squared", vec![]),
            3 => method(v, "distance", vec![self.expr(&vt, d1, true)]),
            4 => method(v, self.r.pick(&["element_sum", "element_product", "min_element", "max_element"]), vec![]),
            5 => method(v, "distance_squared", vec![self.expr(&vt, d1, true)]),
            6 => {
                let idx = self.index_expr(n as u32);
                Expr::Index(b(v), b(idx))
            }
            _ => {
                let i = self.r.below(n as u64) as usize;
                Expr::Field(b(v), COMP[i].into(), i)
            }
        }
    }

    /// rt-std's generic math: literals suffixed (the parameter types are
    /// generic).
    fn f32_generic_math(&mut self, d1: u32) -> Expr {
        match self.r.below(4) {
            0 => Expr::Free("saturate", vec![self.expr(&F32, d1, false)]),
            1 => Expr::Free("step", vec![self.expr(&F32, d1, false), self.expr(&F32, d1, false)]),
            2 => {
                let lo = self.r.range(-4, 2) as f32;
                let hi = lo + self.r.range(1, 4) as f32;
                let x = self.expr(&F32, d1, false);
                Expr::Free("smoothstep", vec![lit(LitV::F32(lo), true), lit(LitV::F32(hi), true), x])
            }
            _ => Expr::Free(
                "mix",
                vec![self.expr(&F32, d1, false), self.expr(&F32, d1, false), self.expr(&F32, d1, false)],
            ),
        }
    }

    pub(super) fn int_expr(&mut self, s: Scalar, d: u32, typed: bool) -> Expr {
        let t = Ty::S(s);
        let d1 = d - 1;
        match self.r.below(100) {
            0..=24 => self.int_arith(s, d, typed),
            25..=29 => self.int_wrapping_method(s, d1),
            30..=44 => {
                let op = self.r.pick(&[BinOp::BitAnd, BinOp::BitOr, BinOp::BitXor]);
                let (a, c) = self.operands(&t, &t, d, typed);
                bin(op, a, c)
            }
            45..=54 => {
                let op = self.r.pick(&[BinOp::Shl, BinOp::Shr]);
                let a = self.expr(&t, d1, false);
                let c = self.shift_amount(&t, d);
                bin(op, a, c)
            }
            55..=59 => {
                let x = self.expr(&t, d1, typed);
                // `-x` of a constant `i32::MIN` is a Rust compile error.
                if s == Scalar::I32 && self.r.chance(50) && !self.is_const(&x) {
                    Expr::Unary(UnOp::Neg, b(x))
                } else {
                    Expr::Unary(UnOp::Not, b(x))
                }
            }
            60..=64 => self.int_min_max_method(s, d1),
            65..=69 => self.int_bit_count(s, d1),
            70..=79 => {
                let other = if s == Scalar::I32 { Scalar::U32 } else { Scalar::I32 };
                let from = self.r.pick(&[Scalar::F32, Scalar::F32, other, Scalar::Bool]);
                let d2 = if from == Scalar::Bool { d1.min(1) } else { d1 };
                Expr::Cast(b(self.expr(&Ty::S(from), d2, false)), s)
            }
            80..=87 => self.int_of_vector(s, d1),
            88..=91 if self.ret.is_none() && !self.no_buf => {
                let i = self.scratch_index();
                let load = Expr::BufLoad(0, b(i), self.r.chance(50));
                if s == Scalar::U32 { load } else { Expr::Cast(b(load), s) }
            }
            92..=94 if self.r.chance(40) => {
                let x = self.expr(&U32, d1, false);
                let y = self.expr(&U32, d1, true);
                let c = method(x, "is_multiple_of", vec![y]);
                Expr::Cast(b(c), s)
            }
            92..=94 => self.int_std_method(s, d1),
            _ => self.leaf(&t, typed),
        }
    }

    /// `a op b` of `+ - * / %`, the dividing ones by [`Gen::divisor`], the
    /// others through [`Gen::int_op`].
    fn int_arith(&mut self, s: Scalar, d: u32, typed: bool) -> Expr {
        let t = Ty::S(s);
        let d1 = d - 1;
        let op = [BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Rem][self.r.weighted(&[4, 4, 3, 2, 2])];
        if matches!(op, BinOp::Div | BinOp::Rem) {
            let a = self.expr(&t, d1, typed);
            let c = self.divisor(&t, d);
            bin(op, a, c)
        } else {
            let (a, c) = self.operands(&t, &t, d, typed);
            self.int_op(s, op, a, c)
        }
    }

    /// The wrapping and dividing methods, in method or path form. The
    /// dividing methods take any divisor: a zero one is read as one,
    /// `MIN / -1` wraps (saturates for `saturating_div`).
    fn int_wrapping_method(&mut self, s: Scalar, d1: u32) -> Expr {
        let t = Ty::S(s);
        let m = self.r.pick(&[
            "wrapping_add",
            "wrapping_sub",
            "wrapping_mul",
            "div_euclid",
            "rem_euclid",
            "wrapping_div",
            "saturating_div",
        ]);
        let x = self.expr(&t, d1, false);
        let y = self.expr(&t, d1, true);
        if self.r.chance(25) { Expr::Path(s.rust(), m, vec![x, y]) } else { method(x, m, vec![y]) }
    }

    /// `abs`/`signum` (of `i32`), `clamp` by literals, `min`/`max`.
    fn int_min_max_method(&mut self, s: Scalar, d1: u32) -> Expr {
        let t = Ty::S(s);
        let x = self.expr(&t, d1, false);
        match self.r.below(4) {
            0 if s == Scalar::I32 => method(x, self.r.pick(&["abs", "signum"]), vec![]),
            1 => {
                let lo = self.r.range(-20, 10);
                let hi = lo + self.r.range(0, 30);
                let (lo, hi) = if s == Scalar::U32 { (lo.max(0), hi.max(0)) } else { (lo, hi) };
                let l = |v: i64| lit(if s == Scalar::I32 { LitV::I32(v as i32) } else { LitV::U32(v as u32) }, true);
                method(x, "clamp", vec![l(lo), l(hi)])
            }
            _ => method(x, self.r.pick(&["min", "max"]), vec![self.expr(&t, d1, true)]),
        }
    }

    /// The bit-counting methods (and `reverse_bits`) of either integer
    /// type, cast to `s` where their result is not.
    fn int_bit_count(&mut self, s: Scalar, d1: u32) -> Expr {
        let other = if s == Scalar::I32 { Scalar::U32 } else { Scalar::I32 };
        let src = self.r.pick(&[s, other]);
        let x = self.expr(&Ty::S(src), d1, false);
        let m = self.r.pick(&[
            "count_ones",
            "leading_zeros",
            "trailing_zeros",
            "reverse_bits",
            "count_zeros",
            "leading_ones",
            "trailing_ones",
        ]);
        let e = method(x, m, vec![]);
        let result = if m == "reverse_bits" { src } else { Scalar::U32 };
        if result == s { e } else { Expr::Cast(b(e), s) }
    }

    /// An integer vector reduced to an `s`: `dot`, an element, a distance,
    /// a bool vector's `bitmask`.
    fn int_of_vector(&mut self, s: Scalar, d1: u32) -> Expr {
        let vt = self.ivec(s);
        let Ty::V(n, _) = vt else { unreachable!() };
        let v = self.expr(&vt, d1, false);
        match self.r.below(8) {
            0 => method(v, "dot", vec![self.expr(&vt, d1, true)]),
            1 => method(v, self.r.pick(&["element_sum", "element_product", "min_element", "max_element"]), vec![]),
            2 => {
                let idx = self.index_expr(n as u32);
                Expr::Index(b(v), b(idx))
            }
            3 => method(v, "length_squared", vec![]),
            4 if s == Scalar::I32 => method(v, "distance_squared", vec![self.expr(&vt, d1, true)]),
            5 => {
                let m = method(v, "manhattan_distance", vec![self.expr(&vt, d1, true)]);
                if s == Scalar::U32 { m } else { Expr::Cast(b(m), s) }
            }
            6 => {
                let float = self.r.chance(50);
                let m = self.mask_expr(n, d1, float);
                let bits = method(m, "bitmask", vec![]);
                if s == Scalar::U32 { bits } else { Expr::Cast(b(bits), s) }
            }
            _ => {
                let i = self.r.below(n as u64) as usize;
                Expr::Field(b(v), COMP[i].into(), i)
            }
        }
    }

    /// std's methods with the GPU's meaning where std panics (`pow` wraps,
    /// `isqrt`/`ilog2` of a negative or zero are 0).
    fn int_std_method(&mut self, s: Scalar, d1: u32) -> Expr {
        let t = Ty::S(s);
        let x = self.expr(&t, d1, false);
        let (e, result) = match self.r.below(7) {
            0 => (method(x, "wrapping_neg", vec![]), s),
            1 => (method(x, "isqrt", vec![]), s),
            2 => (method(x, self.r.pick(&["ilog2", "ilog10"]), vec![]), Scalar::U32),
            3 => (method(x, "abs_diff", vec![self.expr(&t, d1, true)]), Scalar::U32),
            4 => (method(x, "midpoint", vec![self.expr(&t, d1, true)]), s),
            5 => {
                let k = lit(LitV::U32(self.r.range(0, 40) as u32), false);
                (method(x, self.r.pick(&["pow", "wrapping_pow"]), vec![k]), s)
            }
            _ => (method(x, "saturating_pow", vec![lit(LitV::U32(self.r.range(0, 12) as u32), false)]), s),
        };
        if result == s { e } else { Expr::Cast(b(e), s) }
    }

    pub(super) fn bool_expr(&mut self, d: u32) -> Expr {
        let d1 = d - 1;
        match self.r.below(100) {
            0..=27 => {
                let op = self.r.pick(&[BinOp::Lt, BinOp::Le, BinOp::Gt, BinOp::Ge, BinOp::Eq, BinOp::Ne]);
                let (a, c) = self.operands(&F32, &F32, d, false);
                // A NaN operand: every comparison but `!=` is false (Rust's
                // unordered meaning, which the GPU must keep).
                match self.r.below(12) {
                    0 => bin(op, Expr::Const("f32", "NAN"), c),
                    1 => bin(op, a, Expr::Const("f32", "NAN")),
                    _ => bin(op, a, c),
                }
            }
            28..=47 => {
                let op = self.r.pick(&[BinOp::Lt, BinOp::Le, BinOp::Gt, BinOp::Ge, BinOp::Eq, BinOp::Ne]);
                let t = Ty::S(self.r.pick(&[Scalar::I32, Scalar::U32]));
                let (a, c) = self.operands(&t, &t, d, false);
                bin(op, a, c)
            }
            48..=52 => {
                let t = self.r.pick(&self.vecs);
                let op = self.r.pick(&[BinOp::Eq, BinOp::Ne]);
                let (a, c) = self.operands(&t, &t, d, false);
                bin(op, a, c)
            }
            53..=67 => {
                let op = self.r.pick(&[BinOp::And, BinOp::Or]);
                bin(op, self.expr(&BOOL, d1, false), self.expr(&BOOL, d1, false))
            }
            68..=75 => Expr::Unary(UnOp::Not, b(self.expr(&BOOL, d1, false))),
            76..=83 => {
                let op = self.r.pick(&[BinOp::BitAnd, BinOp::BitOr, BinOp::BitXor, BinOp::Eq, BinOp::Ne]);
                bin(op, self.expr(&BOOL, d1, false), self.expr(&BOOL, d1, false))
            }
            84..=89 => {
                let x = self.expr(&U32, d1, false);
                method(x, "is_multiple_of", vec![self.expr(&U32, d1, true)])
            }
            90..=95 => {
                let n = self.r.range(2, 4) as u8;
                let float = self.r.chance(50);
                let m = self.mask_expr(n, d1, float);
                method(m, self.r.pick(&["any", "all"]), vec![])
            }
            _ => self.leaf(&BOOL, false),
        }
    }
}
