// `IndexMut` for a user struct: WGSL functions return no references, so
// `c[i] = v` has nothing to call.
use rt_std::prelude::*;
use std::ops::{Index, IndexMut};

#[rt_struct(impl Index<usize>, impl IndexMut<usize>)]
pub struct Rgb {
    pub c: [f32; 3],
}

#[rt_impl]
impl Index<usize> for Rgb {
    type Output = f32;
    fn index(&self, i: usize) -> &f32 {
        &self.c[i]
    }
}

#[rt_impl]
impl IndexMut<usize> for Rgb {
    fn index_mut(&mut self, i: usize) -> &mut f32 {
        &mut self.c[i]
    }
}

fn main() {}
