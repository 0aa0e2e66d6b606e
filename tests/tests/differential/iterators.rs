//! Iterators over ranges and fixed arrays, as Rust writes them (`for x in
//! arr`, `.iter()`, `.enumerate()`, `.rev()`, `.step_by()`, `.zip()`,
//! `.map()`, `.filter()`, `.sum()`, `.fold()`, `.any()`, `.all()`,
//! `.count()`, with closures inlined), closures bound to a name,
//! `arr.len()`, labelled `break` and `continue`, `break` with a value, and
//! the patterns a `switch` cannot take: `matches!`, range patterns and
//! guards.

use super::*;

/// A helper whose loops are iterator chains.
#[rt_function]
pub fn weighted(w: [f32; 4], x: f32) -> f32 {
    w.iter().enumerate().map(|(i, wi)| wi * x.powi(i as i32)).sum::<f32>()
}

/// A helper with a range pattern, a guard and a binding.
#[rt_function]
pub fn grade(n: i32) -> u32 {
    match n {
        i32::MIN..=-1 => 0,
        0 => 1,
        1..=9 => 2,
        k if k % 2 == 0 => 3,
        _ => 4,
    }
}

differential! {
    /// Loops and reductions over arrays and ranges.
    fn iterator_chains {
        /// Loops over an array by value, by reference, reversed, numbered
        /// and zipped; `len()`.
        array_loops(x: f32) -> [f32; 6] over one(&spread(16, -2.0, 2.0)), tol CHAINED => {
            let arr = [x, x * 2.0, 0.5 + x * x, 3.0];
            let mut by_value = 0.0;
            for v in arr {
                by_value += v;
            }
            let mut by_ref = 0.0;
            for v in &arr {
                by_ref = by_ref * 0.5 + *v;
            }
            let mut reversed = 0.0;
            for v in arr.iter().rev() {
                reversed = reversed * 0.5 + v;
            }
            let mut numbered = 0.0;
            for (i, &v) in arr.iter().enumerate() {
                numbered += v * i as f32;
            }
            let other = [1.0, -1.0, 2.0];
            let mut zipped = 0.0;
            for (a, b) in arr.iter().zip(other.iter()) {
                zipped += a * b;
            }
            [by_value, by_ref, reversed, numbered, zipped, arr.len() as f32 + other.len() as f32]
        }
        /// Reductions: sums, a fold, `any`/`all`, `count` with a filter, a
        /// helper built of a chain.
        reductions(x: f32) -> [f32; 7] over one(&spread(16, -2.0, 2.0)), tol CHAINED => {
            let arr = [x, 1.0 - x, x * x, -0.5];
            let total: f32 = arr.iter().sum();
            let squares = arr.iter().map(|v| v * v).sum::<f32>();
            let folded = arr.iter().fold(1.0, |acc, v| acc * 0.5 + v);
            let any_big = arr.iter().any(|v| *v > 1.0);
            let all_small = arr.iter().all(|&v| v < 3.0);
            let positive = arr.iter().filter(|v| **v > 0.0).count();
            [total, squares, folded, any_big as u32 as f32, all_small as u32 as f32, positive as f32,
             weighted([1.0, 2.0, -1.0, 0.5], x)]
        }
        /// Ranges reversed, stepped and reduced; integer types from their
        /// uses.
        range_chains(n: u32) -> [u32; 6] over one(&[0, 1, 2, 5, 8, 13]) => {
            let mut rev = 0u32;
            for i in (0..n).rev() {
                rev = rev * 3 + i;
            }
            let mut stepped = 0u32;
            for i in (1..n).step_by(3) {
                stepped = stepped * 7 + i;
            }
            let mut closed = 0u32;
            for i in (2..=n).rev().step_by(2) {
                closed = closed * 5 + i;
            }
            let sum: u32 = (0..n).sum();
            let odd = (0..n).filter(|i| i % 2 == 1).count() as u32;
            let squares = (0..n).map(|i| i * i).fold(1, |a, b| (a * 3 + b) % 100003);
            [rev, stepped, closed, sum, odd, squares]
        }
        /// `loop`s whose `break`s carry the value: an integer settled by
        /// its use, a float from a `match` arm (a `break` out of a
        /// `switch`), and a plain `break` out of an inner `while`.
        loop_values(n: u32) -> [f32; 3] over one(&[0, 1, 2, 5, 9, 17, 40]) => {
            let mut i = 0u32;
            let root = loop {
                if i * i >= n {
                    break i;
                }
                i += 1;
            };
            let mut k = 0u32;
            let picked = loop {
                k += 1;
                match k % 4 {
                    3 => break k as f32 * 0.5,
                    _ if k > n => break -1.0,
                    _ => {}
                }
            };
            let mut steps = 0u32;
            let settled = loop {
                let mut m = steps;
                while m > 0 {
                    if m == 3 {
                        break;
                    }
                    m -= 1;
                }
                steps += 1;
                if steps > n / 3 {
                    break m + steps * 10;
                }
            };
            [root as f32, picked, settled as f32]
        }
        /// Closures bound to a name, reading and writing what they capture;
        /// labelled `break` and `continue` out of nested loops.
        closures_and_labels(n: u32) -> [u32; 4] over one(&[0, 1, 3, 4, 7, 12, 20]) => {
            let k = n + 1;
            let scale = |a: u32| a * k + 1;
            let mut count = 0u32;
            let mut bump = |by: u32| count += by;
            bump(scale(2));
            bump(3);
            let mut found = 0u32;
            'outer: for i in 0..n {
                for j in 0..n {
                    if i * j == 12 {
                        found = i * 100 + j;
                        break 'outer;
                    }
                }
            }
            let mut skipped = 0u32;
            'rows: for i in 0..n {
                let mut j = 0u32;
                while j < 4 {
                    j += 1;
                    if (i + j) % 3 == 0 {
                        continue 'rows;
                    }
                    skipped += 1;
                }
                skipped += 10;
            }
            [scale(n), count, found, skipped]
        }
        /// `matches!`, range patterns and guards, in a helper and inline.
        patterns(a: i32) -> [u32; 4] over one(&[-1000, -1, 0, 1, 5, 9, 10, 11, 12, 100]) => {
            let small = matches!(a, -9..=9);
            let even_big = matches!(a, k if k > 9 && k % 2 == 0);
            let band = match a.unsigned_abs() {
                0..10 => 1,
                10..=99 => 2,
                _ => 3,
            };
            [grade(a), small as u32, even_big as u32, band]
        }
    }
}
