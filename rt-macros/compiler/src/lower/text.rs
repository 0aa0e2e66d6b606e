//! WGSL text with inline markers.
//!
//! Expressions are lowered to strings that are combined freely; to know which
//! WGSL bytes came from which Rust expression, each lowered piece is wrapped
//! in invisible markers (`\u{1}id\u{2}` ... `\u{3}`). Integer literals and
//! types whose integer type is not yet inferred are written as placeholders
//! (`\u{4}L var value\u{5}`, `\u{4}T var\u{5}`). [`finish`] resolves the
//! placeholders, strips the markers and returns the byte range of every
//! marked piece: the source map from WGSL spans to Rust spans. Names the
//! linker renames (a function's own, its trace, helper and dispatch
//! calls) are followed by a [`site`] placeholder, which `finish` turns into
//! the byte offset where the name ends: the facts the linker reads instead
//! of searching the text.
//!
//! This module knows the markers only, not the compiler's types: the
//! placeholders of an integer variable resolve to `i32` or `u32`, as the
//! caller says.

const OPEN: char = '\u{1}';
const MID: char = '\u{2}';
const CLOSE: char = '\u{3}';
const PH_OPEN: char = '\u{4}';
const PH_CLOSE: char = '\u{5}';

/// Wraps `text` in markers for source-map entry `id`.
pub fn mark(id: usize, text: &str) -> String {
    format!("{OPEN}{id}{MID}{text}{CLOSE}")
}

pub fn int_literal_placeholder(var: u32, value: &str) -> String {
    format!("{PH_OPEN}L{var} {value}{PH_CLOSE}")
}

pub fn int_type_placeholder(var: u32) -> String {
    format!("{PH_OPEN}T{var}{PH_CLOSE}")
}

/// A name that per-depth clones rename (the linker's `WgslSite`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Site {
    /// The function's own name, in its definition.
    Definition,
    /// A call of `rt_trace_<payload>`: the payload's WGSL name.
    Trace(String),
    /// A call of the helper of this WGSL name.
    Call(String),
    /// A call of the dispatch function of this name (a call through a
    /// callable id).
    Dispatch(String),
}

/// A placeholder written right after the name `site` describes: [`finish`]
/// removes it and records where the name ends.
pub fn site(site: &Site) -> String {
    match site {
        Site::Definition => format!("{PH_OPEN}D{PH_CLOSE}"),
        Site::Trace(p) => format!("{PH_OPEN}R{p}{PH_CLOSE}"),
        Site::Call(h) => format!("{PH_OPEN}C{h}{PH_CLOSE}"),
        Site::Dispatch(d) => format!("{PH_OPEN}X{d}{PH_CLOSE}"),
    }
}

/// Clean text and what its markers and placeholders said.
pub struct Finished {
    pub text: String,
    /// `(id, byte range)` for every marked piece.
    pub ranges: Vec<(usize, std::ops::Range<usize>)>,
    /// Every [`site`] and the byte offset where its name ends, in text order.
    pub sites: Vec<(Site, usize)>,
}

/// Resolves placeholders and strips markers; returns the clean text,
/// `(id, byte range)` for every marked piece and where each site's name
/// ends. `signed(var)`: whether integer variable `var` is an `i32` (else a
/// `u32`).
pub fn finish(text: &str, signed: &dyn Fn(u32) -> bool) -> Finished {
    let mut out = String::with_capacity(text.len());
    let mut ranges = Vec::new();
    let mut sites = Vec::new();
    let mut stack: Vec<(usize, usize)> = Vec::new();
    let mut chars = text.char_indices().peekable();
    while let Some((_, c)) = chars.next() {
        match c {
            OPEN => {
                let mut id = String::new();
                for (_, d) in chars.by_ref() {
                    if d == MID {
                        break;
                    }
                    id.push(d);
                }
                stack.push((id.parse().unwrap_or(usize::MAX), out.len()));
            }
            CLOSE => {
                if let Some((id, start)) = stack.pop() {
                    ranges.push((id, start..out.len()));
                }
            }
            PH_OPEN => {
                let mut body = String::new();
                for (_, d) in chars.by_ref() {
                    if d == PH_CLOSE {
                        break;
                    }
                    body.push(d);
                }
                let (tag, rest) = body.split_at(1);
                match tag {
                    "D" => sites.push((Site::Definition, out.len())),
                    "R" => sites.push((Site::Trace(rest.to_string()), out.len())),
                    "C" => sites.push((Site::Call(rest.to_string()), out.len())),
                    "X" => sites.push((Site::Dispatch(rest.to_string()), out.len())),
                    "L" => {
                        let (var, value) = rest.split_once(' ').unwrap_or((rest, "0"));
                        let signed = signed(var.parse().unwrap_or(0));
                        out.push_str(value);
                        out.push_str(if signed { "i" } else { "u" });
                    }
                    _ => out.push_str(if signed(rest.parse().unwrap_or(0)) { "i32" } else { "u32" }),
                }
            }
            _ => out.push(c),
        }
    }
    Finished { text: out, ranges, sites }
}

/// Strips markers only (for text that has no placeholders left).
pub fn strip(text: &str) -> String {
    finish(text, &|_| true).text
}

/// Indents every line of `body` by one level.
pub fn indent(body: &str) -> String {
    let mut out = String::new();
    for line in body.lines() {
        if line.is_empty() {
            out.push('\n');
        } else {
            out.push_str("    ");
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}
