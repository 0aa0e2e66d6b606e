//! `render` on files and arguments from strangers: each refused with exit
//! status 2 and one line on stderr naming the file and the glTF object (or
//! the flag), no image; a frame sequence that fails leaves no frame; part
//! files whose headers claim more than they hold are refused in a short
//! line without allocating what they claim.

#[path = "../../rt-scene/tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn render(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render")).args(args).output().expect("render runs")
}

/// `render MODEL --out OUT ...`: a small picture on the CPU backend.
fn render_model(model: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args =
        vec![model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--width", "16", "--height", "16", "--spp", "1"];
    args.extend(["--backend", "cpu"]);
    args.extend(extra);
    render(&args)
}

/// Exit status 2, stderr exactly `render: <line>`, nothing written in
/// `dir` but the model.
fn refused(out: &Output, line: &str, dir: &Path) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "one line expected:\n{err}");
    assert_eq!(err.trim_end(), format!("render: {line}"));
    let written: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.ends_with(".gltf"))
        .collect();
    assert!(written.is_empty(), "wrote {written:?}");
}

fn model(name: &str, text: &str) -> (PathBuf, PathBuf) {
    let dir = common::temp_dir(&format!("cli-{name}"));
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

#[test]
fn bad_gltf_files_exit_2_naming_the_file_and_object() {
    let cases: [common::Case; 4] = [
        (
            "shared.gltf",
            &[(r#"{"mesh":0}],"#, r#"{"mesh":0,"children":[1]}],"#)],
            "nodes[2]: is a second parent of nodes[1], a child of nodes[0] already (a node has one parent)",
        ),
        (
            "position_99.gltf",
            &[(r#""POSITION":0"#, r#""POSITION":99"#)],
            "meshes[0].primitives[0]: attributes.Positions names accessors[99], but the file's accessors end at \
             accessors[5]",
        ),
        (
            "singular.gltf",
            &[(r#"{"mesh":0}],"#, r#"{"mesh":0,"matrix":[1,0,0,0, 0,0,0,0, 0,0,1,0, 0,0,0,1]}],"#)],
            "nodes[2]: its world transform is singular (determinant 0e0): a scale of zero?",
        ),
        (
            "yfov.gltf",
            &[(
                r#"{"mesh":0}],"#,
                r#"{"mesh":0,"camera":0}],"cameras":[{"type":"perspective","perspective":{"yfov":1e39,"znear":0.1}}],"#,
            )],
            "cameras[0]: perspective.yfov inf is outside (0, pi) radians",
        ),
    ];
    for (name, edits, problem) in cases {
        let (dir, path) = model(name, &common::edited(edits));
        let out = render_model(&path, &dir.join("out.png"), &[]);
        refused(&out, &format!("{}: {problem}", path.display()), &dir);
    }
}

#[test]
fn times_distances_and_sizes_out_of_range_exit_2() {
    let (dir, path) = model("ok.gltf", &common::base());
    let out = dir.join("out.png");
    refused(&render_model(&path, &out, &["--time", "NaN"]), "--time NaN is not a finite number of seconds", &dir);
    for (distance, shown) in [("1e-30", "1e-30"), ("3e38", "3e38")] {
        let line = format!(
            "--distance {shown} is outside 1.7320508e-6..=1.7320508e6 (1e-6 to 1e6 times the size of {})",
            path.display()
        );
        refused(&render_model(&path, &out, &["--distance", distance]), &line, &dir);
    }
    let big =
        render(&[path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--width", "16384", "--height", "16384"]);
    refused(
        &big,
        "image size 16384x16384 is 268435456 pixels, over the 41943040 a render holds in memory (16 bytes each, \
         several buffers)",
        &dir,
    );
}

/// Frames 0..3 where writing frame 1 fails (its name is a folder): exit
/// status 1, and frame 0, written before, is removed.
#[test]
fn a_failing_frame_sequence_leaves_no_frame() {
    let (dir, path) = model("frames.gltf", &common::base());
    std::fs::create_dir(dir.join("f_1.png")).unwrap();
    let pattern = dir.join("f_#.png");
    let out = render_model(&path, &pattern, &["--frames", "0..3", "--fps", "2"]);
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(!dir.join("f_0.png").exists());
    assert!(!dir.join("f_2.png").exists());
    std::fs::remove_dir(dir.join("f_1.png")).unwrap();
    let out = render_model(&path, &pattern, &["--frames", "0..3", "--fps", "2"]);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    assert!((0..3).all(|f| dir.join(format!("f_{f}.png")).exists()));
}

#[test]
fn part_headers_that_claim_too_much_are_refused_in_a_short_line() {
    let dir = common::temp_dir("cli-parts");
    let out = dir.join("merged.png");
    let header = |size: &str, tile: &str, rows: &str| {
        format!("rt-part 1\nsize {size}\ntile {tile}\nrows {rows}\nsettings s\npixels 0000000000000000\n\n")
    };
    let cases = [
        (
            "many.rtpart",
            header("1 800000000", "0 100000000", "0 8"),
            "size 1x800000000 is not a picture a render makes",
        ),
        ("tiles.rtpart", header("1 80000", "0 10000", "0 8"), "--tile 0/10000: 80000 rows make at most 4096 parts"),
        ("short.rtpart", header("64 64", "0 1", "0 64"), "0 bytes of pixels where rows 0..64 of 64 need 65536"),
    ];
    for (name, text, problem) in cases {
        let part = dir.join(name);
        std::fs::write(&part, &text).unwrap();
        let result = render(&["--merge", part.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.len() < 300 && err.contains(problem), "{name}: {err}");
        assert!(!out.exists());
    }
    let long = header("64 64", "0 1", "0 64").replace("settings s", &format!("settings {}", "x".repeat(60_000)));
    std::fs::write(dir.join("a.rtpart"), &long).unwrap();
    let result = render(&["--merge", dir.join("a.rtpart").to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(2), "{err}");
    assert!(err.len() < 300, "{err}");
}
