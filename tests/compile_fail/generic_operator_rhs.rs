// An operator impl of a generic struct whose right-hand type is the
// impl's parameter: the impl is chosen by the right-hand type, which
// must not vary with the instance.
use core::ops::Mul;
use rt_std::prelude::*;

#[rt_struct(impl Mul<T>)]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

#[rt_impl]
impl<T: Copy + Mul<Output = T>> Mul<T> for Pair<T> {
    type Output = Self;
    fn mul(self, k: T) -> Self {
        Pair { a: self.a * k, b: self.b * k }
    }
}

fn main() {}
