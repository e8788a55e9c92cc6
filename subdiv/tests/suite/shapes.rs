//! The seeded shapes are pinned bit for bit: the benchmark's irregular mesh and the tests'
//! small irregular meshes come from `irregular` and `irregular_small`, whose jitter and splits
//! are draws of the workbench's one generator (`rng::SplitMix64`); a change of the generator
//! or of the order of its draws shows here first. The hashes were taken before the generator
//! moved to the `rng` crate.

use std::hash::Hasher as _;

use subdiv::shapes::{icosphere, irregular, irregular_small, torus_quads};
use subdiv::PolyMesh;

/// Every bit of a mesh (positions, faces, creases), hashed with the workbench's one hasher
/// (`meshio::hash::FxHasher`, seed 0).
fn bits(m: &PolyMesh) -> u64 {
    let mut h = meshio::hash::FxHasher::default();
    h.write_usize(m.num_vertices());
    for p in m.positions() {
        p.iter().for_each(|c| h.write_u64(c.to_bits()));
    }
    for f in m.faces() {
        h.write_usize(f.len());
        f.iter().for_each(|&v| h.write_u64(u64::from(v)));
    }
    for [a, b] in m.creases() {
        h.write_usize(a);
        h.write_usize(b);
    }
    h.finish()
}

#[test]
fn seeded_shapes_are_pinned_bit_for_bit() {
    let mut all: Vec<(String, PolyMesh)> = (0..4)
        .map(|s| (format!("irregular_small({s})"), irregular_small(s)))
        .collect();
    all.push((
        "irregular(icosphere(2), 0.3, 0.2, 0.1, 7)".into(),
        irregular(&icosphere(2), 0.3, 0.2, 0.1, 7),
    ));
    all.push((
        "irregular(torus_quads(8, 6), 0.5, 0.1, 0.2, 3)".into(),
        irregular(&torus_quads(8, 6, 1.0, 0.4), 0.5, 0.1, 0.2, 3),
    ));
    for (name, m) in subdiv::bench_meshes::bench_meshes() {
        all.push((format!("bench {name}"), m));
    }
    let got: Vec<(String, u64)> = all.iter().map(|(n, m)| (n.clone(), bits(m))).collect();
    let want: Vec<(String, u64)> = PINNED.iter().map(|(n, h)| (n.to_string(), *h)).collect();
    assert_eq!(got, want);
}

/// `(shape, bits)` of [`seeded_shapes_are_pinned_bit_for_bit`].
const PINNED: &[(&str, u64)] = &[
    ("irregular_small(0)", 0x1c0baeb7d05ffe4a),
    ("irregular_small(1)", 0x40e22598586c9f81),
    ("irregular_small(2)", 0x5eb40cd6040fd2a6),
    ("irregular_small(3)", 0xffc201ea698dc1a8),
    (
        "irregular(icosphere(2), 0.3, 0.2, 0.1, 7)",
        0xd09cb23f6dccfa30,
    ),
    (
        "irregular(torus_quads(8, 6), 0.5, 0.1, 0.2, 3)",
        0x047bb75351617ffd,
    ),
    ("bench torus-tri", 0xf1603792785a1a0b),
    ("bench irregular-tri", 0x98ac65d07acedb38),
    ("bench torus-quad", 0xddc5f49fb53a5d07),
];
