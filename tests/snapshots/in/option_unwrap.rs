//! `unwrap` and `expect` of an `Option`: the flag tested, `rt_throw` of
//! `EXCEPTION_PANIC` where it is `None`, the value (zero then) used.
use rt_std::prelude::*;

/// A payload that may carry a hit distance.
#[rt_payload]
pub struct MaybeT {
    pub t: f32,
    pub has: bool,
}

#[rt_program(miss)]
pub fn maybe_t_miss(prd: &mut MaybeT) {
    let o = if prd.has { Some(prd.t) } else { None };
    prd.t = o.unwrap() * 2.0 + Some(1.0f32).expect("one");
}
