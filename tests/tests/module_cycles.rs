//! No import cycles between a crate's source files.
//!
//! File A depends on file B when A names a path into B's module:
//! `crate::a::b::Item` or `super::b::Item` (in a `use` or inline) depends on
//! the deepest module file that exists on the path (`a/b.rs`, `a/b/mod.rs`,
//! else `a.rs`, ..., else `lib.rs`), and a name that module re-exports
//! (`pub use x::Item`) is followed to the module that defines it. A parent
//! naming its own children by bare `child::item` is not a dependency, nor is
//! a bare path (an external crate's, or a local name). Comments, string and
//! character literals are removed first.
//!
//! [`cycles`] takes a crate's `src` folder, so the same check can be pointed
//! at any crate of the workspace.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module path (`["backend", "wgpu"]`), relative to the crate root.
type ModPath = Vec<String>;

/// The crate's module files by module path.
struct Crate {
    files: BTreeMap<ModPath, PathBuf>,
    /// Per module file: a name it re-exports → the absolute path it names.
    reexports: BTreeMap<ModPath, BTreeMap<String, ModPath>>,
    /// Per module file: the absolute paths it names (resolved against its
    /// inline modules).
    uses: BTreeMap<ModPath, Vec<ModPath>>,
}

/// Removes comments, string literals (raw and byte strings included) and
/// character literals, keeping lifetimes and line structure.
fn strip(src: &str) -> String {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(' ');
        } else if (c == 'r' || (c == 'b' && next == Some('r'))) && (i == 0 || !ident(b[i - 1])) && {
            let mut j = i + if c == 'b' { 2 } else { 1 };
            while b.get(j) == Some(&'#') {
                j += 1;
            }
            b.get(j) == Some(&'"')
        } {
            // A raw string: r"...", r#"..."#, br"...".
            i += if c == 'b' { 2 } else { 1 };
            let mut hashes = 0;
            while b[i] == '#' {
                hashes += 1;
                i += 1;
            }
            i += 1;
            loop {
                if i >= b.len() {
                    break;
                }
                if b[i] == '"' && (0..hashes).all(|k| b.get(i + 1 + k) == Some(&'#')) {
                    i += 1 + hashes;
                    break;
                }
                i += 1;
            }
            out.push_str("\"\"");
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' {
            // A character literal ('a', '\n', '\u{..}') or a lifetime ('a).
            let close = if next == Some('\\') {
                (i + 3..b.len().min(i + 13)).find(|&j| b[j] == '\'')
            } else if b.get(i + 2) == Some(&'\'') {
                Some(i + 2)
            } else {
                None
            };
            match close {
                Some(j) => {
                    out.push_str("' '");
                    i = j + 1;
                }
                None => {
                    out.push(c);
                    i += 1;
                }
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Punct(&'static str),
}

fn tokens(src: &str) -> Vec<Tok> {
    let b: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_') {
                i += 1;
            }
            let word: String = b[start..i].iter().collect();
            // `r#ident`
            let word = word.strip_prefix("r#").map(str::to_string).unwrap_or(word);
            out.push(Tok::Ident(word));
            continue;
        }
        if c == ':' && b.get(i + 1) == Some(&':') {
            out.push(Tok::Punct("::"));
            i += 2;
            continue;
        }
        let p = match c {
            '{' => Some("{"),
            '}' => Some("}"),
            ',' => Some(","),
            ';' => Some(";"),
            '*' => Some("*"),
            _ => None,
        };
        if let Some(p) = p {
            out.push(Tok::Punct(p));
        } else if !c.is_whitespace() {
            out.push(Tok::Punct("other"));
        }
        i += 1;
    }
    out
}

/// Makes `path` (relative to `module`: `crate::`, `super::`, `self::`)
/// absolute; `None` for a bare path.
fn absolute(module: &[String], path: &[String]) -> Option<ModPath> {
    let mut out: ModPath = module.to_vec();
    let mut rest = path;
    match rest.first().map(String::as_str) {
        Some("crate") => {
            out.clear();
            rest = &rest[1..];
        }
        Some("super") | Some("self") => {
            while let Some(first) = rest.first() {
                match first.as_str() {
                    "super" => {
                        out.pop()?;
                    }
                    "self" => {}
                    _ => break,
                }
                rest = &rest[1..];
            }
        }
        _ => return None,
    }
    out.extend(rest.iter().cloned());
    Some(out)
}

/// Expands a `use` tree starting at `toks[*i]` into its paths, appended to
/// `out` after `prefix`; stops after the tree.
fn use_tree(toks: &[Tok], i: &mut usize, prefix: &[String], out: &mut Vec<(ModPath, Option<String>)>) {
    let mut path = prefix.to_vec();
    loop {
        match toks.get(*i) {
            Some(Tok::Ident(w)) => {
                path.push(w.clone());
                *i += 1;
                if toks.get(*i) == Some(&Tok::Punct("::")) {
                    *i += 1;
                    continue;
                }
                // `as name`
                let mut name = path.last().cloned();
                if toks.get(*i) == Some(&Tok::Ident("as".into())) {
                    if let Some(Tok::Ident(n)) = toks.get(*i + 1) {
                        name = Some(n.clone());
                    }
                    *i += 2;
                }
                // `use a::b::{self}` names `a::b` itself.
                if path.last().map(String::as_str) == Some("self") && path.len() > 1 {
                    path.pop();
                    if name.as_deref() == Some("self") {
                        name = path.last().cloned();
                    }
                }
                out.push((path, name));
                return;
            }
            Some(Tok::Punct("*")) => {
                *i += 1;
                out.push((path, None));
                return;
            }
            Some(Tok::Punct("{")) => {
                *i += 1;
                loop {
                    match toks.get(*i) {
                        Some(Tok::Punct("}")) => {
                            *i += 1;
                            return;
                        }
                        Some(Tok::Punct(",")) => *i += 1,
                        None => return,
                        _ => use_tree(toks, i, &path, out),
                    }
                }
            }
            _ => {
                out.push((path, None));
                return;
            }
        }
    }
}

/// The module file that a path's module path points to, with what is left.
fn module_file(path: &[String], files: &BTreeMap<ModPath, PathBuf>) -> (ModPath, Vec<String>) {
    for n in (0..=path.len()).rev() {
        if files.contains_key(&path[..n]) {
            return (path[..n].to_vec(), path[n..].to_vec());
        }
    }
    (Vec::new(), path.to_vec())
}

impl Crate {
    fn load(src: &Path) -> Crate {
        let mut files = BTreeMap::new();
        fn walk(dir: &Path, src: &Path, files: &mut BTreeMap<ModPath, PathBuf>) {
            let mut entries: Vec<_> = std::fs::read_dir(dir)
                .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
                .map(|e| e.expect("a directory entry").path())
                .collect();
            entries.sort();
            for p in entries {
                if p.is_dir() {
                    walk(&p, src, files);
                } else if p.extension().is_some_and(|e| e == "rs") {
                    let rel = p.strip_prefix(src).expect("under src");
                    let mut module: ModPath =
                        rel.parent().into_iter().flat_map(|d| d.iter()).map(|s| s.to_string_lossy().into()).collect();
                    let stem = p.file_stem().expect("a file name").to_string_lossy().to_string();
                    if !(stem == "mod" || (module.is_empty() && (stem == "lib" || stem == "main"))) {
                        module.push(stem);
                    }
                    files.insert(module, p);
                }
            }
        }
        walk(src, src, &mut files);
        let mut reexports = BTreeMap::new();
        let mut uses = BTreeMap::new();
        for (module, file) in &files {
            let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("reading {}: {e}", file.display()));
            let toks = tokens(&strip(&text));
            let (named, exported) = scan(module, &toks);
            uses.insert(module.clone(), named);
            reexports.insert(module.clone(), exported);
        }
        Crate { files, reexports, uses }
    }

    /// The module file that defines what `path` names, following
    /// re-exports.
    fn resolve(&self, path: &[String], depth: usize) -> ModPath {
        let (file, rest) = module_file(path, &self.files);
        if depth < 16
            && let Some(name) = rest.first()
            && let Some(target) = self.reexports.get(&file).and_then(|r| r.get(name))
        {
            let mut target = target.clone();
            target.extend(rest[1..].iter().cloned());
            return self.resolve(&target, depth + 1);
        }
        file
    }

    /// File-level dependencies.
    fn graph(&self) -> BTreeMap<ModPath, BTreeSet<ModPath>> {
        let mut graph = BTreeMap::new();
        for (module, named) in &self.uses {
            let deps: BTreeSet<ModPath> = named.iter().map(|p| self.resolve(p, 0)).filter(|d| d != module).collect();
            graph.insert(module.clone(), deps);
        }
        graph
    }

    fn name(&self, module: &ModPath, src: &Path) -> String {
        let file = &self.files[module];
        file.strip_prefix(src).unwrap_or(file).display().to_string()
    }
}

/// The absolute paths a file names, and the names it re-exports (with what
/// they name). Bare paths (a parent's children, external crates) are left
/// out of the first, kept (made absolute) in the second.
fn scan(module: &ModPath, toks: &[Tok]) -> (Vec<ModPath>, BTreeMap<String, ModPath>) {
    let mut named = Vec::new();
    let mut exported = BTreeMap::new();
    // Inline modules: (name, brace depth at which it closes).
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    let mut i = 0;
    let here = |inline: &Vec<(String, usize)>| -> ModPath {
        let mut m = module.clone();
        m.extend(inline.iter().map(|(n, _)| n.clone()));
        m
    };
    while i < toks.len() {
        match &toks[i] {
            Tok::Punct("{") => {
                depth += 1;
                i += 1;
            }
            Tok::Punct("}") => {
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
                depth = depth.saturating_sub(1);
                i += 1;
            }
            Tok::Ident(w) if w == "mod" => {
                if let (Some(Tok::Ident(name)), Some(Tok::Punct("{"))) = (toks.get(i + 1), toks.get(i + 2)) {
                    depth += 1;
                    inline.push((name.clone(), depth));
                    i += 3;
                } else {
                    i += 1;
                }
            }
            Tok::Ident(w) if w == "use" => {
                let public = i > 0 && matches!(toks.get(i.wrapping_sub(1)), Some(Tok::Ident(p)) if p == "pub")
                    || (i >= 4 && toks[i - 1] == Tok::Punct("other") && toks[i - 4] == Tok::Ident("pub".into()));
                i += 1;
                let mut paths = Vec::new();
                use_tree(toks, &mut i, &[], &mut paths);
                let m = here(&inline);
                for (path, name) in paths {
                    let abs = absolute(&m, &path);
                    if let Some(abs) = &abs {
                        named.push(abs.clone());
                    }
                    if public
                        && inline.is_empty()
                        && let Some(name) = name
                    {
                        // A bare re-export names a child (or an external
                        // crate, which resolves to nothing in the crate).
                        let target = abs.unwrap_or_else(|| {
                            let mut t = module.clone();
                            t.extend(path.iter().cloned());
                            t
                        });
                        exported.insert(name, target);
                    }
                }
            }
            Tok::Ident(w)
                if (w == "crate" || w == "super" || w == "self") && toks.get(i + 1) == Some(&Tok::Punct("::")) =>
            {
                let mut path = vec![w.clone()];
                i += 2;
                while let Some(Tok::Ident(seg)) = toks.get(i) {
                    path.push(seg.clone());
                    if toks.get(i + 1) == Some(&Tok::Punct("::")) && matches!(toks.get(i + 2), Some(Tok::Ident(_))) {
                        i += 2;
                    } else {
                        i += 1;
                        break;
                    }
                }
                if let Some(abs) = absolute(&here(&inline), &path) {
                    named.push(abs);
                }
            }
            _ => i += 1,
        }
    }
    (named, exported)
}

/// Every cycle of file dependencies in the crate whose sources are in
/// `src`, each spelled `a.rs → b.rs → a.rs` (one per strongly connected
/// group of files).
pub fn cycles(src: &Path) -> Vec<String> {
    let krate = Crate::load(src);
    let graph = krate.graph();
    let mut found = Vec::new();
    let mut reported: BTreeSet<ModPath> = BTreeSet::new();
    for start in graph.keys() {
        if reported.contains(start) {
            continue;
        }
        // The shortest path back to `start`, by breadth-first search.
        let mut parent: BTreeMap<ModPath, ModPath> = BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([start.clone()]);
        let mut closing = None;
        'search: while let Some(n) = queue.pop_front() {
            for d in &graph[&n] {
                if d == start {
                    closing = Some(n.clone());
                    break 'search;
                }
                if !parent.contains_key(d) && graph.contains_key(d) {
                    parent.insert(d.clone(), n.clone());
                    queue.push_back(d.clone());
                }
            }
        }
        if let Some(mut n) = closing {
            let mut chain = vec![start.clone()];
            let mut back = vec![n.clone()];
            while n != *start {
                n = parent[&n].clone();
                if n != *start {
                    back.push(n.clone());
                }
            }
            chain.extend(back.into_iter().rev());
            chain.push(start.clone());
            reported.extend(chain.iter().cloned());
            found.push(chain.iter().map(|m| krate.name(m, src)).collect::<Vec<_>>().join(" → "));
        }
    }
    found
}

/// Fails with every cycle spelled out.
pub fn assert_no_cycles(src: &Path) {
    let found = cycles(src);
    assert!(found.is_empty(), "import cycles between the files of {}:\n  {}", src.display(), found.join("\n  "));
}

fn crate_src(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

#[test]
fn rt_runtime_has_no_import_cycle() {
    assert_no_cycles(&crate_src("../rt-runtime/src"));
}

#[test]
fn rt_compiler_has_no_import_cycle() {
    assert_no_cycles(&crate_src("../rt-macros/compiler/src"));
}

/// rt-runtime's top-level modules, bottom first, as ARCHITECTURE.md
/// states them: a file may name its own module's files and those of the
/// layers below, never a layer above. (A doc link is a comment, not an
/// import.)
const RT_RUNTIME_LAYERS: &[&[&str]] = &[
    &["error", "env_settings", "handles", "motion", "panics", "texels", "buffer"],
    &["vars", "vertex_motion"],
    &["scene"],
    &["link"],
    &["accel"],
    &["backend"],
    &["postprocess"],
    &["usage"],
    &["context", "image_out"],
    &["command_list"],
    &[""],
];

#[test]
fn rt_runtime_imports_run_one_way() {
    let src = crate_src("../rt-runtime/src");
    let krate = Crate::load(&src);
    let layer = |m: &ModPath| {
        let top = m.first().map_or("", String::as_str);
        RT_RUNTIME_LAYERS
            .iter()
            .position(|l| l.contains(&top))
            .unwrap_or_else(|| panic!("rt-runtime's module `{top}` has no layer in RT_RUNTIME_LAYERS: add it"))
    };
    let mut upward = Vec::new();
    for (from, deps) in krate.graph() {
        for to in deps.iter().filter(|to| krate.files.contains_key(*to)) {
            if layer(to) > layer(&from) {
                upward.push(format!("{} names {}", krate.name(&from, &src), krate.name(to, &src)));
            }
        }
    }
    assert!(upward.is_empty(), "imports that run up rt-runtime's layers:\n  {}", upward.join("\n  "));
}

/// Every crate of the workspace (the members of its `Cargo.toml`), each
/// with its cycles spelled out: a crate added later is covered without a
/// line here.
#[test]
fn every_crate_of_the_workspace_has_no_import_cycle() {
    let root = crate_src("..");
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).expect("the workspace's Cargo.toml");
    let members = manifest
        .lines()
        .find_map(|l| l.trim().strip_prefix("members = ["))
        .expect("a one-line `members = [...]` in the workspace's Cargo.toml");
    let mut found = Vec::new();
    let mut checked = 0;
    for member in members.trim_end_matches(']').split(',').map(|m| m.trim().trim_matches('"')).filter(|m| !m.is_empty())
    {
        let src = root.join(member).join("src");
        assert!(src.is_dir(), "workspace member {member} has no src folder");
        checked += 1;
        found.extend(cycles(&src).into_iter().map(|c| format!("{member}: {c}")));
    }
    assert!(checked >= 10, "only {checked} crates found in the workspace's members");
    assert!(found.is_empty(), "import cycles between files:\n  {}", found.join("\n  "));
}

/// The check finds a cycle through a re-export and a `super` path, and
/// ignores comments, strings and a parent's bare child paths.
#[test]
fn the_check_finds_cycles_and_ignores_what_is_not_a_path() {
    let dir = std::env::temp_dir().join(format!("module_cycles_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("b")).unwrap();
    let write = |f: &str, s: &str| std::fs::write(dir.join(f), s).unwrap();
    write("lib.rs", "pub mod a;\npub mod b;\npub use a::Thing;\n");
    write("a.rs", "// use crate::b::X;\nconst S: &str = \"crate::b::x\";\npub struct Thing;\n");
    write("b/mod.rs", "pub mod c;\nuse c::Y;\n");
    write("b/c.rs", "pub struct Y;\nfn f() -> crate::Thing { let _ = r#\"super::z\"#; crate::a::Thing }\n");
    assert!(cycles(&dir).is_empty(), "{:?}", cycles(&dir));
    // a → b/c.rs (via a re-export of b), and b/c.rs → a.rs (via lib.rs's).
    write("b/mod.rs", "pub mod c;\npub use c::Y;\n");
    write("a.rs", "use crate::b::{self, Y};\npub struct Thing;\nfn g(_: &b::Y) {}\n");
    let found = cycles(&dir);
    assert_eq!(found, ["a.rs → b/c.rs → a.rs"]);
    // `super::` from an inline module names its own file.
    write("a.rs", "pub struct Thing;\n#[cfg(test)]\nmod tests {\n    use super::Thing;\n}\n");
    write("b/c.rs", "pub struct Y;\nmod inner { use super::super::c::Y; use crate::a::Thing; }\n");
    assert!(cycles(&dir).is_empty(), "{:?}", cycles(&dir));
    let _ = std::fs::remove_dir_all(&dir);
}
