//! WGSL snapshot tests: every program in `snapshots/in/*.rs` and in the
//! examples of the seed lecture (`EXAMPLE_FILES`) is lowered (with
//! every `rt_*` item of the corpus as a possible dependency) and compared
//! with `snapshots/out/<program>.wgsl`; every snapshot is then validated by
//! naga on its own. Run with `RT_BLESS=1` to rewrite the snapshots.

use rt_compiler::{Declared, Item};
use snapshot_modules::corpus_dir;
use std::path::PathBuf;

/// The examples whose programs are in the corpus: the seed lecture's.
const EXAMPLE_FILES: [&str; 8] =
    ["common.rs", "normal.rs", "diffuse.rs", "phong.rs", "shadows.rs", "reflections.rs", "envmap.rs", "convex_hull.rs"];

/// `(file, program kind, program)` for every program, and every item.
fn corpus() -> (Vec<(String, rt_compiler::Kind, syn::ItemFn)>, Vec<Item>) {
    let mut files: Vec<PathBuf> = std::fs::read_dir(corpus_dir().join("in"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    files.sort();
    // The seed lecture's programs, as the examples run them.
    let examples = corpus_dir().join("../../examples/src");
    files.extend(EXAMPLE_FILES.iter().map(|f| examples.join(f)));
    let mut programs = Vec::new();
    let mut items = Vec::new();
    let mut names = std::collections::HashSet::new();
    for f in files {
        let is_example = f.starts_with(&examples);
        let text = std::fs::read_to_string(&f).unwrap();
        let file: syn::File = syn::parse_str(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        for it in &file.items {
            match rt_compiler::declared(it) {
                Some(Ok(Declared::Program(k, func))) => {
                    programs.push((f.file_name().unwrap().to_string_lossy().into_owned(), k, func))
                }
                // The examples' shared types are `seed_common.rs`'s (the
                // test below holds them equal); their helpers may repeat
                // the corpus's own.
                Some(Ok(Declared::Item(i))) if is_example && item_name(&i).is_some_and(|n| names.contains(&n)) => {}
                Some(Ok(Declared::Item(i))) => {
                    names.extend(item_name(&i));
                    items.push(i)
                }
                Some(Err(e)) => panic!("{}: {}", f.display(), e.message),
                None => {}
            }
        }
    }
    (programs, items)
}

/// The name an item declares (a struct's, a helper's, a constant's).
fn item_name(item: &Item) -> Option<String> {
    match item {
        Item::Struct(s, _) => Some(s.ident.to_string()),
        Item::Function(f) => Some(f.sig.ident.to_string()),
        Item::Const(c) => Some(c.ident.to_string()),
        Item::Enum(e) => Some(e.ident.to_string()),
        Item::Trait(t) => Some(t.ident.to_string()),
        Item::Alias(t) => Some(t.ident.to_string()),
        Item::Impl(_) => None,
    }
}

/// The items `file` declares, by name, as tokens without their doc comments.
fn undocumented_items(file: &std::path::Path) -> std::collections::BTreeMap<String, String> {
    let text = std::fs::read_to_string(file).unwrap();
    let parsed: syn::File = syn::parse_str(&text).unwrap();
    let mut out = std::collections::BTreeMap::new();
    for mut item in parsed.items {
        let (name, attrs) = match &mut item {
            syn::Item::Struct(s) => (s.ident.to_string(), &mut s.attrs),
            syn::Item::Const(c) => (c.ident.to_string(), &mut c.attrs),
            _ => continue,
        };
        attrs.retain(|a| !a.path().is_ident("doc"));
        out.insert(name, quote::quote!(#item).to_string());
    }
    out
}

/// The corpus's shared types (`seed_common.rs`, which the other corpus
/// files use) are the examples' own, so the examples' programs lower
/// against what they are compiled with.
#[test]
fn the_corpus_shares_the_examples_types() {
    let corpus = undocumented_items(&corpus_dir().join("in/seed_common.rs"));
    let examples = undocumented_items(&corpus_dir().join("../../examples/src/common.rs"));
    assert!(corpus.len() >= 6, "{corpus:?}");
    for (name, item) in &corpus {
        assert_eq!(Some(item), examples.get(name), "`{name}` of seed_common.rs drifted from examples/src/common.rs");
    }
}

#[path = "common/snapshot_modules.rs"]
mod snapshot_modules;
use snapshot_modules::RESUMABLE;

/// The snapshot text: the module without the fixed runtime prelude, then a
/// tracing program's resumable form (with the resumable forms of the
/// helpers it calls) or why it has none. A module over the atomic heap says
/// so in its first line.
fn snapshot_text(l: &rt_compiler::Lowered) -> String {
    let (body, heap) = match l.wgsl.strip_prefix(rt_compiler::lower::PRELUDE.as_str()) {
        Some(body) => (body, ""),
        None => (
            l.wgsl.strip_prefix(rt_compiler::lower::ATOMIC_PRELUDE.as_str()).expect("module starts with a prelude"),
            " (atomic heap)",
        ),
    };
    let mut text = format!("// {} program `{}`{heap}\n{}", l.kind.unwrap().name(), l.name, body);
    if let Some(r) = &l.resumable {
        text.push_str(RESUMABLE);
        for (_, f) in &l.resumable_functions {
            text.push_str(f);
        }
        text.push_str(r);
    }
    if let Some(why) = &l.not_resumable {
        text.push_str(&format!("\n// ---- no resumable form: {why}\n"));
    }
    text
}

#[test]
fn snapshots_match_and_validate() {
    let (programs, items) = corpus();
    let bless = std::env::var_os("RT_BLESS").is_some();
    let out_dir = corpus_dir().join("out");
    let mut failures = Vec::new();
    let mut names = std::collections::HashSet::new();
    for (file, kind, f) in &programs {
        let name = f.sig.ident.to_string();
        assert!(names.insert(name.clone()), "program name `{name}` appears twice in the corpus");
        let lowered = match rt_compiler::lower::lower(rt_compiler::lower::Entry::Program(*kind, f), &items) {
            Ok(l) => l,
            Err(e) => {
                failures.push(format!("{file}: `{name}` does not lower:\n{e}"));
                continue;
            }
        };
        let text = snapshot_text(&lowered);
        let path = out_dir.join(format!("{name}.wgsl"));
        if bless {
            std::fs::write(&path, &text).unwrap();
        } else {
            match std::fs::read_to_string(&path) {
                Ok(expected) if expected == text => {}
                Ok(expected) => failures.push(format!(
                    "{file}: `{name}` differs from {} (RT_BLESS=1 to accept)\n--- expected\n{expected}\n--- got\n{text}",
                    path.display()
                )),
                Err(_) => failures.push(format!("{file}: missing snapshot {} (RT_BLESS=1 to create)", path.display())),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(programs.len() >= 25, "the corpus has {} programs, fewer than 25", programs.len());
}

#[test]
fn every_checked_in_snapshot_validates_with_naga() {
    let modules = snapshot_modules::modules();
    for (path, module) in &modules {
        let parsed = naga::front::wgsl::parse_str(module)
            .unwrap_or_else(|e| panic!("{}: {}", path.display(), e.emit_to_string(module)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
            .validate(&parsed)
            .unwrap_or_else(|e| panic!("{}: {}", path.display(), e.emit_to_string(module)));
    }
    assert!(modules.len() >= 25, "only {} snapshots", modules.len());
}

/// Every corpus file is also a module of the `rt-tests` library, so rustc
/// compiles it through the real macros (the snapshot is of a program that
/// is Rust, and its CPU copy builds).
#[test]
fn every_corpus_file_is_compiled_by_rustc() {
    let lib = std::fs::read_to_string(corpus_dir().join("../src/lib.rs")).unwrap();
    let missing: Vec<String> = std::fs::read_dir(corpus_dir().join("in"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".rs") && !lib.contains(&format!("\"../snapshots/in/{n}\"")))
        .collect();
    assert!(missing.is_empty(), "snapshots/in files not in src/lib.rs (add a #[path] module): {missing:?}");
}

/// The typed form (`rt_compiler::typed`) of every corpus program: every
/// expression the lowering typed has a settled type (no integer left to
/// infer), and the only expressions without one are those whose parts are
/// typed: a called function's path, a range (its bounds are typed), a
/// block (its statements and tail are), a shared `&` argument (its operand
/// is), an array repeat's length (a constant); and `expect`'s message,
/// which WGSL has no strings for.
#[test]
fn every_expression_of_the_corpus_has_a_settled_type() {
    use syn::visit::Visit;
    /// Addresses of the expressions a reader never needs typed.
    #[derive(Default)]
    struct Excused(std::collections::HashSet<usize>);
    impl<'a> Visit<'a> for Excused {
        fn visit_expr(&mut self, e: &'a syn::Expr) {
            match e {
                syn::Expr::Call(c) => {
                    self.0.insert(rt_compiler::typed::address(&c.func));
                }
                syn::Expr::Repeat(r) => {
                    self.0.insert(rt_compiler::typed::address(&r.len));
                }
                syn::Expr::Range(_) | syn::Expr::Block(_) => {
                    self.0.insert(rt_compiler::typed::address(e));
                }
                syn::Expr::Reference(r) if r.mutability.is_none() => {
                    self.0.insert(rt_compiler::typed::address(e));
                }
                // `o.expect("why")`: WGSL has no strings; the message stays
                // the CPU's.
                syn::Expr::MethodCall(m) if m.method == "expect" => {
                    self.0.extend(m.args.iter().map(rt_compiler::typed::address));
                }
                _ => {}
            }
            syn::visit::visit_expr(self, e);
        }
    }
    let (programs, items) = corpus();
    let (mut typed, mut all, mut unexpected) = (0, 0, Vec::new());
    for (file, kind, f) in &programs {
        let Ok(lowered) = rt_compiler::lower::lower(rt_compiler::lower::Entry::Program(*kind, f), &items) else {
            continue;
        };
        let program = (f.sig.ident.to_string(), lowered.typed.expect("a program's typed form"));
        for (name, form) in std::iter::once(program).chain(lowered.typed_helpers) {
            let mut excused = Excused::default();
            excused.visit_block(&form.body);
            for (e, ty) in form.typed_expressions() {
                all += 1;
                match ty {
                    Some(t) => {
                        typed += 1;
                        let settled = !format!("{t:?}").contains("IntVar");
                        assert!(settled, "{file} `{name}`: `{}`: {t:?} not settled", quote::quote!(#e));
                    }
                    None if excused.0.contains(&rt_compiler::typed::address(e)) => {}
                    None => unexpected.push(format!("{file} `{name}`: `{}`", quote::quote!(#e))),
                }
            }
        }
    }
    assert!(unexpected.is_empty(), "expressions the typed form lacks:\n{}", unexpected.join("\n"));
    assert!(typed * 10 > all * 9, "only {typed} of {all} expressions typed");
    eprintln!("{typed} of {all} expressions typed");
}
