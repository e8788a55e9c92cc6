mod support;
use support::*;

#[test]
fn table() {
    for est in estimate::ESTIMATORS {
        for l in [2, 3, 4, 5] {
            let d = surface::datasets::sphere(l).unwrap();
            let e = run(*est, &d.mesh, None);
            let r = errors(&e, &d.mesh);
            println!(
                "{} sphere{} {:.3e} {:.3e} {:.3e} fb={}",
                est.name(),
                l,
                r.normal_deg,
                r.k,
                r.h,
                e.fallbacks.len()
            );
        }
        for n in [16, 32, 64, 128] {
            let d = surface::datasets::ring(n, n / 2).unwrap();
            let e = run(*est, &d.mesh, None);
            let r = errors(&e, &d.mesh);
            println!(
                "{} ring{} {:.3e} {:.3e} {:.3e} fb={}",
                est.name(),
                n,
                r.normal_deg,
                r.k,
                r.h,
                e.fallbacks.len()
            );
        }
    }
}

#[test]
fn max_on_jittered_torus() {
    let nu = 32;
    let nv = 16;
    let d = surface::datasets::ring(nu, nv).unwrap();
    let mut m = d.mesh.clone();
    for (k, v) in m.vertices_mut().iter_mut().enumerate() {
        let (i, j) = (k / nv, k % nv);
        let u = std::f64::consts::TAU * (i as f64 + 0.3 * ((k * 7919 % 13) as f64 / 13.0 - 0.5))
            / nu as f64;
        let w = std::f64::consts::TAU * (j as f64 + 0.3 * ((k * 104729 % 17) as f64 / 17.0 - 0.5))
            / nv as f64;
        v.data = curves::analytic::torus_point(u, w, 1.0, 0.4);
    }
    for wt in [
        estimate::NormalWeighting::Max,
        estimate::NormalWeighting::Angle,
        estimate::NormalWeighting::Area,
    ] {
        let n = estimate::vertex_normals(&m, wt);
        let e: f64 = n
            .normals
            .iter()
            .zip(m.vertices())
            .map(|(a, v)| angle_deg(a, &v.data.n).powi(2))
            .sum::<f64>()
            / m.num_vertices() as f64;
        println!("{wt:?} jittered rms deg {}", e.sqrt());
    }
    for est in estimate::ESTIMATORS {
        let e = run(*est, &m, None);
        let r = errors(&e, &m);
        println!(
            "{} jittered ring32 {:.3e} {:.3e} {:.3e}",
            est.name(),
            r.normal_deg,
            r.k,
            r.h
        );
    }
}
