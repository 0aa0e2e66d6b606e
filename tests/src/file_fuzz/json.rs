//! Structure-aware mutations of a glTF document as JSON: numbers replaced
//! by values at the edges of what the format and the readers assume
//! (indices one past the end, component type codes, strides, counts near
//! 2^32, floats beyond f32), enumerated strings swapped for others (or
//! bogus ones), keys and elements deleted or duplicated, references
//! copied between objects (which makes shared children and cycles),
//! attribute names renamed.

use crate::fuzz::generate::Rng;
use serde_json::{Value, json};

/// One step from a value to a child.
#[derive(Clone, Debug)]
enum Seg {
    Key(String),
    Index(usize),
}

fn paths(v: &Value, at: &mut Vec<Seg>, out: &mut Vec<Vec<Seg>>) {
    out.push(at.clone());
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                at.push(Seg::Key(k.clone()));
                paths(child, at, out);
                at.pop();
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                at.push(Seg::Index(i));
                paths(child, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn get_mut<'a>(v: &'a mut Value, path: &[Seg]) -> Option<&'a mut Value> {
    path.iter().try_fold(v, |v, seg| match seg {
        Seg::Key(k) => v.get_mut(k.as_str()),
        Seg::Index(i) => v.get_mut(*i),
    })
}

const NUMBERS: &[f64] = &[
    0.0,
    1.0,
    -1.0,
    2.0,
    3.0,
    4.0,
    5.0,
    6.0,
    7.0,
    8.0,
    12.0,
    99.0,
    255.0,
    256.0,
    65535.0,
    4294967295.0,
    4294967296.0,
    2147483647.0,
    1e39,
    -1e39,
    3e38,
    -3e38,
    1e-30,
    0.5,
    -0.0,
    5120.0,
    5121.0,
    5122.0,
    5123.0,
    5125.0,
    5126.0,
    5124.0,
    34962.0,
    34963.0,
    9728.0,
    10497.0,
    1e12,
];

const STRINGS: &[&str] = &[
    "bogus",
    "SCALAR",
    "VEC2",
    "VEC3",
    "VEC4",
    "MAT4",
    "translation",
    "rotation",
    "scale",
    "weights",
    "LINEAR",
    "STEP",
    "CUBICSPLINE",
    "perspective",
    "orthographic",
    "spot",
    "point",
    "directional",
    "/dev/zero",
    "../secret.bin",
    "data:application/octet-stream;base64,AAAA",
    "data:image/png;base64,iVBORw0KGgo=",
    "image/png",
    "",
    "BLEND",
    "seed.bin",
    "%2e%2e/secret.bin",
];

const KEYS: &[&str] = &[
    "children",
    "mesh",
    "camera",
    "skin",
    "matrix",
    "byteStride",
    "sparse",
    "indices",
    "material",
    "targets",
    "scale",
    "rotation",
    "translation",
    "byteOffset",
    "count",
    "bufferView",
    "componentType",
    "type",
    "uri",
    "mimeType",
    "sampler",
    "source",
    "index",
    "input",
    "output",
    "node",
    "path",
    "interpolation",
    "yfov",
    "scene",
    "nodes",
];

const ATTRIBUTES: &[&str] =
    &["POSITION", "NORMAL", "TANGENT", "TEXCOORD_0", "TEXCOORD_1", "COLOR_0", "JOINTS_0", "WEIGHTS_0", "_X"];

/// Applies one to four mutations to `doc`.
pub fn mutate(rng: &mut Rng, doc: &mut Value) {
    for _ in 0..rng.range(1, 4) {
        let mut all = Vec::new();
        paths(doc, &mut Vec::new(), &mut all);
        let path = rng.pick(&all);
        match rng.weighted(&[30, 12, 10, 8, 14, 8, 6]) {
            0 => number(rng, doc, &all),
            1 => {
                let strings: Vec<_> =
                    all.iter().filter(|p| get_mut(doc, p).is_some_and(|v| v.is_string())).cloned().collect();
                if let Some(v) = (!strings.is_empty()).then(|| rng.pick(&strings)).and_then(|p| get_mut(doc, &p)) {
                    *v = json!(rng.pick(STRINGS));
                }
            }
            2 => delete(rng, doc, &path),
            3 => duplicate(rng, doc, &path),
            4 => {
                // A key set on some object, its value copied from
                // elsewhere (a reference, a whole subtree) or a number.
                let objects: Vec<_> =
                    all.iter().filter(|p| get_mut(doc, p).is_some_and(|v| v.is_object())).cloned().collect();
                let value = if rng.chance(60) { get_mut(doc, &rng.pick(&all)).map(|v| v.clone()) } else { None };
                let value = value.unwrap_or_else(|| json!(rng.pick(NUMBERS)));
                let key = rng.pick(KEYS);
                if let Some(Value::Object(map)) = get_mut(doc, &rng.pick(&objects)) {
                    map.insert(key.to_string(), value);
                }
            }
            5 => {
                // A node made a child of another (shared children, cycles).
                let n = doc["nodes"].as_array().map_or(0, Vec::len) as i64;
                if n > 0 {
                    let (a, b) = (rng.range(0, n - 1) as usize, rng.range(0, n) as usize);
                    let node = &mut doc["nodes"][a];
                    match node.get_mut("children").and_then(Value::as_array_mut) {
                        Some(children) => children.push(json!(b)),
                        None => node["children"] = json!([b]),
                    }
                }
            }
            _ => {
                // An attribute renamed.
                let prims: Vec<_> = all
                    .iter()
                    .filter(|p| matches!(p.last(), Some(Seg::Key(k)) if k == "attributes"))
                    .cloned()
                    .collect();
                if let Some(Value::Object(map)) =
                    (!prims.is_empty()).then(|| rng.pick(&prims)).and_then(|p| get_mut(doc, &p))
                {
                    let keys: Vec<String> = map.keys().cloned().collect();
                    if let Some(v) = map.remove(&rng.pick(&keys)) {
                        map.insert(rng.pick(ATTRIBUTES).to_string(), v);
                    }
                }
            }
        }
    }
}

fn number(rng: &mut Rng, doc: &mut Value, all: &[Vec<Seg>]) {
    let numbers: Vec<_> = all.iter().filter(|p| get_mut(doc, p).is_some_and(|v| v.is_number())).cloned().collect();
    if numbers.is_empty() {
        return;
    }
    let path = rng.pick(&numbers);
    let Some(v) = get_mut(doc, &path) else { return };
    let old = v.as_f64().unwrap_or(0.0);
    let new = match rng.below(4) {
        0 => old + rng.range(-2, 2) as f64,
        1 => old * 2.0 + 1.0,
        _ => rng.pick(NUMBERS),
    };
    *v = if new.fract() == 0.0 && new.abs() < 1e15 {
        if new >= 0.0 { json!(new as u64) } else { json!(new as i64) }
    } else {
        serde_json::Number::from_f64(new).map_or(json!(0), Value::Number)
    };
}

fn delete(rng: &mut Rng, doc: &mut Value, path: &[Seg]) {
    let Some((last, parent)) = path.split_last() else { return };
    match (get_mut(doc, parent), last) {
        (Some(Value::Object(map)), Seg::Key(k)) => {
            map.remove(k);
        }
        (Some(Value::Array(items)), Seg::Index(i)) if rng.chance(70) => {
            items.remove(*i);
        }
        (Some(Value::Array(items)), Seg::Index(_)) => items.clear(),
        _ => {}
    }
}

fn duplicate(rng: &mut Rng, doc: &mut Value, path: &[Seg]) {
    let Some((Seg::Index(i), parent)) = path.split_last() else { return };
    if let Some(Value::Array(items)) = get_mut(doc, parent) {
        let copy = items[*i].clone();
        for _ in 0..rng.range(1, 3) {
            items.push(copy.clone());
        }
    }
}
