//! The file fuzzer (see `rt_tests::file_fuzz`): 2,500 mutated glTF, GLB,
//! OBJ/MTL and part files each a run (10,000 in all), seeded, each loaded as
//! `render` loads it (`rt_scene::load_with`, `Part::load` and `merge`),
//! which must accept it or refuse it in one line naming the file, without
//! a panic, within a memory budget (this binary counts its allocations)
//! and a time limit (a watchdog ends a case that hangs). Every input it
//! found breaking that contract is a regression case below.
//! `RT_FILE_FUZZ=20000 RT_FILE_FUZZ_SEED=7` runs more or others (cases per
//! format); `RT_FILE_FUZZ_ONLY=<format>:<index>` one.

use rt_tests::file_fuzz::{self, Format, Outcome};
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering::Relaxed};
use std::time::{Duration, Instant};

/// Counts live bytes and their peak; refuses (so the process aborts) any
/// allocation that would take the live bytes past [`HARD_CAP`], naming the
/// case that asked, so a memory bomb ends the run rather than the machine.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
/// The case being loaded: format in the top byte, index below; 0 between.
static CASE: AtomicU64 = AtomicU64::new(0);
/// When it began, in ms since the run began (for the watchdog).
static CASE_START_MS: AtomicU64 = AtomicU64::new(0);
const HARD_CAP: usize = 3 << 30;

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !reserve(layout.size()) {
            return std::ptr::null_mut();
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !reserve(layout.size()) {
            return std::ptr::null_mut();
        }
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() && !reserve(new_size - layout.size()) {
            return std::ptr::null_mut();
        }
        let out = unsafe { System.realloc(ptr, layout, new_size) };
        if new_size < layout.size() {
            LIVE.fetch_sub(layout.size() - new_size, Relaxed);
        }
        out
    }
}

fn reserve(size: usize) -> bool {
    let live = LIVE.fetch_add(size, Relaxed) + size;
    if live > HARD_CAP {
        LIVE.fetch_sub(size, Relaxed);
        // No allocation here: the message is written from the stack.
        let case = CASE.load(Relaxed);
        let mut line = *b"file fuzz: memory cap reached in case ?:0000000000\n";
        line[38] = b"?gbor"[(case >> 56) as usize % 5];
        let mut i = case & 0xffff_ffff;
        for d in (41..51).rev() {
            line[d] = b'0' + (i % 10) as u8;
            i /= 10;
        }
        let _ = std::io::Write::write_all(&mut std::io::stderr(), &line);
        return false;
    }
    PEAK.fetch_max(live, Relaxed);
    true
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The tests here measure memory, so they take turns.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn since_start() -> u64 {
    static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_millis() as u64
}

/// Aborts the process, naming the case, when one runs past a minute (a
/// read that blocks, a loop that does not end).
fn watchdog() {
    static STARTED: std::sync::Once = std::sync::Once::new();
    STARTED.call_once(|| {
        since_start();
        std::thread::spawn(|| {
            loop {
                std::thread::sleep(Duration::from_secs(1));
                let case = CASE.load(Relaxed);
                if case != 0 && since_start() - CASE_START_MS.load(Relaxed) > 60_000 {
                    eprintln!("file fuzz: case {:#x} hangs (over 60 s)", case);
                    std::process::abort();
                }
            }
        });
    });
}

/// Loads `path` as `render` would, counting the peak of live bytes above
/// those before.
fn load(case: &file_fuzz::Case, path: &Path) -> Outcome {
    let (format, index) = (case.format, case.index);
    let tag = Format::ALL.iter().position(|f| *f == format).unwrap() as u64 + 1;
    CASE_START_MS.store(since_start(), Relaxed);
    CASE.store(tag << 56 | index as u64, Relaxed);
    let before = LIVE.load(Relaxed);
    PEAK.store(before, Relaxed);
    let result = match format {
        Format::Part => examples::parts::Part::load(path)
            .and_then(|part| examples::parts::merge(&[(path.to_path_buf(), part)]).map(|_| ()))
            .map_err(|e| e.to_string()),
        _ => {
            let mut ctx = rt_runtime::Context::new();
            rt_scene::load_with(&mut ctx, path, &rt_scene::LoadLimits::default()).map(|_| ()).map_err(|e| e.to_string())
        }
    };
    let peak_bytes = PEAK.load(Relaxed).saturating_sub(before);
    CASE.store(0, Relaxed);
    Outcome { result, peak_bytes }
}

fn run(cfg: &file_fuzz::Config) -> file_fuzz::Report {
    watchdog();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-file-fuzz");
    file_fuzz::run(cfg, &dir, &load)
}

/// Every input the fuzzer found breaking the contract
/// (`tests/fuzz_regressions/<what>/`, each a folder of the case's files).
///
/// `gltf-count-zero`: seed 0xf11e, gltf case 1385. An animation output
/// accessor with `"count": 0`; the `gltf` crate's reader computes
/// `count - 1` (an overflow panic in debug builds). Accessors of count 0
/// are refused, as the specification asks for at least 1.
///
/// `gltf-long-quote`: seed 7, gltf case 8221. A buffer view whose
/// `buffer` is the base64 data URI, a string: the JSON error quoted the
/// whole string in its one line (over 600 characters). Quoted values are
/// clipped.
#[test]
fn inputs_the_fuzzer_found_are_read_or_refused_by_name() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    watchdog();
    let cfg = file_fuzz::Config::from_env(0, 0);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz_regressions");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-file-fuzz-regressions");
    let mut seen = 0;
    for entry in std::fs::read_dir(&root).unwrap() {
        let at = entry.unwrap().path();
        let case = file_fuzz::saved(&at);
        let (outcome, _, failure) = file_fuzz::run_case(&cfg, &case, &dir, &load);
        assert!(failure.is_none(), "{}: {failure:?}", at.display());
        assert!(outcome.is_some_and(|o| o.result.is_err()), "{}: refused", at.display());
        seen += 1;
    }
    assert!(seen >= 1);
}

#[test]
fn the_seed_files_load() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-file-fuzz-seeds");
    let cfg = file_fuzz::Config::from_env(0, 0);
    let (doc, bin) = file_fuzz::seeds::gltf();
    let glb = file_fuzz::bytes::glb(&serde_json::to_vec(&doc).unwrap(), &bin);
    let cases = [
        (Format::Glb, vec![("case.glb".to_string(), glb)]),
        (
            Format::Obj,
            vec![("case.obj".into(), file_fuzz::seeds::OBJ.into()), ("seed.mtl".into(), file_fuzz::seeds::MTL.into())],
        ),
        (Format::Part, vec![("case.rtpart".into(), file_fuzz::seeds::part())]),
    ];
    for (format, files) in cases {
        let main = files[0].0.clone();
        let case = file_fuzz::Case { format, index: 0, files, main };
        let (outcome, _, failure) = file_fuzz::run_case(&cfg, &case, &dir, &load);
        assert!(failure.is_none(), "{failure:?}");
        assert_eq!(outcome.unwrap().result, Ok(()), "{format:?}");
    }
}

#[test]
fn mutated_files_are_read_or_refused_by_name_within_bounds() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let cfg = file_fuzz::Config::from_env(0xf11e, 2500);
    let report = run(&cfg);
    eprintln!("{}", report.summary());
    if !report.failures.is_empty() {
        let artifacts = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-file-fuzz-failures");
        let mut msg = String::new();
        for f in report.failures.iter().take(8) {
            let at = file_fuzz::save(f, &artifacts);
            msg.push_str(&format!(
                "\n==== {} case {} ({}): {}\n     rerun with RT_FILE_FUZZ_SEED={} RT_FILE_FUZZ_ONLY={}:{}; files in {}",
                f.case.format.name(),
                f.case.index,
                f.kind,
                f.detail,
                cfg.seed,
                f.case.format.name(),
                f.case.index,
                at.display()
            ));
        }
        panic!("{} of the cases break the contract:{msg}", report.failures.len());
    }
}
