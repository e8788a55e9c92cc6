//! `tess --kp`: the principal curvatures and directions of every vertex, from the patches'
//! exact second derivatives, consistent with `kg` and `km` in the pipeline's sign, the same in
//! `Triangle` and `TriangleMesh` records, scaled like `km` when the patches are.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use serde_json::Value;

use crate::support::{json_records, ok};

/// Rounding of the closed forms relating the four quantities (products and sums of a few
/// terms of order one).
const ROUND: f64 = 1e-12;

fn octa() -> Vec<u8> {
    std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m")).unwrap()
}

fn vec3(v: &Value) -> [f64; 3] {
    let a = v.as_array().unwrap();
    [0, 1, 2].map(|i| a[i].as_f64().unwrap())
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[test]
fn principal_frames_agree_with_kg_km_and_the_normal() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let out = ok(&["tess", "-s", "3", "--kg", "--km", "--kp"], &patches);
    let records = json_records(&out);
    assert_eq!(records.len(), 24 * 9);
    for r in &records {
        for k in ["vertex1", "vertex2", "vertex3"] {
            let v = &r[k];
            let (k1, k2) = (v["k1"].as_f64().unwrap(), v["k2"].as_f64().unwrap());
            let (kg, km) = (v["kg"].as_f64().unwrap(), v["km"].as_f64().unwrap());
            let (n, d1, d2) = (vec3(&v["norm"]), vec3(&v["d1"]), vec3(&v["d2"]));
            assert!(k1 >= k2, "{v}");
            assert!((k1 * k2 - kg).abs() < ROUND * (1.0 + kg.abs()), "{v}");
            assert!(
                (0.5 * (k1 + k2) - km).abs() < ROUND * (1.0 + km.abs()),
                "{v}"
            );
            assert!(
                (dot(d1, d1) - 1.0).abs() < ROUND && dot(d1, n).abs() < ROUND,
                "{v}"
            );
            let c = cross(n, d1);
            assert!(
                (0..3).all(|i| (c[i] - d2[i]).abs() < ROUND),
                "d2 = n × d1: {v}"
            );
        }
    }
    // The octahedron's fit bends away from its outward normals everywhere: both principal
    // curvatures are negative in the pipeline's sign (that of km: −1 on the unit sphere).
    let first = &records[0]["vertex1"];
    assert!(first["k1"].as_f64().unwrap() < 0.0, "{first}");
}

#[test]
fn mesh_records_carry_the_same_frames_and_scale_like_km() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let mesh = json_records(&ok(&["tess", "-s", "2", "--kp", "--mesh"], &patches));
    let tris = json_records(&ok(&["tess", "-s", "2", "--kp"], &patches));
    // The first patch's first triangle, vertex by vertex, in both forms.
    let m = &mesh[0];
    let t = &m["triangles"][0];
    for (slot, k) in ["vertex1", "vertex2", "vertex3"].iter().enumerate() {
        let i = t[slot].as_u64().unwrap() as usize;
        assert_eq!(m["k1"][i], tris[0][k]["k1"]);
        assert_eq!(m["d2"][i], tris[0][k]["d2"]);
    }
    // Without --kp, nothing of it.
    let plain = json_records(&ok(&["tess", "-s", "2"], &patches));
    assert!(plain[0]["vertex1"].get("k1").is_none());
}
