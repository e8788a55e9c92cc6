//! The workspace's binary patch file (`.bzp`) in the pipeline: `fit` writes it (the bytes
//! `surface::patch_io` writes for `experiments fit --out FILE.bzp`), every filter reads it as
//! the `BezierTriangle` records of its patches, and a damaged or hostile file is an error
//! naming what is wrong, not a crash or an allocation.

use crate::support::{ok, testbed};

const OCTA: &[u8] = include_bytes!("../../../data/octa.m");

#[test]
fn fit_writes_the_binary_patch_file_of_the_library() {
    let bzp = ok(&["fit", "--format", "bzp"], OCTA);
    assert!(bzp.starts_with(surface::patch_io::BINARY_MAGIC));
    // The library reads it back: 8 faces × 3 quartic patches of 15 points.
    let (degree, per_face, points) = surface::patch_io::read_binary(&bzp).expect("reads back");
    assert_eq!((degree, per_face, points.len()), (4, 3, 8 * 3 * 15));
    // Its points are the JSON records' (the same fit, the same patch record).
    let json = ok(&["fit"], OCTA);
    let records: Vec<serde_json::Value> = json
        .split(|&c| c == b'\n')
        .filter(|l| !l.is_empty())
        .map(|l| serde_json::from_slice(l).expect("json"))
        .collect();
    assert_eq!(records.len(), 24);
    for (r, net) in records.iter().zip(points.chunks(15)) {
        let pts = r["points"].as_array().expect("points");
        for (p, q) in pts.iter().zip(net) {
            let c: Vec<f64> = p
                .as_array()
                .expect("xyz")
                .iter()
                .map(|x| x.as_f64().expect("number"))
                .collect();
            assert_eq!(c, vec![q.x, q.y, q.z], "bit for bit");
        }
    }
}

#[test]
fn every_filter_reads_the_binary_patch_file_as_its_patch_records() {
    let bzp = ok(&["fit", "--format", "bzp"], OCTA);
    let from_bzp = ok(&["tess", "-s", "3", "--kg", "--format", "json"], &bzp);
    let from_json = ok(&["tess", "-s", "3", "--kg"], &ok(&["fit"], OCTA));
    // The JSON patches also carry the scheme's name, which the binary file does not hold.
    let from_json =
        String::from_utf8_lossy(&from_json).replace(",\"scheme\":\"shirman-sequin\"", "");
    assert_eq!(String::from_utf8_lossy(&from_bzp), from_json);
    // With no --format, the filters after it write the stream binary form.
    let out = ok(&["tess", "-s", "1"], &bzp);
    assert!(out.starts_with(b"TBIN1\n"));
    let g1 = testbed(&["g1", "--strict"], &bzp);
    assert!(
        g1.status.success(),
        "{}",
        String::from_utf8_lossy(&g1.stderr)
    );
}

#[test]
fn damaged_or_hostile_patch_files_are_errors_that_say_where() {
    let bzp = ok(&["fit", "--format", "bzp"], OCTA);
    // Cut inside the last patch.
    let cut = &bzp[..bzp.len() - 100];
    let out = testbed(&["tess"], cut);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("ends inside patch 23 of 24"), "{err}");
    // A header promising 10¹² faces: an error at the first missing patch, no allocation.
    let hostile = b"BEZPATCH1\n{\"degree\":4,\"patches_per_face\":3,\"faces\":1000000000000,\"points_per_patch\":15,\"scalar\":\"f64le\"}\n";
    let out = testbed(&["tess"], hostile);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("ends inside patch 0"));
    // A header with absurd points a patch, or no end of line.
    let huge = b"BEZPATCH1\n{\"degree\":4,\"patches_per_face\":1,\"faces\":1,\"points_per_patch\":1000000000,\"form\":\"x\",\"scalar\":\"f64le\"}\n";
    let out = testbed(&["tess"], huge);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("points a patch"));
    let endless = [b"BEZPATCH1\n".as_slice(), &[b'{'; 10_000]].concat();
    let out = testbed(&["tess"], &endless);
    assert_eq!(out.status.code(), Some(1));
    // Only fit writes it.
    let out = testbed(&["tess", "--format", "bzp"], &bzp);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("only `fit` writes it"));
}
