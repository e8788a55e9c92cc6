//! The benchmark's meshes, shared by `benches/subdivision.rs` and the example that exports them
//! for the C++ timings (`scripts/golden_subdivision.py --bench`).

use crate::mesh::PolyMesh;
use crate::shapes::{icosphere, irregular, torus_quads, torus_triangles};

/// `(name, mesh)`: about 10⁵ faces each.
///
/// - `torus-tri`: a 224 × 224 torus grid split into 100 352 triangles, all valence 6;
/// - `irregular-tri`: the level-6 icosphere (81 920 triangles) with a tenth of its faces split
///   1→3 at lifted centroids and jittered positions: about 98 000 triangles, valences 3 to 9;
/// - `torus-quad`: a 316 × 316 torus grid, 99 856 quads, all valence 4.
pub fn bench_meshes() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("torus-tri", torus_triangles(224, 224, 1.0, 0.4)),
        (
            "irregular-tri",
            irregular(&icosphere(6), 0.1, 0.1, 0.1, 0x5EED),
        ),
        ("torus-quad", torus_quads(316, 316, 1.0, 0.4)),
    ]
}
