//! `#[rt_trait]`s: a trait with a default method and a default constant,
//! implemented for a struct and a payload (`#[rt_struct(impl Trait)]`,
//! `#[rt_payload(impl Trait)]`), one overriding both; calls by the
//! receiver's type and through a generic helper bounded by the trait.
use rt_std::prelude::*;

/// Something with a brightness.
#[rt_trait]
pub trait Shine {
    const SCALE: f32 = 1.0;
    fn level(&self) -> f32;
    fn shine(&self, by: f32) -> f32 {
        self.level() * by * Self::SCALE
    }
}

/// A lamp.
#[rt_struct(impl Shine)]
pub struct Lamp {
    pub power: f32,
}

#[rt_impl]
impl Shine for Lamp {
    fn level(&self) -> f32 {
        self.power
    }
}

/// A payload that glows too.
#[rt_payload(impl Shine)]
pub struct ShineRay {
    pub energy: f32,
}

#[rt_impl]
impl Shine for ShineRay {
    const SCALE: f32 = 0.5;
    fn level(&self) -> f32 {
        self.energy
    }
    fn shine(&self, by: f32) -> f32 {
        self.energy + by * Self::SCALE
    }
}

/// Generic over the trait.
#[rt_function]
pub fn brighter<S: Shine>(s: S, h: f32) -> f32 {
    s.shine(h) + S::SCALE
}

#[rt_program(miss)]
pub fn shine_miss(prd: &mut ShineRay) {
    let lamp = Lamp { power: 2.0 };
    prd.energy = lamp.shine(prd.energy) + brighter(lamp, 1.0) + brighter(*prd, 0.5) + prd.shine(1.0);
}
