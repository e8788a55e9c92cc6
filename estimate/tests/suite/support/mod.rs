//! Shared support of the estimator tests: error measures against exact vertex data, test
//! meshes (quadric height fields, fans, open patches, anisotropic cylinders, broken meshes) and
//! rigid motions.

#![allow(dead_code)] // each test file uses part of the support
#![allow(clippy::expect_used)] // test fixtures built from fixed valid data

use estimate::{principal_curvatures, Estimate, Estimator};
use mesh::{Mesh, Vertex};
use nalgebra::{Matrix3, Point3, Rotation3, Vector3};

/// Normals that are exact by symmetry or construction (a flat triangle's, a symmetric fan's)
/// come out to rounding.
pub const SYMMETRIC_NORMAL: f64 = 1e-12;

/// Smallest accepted order where about 2 is observed (the margin absorbs pre-asymptotic
/// resolutions).
pub const ORDER_2: f64 = 1.8;

/// Smallest accepted order where about 4 is observed.
pub const ORDER_4: f64 = 3.4;

/// Root-mean-square errors of an estimate against the exact data carried by the mesh.
#[derive(Clone, Copy, Debug)]
pub struct Errors {
    /// Normal angle error, degrees (RMS).
    pub normal_deg: f64,
    /// Gaussian-curvature error (RMS).
    pub k: f64,
    /// Mean-curvature error (RMS).
    pub h: f64,
}

/// Angle between two unit vectors in degrees (robust near 0).
pub fn angle_deg(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b)).to_degrees()
}

/// Gaussian and mean curvature of a tensor with its normal.
pub fn k_h(s: &Matrix3<f64>, n: &Vector3<f64>) -> (f64, f64) {
    let [a, b] = principal_curvatures(s, n);
    (a * b, 0.5 * (a + b))
}

/// RMS errors over the vertices selected by `keep`.
pub fn errors_where(est: &Estimate, mesh: &Mesh, keep: impl Fn(usize) -> bool) -> Errors {
    let (mut sn, mut sk, mut sh, mut count) = (0.0, 0.0, 0.0, 0usize);
    for (v, vert) in mesh.vertices().iter().enumerate() {
        if !keep(v) {
            continue;
        }
        let d = angle_deg(&est.normals[v], &vert.data.n);
        let (k, h) = k_h(&est.shapes[v], &est.normals[v]);
        let (k0, h0) = k_h(&vert.data.shape, &vert.data.n);
        sn += d * d;
        sk += (k - k0).powi(2);
        sh += (h - h0).powi(2);
        count += 1;
    }
    let c = count.max(1) as f64;
    Errors {
        normal_deg: (sn / c).sqrt(),
        k: (sk / c).sqrt(),
        h: (sh / c).sqrt(),
    }
}

/// RMS errors over all vertices.
pub fn errors(est: &Estimate, mesh: &Mesh) -> Errors {
    errors_where(est, mesh, |_| true)
}

/// Observed order of convergence between two errors at spacings in ratio `refine` (2 for one
/// halving).
pub fn order(coarse: f64, fine: f64, refine: f64) -> f64 {
    (coarse / fine).ln() / refine.ln()
}

/// Every normal unit and finite, every tensor finite and symmetric with `S n ≈ 0`.
pub fn assert_sane(est: &Estimate, nv: usize) {
    /// Unit length and `S n = 0` hold to rounding after normalization and projection.
    const ROUNDING: f64 = 1e-12;
    assert_eq!(est.normals.len(), nv);
    assert_eq!(est.shapes.len(), nv);
    for (v, (n, s)) in est.normals.iter().zip(&est.shapes).enumerate() {
        assert!(n.iter().all(|c| c.is_finite()), "vertex {v}: normal {n:?}");
        assert!(
            (n.norm() - 1.0).abs() < ROUNDING,
            "vertex {v}: |n| = {}",
            n.norm()
        );
        assert!(s.iter().all(|c| c.is_finite()), "vertex {v}: S {s:?}");
        let scale = s.norm().max(1.0);
        assert!(
            (s - s.transpose()).norm() < ROUNDING * scale,
            "vertex {v}: S not symmetric"
        );
        assert!(
            (s * n).norm() < ROUNDING * scale,
            "vertex {v}: S n = {:?}",
            s * n
        );
    }
}

/// A vertex whose normal is a placeholder (the estimators must not read it).
pub fn vx(p: Point3<f64>) -> Vertex {
    Vertex::without_curvature(p, Vector3::z())
}

/// The height `z = ½(a x² + 2b xy + c y²)`.
pub fn quad_height(a: f64, b: f64, c: f64, x: f64, y: f64) -> f64 {
    0.5 * (a * x * x + 2.0 * b * x * y + c * y * y)
}

/// A `(2m+1)²` grid of spacing `h` over `[-mh, mh]²` lifted to `z = f(x, y)`, quads split along
/// the same diagonal (point-symmetric about the centre vertex); returns the mesh and the index
/// of the centre vertex.
pub fn height_grid(m: usize, h: f64, f: impl Fn(f64, f64) -> f64) -> (Mesh, usize) {
    let n = 2 * m + 1;
    let mut verts = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let x = (i as f64 - m as f64) * h;
            let y = (j as f64 - m as f64) * h;
            verts.push(vx(Point3::new(x, y, f(x, y))));
        }
    }
    let idx = |i: usize, j: usize| j * n + i;
    let mut faces = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            faces.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            faces.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    (Mesh::new(verts, faces).expect("valid grid"), idx(m, m))
}

/// A fan of `k` triangles around a centre on the unit sphere's north pole, its rim on the
/// sphere at polar angle `theta`; returns the mesh (centre is vertex 0).
pub fn sphere_fan(k: usize, theta: f64) -> Mesh {
    let mut verts = vec![vx(Point3::new(0.0, 0.0, 1.0))];
    for i in 0..k {
        let phi = std::f64::consts::TAU * i as f64 / k as f64;
        verts.push(vx(Point3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        )));
    }
    let faces = (0..k).map(|i| [0, 1 + i, 1 + (i + 1) % k]).collect();
    Mesh::new(verts, faces).expect("valid fan")
}

/// The faces of a data set's mesh kept by `keep(face centroid)`, vertices renumbered, exact
/// vertex data kept.
pub fn sub_mesh(mesh: &Mesh, keep: impl Fn(&Point3<f64>) -> bool) -> Mesh {
    let verts = mesh.vertices();
    let mut map = vec![usize::MAX; verts.len()];
    let mut out_verts = Vec::new();
    let mut faces = Vec::new();
    for f in mesh.faces() {
        let c = Point3::from(
            f.iter()
                .map(|&i| verts[i].data.p.coords)
                .sum::<Vector3<f64>>()
                / 3.0,
        );
        if !keep(&c) {
            continue;
        }
        faces.push(f.map(|i| {
            if map[i] == usize::MAX {
                map[i] = out_verts.len();
                out_verts.push(verts[i].clone());
            }
            map[i]
        }));
    }
    Mesh::new(out_verts, faces).expect("a sub-mesh of a valid mesh")
}

/// A cylinder of radius `r` about the z axis: `nu` steps around, `nz` rows of height `dz`
/// (open at both ends), exact normals and tensors `−(1/r) e_θ e_θᵀ`.
pub fn cylinder(r: f64, nu: usize, nz: usize, dz: f64) -> Mesh {
    let mut verts = Vec::new();
    for j in 0..=nz {
        for i in 0..nu {
            let t = std::f64::consts::TAU * i as f64 / nu as f64;
            let n = Vector3::new(t.cos(), t.sin(), 0.0);
            let e = Vector3::new(-t.sin(), t.cos(), 0.0);
            let p = Point3::new(r * t.cos(), r * t.sin(), (j as f64 - nz as f64 / 2.0) * dz);
            verts.push(Vertex::new(mesh::VertexData::new(
                p,
                n,
                -(e * e.transpose()) / r,
            )));
        }
    }
    let idx = |i: usize, j: usize| j * nu + i % nu;
    let mut faces = Vec::new();
    for j in 0..nz {
        for i in 0..nu {
            faces.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            faces.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    Mesh::new(verts, faces).expect("valid cylinder")
}

/// The mesh moved by `x ↦ s R x + t` (exact data transformed too: `n ↦ R n`,
/// `S ↦ R S Rᵀ / s`).
pub fn transformed(mesh: &Mesh, r: &Rotation3<f64>, t: &Vector3<f64>, s: f64) -> Mesh {
    let mut out = mesh.clone();
    for v in out.vertices_mut() {
        v.data.p = Point3::from(r * v.data.p.coords * s + t);
        v.data.n = r * v.data.n;
        v.data.shape = r.matrix() * v.data.shape * r.matrix().transpose() / s;
    }
    out
}

/// The exact normals of a mesh (to pass as `given`).
pub fn exact_normals(mesh: &Mesh) -> Vec<Vector3<f64>> {
    mesh.vertices().iter().map(|v| v.data.n).collect()
}

/// A mesh with every kind of defect a repaired file may bring: a zero-area face (made after
/// construction by moving a vertex onto an edge), a needle, an isolated vertex, a lone single
/// triangle (second component), and a valence-3 vertex.
pub fn broken_mesh() -> (Mesh, BrokenIndices) {
    let p = |x: f64, y: f64, z: f64| vx(Point3::new(x, y, z));
    let mut verts = vec![
        // A 3×3 grid patch, slightly curved.
        p(0.0, 0.0, 0.0),
        p(1.0, 0.0, 0.1),
        p(2.0, 0.0, 0.4),
        p(0.0, 1.0, 0.1),
        p(1.0, 1.0, 0.2),
        p(2.0, 1.0, 0.5),
        p(0.0, 2.0, 0.4),
        p(1.0, 2.0, 0.5),
        p(2.0, 2.0, 0.8),
        // 9: needle tip far along +x from 2 and 5.
        p(40.0, 0.5, 0.45),
        // 10: isolated.
        p(5.0, 5.0, 5.0),
        // 11..13: a lone triangle.
        p(10.0, 0.0, 0.0),
        p(11.0, 0.0, 0.0),
        p(10.0, 1.0, 0.0),
        // 14..16: a separate valence-3 tetrahedron-corner fan (an open 3-face fan).
        p(20.0, 0.0, 1.0),
        p(21.0, 0.0, 0.0),
        p(19.5, 0.87, 0.0),
        p(19.5, -0.87, 0.0),
    ];
    let mut faces = vec![];
    let idx = |i: usize, j: usize| j * 3 + i;
    for j in 0..2 {
        for i in 0..2 {
            faces.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            faces.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    faces.push([2, 9, 5]);
    faces.push([11, 12, 13]);
    faces.push([14, 15, 16]);
    faces.push([14, 16, 17]);
    faces.push([14, 17, 15]);
    let _ = &mut verts;
    let mut mesh = Mesh::new(verts, faces).expect("valid before the defect");
    // Make face [0, 1, 4] zero-area: move vertex 1 onto the segment 0–4... keep vertex 1 shared
    // with face [1, 2, 5]; the face [0,1,4] becomes collinear.
    mesh.vertices_mut()[1].data.p = Point3::new(0.5, 0.5, 0.1);
    (
        mesh,
        BrokenIndices {
            isolated: 10,
            needle_tip: 9,
            lone: [11, 12, 13],
            valence3: 14,
        },
    )
}

/// Notable vertices of [`broken_mesh`].
#[derive(Clone, Copy, Debug)]
pub struct BrokenIndices {
    /// The vertex with no faces.
    pub isolated: usize,
    /// The far end of the needle.
    pub needle_tip: usize,
    /// The single triangle's vertices.
    pub lone: [usize; 3],
    /// The centre of the valence-3 fan.
    pub valence3: usize,
}

/// A mesh whose every face has zero area: a fan flattened onto a line (after construction).
pub fn all_degenerate_fan() -> Mesh {
    let mut m = sphere_fan(5, 0.3);
    for (i, v) in m.vertices_mut().iter_mut().enumerate() {
        v.data.p = Point3::new(i as f64, 0.0, 0.0);
    }
    m
}

/// Runs `est` and checks sanity; returns the estimate.
pub fn run(est: &dyn Estimator, mesh: &Mesh, given: Option<&[Vector3<f64>]>) -> Estimate {
    let e = est.estimate(mesh, given);
    assert_sane(&e, mesh.num_vertices());
    e
}

/// Errors of `est` on the sphere at levels 3, 4, 5 (edge length halves each level) and the ring
/// at 32×16, 64×32, 128×64, in that order.
pub fn convergence(est: &dyn Estimator) -> (Vec<Errors>, Vec<Errors>) {
    let sphere = [3, 4, 5]
        .iter()
        .map(|&l| {
            let d = mesh::datasets::sphere(l).expect("valid");
            errors(&run(est, &d.mesh, None), &d.mesh)
        })
        .collect();
    let ring = [32, 64, 128]
        .iter()
        .map(|&n| {
            let d = mesh::datasets::ring(n, n / 2).expect("valid");
            errors(&run(est, &d.mesh, None), &d.mesh)
        })
        .collect();
    (sphere, ring)
}

/// Asserts that each error decreases with every halving at least at `min_order`; `what`
/// names the quantity.
pub fn assert_order(errs: &[f64], min_order: f64, what: &str) {
    for w in errs.windows(2) {
        let o = order(w[0], w[1], 2.0);
        assert!(
            o >= min_order,
            "{what}: errors {errs:?}, order {o} < {min_order}"
        );
    }
}

/// The tensor `[[a, b, 0], [b, c, 0], [0, 0, 0]]` rotated by `r`.
pub fn quad_tensor(a: f64, b: f64, c: f64, r: &Rotation3<f64>) -> Matrix3<f64> {
    let s = Matrix3::new(a, b, 0.0, b, c, 0.0, 0.0, 0.0, 0.0);
    r.matrix() * s * r.matrix().transpose()
}

/// Checks that `est` reproduces `z = ½(a x² + 2b xy + c y²)` exactly at the centre of a
/// point-symmetric grid (where the angle-weighted normal is exactly `+z`), untilted and moved
/// by a rotation and translation, with and without the exact normal given.
pub fn assert_reproduces_quadric(est: &dyn Estimator) {
    /// An exact fit of well-conditioned small systems: rounding only.
    const EXACT: f64 = 1e-10;
    let (a, b, c) = (1.3, -0.4, 0.7);
    let (mesh, centre) = height_grid(4, 0.1, |x, y| quad_height(a, b, c, x, y));
    let tilts = [
        (Rotation3::identity(), Vector3::zeros()),
        (
            Rotation3::from_euler_angles(0.4, -0.7, 1.1),
            Vector3::new(3.0, -2.0, 5.0),
        ),
    ];
    for (r, t) in tilts {
        let moved = transformed(&mesh, &r, &t, 1.0);
        let n = r * Vector3::z();
        let mut given = vec![Vector3::z(); moved.num_vertices()];
        given[centre] = n;
        for g in [None, Some(given.as_slice())] {
            let e = run(est, &moved, g);
            let want = quad_tensor(a, b, c, &r);
            assert!(
                (e.normals[centre] - n).norm() < EXACT,
                "{}: normal {:?}",
                est.name(),
                e.normals[centre]
            );
            assert!(
                (e.shapes[centre] - want).norm() < EXACT,
                "{}: S {:?}, want {want:?}",
                est.name(),
                e.shapes[centre]
            );
        }
    }
}
