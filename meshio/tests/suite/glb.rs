//! glTF binary: the written file loads in the independent `gltf` crate (which validates the
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design
//! document), with the right accessors, min/max and values.

use crate::common;

use meshio::{format_by_name, MeshFormat, RawMesh, UpAxis, WriteOptions};

fn glb() -> &'static dyn MeshFormat {
    format_by_name("glb").expect("glb")
}

/// Loads `bytes` with `gltf` and returns positions, normals, colours, indices.
#[allow(clippy::type_complexity)]
fn load(
    bytes: &[u8],
) -> (
    Vec<[f32; 3]>,
    Option<Vec<[f32; 3]>>,
    Option<Vec<[f32; 3]>>,
    Vec<u32>,
    ([f32; 3], [f32; 3]),
) {
    assert_eq!(&bytes[..4], b"glTF");
    assert_eq!(bytes.len() % 4, 0);
    let doc = gltf::Gltf::from_slice(bytes).expect("gltf loads and validates");
    assert_eq!(doc.document.scenes().count(), 1);
    assert_eq!(doc.document.nodes().count(), 1);
    let blob = doc.blob.clone().expect("BIN chunk");
    for v in doc.document.views() {
        assert_eq!(v.offset() % 4, 0, "buffer views are 4-byte aligned");
    }
    let mesh = doc.document.meshes().next().expect("mesh");
    let prim = mesh.primitives().next().expect("primitive");
    assert_eq!(prim.mode(), gltf::mesh::Mode::Triangles);
    let bb = prim.bounding_box();
    let reader = prim.reader(|b| (b.index() == 0).then_some(blob.as_slice()));
    let positions: Vec<[f32; 3]> = reader.read_positions().expect("positions").collect();
    let normals = reader.read_normals().map(Iterator::collect);
    let colors = reader.read_colors(0).map(|c| c.into_rgb_f32().collect());
    let indices: Vec<u32> = reader.read_indices().expect("indices").into_u32().collect();
    (positions, normals, colors, indices, (bb.min, bb.max))
}

#[test]
fn cube_loads_with_all_attributes() {
    let cube = common::cube();
    // Y up: written as it is.
    let bytes = glb()
        .write(&cube, &WriteOptions::new().up(UpAxis::Y))
        .expect("write");
    let (p, n, c, idx, (min, max)) = load(&bytes);
    assert_eq!(p.len(), 8);
    assert_eq!(idx.len(), 36);
    assert_eq!(min, [0.0; 3]);
    assert_eq!(max, [1.0; 3]);
    for (a, b) in p.iter().zip(&cube.positions) {
        assert_eq!(*a, [b.x as f32, b.y as f32, b.z as f32]);
    }
    let n = n.expect("normals");
    for (a, b) in n.iter().zip(cube.normals.as_ref().expect("n")) {
        let u = b.normalize();
        assert_eq!(*a, [u.x as f32, u.y as f32, u.z as f32]);
    }
    assert_eq!(c.as_deref(), cube.colors.as_deref());
    // Fan triangulation of each quad.
    let first = cube.polygons.get(0);
    assert_eq!(
        &idx[..6],
        &[first[0], first[1], first[2], first[0], first[2], first[3]].map(|i| i as u32)
    );
}

#[test]
fn grid_without_normals_loads() {
    let m: RawMesh = common::grid(20);
    let bytes = glb()
        .write(&m, &WriteOptions::new().up(UpAxis::Y))
        .expect("write");
    let (p, n, c, idx, (min, max)) = load(&bytes);
    assert_eq!(p.len(), 21 * 21);
    assert_eq!(idx.len(), 3 * 800);
    assert!(n.is_none() && c.is_none());
    let zmax = m
        .positions
        .iter()
        .map(|q| q.z as f32)
        .fold(f32::MIN, f32::max);
    assert_eq!(max[2], zmax);
    assert_eq!(min[0], 0.0);
    let tris: Vec<u32> = m.polygons.iter().flatten().map(|&i| i as u32).collect();
    assert_eq!(idx, tris);
}

#[test]
fn empty_mesh_and_zero_normal_are_refused() {
    assert!(glb()
        .write(&RawMesh::default(), &WriteOptions::new())
        .is_err());
    let mut m = common::bare_cube();
    m.normals = Some(vec![nalgebra::Vector3::zeros(); 8]);
    assert!(glb().write(&m, &WriteOptions::new()).is_err());
}
