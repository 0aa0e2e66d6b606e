//! Line-aware mutations of text formats (OBJ, MTL, a part file's header):
//! lines deleted, repeated or swapped, numbers replaced by values at the
//! edges (NaN, infinities, beyond f32, huge and zero indices), keywords
//! swapped, words dropped, separators turned into tabs.

use crate::fuzz::generate::Rng;

const NUMBERS: &[&str] = &[
    "0",
    "1",
    "-1",
    "2",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "1e39",
    "-1e39",
    "3e38",
    "1e-45",
    "99999999999",
    "4294967295",
    "4294967296",
    "100000000",
    "-2147483648",
    "0.5",
    "",
    "x",
    "1/",
    "//",
    "1//1",
    "0/0/0",
];

/// Applies one to four line mutations to `text`, using `keywords` of its
/// format.
pub fn mutate(rng: &mut Rng, text: &str, keywords: &[&str]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..rng.range(1, 4) {
        if lines.is_empty() {
            lines.push(rng.pick(keywords).to_string());
        }
        let i = rng.below(lines.len() as u64) as usize;
        match rng.weighted(&[10, 10, 6, 30, 12, 10, 8, 6]) {
            0 => {
                lines.remove(i);
            }
            1 => {
                let copy = lines[i].clone();
                for _ in 0..rng.range(1, 3) {
                    lines.insert(i, copy.clone());
                }
            }
            2 => {
                let j = rng.below(lines.len() as u64) as usize;
                lines.swap(i, j);
            }
            3 => {
                let mut words: Vec<String> = lines[i].split(' ').map(str::to_string).collect();
                let w = rng.range(if words.len() > 1 { 1 } else { 0 }, words.len() as i64 - 1) as usize;
                words[w] = rng.pick(NUMBERS).to_string();
                lines[i] = words.join(" ");
            }
            4 => {
                let mut words: Vec<&str> = lines[i].split(' ').collect();
                words[0] = rng.pick(keywords);
                lines[i] = words.join(" ");
            }
            5 => {
                let mut words: Vec<&str> = lines[i].split(' ').collect();
                let keep = rng.range(0, words.len() as i64) as usize;
                words.truncate(keep.max(1));
                lines[i] = words.join(" ");
            }
            6 => lines[i] = lines[i].replace(' ', if rng.chance(50) { "\t" } else { "  " }),
            _ => {
                let extra =
                    format!("{} {} {} {}", rng.pick(keywords), rng.pick(NUMBERS), rng.pick(NUMBERS), rng.pick(NUMBERS));
                lines.insert(i, extra);
            }
        }
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}
