//! A small valid glTF file to mutate, and loading through
//! `rt_scene::load_with` from a fresh folder.
#![allow(dead_code)]

use rt_runtime::Context;
use rt_scene::glb::base64_encode;
use rt_scene::{LoadLimits, SceneError};
use std::path::{Path, PathBuf};

/// A file name, the edits that make it from [`base`], and the problem
/// its refusal names.
pub type Case<'a> = (&'a str, &'a [(&'a str, &'a str)], &'a str);

pub fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("rt-scene-hostile-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A valid file: one triangle (positions, u16 indices, texture
/// coordinates) shown by nodes 0 (whose child is node 1) and 2, node 1
/// moved by an animation of its translation (keys at 0 and 1 s).
pub fn base() -> String {
    let floats = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    let mut bin = floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    bin.extend([0u8, 0, 1, 0, 2, 0, 0, 0]);
    bin.extend(floats(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]));
    bin.extend(floats(&[0.0, 1.0]));
    bin.extend(floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0]));
    bin.extend(floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]));
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,2]}}],
"nodes":[{{"mesh":0,"children":[1]}},{{"mesh":0,"translation":[0,0,1]}},{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":2}},"indices":1}}]}}],
"animations":[{{"channels":[{{"sampler":0,"target":{{"node":1,"path":"translation"}}}}],"samplers":[{{"input":3,"output":4}}]}}],
"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}},
{{"buffer":0,"byteOffset":44,"byteLength":24}},{{"buffer":0,"byteOffset":68,"byteLength":8}},
{{"buffer":0,"byteOffset":76,"byteLength":24}},{{"buffer":0,"byteOffset":100,"byteLength":32}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}},
{{"bufferView":2,"componentType":5126,"count":3,"type":"VEC2"}},
{{"bufferView":3,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]}},
{{"bufferView":4,"componentType":5126,"count":2,"type":"VEC3"}},
{{"bufferView":5,"componentType":5126,"count":2,"type":"VEC4"}}]}}"#,
        bin.len(),
        base64_encode(&bin)
    )
}

/// `base()` with each `(from, to)` replaced (each must occur).
pub fn edited(edits: &[(&str, &str)]) -> String {
    let mut text = base();
    for (from, to) in edits {
        assert!(text.contains(from), "{from} not in the base file");
        text = text.replacen(from, to, 1);
    }
    text
}

/// Loads `text` as `name` in a fresh folder through `rt_scene::load_with`.
pub fn load_text(name: &str, text: &str, limits: &LoadLimits) -> (PathBuf, Result<rt_scene::Loaded, SceneError>) {
    let dir = temp_dir(name);
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let mut ctx = Context::new();
    let result = rt_scene::load_with(&mut ctx, &path, limits);
    (path, result)
}

/// The refusal of `text`, with its file name (the folder) taken off.
pub fn refused_with(name: &str, text: &str, limits: &LoadLimits) -> String {
    let (path, result) = load_text(name, text, limits);
    let e = result.map(|_| ()).expect_err("must be refused");
    assert!(e.is_bad_input(), "{e}");
    let line = e.to_string();
    let prefix = format!("{}: ", path.display());
    line.strip_prefix(&prefix).unwrap_or_else(|| panic!("`{line}` does not begin with the file")).to_string()
}

pub fn refused(name: &str, text: &str) -> String {
    refused_with(name, text, &LoadLimits::default())
}
