//! A seeded, structure-aware mutation fuzzer for the files a user hands
//! `render`: glTF (JSON with its buffer embedded or beside it), GLB, OBJ
//! with its MTL, and part files.
//!
//! ## Design
//! 1. [`seeds`] holds one valid file per format that uses most of what its
//!    loader reads. [`case`] makes the input of a (format, index) from the
//!    run's seed: the seed file mutated by structure ([`json`] for glTF
//!    documents, [`text`] for the line formats) and by bytes ([`bytes`]:
//!    noise, and the GLB container's header words).
//! 2. [`run`] writes each case's files into a folder of its own
//!    ([`run_case`]; beside a `secret.bin` in the folder above, for `../`
//!    URIs to find) and hands the main file to the caller's loader, which
//!    says what happened and how many bytes the load allocated at its peak
//!    (the test binary counts its allocations). A failing case is saved by
//!    [`save`]; checked in under `tests/fuzz_regressions/`, [`saved`] reads
//!    it back.
//! 3. What a case must do: return (accepted) or refuse with one line that
//!    begins with the file's name (or that of the `.mtl` it read); never
//!    panic (a panic caught at `rt_scene::load`'s boundary is a failure
//!    too), stay under [`Config::memory_budget`] and [`Config::time_limit`].
//!
//! `RT_FILE_FUZZ=<cases per format>`, `RT_FILE_FUZZ_SEED=<seed>`,
//! `RT_FILE_FUZZ_ONLY=<format>:<index>` choose what a run does.

pub mod bytes;
pub mod json;
pub mod seeds;
pub mod text;

use crate::fuzz::generate::Rng;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The formats fuzzed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Gltf,
    Glb,
    Obj,
    Part,
}

impl Format {
    pub const ALL: [Format; 4] = [Format::Gltf, Format::Glb, Format::Obj, Format::Part];

    pub fn name(self) -> &'static str {
        match self {
            Format::Gltf => "gltf",
            Format::Glb => "glb",
            Format::Obj => "obj",
            Format::Part => "rtpart",
        }
    }
}

/// What a run does.
#[derive(Clone, Debug)]
pub struct Config {
    pub seed: u64,
    /// Case indices `first..first + cases`, per format.
    pub first: usize,
    pub cases: usize,
    pub formats: Vec<Format>,
    /// The most bytes one load may allocate at its peak.
    pub memory_budget: usize,
    /// The longest one load may take.
    pub time_limit: Duration,
}

impl Config {
    /// The defaults, overridden by `RT_FILE_FUZZ_SEED`, `RT_FILE_FUZZ`
    /// (cases per format) and `RT_FILE_FUZZ_ONLY=<format>:<index>`.
    pub fn from_env(seed: u64, cases: usize) -> Config {
        let var = |n: &str| std::env::var(n).ok().and_then(|v| v.parse::<u64>().ok());
        let mut c = Config {
            seed: var("RT_FILE_FUZZ_SEED").unwrap_or(seed),
            first: 0,
            cases: var("RT_FILE_FUZZ").map_or(cases, |v| v as usize),
            formats: Format::ALL.to_vec(),
            memory_budget: 256 << 20,
            time_limit: Duration::from_secs(10),
        };
        if let Some((format, index)) = std::env::var("RT_FILE_FUZZ_ONLY").ok().and_then(|v| {
            let (f, i) = v.split_once(':')?;
            Some((Format::ALL.into_iter().find(|x| x.name() == f)?, i.parse().ok()?))
        }) {
            (c.formats, c.first, c.cases) = (vec![format], index, 1);
        }
        c
    }
}

/// One input: its files (name, bytes) and which is loaded.
#[derive(Clone, Debug)]
pub struct Case {
    pub format: Format,
    pub index: usize,
    pub files: Vec<(String, Vec<u8>)>,
    pub main: String,
}

/// Case `index` of `format` in a run seeded `seed`.
pub fn case(seed: u64, format: Format, index: usize) -> Case {
    let tag = format as u64 + 1;
    let mut rng =
        Rng::new(seed ^ tag.wrapping_mul(0x51_7cc1_b727_220a) ^ (index as u64).wrapping_mul(0x2545_f491_4f6c_dd1d));
    let mut files = Vec::new();
    let main = match format {
        Format::Gltf | Format::Glb => {
            let (mut doc, bin) = seeds::gltf();
            let external = format == Format::Gltf && rng.chance(40);
            if format == Format::Gltf {
                doc["buffers"][0]["uri"] = if external {
                    files.push(("seed.bin".to_string(), bin.clone()));
                    "seed.bin".into()
                } else {
                    format!("data:application/octet-stream;base64,{}", rt_scene::glb::base64_encode(&bin)).into()
                };
            }
            if format == Format::Gltf || rng.chance(75) {
                json::mutate(&mut rng, &mut doc);
            }
            let text = serde_json::to_vec(&doc).expect("a document serialises");
            let mut out = if format == Format::Glb { bytes::glb(&text, &bin) } else { text };
            if format == Format::Glb && rng.chance(25) {
                bytes::glb_header(&mut rng, &mut out);
            }
            if rng.chance(15) {
                bytes::noise(&mut rng, &mut out);
            }
            let name = format!("case.{}", format.name());
            files.push((name.clone(), out));
            name
        }
        Format::Obj => {
            let obj_words = ["v", "vt", "vn", "f", "usemtl", "mtllib", "o", "g", "s", "l", "p"];
            let mtl_words = ["newmtl", "Kd", "Ka", "Ks", "Ke", "Tf", "Ns", "Ni", "d", "Tr", "illum", "map_Kd"];
            let which = rng.below(3);
            let mut obj = if which != 1 { text::mutate(&mut rng, seeds::OBJ, &obj_words) } else { seeds::OBJ.into() }
                .into_bytes();
            let mut mtl = if which != 0 { text::mutate(&mut rng, seeds::MTL, &mtl_words) } else { seeds::MTL.into() }
                .into_bytes();
            if rng.chance(10) {
                let target = if rng.chance(50) { &mut obj } else { &mut mtl };
                bytes::noise(&mut rng, target);
            }
            files.push(("seed.mtl".to_string(), mtl));
            files.push(("case.obj".to_string(), obj));
            "case.obj".to_string()
        }
        Format::Part => {
            let seed = seeds::part();
            let end = seed.windows(2).position(|w| w == b"\n\n").expect("a header") + 2;
            let mut out = match rng.below(5) {
                0..=2 => {
                    let words = ["rt-part", "size", "tile", "rows", "settings", "pixels"];
                    let header = text::mutate(&mut rng, std::str::from_utf8(&seed[..end - 1]).unwrap(), &words);
                    let mut out = header.into_bytes();
                    out.push(b'\n');
                    out.extend(&seed[end..]);
                    out
                }
                _ => seed,
            };
            if rng.chance(30) {
                bytes::noise(&mut rng, &mut out);
            }
            files.push(("case.rtpart".to_string(), out));
            "case.rtpart".to_string()
        }
    };
    Case { format, index, files, main }
}

/// What a load did: refused (the error's text) or not, and the most bytes
/// it had allocated at once.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub result: Result<(), String>,
    pub peak_bytes: usize,
}

/// Per format: cases run, accepted, refused, and the slowest and hungriest
/// one.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    pub cases: usize,
    pub accepted: usize,
    pub refused: usize,
    pub max_peak_bytes: usize,
    pub max_time: Duration,
}

/// A case that broke the contract.
#[derive(Clone, Debug)]
pub struct Failure {
    pub case: Case,
    /// `"panic"`, `"memory"`, `"time"` or `"message"`.
    pub kind: &'static str,
    pub detail: String,
}

#[derive(Debug, Default)]
pub struct Report {
    pub stats: Vec<(Format, Stats)>,
    pub failures: Vec<Failure>,
    pub time: Duration,
}

impl Report {
    pub fn summary(&self) -> String {
        let per: Vec<String> = self
            .stats
            .iter()
            .map(|(f, s)| {
                format!(
                    "{}: {} cases ({} accepted, {} refused; peak {} KiB, slowest {:.1?})",
                    f.name(),
                    s.cases,
                    s.accepted,
                    s.refused,
                    s.max_peak_bytes >> 10,
                    s.max_time
                )
            })
            .collect();
        format!("{}; {} failures in {:.1?}", per.join("; "), self.failures.len(), self.time)
    }
}

/// Runs `cfg`'s cases in `dir` through `load` (given a case's main file).
pub fn run(cfg: &Config, dir: &Path, load: &dyn Fn(&Case, &Path) -> Outcome) -> Report {
    let start = Instant::now();
    let mut report = Report::default();
    for &format in &cfg.formats {
        let mut stats = Stats::default();
        for index in cfg.first..cfg.first + cfg.cases {
            let (outcome, took, failure) = run_case(cfg, &case(cfg.seed, format, index), dir, load);
            stats.cases += 1;
            stats.max_time = stats.max_time.max(took);
            if let Some(o) = outcome {
                stats.max_peak_bytes = stats.max_peak_bytes.max(o.peak_bytes);
                match o.result {
                    Ok(()) => stats.accepted += 1,
                    Err(_) => stats.refused += 1,
                }
            }
            report.failures.extend(failure);
        }
        report.stats.push((format, stats));
    }
    report.time = start.elapsed();
    report
}

/// Writes `c`'s files into `dir/case/` (beside a `secret.bin` in `dir`)
/// and loads its main file: the outcome (none after a panic), the time it
/// took, and what broke the contract, if anything.
pub fn run_case(
    cfg: &Config,
    c: &Case,
    dir: &Path,
    load: &dyn Fn(&Case, &Path) -> Outcome,
) -> (Option<Outcome>, Duration, Option<Failure>) {
    let case_dir = dir.join("case");
    // The folder is emptied rather than made again: on some file systems
    // that costs more than the load.
    match std::fs::read_dir(&case_dir) {
        Ok(entries) => entries.flatten().for_each(|e| {
            let _ = std::fs::remove_file(e.path());
        }),
        Err(_) => std::fs::create_dir_all(&case_dir).expect("the case folder"),
    }
    if !dir.join("secret.bin").exists() {
        std::fs::write(dir.join("secret.bin"), vec![7u8; 4096]).expect("a file outside the case folder");
    }
    for (name, bytes) in &c.files {
        std::fs::write(case_dir.join(name), bytes).expect("a case file");
    }
    let path = case_dir.join(&c.main);
    let t = Instant::now();
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| load(c, &path)));
    let took = t.elapsed();
    let fail = |kind, detail: String| Some(Failure { case: c.clone(), kind, detail });
    match outcome {
        Ok(o) => {
            let failure = judge(cfg, c, &path, &o, took).and_then(|(kind, detail)| fail(kind, detail));
            (Some(o), took, failure)
        }
        Err(p) => {
            let why = p.downcast_ref::<String>().cloned().or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()));
            (None, took, fail("panic", why.unwrap_or_default()))
        }
    }
}

/// A case saved by [`save`] (or checked in from one): its folder's files,
/// the main one the one named `case.*` other than `case.bin`.
pub fn saved(at: &Path) -> Case {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(at)
        .expect("a saved case")
        .map(|e| {
            let e = e.expect("a saved file");
            (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).expect("a saved file"))
        })
        .collect();
    files.sort();
    let main = files.iter().map(|(n, _)| n.clone()).find(|n| n.starts_with("case.")).expect("a case.* file");
    let format = match main.rsplit('.').next() {
        Some("gltf") => Format::Gltf,
        Some("glb") => Format::Glb,
        Some("obj") => Format::Obj,
        _ => Format::Part,
    };
    Case { format, index: 0, files, main }
}

/// What is wrong with an outcome, if anything.
fn judge(cfg: &Config, c: &Case, path: &Path, o: &Outcome, took: Duration) -> Option<(&'static str, String)> {
    if o.peak_bytes > cfg.memory_budget {
        return Some(("memory", format!("allocated {} bytes at its peak", o.peak_bytes)));
    }
    if took > cfg.time_limit {
        return Some(("time", format!("took {took:.1?}")));
    }
    let Err(e) = &o.result else { return None };
    if e.contains("internal error") {
        return Some(("panic", e.clone()));
    }
    let named = std::iter::once(path.display().to_string())
        .chain(c.files.iter().map(|(name, _)| name.clone()))
        .any(|name| e.starts_with(&format!("{name}:")) || e.starts_with(&format!("{name} ")))
        // `render --merge`'s own refusals name the flag.
        || (c.format == Format::Part && e.starts_with("--merge: "));
    if e.contains('\n') || !named || e.len() > 600 {
        return Some(("message", format!("not one short line naming the file: {e:?}")));
    }
    None
}

/// Writes a failing case's files under `dir/<format>-<index>/`.
pub fn save(failure: &Failure, dir: &Path) -> PathBuf {
    let at = dir.join(format!("{}-{}", failure.case.format.name(), failure.case.index));
    std::fs::create_dir_all(&at).expect("the artifacts folder");
    for (name, bytes) in &failure.case.files {
        std::fs::write(at.join(name), bytes).expect("an artifact");
    }
    at
}
