//! Meshes the tests share.

use rt_runtime::TriangleMesh;
use rt_std::prelude::Vec3;

/// A bumpy `n` x `n` grid of quads over [-1, 1]^2 (2 n^2 triangles), its
/// height `0.2 sin(5u) cos(4v)`.
pub fn bumpy_grid(n: u32) -> TriangleMesh {
    grid(n, 1.0, |u, v| 0.2 * (5.0 * u).sin() * (4.0 * v).cos())
}

/// An `n` x `n` grid of quads over [-half, half]^2 (2 n^2 triangles, each
/// quad split along its diagonal from its lower left corner), its height
/// `height(x, y)`.
pub fn grid(n: u32, half: f32, height: impl Fn(f32, f32) -> f32) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    for y in 0..=n {
        for x in 0..=n {
            let (u, v) = ((x as f32 / n as f32 * 2.0 - 1.0) * half, (y as f32 / n as f32 * 2.0 - 1.0) * half);
            mesh.positions.push(Vec3::new(u, v, height(u, v)));
        }
    }
    for y in 0..n {
        for x in 0..n {
            let i = y * (n + 1) + x;
            mesh.indices.push([i, i + 1, i + n + 2]);
            mesh.indices.push([i, i + n + 2, i + n + 1]);
        }
    }
    mesh
}

/// The quad [-1, 1]^2 at z = 0, counter-clockwise seen from +z (its front),
/// split along its diagonal from (-1, -1) to (1, 1) into two triangles.
pub fn unit_quad() -> TriangleMesh {
    TriangleMesh {
        positions: vec![
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..TriangleMesh::default()
    }
}
