//! `docs/subset.md`, the subset of Rust ray programs are written in, against
//! the compiler: each example its table of expressions and statements
//! marks `yes` lowers to WGSL that naga validates, each marked `no` is
//! refused, and each test file the page names exists.

use std::path::Path;

/// The ray-generation program an example is put in: the names the page
/// promises are in scope.
fn program(example: &str) -> String {
    format!(
        "use rt_std::prelude::*;
#[rt_program(ray_generation)]
pub fn subset_row(#[var] mut out: RwBuffer<f32>, #[var] n: u32, #[var] x: f32, #[var] v: Vec3) {{
    let arr = [x, 1.0, 2.0, 3.0];
    let mut acc = 0.0f32;
    {example}
    out[0] = acc + v.x + arr[0];
}}"
    )
}

/// The cells of a table row, `\|` kept inside a cell as `|`.
fn cells(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut chars = line.trim().trim_start_matches('|').chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => {
                out.last_mut().unwrap().push('|');
                chars.next();
            }
            '|' => out.push(String::new()),
            c => out.last_mut().unwrap().push(c),
        }
    }
    out.pop();
    out.into_iter().map(|c| c.trim().to_string()).collect()
}

fn page() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/subset.md")).expect("docs/subset.md")
}

#[test]
fn every_example_is_lowered_or_refused_as_the_page_says() {
    let mut checked = 0;
    let mut wrong = Vec::new();
    for line in page().lines().filter(|l| l.starts_with('|')) {
        let c = cells(line);
        if c.len() != 4 || !matches!(c[2].as_str(), "yes" | "no") {
            continue;
        }
        let example = c[1].trim_matches('`');
        let result = rt_compiler::lower_source(&program(example), "subset_row");
        checked += 1;
        match (c[2].as_str(), result) {
            ("yes", Err(e)) => wrong.push(format!(
                "{} (`{example}`) is marked yes but is refused: {:?}",
                c[0],
                e.0.iter().map(|e| e.message.clone()).collect::<Vec<_>>()
            )),
            ("no", Ok(_)) => wrong.push(format!("{} (`{example}`) is marked no but lowers", c[0])),
            _ => {}
        }
    }
    assert!(checked >= 25, "only {checked} examples found in docs/subset.md");
    assert!(wrong.is_empty(), "docs/subset.md disagrees with the compiler:\n  {}", wrong.join("\n  "));
}

#[test]
fn every_test_file_the_page_names_exists() {
    let tests = Path::new(env!("CARGO_MANIFEST_DIR"));
    let page = page();
    let mut named = 0;
    for word in page.split('`') {
        let path = if word.starts_with("compile_fail/") {
            tests.join(word)
        } else if word.starts_with("differential/") {
            tests.join("tests").join(word)
        } else if let Some(rest) = word.strip_prefix("tests/tests/") {
            tests.join("tests").join(rest)
        } else {
            continue;
        };
        named += 1;
        assert!(path.is_file(), "docs/subset.md names {word}, which does not exist");
    }
    assert!(named >= 10, "only {named} test files named in docs/subset.md");
}
