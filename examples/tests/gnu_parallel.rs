//! README's render spread over machines, run as README writes it: GNU
//! parallel runs `render --tile {}/4` for parts 0 to 3 (here on local
//! workers, `-S :`, in place of README's `-S a,b,c,d`), then `render
//! --merge part*.rtpart` puts the parts together, and the merged image is
//! the single-process render's bit for bit.
//!
//! Without GNU parallel the test passes with a note, unless
//! `RT_REQUIRE_PARALLEL=1` (scripts/test.sh sets it after installing
//! Debian's `parallel`): then it fails, naming what is missing.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("examples-gnu-parallel-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn ok(what: &str, out: Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{what}: {stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn floats(path: &Path) -> Vec<u32> {
    image::open(path).unwrap().to_rgba32f().into_raw().into_iter().map(f32::to_bits).collect()
}

/// Whether GNU parallel (not moreutils' `parallel`, which takes other
/// arguments) is on the path.
fn gnu_parallel() -> bool {
    Command::new("parallel")
        .arg("--version")
        .output()
        .is_ok_and(|out| String::from_utf8_lossy(&out.stdout).contains("GNU parallel"))
}

#[test]
fn readmes_gnu_parallel_command_merges_to_the_single_process_render() {
    if !gnu_parallel() {
        let what = "GNU parallel is not installed (apt-get install parallel)";
        assert!(std::env::var("RT_REQUIRE_PARALLEL").as_deref() != Ok("1"), "RT_REQUIRE_PARALLEL=1 but {what}");
        eprintln!("skipped: {what}");
        return;
    }
    let dir = temp_dir("teapot");
    let render = env!("CARGO_BIN_EXE_render");
    let teapot = examples::scene::shared_scene("teapot.obj");
    let scene = format!("{} --width 48 --height 64 --spp 2 --backend cpu", teapot.display());
    let whole = dir.join("whole.exr");
    ok(
        "the single-process render",
        Command::new("sh").arg("-c").arg(format!("{render} {scene} --out {}", whole.display())).output().unwrap(),
    );
    // README's two commands, with this machine's workers and a smaller
    // picture; run from `dir`, as README's are from the folder the parts
    // go to.
    let job = format!("{render} {scene} --tile {{}}/4 --out part{{}}.rtpart");
    let spread = Command::new("parallel").args(["-S", ":", &job, ":::", "0", "1", "2", "3"]).current_dir(&dir).output();
    let stdout = ok("parallel", spread.unwrap());
    for k in 0..4 {
        assert!(stdout.contains(&format!("(part {k} of 4: rows ")), "{stdout}");
        assert!(dir.join(format!("part{k}.rtpart")).is_file(), "part {k} missing: {stdout}");
    }
    let merge = format!("{render} --merge part*.rtpart --out merged.exr");
    ok("render --merge", Command::new("sh").arg("-c").arg(merge).current_dir(&dir).output().unwrap());
    let (a, b) = (floats(&whole), floats(&dir.join("merged.exr")));
    assert_eq!(a.len(), 48 * 64 * 4);
    assert!(a == b, "the merged image differs from the single-process render");
    // The teapot is in the picture, across the parts.
    assert!(a.chunks(4).map(|p| p[0]).collect::<std::collections::HashSet<_>>().len() > 20);
}
