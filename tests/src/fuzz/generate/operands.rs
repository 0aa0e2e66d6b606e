//! Guarded right operands: divisors and shift amounts.

use super::*;

impl Gen {
    /// The right operand of `op` (guarded divisors, shift amounts).
    pub(super) fn operand_for(&mut self, op: BinOp, t: &Ty, d: u32) -> Expr {
        match (op, t) {
            (BinOp::Div | BinOp::Rem, _) => self.divisor(t, d),
            (BinOp::Shl | BinOp::Shr, _) => self.shift_amount(t, d),
            _ => self.expr(t, d, true),
        }
    }

    /// A divisor of type `t`: floats kept away from zero; integers mostly
    /// non-zero, a quarter of them from -1..=2 (zero and `-1` included:
    /// `rt_std::arith` defines both on every backend). Those mix in the
    /// launch index: naga rejects a division by a *constant* zero (its
    /// constant evaluator reports "Division by zero"), which a generated
    /// expression of literals could be.
    pub(super) fn divisor(&mut self, t: &Ty, d: u32) -> Expr {
        let d = d.saturating_sub(1).max(1);
        match t {
            Ty::S(Scalar::F32) => {
                if self.r.chance(35) {
                    lit(LitV::F32(self.r.pick(&[0.5, 2.0, -3.0, 0.1, 7.0, -0.75])), true)
                } else {
                    let x = self.expr(&F32, d, false);
                    bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), false))
                }
            }
            Ty::S(Scalar::I32) => match self.r.below(4) {
                0 => lit(LitV::I32(self.r.pick(&[2, 3, -2, 7, -5, 16])), true),
                3 => {
                    // -1..=2: zero and -1 as often as not (`rt_std::arith`).
                    let x = bin(BinOp::BitXor, self.expr(&I32, d, false), launch_x_i32());
                    bin(BinOp::Sub, bin(BinOp::BitAnd, x, lit(LitV::I32(3), false)), lit(LitV::I32(1), false))
                }
                1 => {
                    let x = self.expr(&I32, d, false);
                    bin(BinOp::Add, bin(BinOp::BitAnd, x, lit(LitV::I32(15), false)), lit(LitV::I32(1), false))
                }
                _ => {
                    let x = self.expr(&I32, d, false);
                    let m = bin(BinOp::Add, bin(BinOp::BitAnd, x, lit(LitV::I32(15), false)), lit(LitV::I32(2), false));
                    Expr::Unary(UnOp::Neg, b(m))
                }
            },
            Ty::S(_) => match self.r.below(4) {
                0 => lit(LitV::U32(self.r.pick(&[2, 3, 7, 16, 1000])), true),
                3 => {
                    let x = bin(BinOp::BitXor, self.expr(&U32, d, false), Expr::LaunchX);
                    bin(BinOp::BitAnd, x, lit(LitV::U32(3), false))
                }
                1 => {
                    let x = self.expr(&U32, d, false);
                    bin(BinOp::BitOr, x, lit(LitV::U32(1), false))
                }
                _ => {
                    let x = self.expr(&U32, d, false);
                    bin(BinOp::Add, bin(BinOp::Rem, x, lit(LitV::U32(7), false)), lit(LitV::U32(1), false))
                }
            },
            Ty::V(n, Scalar::F32) => {
                let x = self.expr(&Ty::V(*n, Scalar::F32), d, false);
                bin(BinOp::Add, method(x, "abs", vec![]), lit(LitV::F32(0.5), true))
            }
            Ty::V(n, Scalar::I32) => {
                let x = self.expr(&Ty::V(*n, Scalar::I32), d, false);
                if self.r.chance(25) {
                    let x = bin(BinOp::BitXor, x, launch_x_i32());
                    return bin(BinOp::Sub, bin(BinOp::BitAnd, x, lit(LitV::I32(3), true)), lit(LitV::I32(1), true));
                }
                bin(BinOp::Add, bin(BinOp::BitAnd, x, lit(LitV::I32(15), true)), lit(LitV::I32(1), true))
            }
            Ty::V(n, s) => {
                let x = self.expr(&Ty::V(*n, *s), d, false);
                if self.r.chance(25) {
                    return bin(BinOp::BitAnd, bin(BinOp::BitXor, x, Expr::LaunchX), lit(LitV::U32(3), true));
                }
                bin(BinOp::BitOr, x, lit(LitV::U32(1), true))
            }
            _ => unreachable!(),
        }
    }

    /// A shift amount for a value of type `t`: mostly masked or a literal
    /// below 32, sometimes anything (taken modulo 32, see `interp`).
    pub(super) fn shift_amount(&mut self, t: &Ty, d: u32) -> Expr {
        let d = d.saturating_sub(1).max(1);
        let s = self.r.pick(&[Scalar::U32, Scalar::I32]);
        // A vector's shift amount literal needs its suffix: glam shifts by
        // every integer type.
        let vector = matches!(t, Ty::V(..));
        let k = |v: u32| lit(if s == Scalar::I32 { LitV::I32(v as i32) } else { LitV::U32(v) }, vector);
        match (self.r.below(10), t) {
            (0..=3, _) => lit(LitV::U32(self.r.below(32) as u32), vector),
            (4..=5, Ty::V(n, _)) => {
                let vs = self.r.pick(&[Scalar::U32, Scalar::I32]);
                let x = self.expr(&Ty::V(*n, vs), d, false);
                bin(BinOp::BitAnd, x, lit(if vs == Scalar::I32 { LitV::I32(31) } else { LitV::U32(31) }, true))
            }
            (4..=8, _) => {
                let x = self.expr(&Ty::S(s), d, false);
                bin(BinOp::BitAnd, x, k(31))
            }
            _ => {
                // Any amount, taken modulo 32; but an amount rustc can
                // evaluate must be below 32 (`arithmetic_overflow`).
                let x = self.expr(&U32, d, false);
                if self.is_const(&x) { bin(BinOp::BitAnd, x, lit(LitV::U32(31), vector)) } else { x }
            }
        }
    }
}
