//! The headline numbers of README.md and docs/results.md, locked: if a change moves them, this
//! test says so and the documents (and `results/`) must be updated with it.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{dbhs, method_by_name, BoundaryProblem, MethodOptions};
use surface::analytic::{torus_grid_edges, torus_point};
use surface::{compare_with_truth, fit, measure_g1, tessellate, InteriorParameters};

/// The documents print two or three significant digits: agreement to half a unit in the last one.
fn close(got: f64, printed: f64, digits: i32) -> bool {
    let unit = 10f64.powi(printed.abs().log10().floor() as i32 - digits + 1);
    (got - printed).abs() <= 0.5 * unit + 1e-12
}

#[test]
fn dbhs_solution_counts_on_the_16x8_ring() {
    // "224 of 384 edges have three positive solutions, 128 have one, and the 32 edges along the
    // top and bottom circles of the tube have none"; "α = (1.76, 0.028)".
    let mut counts = [0usize; 4];
    let mut shortest = f64::INFINITY;
    for ((ua, va), (ub, vb)) in torus_grid_edges(16, 8) {
        let a = torus_point(ua, va, 1.0, 0.4);
        let b = torus_point(ub, vb, 1.0, 0.4);
        let p = BoundaryProblem::new((0, 1), &a, &b).unwrap();
        let sols = dbhs::solve(&p.unit);
        counts[sols.len().min(3)] += 1;
        if let Some(s) = curves::DbhsPick::Closest
            .pick(&sols)
            .and_then(|i| sols.get(i))
        {
            shortest = shortest.min(s.alpha[0].min(s.alpha[1]));
        }
    }
    assert_eq!(counts, [32, 128, 0, 224]);
    assert!(close(shortest, 0.028, 2), "{shortest}");
}

#[test]
fn the_ring_table() {
    // | chord | 1.7e-3 | 0.96 | 0.97 | 0.31 |, | dBHS | 8.1e-2 | 37.0 | 609 | 106 |,
    // | optimized | 1.6e-3 | 0.72 | 0.54 | 0.24 | (position max, normal RMS °, K RMS, H RMS).
    let data = surface::dataset_by_name("ring", None).unwrap();
    let rows = [
        ("chord", [1.7e-3, 0.96, 0.97, 0.31]),
        ("dbhs", [8.1e-2, 37.0, 609.0, 106.0]),
        ("optimized", [1.6e-3, 0.72, 0.54, 0.24]),
    ];
    for (name, printed) in rows {
        let m = method_by_name(name, &MethodOptions::default()).unwrap();
        let f = fit(&data.mesh, m.as_ref(), &|_| InteriorParameters::default()).unwrap();
        assert!(measure_g1(&data.mesh, &f, 9).max_angle() < 1e-9);
        let t = tessellate(&f.bezier_patches(), 4).unwrap();
        let e = compare_with_truth(&t, data.surface.as_ref());
        let got = [
            e.position_max,
            e.normal_rms_degrees,
            e.gaussian_rms,
            e.mean_rms,
        ];
        for (g, p) in got.iter().zip(printed) {
            let digits = if p >= 100.0 { 3 } else { 2 };
            assert!(
                close(*g, p, digits),
                "{name}: {got:?} against the README's {printed:?}"
            );
        }
    }
}
