//! The streaming writers write exactly the bytes the in-memory writers wrote before them.
//!
//! [`EXPECTED`] holds, for every writable format × mesh × option set, the length and the
//! [`FxHasher`] digest of the bytes `MeshFormat::write` produced before the writers streamed
//! (recorded from that code, commit "streaming: digests of every writer's output"), or the
//! error message when the mesh was refused. The digest is not cryptographic, but an accidental
//! change that keeps both the length and the 64-bit digest is out of reach of an encoder bug.
//! Set `MESHIO_PRINT_DIGESTS=1` to print the table the test compares against.

use std::hash::Hasher;
use std::io::Write;

use meshio::hash::FxHasher;
use meshio::{Curvature, Polygons, RawMesh, UpAxis, WriteError, WriteOptions, FORMATS};
use nalgebra::{Matrix3, Point3, Vector3};

use crate::common::{bare_cube, cube, grid};

/// The meshes: triangles, quads with normals, colours and a property, polygons of mixed size,
/// curvature with directions and a colour map, the testbed format's names, shapes, creases and
/// mesh fields, one triangle, and no faces at all.
fn meshes() -> Vec<(&'static str, RawMesh)> {
    let mut curved = grid(3);
    let n = curved.positions.len();
    let gaussian: Vec<f64> = (0..n).map(|i| 0.5 - i as f64 * 0.0625).collect();
    let mean: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 * 0.125).collect();
    let dirs = (0..n)
        .map(|i| {
            let a = i as f64 * 0.3;
            [
                Vector3::new(a.cos(), a.sin(), 0.0),
                Vector3::new(-a.sin(), a.cos(), 0.0),
            ]
        })
        .collect();
    curved.curvature = Some(Curvature::from_exported(gaussian, mean).with_directions(dirs));
    curved.colors = Some((0..n).map(|i| [i as f32 / n as f32, 0.25, 0.75]).collect());
    curved.color_map = Some(meshio::ColorMap {
        quantity: "gaussian_curvature".into(),
        map: "diverging".into(),
        min: -1.0,
        max: 1.0,
    });
    curved.normals = Some(vec![Vector3::new(0.0, 0.0, 1.0); n]);

    let mut mixed = RawMesh {
        positions: (0..7)
            .map(|i| {
                let a = i as f64 * 0.9;
                Point3::new(a.cos() * 1.5, a.sin() * 0.75, i as f64 / 7.0 - 0.2)
            })
            .collect(),
        ..RawMesh::default()
    };
    let mut polygons = Polygons::new();
    polygons.push(&[0, 1, 2, 3, 4]);
    polygons.push(&[0, 4, 5]);
    polygons.push(&[0, 5, 6, 1]);
    mixed.polygons = polygons;

    let mut named = bare_cube();
    named.vertex_names = Some((0..8).map(|i| format!("v{}", 10 + i)).collect());
    named.face_names = Some((0..6).map(|f| format!("face{f}")).collect());
    named.shapes = Some(
        (0..8)
            .map(|i| Matrix3::from_diagonal(&Vector3::new(1.0, i as f64 * 0.5, -2.0)))
            .collect(),
    );
    named.crease_edges = vec![[0, 2], [2, 3]];
    named.mesh_fields.insert("area".into(), vec![6.0]);
    named
        .mesh_fields
        .insert("centre".into(), vec![0.5, 0.5, 0.5]);

    let one = RawMesh::from_triangles(
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 1e-7),
        ],
        &[[0, 1, 2]],
    );
    let points_only = RawMesh {
        positions: vec![Point3::new(1.0, 2.0, 3.0), Point3::new(-1.0, 0.5, 0.25)],
        ..RawMesh::default()
    };
    vec![
        ("grid", grid(6)),
        ("cube", cube()),
        ("bare_cube", bare_cube()),
        ("curved", curved),
        ("mixed", mixed),
        ("named", named),
        ("one_triangle", one),
        ("points_only", points_only),
        ("empty", RawMesh::default()),
    ]
}

/// The option sets: the defaults, text, 64-bit positions, and `y` up.
fn option_sets() -> Vec<(&'static str, WriteOptions)> {
    vec![
        ("default", WriteOptions::new()),
        ("ascii", WriteOptions::new().ascii()),
        ("double", WriteOptions::new().double_precision()),
        (
            "ascii_double",
            WriteOptions::new().ascii().double_precision(),
        ),
        ("up_y", WriteOptions::new().up(UpAxis::Y)),
    ]
}

/// Length and digest of the bytes, or the error.
fn digest(result: Result<Vec<u8>, WriteError>) -> String {
    match result {
        Ok(bytes) => {
            let mut h = FxHasher::with_seed(0x5eed);
            h.write(&bytes);
            format!("{} {:016x}", bytes.len(), h.finish())
        }
        Err(e) => format!("error: {e}"),
    }
}

/// Every (format, mesh, options) case with its digest now.
fn current() -> Vec<(String, String)> {
    let mut out = Vec::new();
    for format in FORMATS.iter().filter(|f| f.can_write()) {
        for (mname, mesh) in meshes() {
            for (oname, opts) in option_sets() {
                out.push((
                    format!("{}/{mname}/{oname}", format.name()),
                    digest(format.write(&mesh, &opts)),
                ));
            }
        }
    }
    out
}

/// Recorded from the in-memory writers (module docs).
const EXPECTED: &[(&str, &str)] = &[
    ("ply/grid/default", "1737 58abd3184ba58471"),
    ("ply/grid/ascii", "2256 351440356beb2261"),
    ("ply/grid/double", "2328 2e35439ac4dfbe7f"),
    ("ply/grid/ascii_double", "3118 b4e05c3e585cfaa2"),
    ("ply/grid/up_y", "1737 58abd3184ba58471"),
    ("ply/cube/default", "905 075bc003e834d0c1"),
    ("ply/cube/ascii", "1014 e130f0853422d251"),
    ("ply/cube/double", "1004 23bd5e9b25cfe63e"),
    ("ply/cube/ascii_double", "1017 3c23bfc54e21a180"),
    ("ply/cube/up_y", "905 075bc003e834d0c1"),
    ("ply/bare_cube/default", "409 5ac3861d73dc3cd1"),
    ("ply/bare_cube/ascii", "352 92c9d47852d00899"),
    ("ply/bare_cube/double", "508 05bf79a04402824d"),
    ("ply/bare_cube/ascii_double", "355 a06bbadb47b6e5ef"),
    ("ply/bare_cube/up_y", "409 5ac3861d73dc3cd1"),
    ("ply/curved/default", "2489 3c3ac3aee46f168c"),
    ("ply/curved/ascii", "3592 2f5d2e3efa6e3439"),
    ("ply/curved/double", "2684 d6217bf28ca38703"),
    ("ply/curved/ascii_double", "3838 5f794baea5ae142b"),
    ("ply/curved/up_y", "2489 3c3ac3aee46f168c"),
    ("ply/mixed/default", "346 97d850dca2f542d1"),
    ("ply/mixed/ascii", "437 537d0cf710a78929"),
    ("ply/mixed/double", "433 73b7510ea5dde80b"),
    ("ply/mixed/ascii_double", "596 b54c53f5f9352d15"),
    ("ply/mixed/up_y", "346 97d850dca2f542d1"),
    ("ply/named/default", "506 9b77db3013d6a118"),
    ("ply/named/ascii", "443 d74d17476a83d322"),
    ("ply/named/double", "605 df5baf532c74b8ec"),
    ("ply/named/ascii_double", "446 311e8b4b1c674d79"),
    ("ply/named/up_y", "506 9b77db3013d6a118"),
    ("ply/one_triangle/default", "260 c763c03552fb9a1c"),
    ("ply/one_triangle/ascii", "241 97599bf1c710f6c7"),
    ("ply/one_triangle/double", "299 54507a6b7e772da2"),
    ("ply/one_triangle/ascii_double", "244 7d5bd9dba7eebbca"),
    ("ply/one_triangle/up_y", "260 c763c03552fb9a1c"),
    ("ply/points_only/default", "235 7768ac043b8dd205"),
    ("ply/points_only/ascii", "222 98b45e34a3fc4f10"),
    ("ply/points_only/double", "262 53d30be343a986f9"),
    ("ply/points_only/ascii_double", "225 e587bd5aef1e1e06"),
    ("ply/points_only/up_y", "235 7768ac043b8dd205"),
    ("ply/empty/default", "211 2ca0358a9f73e8d5"),
    ("ply/empty/ascii", "196 bb7263b8aa5491f5"),
    ("ply/empty/double", "214 b2e640a0b19ed398"),
    ("ply/empty/ascii_double", "199 ecf8a978b2e6358e"),
    ("ply/empty/up_y", "211 2ca0358a9f73e8d5"),
    ("glb/grid/default", "2168 aeedd76286e86869"),
    ("glb/grid/ascii", "2168 aeedd76286e86869"),
    ("glb/grid/double", "2168 aeedd76286e86869"),
    ("glb/grid/ascii_double", "2168 aeedd76286e86869"),
    ("glb/grid/up_y", "2144 d3c71fd82ca99a51"),
    ("glb/cube/default", "1380 5089d787993a4d14"),
    ("glb/cube/ascii", "1380 5089d787993a4d14"),
    ("glb/cube/double", "1380 5089d787993a4d14"),
    ("glb/cube/ascii_double", "1380 5089d787993a4d14"),
    ("glb/cube/up_y", "1356 5126b2871d3b5e26"),
    ("glb/bare_cube/default", "920 8e4af37f91870549"),
    ("glb/bare_cube/ascii", "920 8e4af37f91870549"),
    ("glb/bare_cube/double", "920 8e4af37f91870549"),
    ("glb/bare_cube/ascii_double", "920 8e4af37f91870549"),
    ("glb/bare_cube/up_y", "896 e307e6899313768e"),
    ("glb/curved/default", "4072 0d8e3be2fdddbc4f"),
    ("glb/curved/ascii", "4072 0d8e3be2fdddbc4f"),
    ("glb/curved/double", "4072 0d8e3be2fdddbc4f"),
    ("glb/curved/ascii_double", "4072 0d8e3be2fdddbc4f"),
    ("glb/curved/up_y", "4052 e40f51b2bf05d5c8"),
    ("glb/mixed/default", "912 a97b383d1f29f297"),
    ("glb/mixed/ascii", "912 a97b383d1f29f297"),
    ("glb/mixed/double", "912 a97b383d1f29f297"),
    ("glb/mixed/ascii_double", "912 a97b383d1f29f297"),
    ("glb/mixed/up_y", "892 2d1d337470ef8d49"),
    ("glb/named/default", "920 8e4af37f91870549"),
    ("glb/named/ascii", "920 8e4af37f91870549"),
    ("glb/named/double", "920 8e4af37f91870549"),
    ("glb/named/ascii_double", "920 8e4af37f91870549"),
    ("glb/named/up_y", "896 e307e6899313768e"),
    ("glb/one_triangle/default", "740 8385d85158c2d8df"),
    ("glb/one_triangle/ascii", "740 8385d85158c2d8df"),
    ("glb/one_triangle/double", "740 8385d85158c2d8df"),
    ("glb/one_triangle/ascii_double", "740 8385d85158c2d8df"),
    ("glb/one_triangle/up_y", "720 944fcbc0db2b27ec"),
    (
        "glb/points_only/default",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/points_only/ascii",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/points_only/double",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/points_only/ascii_double",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/points_only/up_y",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/empty/default",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/empty/ascii",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/empty/double",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/empty/ascii_double",
        "error: glb: glTF needs at least one triangle",
    ),
    (
        "glb/empty/up_y",
        "error: glb: glTF needs at least one triangle",
    ),
    ("off/grid/default", "2965 d003cce9e7ea185f"),
    ("off/grid/ascii", "2965 d003cce9e7ea185f"),
    ("off/grid/double", "2965 d003cce9e7ea185f"),
    ("off/grid/ascii_double", "2965 d003cce9e7ea185f"),
    ("off/grid/up_y", "2965 d003cce9e7ea185f"),
    ("off/cube/default", "443 f3331d52d584d079"),
    ("off/cube/ascii", "443 f3331d52d584d079"),
    ("off/cube/double", "443 f3331d52d584d079"),
    ("off/cube/ascii_double", "443 f3331d52d584d079"),
    ("off/cube/up_y", "443 f3331d52d584d079"),
    ("off/bare_cube/default", "202 a44966161f45cb18"),
    ("off/bare_cube/ascii", "202 a44966161f45cb18"),
    ("off/bare_cube/double", "202 a44966161f45cb18"),
    ("off/bare_cube/ascii_double", "202 a44966161f45cb18"),
    ("off/bare_cube/up_y", "202 a44966161f45cb18"),
    ("off/curved/default", "1444 9a55f7230cc80d3f"),
    ("off/curved/ascii", "1444 9a55f7230cc80d3f"),
    ("off/curved/double", "1444 9a55f7230cc80d3f"),
    ("off/curved/ascii_double", "1444 9a55f7230cc80d3f"),
    ("off/curved/up_y", "1444 9a55f7230cc80d3f"),
    ("off/mixed/default", "443 761245a8242c4f65"),
    ("off/mixed/ascii", "443 761245a8242c4f65"),
    ("off/mixed/double", "443 761245a8242c4f65"),
    ("off/mixed/ascii_double", "443 761245a8242c4f65"),
    ("off/mixed/up_y", "443 761245a8242c4f65"),
    ("off/named/default", "202 a44966161f45cb18"),
    ("off/named/ascii", "202 a44966161f45cb18"),
    ("off/named/double", "202 a44966161f45cb18"),
    ("off/named/ascii_double", "202 a44966161f45cb18"),
    ("off/named/up_y", "202 a44966161f45cb18"),
    ("off/one_triangle/default", "91 f20b604d2a468786"),
    ("off/one_triangle/ascii", "91 f20b604d2a468786"),
    ("off/one_triangle/double", "91 f20b604d2a468786"),
    ("off/one_triangle/ascii_double", "91 f20b604d2a468786"),
    ("off/one_triangle/up_y", "91 f20b604d2a468786"),
    ("off/points_only/default", "72 40887ed2b412e7cb"),
    ("off/points_only/ascii", "72 40887ed2b412e7cb"),
    ("off/points_only/double", "72 40887ed2b412e7cb"),
    ("off/points_only/ascii_double", "72 40887ed2b412e7cb"),
    ("off/points_only/up_y", "72 40887ed2b412e7cb"),
    ("off/empty/default", "46 f2fbe31c1c23b48f"),
    ("off/empty/ascii", "46 f2fbe31c1c23b48f"),
    ("off/empty/double", "46 f2fbe31c1c23b48f"),
    ("off/empty/ascii_double", "46 f2fbe31c1c23b48f"),
    ("off/empty/up_y", "46 f2fbe31c1c23b48f"),
    ("stl/grid/default", "3684 9bde4e9c04c62fb3"),
    ("stl/grid/ascii", "15116 67bcfbedd233afc1"),
    ("stl/grid/double", "3684 9bde4e9c04c62fb3"),
    ("stl/grid/ascii_double", "15116 67bcfbedd233afc1"),
    ("stl/grid/up_y", "3684 9bde4e9c04c62fb3"),
    ("stl/cube/default", "684 df9df31a1b21fdba"),
    ("stl/cube/ascii", "1715 0d3d882e63763d70"),
    ("stl/cube/double", "684 df9df31a1b21fdba"),
    ("stl/cube/ascii_double", "1715 0d3d882e63763d70"),
    ("stl/cube/up_y", "684 df9df31a1b21fdba"),
    ("stl/bare_cube/default", "684 df9df31a1b21fdba"),
    ("stl/bare_cube/ascii", "1715 0d3d882e63763d70"),
    ("stl/bare_cube/double", "684 df9df31a1b21fdba"),
    ("stl/bare_cube/ascii_double", "1715 0d3d882e63763d70"),
    ("stl/bare_cube/up_y", "684 df9df31a1b21fdba"),
    ("stl/curved/default", "984 b3c9b8e50637739e"),
    ("stl/curved/ascii", "3763 ba777e4eaa234904"),
    ("stl/curved/double", "984 b3c9b8e50637739e"),
    ("stl/curved/ascii_double", "3763 ba777e4eaa234904"),
    ("stl/curved/up_y", "984 b3c9b8e50637739e"),
    ("stl/mixed/default", "384 024e8398664cf45c"),
    ("stl/mixed/ascii", "1254 d82b36c9f51d14b9"),
    ("stl/mixed/double", "384 024e8398664cf45c"),
    ("stl/mixed/ascii_double", "1254 d82b36c9f51d14b9"),
    ("stl/mixed/up_y", "384 024e8398664cf45c"),
    ("stl/named/default", "684 df9df31a1b21fdba"),
    ("stl/named/ascii", "1715 0d3d882e63763d70"),
    ("stl/named/double", "684 df9df31a1b21fdba"),
    ("stl/named/ascii_double", "1715 0d3d882e63763d70"),
    ("stl/named/up_y", "684 df9df31a1b21fdba"),
    ("stl/one_triangle/default", "134 8f90d370cba564ca"),
    ("stl/one_triangle/ascii", "172 66d47be4fda08e6e"),
    ("stl/one_triangle/double", "134 8f90d370cba564ca"),
    ("stl/one_triangle/ascii_double", "172 66d47be4fda08e6e"),
    ("stl/one_triangle/up_y", "134 8f90d370cba564ca"),
    ("stl/points_only/default", "84 2043e373a0f8f030"),
    ("stl/points_only/ascii", "29 f9bf11ccc32904d5"),
    ("stl/points_only/double", "84 2043e373a0f8f030"),
    ("stl/points_only/ascii_double", "29 f9bf11ccc32904d5"),
    ("stl/points_only/up_y", "84 2043e373a0f8f030"),
    ("stl/empty/default", "84 2043e373a0f8f030"),
    ("stl/empty/ascii", "29 f9bf11ccc32904d5"),
    ("stl/empty/double", "84 2043e373a0f8f030"),
    ("stl/empty/ascii_double", "29 f9bf11ccc32904d5"),
    ("stl/empty/up_y", "84 2043e373a0f8f030"),
    ("testbed/grid/default", "5463 a5d29f6cd9dead8c"),
    ("testbed/grid/ascii", "5463 a5d29f6cd9dead8c"),
    ("testbed/grid/double", "5463 a5d29f6cd9dead8c"),
    ("testbed/grid/ascii_double", "5463 a5d29f6cd9dead8c"),
    ("testbed/grid/up_y", "5463 a5d29f6cd9dead8c"),
    ("testbed/cube/default", "823 a5db9edd95b3855f"),
    ("testbed/cube/ascii", "823 a5db9edd95b3855f"),
    ("testbed/cube/double", "823 a5db9edd95b3855f"),
    ("testbed/cube/ascii_double", "823 a5db9edd95b3855f"),
    ("testbed/cube/up_y", "823 a5db9edd95b3855f"),
    ("testbed/bare_cube/default", "495 be96bc42642a798d"),
    ("testbed/bare_cube/ascii", "495 be96bc42642a798d"),
    ("testbed/bare_cube/double", "495 be96bc42642a798d"),
    ("testbed/bare_cube/ascii_double", "495 be96bc42642a798d"),
    ("testbed/bare_cube/up_y", "495 be96bc42642a798d"),
    ("testbed/curved/default", "1908 1e83c4fcfad3e1f1"),
    ("testbed/curved/ascii", "1908 1e83c4fcfad3e1f1"),
    ("testbed/curved/double", "1908 1e83c4fcfad3e1f1"),
    ("testbed/curved/ascii_double", "1908 1e83c4fcfad3e1f1"),
    ("testbed/curved/up_y", "1908 1e83c4fcfad3e1f1"),
    ("testbed/mixed/default", "659 e8d161974561c43f"),
    ("testbed/mixed/ascii", "659 e8d161974561c43f"),
    ("testbed/mixed/double", "659 e8d161974561c43f"),
    ("testbed/mixed/ascii_double", "659 e8d161974561c43f"),
    ("testbed/mixed/up_y", "659 e8d161974561c43f"),
    ("testbed/named/default", "993 e695549c4e562a51"),
    ("testbed/named/ascii", "993 e695549c4e562a51"),
    ("testbed/named/double", "993 e695549c4e562a51"),
    ("testbed/named/ascii_double", "993 e695549c4e562a51"),
    ("testbed/named/up_y", "993 e695549c4e562a51"),
    ("testbed/one_triangle/default", "167 3d3245565b1d7335"),
    ("testbed/one_triangle/ascii", "167 3d3245565b1d7335"),
    ("testbed/one_triangle/double", "167 3d3245565b1d7335"),
    ("testbed/one_triangle/ascii_double", "167 3d3245565b1d7335"),
    ("testbed/one_triangle/up_y", "167 3d3245565b1d7335"),
    ("testbed/points_only/default", "109 a2ba39dabb5d72be"),
    ("testbed/points_only/ascii", "109 a2ba39dabb5d72be"),
    ("testbed/points_only/double", "109 a2ba39dabb5d72be"),
    ("testbed/points_only/ascii_double", "109 a2ba39dabb5d72be"),
    ("testbed/points_only/up_y", "109 a2ba39dabb5d72be"),
    ("testbed/empty/default", "31 e8802a4f705f6ab5"),
    ("testbed/empty/ascii", "31 e8802a4f705f6ab5"),
    ("testbed/empty/double", "31 e8802a4f705f6ab5"),
    ("testbed/empty/ascii_double", "31 e8802a4f705f6ab5"),
    ("testbed/empty/up_y", "31 e8802a4f705f6ab5"),
    ("obj/grid/default", "3057 c24e81e80453285c"),
    ("obj/grid/ascii", "3057 c24e81e80453285c"),
    ("obj/grid/double", "3057 c24e81e80453285c"),
    ("obj/grid/ascii_double", "3057 c24e81e80453285c"),
    ("obj/grid/up_y", "3057 c24e81e80453285c"),
    ("obj/cube/default", "729 358b2903e88f5ca1"),
    ("obj/cube/ascii", "729 358b2903e88f5ca1"),
    ("obj/cube/double", "729 358b2903e88f5ca1"),
    ("obj/cube/ascii_double", "729 358b2903e88f5ca1"),
    ("obj/cube/up_y", "729 358b2903e88f5ca1"),
    ("obj/bare_cube/default", "208 a4526c3d835d5b62"),
    ("obj/bare_cube/ascii", "208 a4526c3d835d5b62"),
    ("obj/bare_cube/double", "208 a4526c3d835d5b62"),
    ("obj/bare_cube/ascii_double", "208 a4526c3d835d5b62"),
    ("obj/bare_cube/up_y", "208 a4526c3d835d5b62"),
    ("obj/curved/default", "2093 32097b5b4dfd93c7"),
    ("obj/curved/ascii", "2093 32097b5b4dfd93c7"),
    ("obj/curved/double", "2093 32097b5b4dfd93c7"),
    ("obj/curved/ascii_double", "2093 32097b5b4dfd93c7"),
    ("obj/curved/up_y", "2093 32097b5b4dfd93c7"),
    ("obj/mixed/default", "447 a61740dd14c8f941"),
    ("obj/mixed/ascii", "447 a61740dd14c8f941"),
    ("obj/mixed/double", "447 a61740dd14c8f941"),
    ("obj/mixed/ascii_double", "447 a61740dd14c8f941"),
    ("obj/mixed/up_y", "447 a61740dd14c8f941"),
    ("obj/named/default", "208 a4526c3d835d5b62"),
    ("obj/named/ascii", "208 a4526c3d835d5b62"),
    ("obj/named/double", "208 a4526c3d835d5b62"),
    ("obj/named/ascii_double", "208 a4526c3d835d5b62"),
    ("obj/named/up_y", "208 a4526c3d835d5b62"),
    ("obj/one_triangle/default", "87 c69bae38e8af9985"),
    ("obj/one_triangle/ascii", "87 c69bae38e8af9985"),
    ("obj/one_triangle/double", "87 c69bae38e8af9985"),
    ("obj/one_triangle/ascii_double", "87 c69bae38e8af9985"),
    ("obj/one_triangle/up_y", "87 c69bae38e8af9985"),
    ("obj/points_only/default", "66 62963ba11d652529"),
    ("obj/points_only/ascii", "66 62963ba11d652529"),
    ("obj/points_only/double", "66 62963ba11d652529"),
    ("obj/points_only/ascii_double", "66 62963ba11d652529"),
    ("obj/points_only/up_y", "66 62963ba11d652529"),
    ("obj/empty/default", "36 9c78d9e45ea30ee5"),
    ("obj/empty/ascii", "36 9c78d9e45ea30ee5"),
    ("obj/empty/double", "36 9c78d9e45ea30ee5"),
    ("obj/empty/ascii_double", "36 9c78d9e45ea30ee5"),
    ("obj/empty/up_y", "36 9c78d9e45ea30ee5"),
];

#[test]
fn writers_write_the_recorded_bytes() {
    let now = current();
    if std::env::var_os("MESHIO_PRINT_DIGESTS").is_some() {
        for (k, v) in &now {
            println!("    ({k:?}, {v:?}),");
        }
    }
    assert_eq!(now.len(), EXPECTED.len(), "cases");
    for ((k, v), (ek, ev)) in now.iter().zip(EXPECTED) {
        assert_eq!(k, ek);
        assert_eq!(v, ev, "{k}");
    }
}

/// A writer that takes `room` bytes and then fails, counting what it was offered.
struct Failing {
    room: usize,
    taken: usize,
}

impl Write for Failing {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.taken >= self.room {
            return Err(std::io::Error::other("disk full"));
        }
        let n = buf.len().min(self.room - self.taken);
        self.taken += n;
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A writer that counts the bytes and the calls it gets.
#[derive(Default)]
struct Counting {
    bytes: usize,
    calls: usize,
}

impl Write for Counting {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.bytes += buf.len();
        self.calls += 1;
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn a_failing_writer_gives_an_io_error() {
    // A grid big enough that every format's file exceeds one sink buffer (256 KiB), failing
    // at once and failing part way.
    let mesh = grid(120);
    for format in FORMATS.iter().filter(|f| f.can_write()) {
        for (oname, opts) in option_sets() {
            for room in [0, 1000, 300_000] {
                let mut out = Failing { room, taken: 0 };
                match format.write_to(&mesh, &opts, &mut out) {
                    Err(WriteError::Io {
                        format: name,
                        source,
                    }) => {
                        assert_eq!(name, format.name());
                        assert_eq!(source.to_string(), "disk full");
                    }
                    other => panic!("{}/{oname}/{room}: {other:?}", format.name()),
                }
            }
        }
    }
}

/// Meshes every writer refuses: a NaN position, a face index out of range, and curvature
/// beyond `f32` for the formats that store it.
fn refused() -> Vec<(&'static str, RawMesh)> {
    let mut nan = grid(4);
    if let Some(p) = nan.positions.last_mut() {
        p.z = f64::NAN;
    }
    let mut out_of_range = grid(4);
    let n = out_of_range.positions.len();
    out_of_range.polygons.push(&[0, 1, n]);
    let mut huge = grid(4);
    let n = huge.positions.len();
    let mut gaussian = vec![1.0; n];
    gaussian[n - 1] = 1e300;
    huge.curvature = Some(Curvature::from_exported(gaussian, vec![1.0; n]));
    vec![
        ("nan", nan),
        ("out_of_range", out_of_range),
        ("huge_curvature", huge),
    ]
}

#[test]
fn a_refused_mesh_writes_no_byte() {
    for format in FORMATS.iter().filter(|f| f.can_write()) {
        for (mname, mesh) in refused() {
            if mname == "huge_curvature" && !format.writes_curvature() {
                continue;
            }
            for (oname, opts) in option_sets() {
                let mut out = Counting::default();
                let result = format.write_to(&mesh, &opts, &mut out);
                let case = format!("{}/{mname}/{oname}", format.name());
                assert!(
                    matches!(result, Err(WriteError::Invalid { .. })),
                    "{case}: {result:?}"
                );
                assert_eq!(out.bytes, 0, "{case}");
            }
        }
    }
}

#[test]
fn bytes_go_out_in_big_chunks() {
    // The sink hands its 256 KiB buffer on when the next record does not fit, and records are
    // far shorter than half of it, so every write but the last carries more than half a
    // buffer: a file of B bytes takes at most B / 128 KiB + 1 writes.
    const CHUNK: usize = 256 * 1024;
    let mesh = grid(200);
    for format in FORMATS.iter().filter(|f| f.can_write()) {
        let mut out = Counting::default();
        format
            .write_to(&mesh, &WriteOptions::new(), &mut out)
            .expect("write");
        let bound = out.bytes / (CHUNK / 2) + 1;
        assert!(out.bytes > CHUNK, "{}", format.name());
        assert!(
            out.calls <= bound,
            "{}: {} calls for {} bytes",
            format.name(),
            out.calls,
            out.bytes
        );
    }
}
