//! The tessellation's mesh file: a format is asked only for what it stores, curvature no
//! 32-bit float holds is refused before the fit, the written curvature follows the exported
//! convention (H > 0 on a sphere with outward normals), and `--up` reaches the glTF writer.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use std::time::Instant;

use fitjob::output::MeshOutputOptions;
use fitjob::{FitOptions, InputOptions, JobError, Source};
use meshio::{MeshFormat, UpAxis};
use nalgebra::Point3;

/// The unit octahedron scaled by `scale`, as a raw mesh in memory.
fn octahedron(scale: f64) -> InputOptions {
    let p = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ]
    .map(|c| Point3::from(c.map(|x: f64| x * scale)));
    let tris = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    InputOptions {
        source: Source::Raw {
            label: format!("octahedron × {scale:e}"),
            raw: Box::new(meshio::RawMesh::from_triangles(p.to_vec(), &tris)),
        },
        ..InputOptions::default()
    }
}

fn fit(input: InputOptions, out: &std::path::Path, up: UpAxis) -> Result<(), Box<JobError>> {
    fitjob::run(
        FitOptions {
            input,
            mesh_out: Some(out.to_path_buf()),
            mesh_options: MeshOutputOptions { up },
            ..FitOptions::default()
        },
        &mut |_| {},
    )
    .map(|_| ())
    .map_err(Box::new)
}

/// Unit coordinates through `f32` and back: rounding of 2^-24, well below this.
const F32_ROUNDING: f64 = 1e-6;

/// The pre-fit refusal takes no fit: far below this, on any machine.
const REFUSAL_SECONDS: f64 = 1.0;

#[test]
fn formats_without_curvature_write_a_tiny_model_and_ply_refuses_it_before_the_fit() {
    let dir = tempfile::tempdir().unwrap();
    // At scale 1e-154 the Gaussian curvature is about 1e308: OBJ, OFF and STL store none, so
    // they are written (this failed with "property gaussian … not finite" after the fit).
    for ext in ["obj", "off", "stl"] {
        let out = dir.path().join(format!("tiny.{ext}"));
        fit(octahedron(1e-154), &out, UpAxis::Z).unwrap_or_else(|e| panic!("{ext}: {e}"));
        assert!(std::fs::metadata(&out).unwrap().len() > 0, "{ext}");
    }
    // PLY and glTF store it as 32-bit floats: refused before any work, saying why.
    for ext in ["ply", "glb"] {
        let out = dir.path().join(format!("tiny.{ext}"));
        let t = Instant::now();
        let e = fit(octahedron(1e-154), &out, UpAxis::Z).expect_err(ext);
        assert!(
            t.elapsed().as_secs_f64() < REFUSAL_SECONDS,
            "{ext}: refused late"
        );
        let text = fitjob::chain(e.as_ref());
        assert!(
            text.contains("e-154") && text.contains(".obj"),
            "{ext}: {text}"
        );
        assert!(!out.exists(), "{ext}: nothing written");
    }
}

#[test]
fn the_written_curvature_is_positive_on_a_sphere_with_outward_normals() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = || InputOptions {
        source: Source::DataSet {
            name: "sphere".into(),
            resolution: None,
        },
        ..InputOptions::default()
    };
    for ext in ["ply", "glb"] {
        let out = dir.path().join(format!("sphere.{ext}"));
        fit(sphere(), &out, UpAxis::Z).unwrap();
        let back = meshio::read_file(&out).unwrap();
        let c = back.curvature.expect("curvature written");
        assert!(c.mean.iter().all(|&h| h > 0.0), "{ext}: H > 0 everywhere");
        assert!(
            c.gaussian.iter().all(|&k| k > 0.0),
            "{ext}: K > 0 everywhere"
        );
        // Outward normals: n · p > 0 at every vertex of the unit sphere.
        let normals = back.normals.expect("normals");
        assert!(back
            .positions
            .iter()
            .zip(&normals)
            .all(|(p, n)| p.coords.dot(n) > 0.0));
    }
    // An OBJ gets no curvature to store, and none appears.
    let out = dir.path().join("sphere.obj");
    fit(sphere(), &out, UpAxis::Z).unwrap();
    assert!(meshio::read_file(&out).unwrap().curvature.is_none());
    assert!(!meshio::obj::Obj.writes_curvature());
}

#[test]
fn up_reaches_the_gltf_writer() {
    let dir = tempfile::tempdir().unwrap();
    let (z, y) = (dir.path().join("z.glb"), dir.path().join("y.glb"));
    fit(octahedron(1.0), &z, UpAxis::Z).unwrap();
    fit(octahedron(1.0), &y, UpAxis::Y).unwrap();
    let extras = |p: &std::path::Path| {
        let bytes = std::fs::read(p).unwrap();
        let n = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let doc: serde_json::Value = serde_json::from_slice(&bytes[20..20 + n]).unwrap();
        doc["asset"]["extras"]["data_up_axis"].clone()
    };
    assert_eq!(extras(&z), "z");
    assert_eq!(extras(&y), "y");
    // Both read back as the same mesh: the reader undoes what the writer did.
    let (a, b) = (
        meshio::read_file(&z).unwrap(),
        meshio::read_file(&y).unwrap(),
    );
    for (p, q) in a.positions.iter().zip(&b.positions) {
        assert!((p - q).norm() < F32_ROUNDING, "{p} vs {q}");
    }
}

/// The principal frame written with a tessellation of the sphere data set: unit directions in
/// the tangent plane, orthogonal, `d2 = n × d1`, and `k1 ≥ k2` with `k1 k2 = K` (to the
/// `f32` the file stores). The sphere's fit is not exactly umbilic, so the directions are the
/// patches' own (the estimate of `estimate::principal_frame` on each vertex's shape tensor).
#[test]
fn a_ply_tessellation_carries_the_principal_frame() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sphere.ply");
    fitjob::run(
        FitOptions {
            input: InputOptions {
                source: Source::DataSet {
                    name: "sphere".into(),
                    resolution: None,
                },
                ..InputOptions::default()
            },
            mesh_out: Some(out.clone()),
            ..FitOptions::default()
        },
        &mut |_| {},
    )
    .unwrap();
    let raw = meshio::read_file(&out).unwrap();
    let c = raw.curvature.expect("curvature");
    let ds = c.directions.as_ref().expect("principal directions");
    let ns = raw.normals.expect("normals");
    assert_eq!(ds.len(), ns.len());
    for (i, ([d1, d2], n)) in ds.iter().zip(&ns).enumerate() {
        let n = n.normalize();
        assert!((d1.norm() - 1.0).abs() < F32_ROUNDING, "vertex {i}");
        assert!(
            d1.dot(&n).abs() < F32_ROUNDING && d1.dot(d2).abs() < F32_ROUNDING,
            "vertex {i}"
        );
        assert!((n.cross(d1) - d2).norm() < 4.0 * F32_ROUNDING, "vertex {i}");
        let [k1, k2] = c.principal(i).unwrap();
        assert!(k1 >= k2 && k1 > 0.0, "vertex {i}: H > 0 on the sphere");
    }
}
