//! Mutated and truncated files of every format never make a reader panic.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use std::path::Path;

use meshio::{format_by_name, read_bytes, WriteOptions, FORMATS};
use proptest::prelude::*;

/// Valid files of every format and variant.
fn seeds() -> Vec<Vec<u8>> {
    let cube = common::cube();
    let mut out = Vec::new();
    for name in ["ply", "obj", "stl", "off", "testbed"] {
        let f = format_by_name(name).expect("format");
        for opts in [
            WriteOptions::new(),
            WriteOptions::new().ascii(),
            WriteOptions::new().double_precision(),
        ] {
            out.push(f.write(&cube, &opts).expect("write"));
        }
    }
    out.push(include_bytes!("../../../data/octa.m").to_vec());
    out.push(b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar uint vertex_indices\nelement edge 1\nproperty list uchar int e\nend_header\n\0\0\0\0\0\0\0\0\0\0\0\0\x3f\x80\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x3f\x80\0\0\0\0\0\0\x03\0\0\0\0\0\0\0\x01\0\0\0\x02\x02\0\0\0\0\0\0\0\x01".to_vec());
    out.push(
        b"v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 -2//1 3/1\nf 1 2 3\ng x\n"
            .to_vec(),
    );
    // Crease edges: a PLY edge element (every encoding), and an OBJ with normals per face
    // corner and smoothing groups.
    let mut creased = common::cube();
    creased.crease_edges = vec![[0, 1], [0, 2], [1, 3], [2, 3], [4, 5]];
    let ply = format_by_name("ply").expect("ply");
    for opts in [
        WriteOptions::new(),
        WriteOptions::new().ascii(),
        WriteOptions::new().double_precision(),
    ] {
        out.push(ply.write(&creased, &opts).expect("write"));
    }
    out.push(
        b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nvn 0 0 1\nvn 0 0.6 0.8\ns 1\n\
          f 1//1 2//1 3//1 4//1\ns off\nf 2//2 5//2 3//2\ns 2\nf 3 5 4\n"
            .to_vec(),
    );
    out.push(b"CNOFF 3 1 0\n0 0 0 0 0 1 255 0 0 255\n1 0 0 0 0 1 0.5 0.5 0.5\n0 1 0 0 0 1 0 0 0\n3 0 1 2 1 0 0\n".to_vec());
    out
}

fn mutate(mut bytes: Vec<u8>, ops: &[(u8, usize, u8)]) -> Vec<u8> {
    for &(op, at, value) in ops {
        let len = bytes.len();
        let at = if len == 0 { 0 } else { at % (len + 1) };
        match op % 4 {
            0 => {
                if let Some(b) = bytes.get_mut(at) {
                    *b ^= value | 1;
                }
            }
            1 => bytes.truncate(at),
            2 => bytes.insert(at.min(len), value),
            _ => {
                // Digits and separators: mutations that keep text files parsing further.
                let chars = b"0123456789-.e \n/[],;";
                if let Some(b) = bytes.get_mut(at) {
                    *b = chars[value as usize % chars.len()];
                }
            }
        }
    }
    bytes
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, ..ProptestConfig::default() })]

    #[test]
    fn readers_never_panic(
        seed in any::<prop::sample::Index>(),
        ops in prop::collection::vec((any::<u8>(), any::<usize>(), any::<u8>()), 1..6),
    ) {
        let seeds = seeds();
        let bytes = mutate(seed.get(&seeds).clone(), &ops);
        for f in FORMATS {
            let _ = f.read(&bytes);
            let _ = f.sniff(&bytes);
        }
        let _ = read_bytes(Path::new("fuzzed.bin"), &bytes);
    }
}
