//! The benchmark scenes: three meshes from `../shared/scenes` and one
//! generated scene of over two million triangles, each with a camera framed
//! from its bounds.

use glam::{Mat3, Vec3};
use rt_runtime::TriangleMesh;
use std::path::{Path, PathBuf};

/// One scene as every backend and peer sees it: flat triangles.
pub struct BenchScene {
    pub name: &'static str,
    pub mesh: TriangleMesh,
    /// From the scene's centre towards the eye, in units of its bounding
    /// sphere's radius.
    pub view: Vec3,
    /// Where it comes from, for the JSON.
    pub source: String,
}

/// The camera of every workload: (eye, u, v, w) as the pinhole program and
/// the peers read them.
pub type Camera = (Vec3, Vec3, Vec3, Vec3);

impl BenchScene {
    pub fn triangles(&self) -> usize {
        self.mesh.indices.len()
    }

    /// A pinhole camera looking at the centre of the bounds from `view`.
    pub fn camera(&self, width: u32, height: u32) -> Camera {
        let (lo, hi) = self
            .mesh
            .positions
            .iter()
            .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), p| (a.min(*p), b.max(*p)));
        let center = (lo + hi) * 0.5;
        let radius = (hi - lo).length() * 0.5;
        let eye = center + self.view * radius;
        let w = (center - eye).normalize();
        let u = w.cross(Vec3::Y).normalize() * (width as f32 / height as f32) * 0.45;
        let v = u.cross(w).normalize() * 0.45;
        (eye, u, v, w)
    }

    /// The triangles as obvhs takes them (also what Embree and the
    /// hand-written kernel get).
    pub fn obvhs_triangles(&self) -> Vec<obvhs::triangle::Triangle> {
        self.mesh
            .indices
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.mesh.positions[i as usize].into());
                obvhs::triangle::Triangle { v0: a, v1: b, v2: c }
            })
            .collect()
    }
}

/// Where the shared scenes are: `$RT_SCENES_DIR`, else the first
/// `shared/scenes` beside the workspace or one of its parents (a git
/// worktree lives a level deeper than the main checkout).
pub fn scenes_dir() -> Result<PathBuf, String> {
    if let Some(dir) = std::env::var_os("RT_SCENES_DIR") {
        return Ok(PathBuf::from(dir));
    }
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    workspace
        .ancestors()
        .map(|a| a.join("../shared/scenes"))
        .take(4)
        .find(|d| d.join("stanford-bunny.obj").is_file())
        .ok_or_else(|| {
            format!(
                "no shared/scenes with stanford-bunny.obj beside {} or its parents: set RT_SCENES_DIR to the folder of the shared test scenes",
                workspace.display()
            )
        })
}

/// Every triangle of every object in an OBJ file, quads triangulated, as
/// the examples load it (`rt_scene::obj`); the peers take flat triangles,
/// so only positions and indices are kept.
pub fn load_obj(path: &Path) -> Result<TriangleMesh, String> {
    let loaded = rt_scene::obj::load_obj(path).map_err(|e| e.to_string())?;
    let mesh = TriangleMesh { positions: loaded.mesh.positions, indices: loaded.mesh.indices, ..Default::default() };
    if mesh.indices.is_empty() {
        return Err(format!("{}: no triangles", path.display()));
    }
    Ok(mesh)
}

/// `copies` copies of `mesh` as one flat mesh: a wall of `columns` columns
/// facing +z, each copy turned about y by its own angle and pushed back by
/// its own depth so the wall is not a flat repetition.
pub fn wall_of_copies(mesh: &TriangleMesh, copies: u32, columns: u32) -> TriangleMesh {
    let (lo, hi) =
        mesh.positions.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), p| (a.min(*p), b.max(*p)));
    let size = hi - lo;
    let center = (lo + hi) * 0.5;
    let step = size.x.max(size.z) * 1.05;
    let mut out = TriangleMesh {
        positions: Vec::with_capacity(mesh.positions.len() * copies as usize),
        indices: Vec::with_capacity(mesh.indices.len() * copies as usize),
        ..TriangleMesh::default()
    };
    for k in 0..copies {
        let (col, row) = (k % columns, k / columns);
        let rot = Mat3::from_rotation_y(k as f32 * 2.399);
        let offset = Vec3::new(col as f32 * step, row as f32 * size.y * 1.02, -(((k * 7) % 5) as f32) * 0.2 * step);
        let base = out.positions.len() as u32;
        out.positions.extend(mesh.positions.iter().map(|p| rot * (*p - center) + offset));
        out.indices.extend(mesh.indices.iter().map(|t| t.map(|i| base + i)));
    }
    out
}

/// The bench's four scenes (the bunny, the teapot, the Cornell box and a
/// wall of 30 bunnies), in the order they are reported.
pub fn load_all(dir: &Path) -> Result<Vec<BenchScene>, String> {
    let front = Vec3::new(0.0, 0.1, 2.2);
    let bunny = load_obj(&dir.join("stanford-bunny.obj"))?;
    let teapot = load_obj(&dir.join("teapot.obj"))?;
    // The box is open towards -z: look in through the open side.
    let cornell = load_obj(&dir.join("cornell_box.obj"))?;
    // 30 copies of the bunny: 2,083,530 triangles.
    let wall = wall_of_copies(&bunny, 30, 6);
    let wall_tris = wall.indices.len();
    Ok(vec![
        BenchScene { name: "bunny", mesh: bunny, view: front, source: "stanford-bunny.obj".into() },
        BenchScene { name: "teapot", mesh: teapot, view: front, source: "teapot.obj".into() },
        BenchScene {
            name: "cornell_box",
            mesh: cornell,
            view: Vec3::new(0.0, 0.0, -1.6),
            source: "cornell_box.obj (quads triangulated, all objects)".into(),
        },
        BenchScene {
            name: "bunny_wall_2m",
            mesh: wall,
            view: Vec3::new(0.0, 0.1, 1.6),
            source: format!(
                "generated: 30 copies of the bunny (each turned about y, 6 columns x 5 rows, staggered in depth) baked into one flat mesh of {wall_tris} triangles; every backend and peer gets the same flat mesh (no instancing)"
            ),
        },
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shared meshes load as every face of the files, fans of triangles
    /// (what tobj, which the bench used before, gave).
    #[test]
    fn the_shared_meshes_load_whole() {
        let dir = scenes_dir().unwrap();
        for (file, triangles) in [("stanford-bunny.obj", 69_451), ("teapot.obj", 6_320), ("cornell_box.obj", 34)] {
            let mesh = load_obj(&dir.join(file)).unwrap();
            assert_eq!(mesh.indices.len(), triangles, "{file}");
            assert!(mesh.normals.is_none() && mesh.material_indices.is_none(), "{file}: flat triangles only");
        }
        let missing = load_obj(&dir.join("no-such.obj")).unwrap_err();
        assert!(missing.ends_with("no-such.obj: cannot read the file: no such file"), "{missing}");
    }
}
