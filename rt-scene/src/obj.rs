//! OBJ meshes, loaded with `tobj` into one [`TriangleMesh`] with a
//! material per `.mtl` material, and checked first so that a bad file is
//! one clear message naming the file, the line and the problem.
//!
//! `tobj` reports what is wrong but not where, and accepts some things a
//! renderer cannot use (NaN coordinates), so [`check_obj`] reads the text
//! once before it: numbers that do not parse, non-finite coordinates, face
//! indices that are zero or out of range, faces of fewer than three
//! vertices, each with its line. What it passes, `tobj` loads (triangulating
//! polygons); a mesh with no triangles is refused after loading.
//!
//! (Moved here from the examples crate, where `examples::mesh` re-exports
//! it, so the `render` binary, the examples and users share one loader.)

use crate::limits::LoadLimits;
use glam::Vec3;
use rt_runtime::TriangleMesh;
use std::fmt;
use std::path::Path;

/// Why a mesh could not be loaded: the file, the line when known, and the
/// problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshError {
    /// The `.obj` or `.mtl` file, as named.
    pub file: String,
    /// The line at fault, 1-based, when known.
    pub line: Option<usize>,
    /// What is wrong, in a sentence.
    pub problem: String,
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}: {}", self.file, self.problem),
            None => write!(f, "{}: {}", self.file, self.problem),
        }
    }
}

impl std::error::Error for MeshError {}

/// A material of a loaded mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshMaterial {
    /// The `.mtl`'s name for it (`newmtl`).
    pub name: String,
    /// `Kd`, or [`DEFAULT_GREY`] when the material has none.
    pub diffuse: Vec3,
    /// `Ke`; else `Ka` when it exceeds 1 in some channel (the Cornell box's
    /// `.mtl` writes its light's emission as `Ka 20 20 20`); else zero.
    pub emission: Vec3,
}

/// The diffuse colour of meshes without materials.
pub const DEFAULT_GREY: Vec3 = Vec3::splat(0.7);

/// A loaded OBJ: one triangle mesh over all its objects, with per-triangle
/// material indices into `materials`.
#[derive(Clone, Debug)]
pub struct LoadedMesh {
    /// Positions, triangles, per-vertex shading normals (the file's, or
    /// smoothed across edges sharper than [`CREASE_DEGREES`] only) and
    /// `material_indices`.
    pub mesh: TriangleMesh,
    /// At least one; the last is [`DEFAULT_GREY`] when some object has no
    /// material.
    pub materials: Vec<MeshMaterial>,
    /// The lowest corner of the mesh's bounds.
    pub min: Vec3,
    /// The highest corner of the mesh's bounds.
    pub max: Vec3,
    /// What was odd but not fatal (a missing `.mtl`), one line each.
    pub warnings: Vec<String>,
}

/// Edges sharper than this keep their facets when normals are computed.
pub const CREASE_DEGREES: f32 = 50.0;

/// Loads the OBJ at `path` (and its `.mtl` files, relative to it) within
/// the default [`LoadLimits`].
pub fn load_obj(path: &Path) -> Result<LoadedMesh, MeshError> {
    load_obj_with(path, &LoadLimits::default())
}

/// [`load_obj`] within `limits`: the OBJ and its `.mtl`s regular files
/// within the size bound, `.mtl`s inside the OBJ's folder (or an allowed
/// one), the triangles within the bound.
pub fn load_obj_with(path: &Path, limits: &LoadLimits) -> Result<LoadedMesh, MeshError> {
    let file = path.display().to_string();
    let text = crate::limits::read_text(path, limits).map_err(|why| MeshError {
        file: file.clone(),
        line: None,
        problem: format!("cannot read the file: {why}"),
    })?;
    let dir = path.parent();
    let read = |mtl: &Path| {
        let path = crate::limits::resolve(dir, &mtl.to_string_lossy(), limits)?;
        crate::limits::read_text(&path, limits).map_err(|why| format!("{}: {why}", path.display()))
    };
    let loaded = parse_obj_with_mtl(&text, &file, &read)?;
    let triangles = loaded.mesh.indices.len() as u64;
    if let Some(problem) =
        crate::limits::over("its count of triangles", triangles, limits.max_triangles, "max_triangles")
    {
        return Err(MeshError { file, line: None, problem });
    }
    Ok(loaded)
}

/// Loads OBJ text; `file` names it in messages, `.mtl` files are looked up
/// in `dir`.
pub fn parse_obj(text: &str, file: &str, dir: Option<&Path>) -> Result<LoadedMesh, MeshError> {
    let limits = LoadLimits::default();
    let read = |mtl: &Path| {
        let path = crate::limits::resolve(dir, &mtl.to_string_lossy(), &limits)?;
        crate::limits::read_text(&path, &limits).map_err(|why| format!("{}: {why}", path.display()))
    };
    parse_obj_with_mtl(text, file, &read)
}

/// [`parse_obj`] with each `.mtl` file's text from `mtl`, given the name
/// the OBJ's `mtllib` line says (or why it has none): where there are no
/// files to read, as in a browser page.
pub fn parse_obj_with_mtl(
    text: &str,
    file: &str,
    mtl: &dyn Fn(&Path) -> Result<String, String>,
) -> Result<LoadedMesh, MeshError> {
    let err = |line: Option<usize>, problem: String| MeshError { file: file.to_string(), line, problem };
    check_obj(text).map_err(|(line, problem)| err(Some(line), problem))?;

    // tobj's `merging` and `reordering` features add fields: keep the
    // update, which is needless only while no crate turns them on.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let mut warnings = Vec::new();
    let mtl_problems = std::cell::RefCell::new(Vec::new());
    let mtl_error = std::cell::RefCell::new(None);
    let text = normalise(text);
    let (models, materials) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |name| {
        let result = match mtl(name) {
            Ok(text) => match crate::mtl::normalise(&text) {
                Ok(text) => tobj::load_mtl_buf(&mut text.as_bytes()).map_err(|e| format!("{}: {e}", name.display())),
                Err((line, problem)) => {
                    let file = name.display().to_string();
                    *mtl_error.borrow_mut() = Some(MeshError { file, line: Some(line), problem });
                    return Err(tobj::LoadError::MaterialParseError);
                }
            },
            Err(why) => Err(why),
        };
        result.map_err(|why| {
            mtl_problems.borrow_mut().push(format!("{why}; using default grey"));
            tobj::LoadError::OpenFileFailed
        })
    })
    .map_err(|e| err(None, format!("not a valid OBJ file ({e})")))?;
    if let Some(e) = mtl_error.into_inner() {
        return Err(e);
    }
    warnings.extend(mtl_problems.into_inner());
    let materials = materials.unwrap_or_default();

    let mut out_materials: Vec<MeshMaterial> = materials
        .iter()
        .map(|m| {
            let v = |a: Option<[f32; 3]>| a.map(Vec3::from_array);
            let ambient = v(m.ambient).unwrap_or(Vec3::ZERO);
            let emission = v(m.emissive).unwrap_or(if ambient.max_element() > 1.0 { ambient } else { Vec3::ZERO });
            MeshMaterial { name: m.name.clone(), diffuse: v(m.diffuse).unwrap_or(DEFAULT_GREY), emission }
        })
        .collect();
    let default_index = out_materials.len() as u32;
    let mut needs_default = out_materials.is_empty();

    let mut mesh = TriangleMesh::default();
    let mut material_indices = Vec::new();
    let mut file_normals = Vec::new();
    let mut all_have_normals = true;
    for model in &models {
        let m = &model.mesh;
        let base = mesh.positions.len() as u32;
        let count = m.positions.len() / 3;
        mesh.positions.extend(m.positions.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])));
        if m.normals.len() == m.positions.len() {
            file_normals.extend(m.normals.chunks_exact(3).map(|n| Vec3::new(n[0], n[1], n[2])));
        } else {
            all_have_normals = false;
        }
        let material = match m.material_id {
            Some(id) if id < out_materials.len() => id as u32,
            _ => {
                needs_default = true;
                default_index
            }
        };
        for t in m.indices.chunks_exact(3) {
            if t.iter().any(|&i| i as usize >= count) {
                return Err(err(None, format!("object `{}` has a face index out of range", model.name)));
            }
            mesh.indices.push([base + t[0], base + t[1], base + t[2]]);
            material_indices.push(material);
        }
    }
    if mesh.indices.is_empty() {
        return Err(err(None, "the mesh is empty: it has no faces".into()));
    }
    if needs_default {
        out_materials.push(MeshMaterial { name: "default".into(), diffuse: DEFAULT_GREY, emission: Vec3::ZERO });
    }
    mesh.material_indices = Some(material_indices);

    let (mut min, mut max) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for tri in &mesh.indices {
        for &i in tri {
            min = min.min(mesh.positions[i as usize]);
            max = max.max(mesh.positions[i as usize]);
        }
    }
    if !(max - min).length().is_finite() {
        return Err(err(None, format!("the mesh spans {min} to {max}: too large to render in f32")));
    }
    if all_have_normals && file_normals.len() == mesh.positions.len() {
        mesh.normals = Some(file_normals.into_iter().map(|n| n.normalize_or(Vec3::Y)).collect());
    } else {
        mesh = with_crease_normals(mesh, CREASE_DEGREES);
    }
    mesh.validate().map_err(|problem| err(None, problem))?;
    Ok(LoadedMesh { mesh, materials: out_materials, min, max, warnings })
}

/// Checks OBJ text line by line for what would make a bad mesh; returns the
/// first problem with its (1-based) line.
pub fn check_obj(text: &str) -> Result<(), (usize, String)> {
    // Face indices may refer forward (tobj resolves them at the end), so
    // count every element first.
    let (mut total_v, mut total_vt, mut total_vn) = (0usize, 0usize, 0usize);
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => total_v += 1,
            Some("vt") => total_vt += 1,
            Some("vn") => total_vn += 1,
            _ => {}
        }
    }
    let (mut seen_v, mut seen_vt, mut seen_vn) = (0usize, 0usize, 0usize);
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else { continue };
        let rest: Vec<&str> = words.collect();
        match keyword {
            "v" => {
                seen_v += 1;
                let xyz = numbers(&rest, 3, "a vertex").map_err(|p| (n, p))?;
                if let Some(bad) = xyz.iter().find(|x| !x.is_finite()) {
                    return Err((n, format!("vertex {seen_v} has a non-finite coordinate ({bad})")));
                }
                match rest.len() {
                    3 | 6 => {}
                    4 => {
                        let w = numbers(&rest[3..], 1, "a vertex's w").map_err(|p| (n, p))?[0];
                        if w == 0.0 || !w.is_finite() {
                            return Err((n, format!("vertex {seen_v} has weight w = {w}")));
                        }
                    }
                    k => {
                        return Err((
                            n,
                            format!("a vertex has {k} numbers; expected 3 (x y z), 4 (with w) or 6 (with r g b)"),
                        ));
                    }
                }
            }
            "vt" => {
                seen_vt += 1;
                numbers(&rest, rest.len().clamp(1, 3), "a texture coordinate").map_err(|p| (n, p))?;
            }
            "vn" => {
                seen_vn += 1;
                numbers(&rest, 3, "a normal").map_err(|p| (n, p))?;
            }
            "f" => {
                if rest.len() < 3 {
                    return Err((n, format!("a face needs at least 3 vertices, this one has {}", rest.len())));
                }
                for corner in &rest {
                    let mut parts = corner.split('/');
                    for (what, seen, total) in [
                        ("vertex", seen_v, total_v),
                        ("texture coordinate", seen_vt, total_vt),
                        ("normal", seen_vn, total_vn),
                    ] {
                        let part = parts.next().unwrap_or("");
                        // `v//vn` and `v` leave the optional indices empty.
                        if part.is_empty() && what != "vertex" {
                            continue;
                        }
                        check_index(part, what, seen, total).map_err(|p| (n, p))?;
                    }
                    if parts.next().is_some() {
                        return Err((
                            n,
                            format!("face corner `{}` has more than 3 indices", crate::clip::clip(corner)),
                        ));
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// OBJ text in the form `tobj` reads: a one-number `vt u` as `vt u 0`
/// (the format makes v optional, `tobj` asks for it), and `usemtl` and
/// `mtllib` names after a tab as after a space (`tobj` splits these lines
/// at a space). Checked by [`check_obj`] first.
fn normalise(text: &str) -> std::borrow::Cow<'_, str> {
    let needs = |line: &str| {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vt") => words.count() == 1,
            Some("usemtl") | Some("mtllib") => !line.trim_start()[6..].starts_with(' '),
            _ => false,
        }
    };
    if !text.lines().any(needs) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 64);
    for line in text.lines() {
        if needs(line) {
            let words: Vec<&str> = line.split_whitespace().collect();
            match words[0] {
                "vt" => out.push_str(&format!("vt {} 0", words[1])),
                keyword => out.push_str(&format!("{keyword} {}", line.trim_start()[6..].trim())),
            }
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    std::borrow::Cow::Owned(out)
}

/// The first `count` words as finite-or-not floats.
fn numbers(words: &[&str], count: usize, what: &str) -> Result<Vec<f32>, String> {
    if words.len() < count {
        return Err(format!("{what} needs {count} numbers, found {}", words.len()));
    }
    words[..count]
        .iter()
        .map(|w| w.parse::<f32>().map_err(|_| format!("{what} has `{}`, which is not a number", crate::clip::clip(w))))
        .collect()
}

/// A face index: 1-based into the whole file's elements, or negative,
/// relative to the `seen` so far.
fn check_index(s: &str, what: &str, seen: usize, total: usize) -> Result<(), String> {
    let i: i64 = s.parse().map_err(|_| format!("face {what} index `{}` is not an integer", crate::clip::clip(s)))?;
    let ok = match i {
        0 => return Err(format!("face {what} index 0 is invalid (OBJ indices start at 1)")),
        i if i > 0 => (i as u64) <= total as u64,
        i => i.unsigned_abs() <= seen as u64,
    };
    if !ok {
        let count = if i > 0 { total } else { seen };
        let so_far = if i > 0 { "" } else { " so far" };
        let there = match (count, what) {
            (1, _) => format!("there is 1 {what}"),
            (_, "vertex") => format!("there are {count} vertices"),
            _ => format!("there are {count} {what}s"),
        };
        return Err(format!("face {what} index {i} is out of range: {there}{so_far}"));
    }
    Ok(())
}

/// One vertex per triangle corner, with normals averaged (weighted by
/// area) over the triangles around the vertex that meet the corner's own
/// at less than `crease_degrees`; positions are copied bit for bit, so the
/// surface stays watertight.
pub fn with_crease_normals(mesh: TriangleMesh, crease_degrees: f32) -> TriangleMesh {
    let cos_crease = crease_degrees.to_radians().cos();
    let face: Vec<Vec3> = mesh
        .indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            (b - a).cross(c - a)
        })
        .collect();
    let unit: Vec<Vec3> = face.iter().map(|n| n.normalize_or_zero()).collect();
    // Triangles around each vertex (CSR).
    let mut start = vec![0u32; mesh.positions.len() + 1];
    for t in &mesh.indices {
        for &i in t {
            start[i as usize + 1] += 1;
        }
    }
    for i in 0..mesh.positions.len() {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut around = vec![0u32; start[mesh.positions.len()] as usize];
    for (t, tri) in mesh.indices.iter().enumerate() {
        for &i in tri {
            around[fill[i as usize] as usize] = t as u32;
            fill[i as usize] += 1;
        }
    }
    let mut out = TriangleMesh {
        positions: Vec::with_capacity(mesh.indices.len() * 3),
        indices: Vec::with_capacity(mesh.indices.len()),
        normals: Some(Vec::with_capacity(mesh.indices.len() * 3)),
        texcoords: mesh.texcoords.as_ref().map(|_| Vec::with_capacity(mesh.indices.len() * 3)),
        material_indices: mesh.material_indices.clone(),
    };
    let normals = out.normals.as_mut().expect("set above");
    for (t, tri) in mesh.indices.iter().enumerate() {
        let base = out.positions.len() as u32;
        for &i in tri {
            let mut n = Vec3::ZERO;
            for &other in &around[start[i as usize] as usize..start[i as usize + 1] as usize] {
                if unit[other as usize].dot(unit[t]) >= cos_crease {
                    n += face[other as usize];
                }
            }
            out.positions.push(mesh.positions[i as usize]);
            normals.push(n.try_normalize().unwrap_or(unit[t]));
            if let (Some(src), Some(dst)) = (&mesh.texcoords, out.texcoords.as_mut()) {
                dst.push(src[i as usize]);
            }
        }
        out.indices.push([base, base + 1, base + 2]);
    }
    out
}

/// The positions of the `v` lines after `o NAME` (up to the next `o`): a
/// way to find geometry whose faces a file leaves commented out.
pub fn object_vertices(text: &str, name: &str) -> Vec<Vec3> {
    let mut inside = false;
    let mut out = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("o") => inside = words.next() == Some(name),
            Some("v") if inside => {
                let xyz: Vec<f32> = words.take(3).filter_map(|w| w.parse().ok()).collect();
                if let [x, y, z] = xyz[..] {
                    out.push(Vec3::new(x, y, z));
                }
            }
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube, four vertices per face (so every face is flat).
    fn unit_cube() -> TriangleMesh {
        let mut mesh = TriangleMesh::default();
        for (n, t1, t2) in [
            (Vec3::X, Vec3::Y, Vec3::Z),
            (-Vec3::X, Vec3::Z, Vec3::Y),
            (Vec3::Y, Vec3::Z, Vec3::X),
            (-Vec3::Y, Vec3::X, Vec3::Z),
            (Vec3::Z, Vec3::X, Vec3::Y),
            (-Vec3::Z, Vec3::Y, Vec3::X),
        ] {
            let base = mesh.positions.len() as u32;
            for (s1, s2) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions.push((n + t1 * s1 + t2 * s2) * 0.5);
            }
            mesh.indices.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
        }
        mesh
    }

    fn load(text: &str) -> Result<LoadedMesh, MeshError> {
        parse_obj(text, "test.obj", None)
    }

    #[test]
    fn accepts_the_usual_index_forms_and_triangulates_polygons() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n\
                    f 1/1/1 2/2/1 3/3/1\nf 1//1 3//1 4//1\nf -5 -4 -3 -2 -1\n";
        let m = load(text).unwrap();
        assert_eq!(m.mesh.indices.len(), 1 + 1 + 3);
        assert_eq!((m.min, m.max), (Vec3::ZERO, Vec3::new(1.0, 1.5, 0.0)));
        // No materials: every triangle is the default grey.
        assert_eq!(m.materials.len(), 1);
        assert_eq!(m.materials[0].diffuse, DEFAULT_GREY);
        assert!(m.mesh.material_indices.as_ref().unwrap().iter().all(|&i| i == 0));
        assert!(m.mesh.validate().is_ok());
    }

    #[test]
    fn problems_name_their_line() {
        let cases = [
            ("v 0 0 0\nv 1 0\n", 2, "a vertex needs 3 numbers, found 2"),
            ("v 0 0 0 0\n", 1, "vertex 1 has weight w = 0"),
            ("v 0 0 0 1 1\n", 1, "a vertex has 5 numbers; expected 3 (x y z), 4 (with w) or 6 (with r g b)"),
            ("vt 0 x\n", 1, "a texture coordinate has `x`, which is not a number"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2 2 3\n",
                4,
                "face texture coordinate index 2 is out of range: there are 0 texture coordinates",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n",
                6,
                "face corner `1/1/1/1` has more than 3 indices",
            ),
        ];
        for (text, line, problem) in cases {
            let e = load(text).unwrap_err();
            assert_eq!((e.line, e.problem.as_str()), (Some(line), problem), "{text:?}");
            assert_eq!(e.to_string(), format!("test.obj:{line}: {problem}"));
        }
    }

    #[test]
    fn the_cornell_box_has_its_materials_and_a_commented_out_light() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/scenes/cornell_box.obj");
        let m = load_obj(&path).unwrap();
        assert_eq!(m.mesh.indices.len(), 34, "17 quads");
        let names: Vec<&str> = m.materials.iter().map(|m| m.name.as_str()).collect();
        for name in ["white", "red", "green", "light"] {
            assert!(names.contains(&name), "{names:?}");
        }
        let red = m.materials.iter().find(|m| m.name == "red").unwrap();
        assert_eq!((red.diffuse, red.emission), (Vec3::X, Vec3::ZERO));
        let light = m.materials.iter().find(|m| m.name == "light").unwrap();
        assert_eq!(light.emission, Vec3::splat(20.0));
        // The red wall's two triangles use the red material.
        let red_index = m.materials.iter().position(|m| m.name == "red").unwrap() as u32;
        assert_eq!(m.mesh.material_indices.as_ref().unwrap().iter().filter(|&&i| i == red_index).count(), 2);
        let text = std::fs::read_to_string(&path).unwrap();
        let quad = object_vertices(&text, "light");
        assert_eq!(quad.len(), 4);
        assert!(quad.iter().all(|p| p.y == 548.0));
    }

    #[test]
    fn crease_normals_keep_a_cube_flat_and_smooth_a_gentle_fold() {
        let cube = unit_cube();
        let flat = with_crease_normals(cube.clone(), CREASE_DEGREES);
        for (t, tri) in flat.indices.iter().enumerate() {
            let [a, b, c] = tri.map(|i| flat.positions[i as usize]);
            let face = (b - a).cross(c - a).normalize();
            for &i in tri {
                assert!((flat.normals.as_ref().unwrap()[i as usize] - face).length() < 1e-5, "triangle {t}");
            }
        }
        // Two triangles folded by 20 degrees share the averaged normal at
        // their common edge.
        let s = 20f32.to_radians();
        let fold = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::Z, Vec3::new(1.0, 0.0, 0.0), Vec3::new(-s.cos(), s.sin(), 0.0)],
            indices: vec![[0, 1, 2], [0, 3, 1]],
            ..TriangleMesh::default()
        };
        let smooth = with_crease_normals(fold, CREASE_DEGREES);
        let n = smooth.normals.unwrap();
        assert!((n[0] - n[3]).length() < 1e-5, "{} vs {}", n[0], n[3]);
        let half = 10f32.to_radians();
        assert!((n[0] - Vec3::new(half.sin(), half.cos(), 0.0)).length() < 1e-5, "{}", n[0]);
        assert_eq!(smooth.positions.len(), 6);
    }
}
