// A method calling itself: WGSL has no recursion.
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Counter {
    pub n: u32,
}

#[rt_impl]
impl Counter {
    pub fn count_down(&mut self) {
        if self.n > 0 {
            self.n -= 1;
            self.count_down();
        }
    }
}

fn main() {}
