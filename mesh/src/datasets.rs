//! Analytic data sets: meshes sampled from surfaces whose positions, normals and curvatures are
//! known exactly, and the surfaces themselves for measuring fitted shapes against.
//!
//! The testbed's data sets (Lounsbery et al. 1990, §5: "samplings of the sphere", the ring and
//! the capsule of the later survey, and the octahedron of Figure 2), each a [`DataSet`]: a
//! [`Mesh`] whose vertices carry exact `(p, n, S)` (from [`crate::analytic`]), and an
//! [`AnalyticSurface`] answering closest-point and curvature queries.
//!
//! | name | surface | resolution (default) | V, E, F at default | χ |
//! |---|---|---|---|---|
//! | `sphere` | unit sphere | subdivision levels `k` of the octahedron (2) | 66, 192, 128 | 2 |
//! | `ring` | torus `R = 1`, `r = 0.4` | `nu` around the axis, `nv = max(3, nu/2)` around the tube (16 → 16 × 8) | 128, 384, 256 | 0 |
//! | `capsule` | cylinder `r = 0.5`, half-length 0.5, hemispherical caps | `n` around (16) | 194, 576, 384 | 2 |
//! | `octa` | unit sphere | none: Figure 2 as is | 6, 12, 8 | 2 |
//!
//! Conventions: outward normals, faces oriented counter-clockwise seen from outside, shape
//! tensors with `κn(d) = dᵀ S d > 0` where the surface bends towards `n`, so convex parts have
//! negative curvatures; mean curvature `H = (κ1 + κ2)/2` with the same sign (unit sphere:
//! `K = 1`, `H = −1`). Curvature formulas: do Carmo, *Differential Geometry of Curves and
//! Surfaces*, §3-2 and §3-3 (sphere, cylinder, torus).
//!
//! **Sphere**: the octahedron of `data/octa.m` split `k` times (each triangle into four at its
//! edge midpoints), every vertex pushed radially to the unit sphere.
//!
//! **Ring**: the grid `(u_i, v_j) = (2π i/nu, 2π j/nv)` of `crate::analytic::torus_point`, each
//! grid quad `(i,j), (i+1,j), (i+1,j+1), (i,j+1)` split along `(i,j)–(i+1,j+1)` — the diagonal
//! convention of `crate::analytic::torus_grid_edges`, so the mesh's edges are exactly those.
//! Coarse on purpose at the default: the seeds' ring shows defects on a coarse sampling.
//!
//! **Capsule**: a surface of revolution about z sampled on `n` meridians. The profile runs from
//! the south pole: `max(1, n/4)` equal steps of polar angle over the lower hemisphere, then
//! `m = max(1, round(2h / (2π r / n)))` equal steps along the cylinder (so cylinder triangles are
//! about as long as they are wide: `m = 5` at `n = 16`), then the upper hemisphere like the
//! lower. Quads are split like the ring's, poles are fans. On the two **seam circles**
//! `z = ±h` the curvature jumps (meridian curvature 0 on the cylinder, `−1/r` on the caps); a seam
//! vertex carries the **cylinder's** tensor `−(1/r) e_θ e_θᵀ`, as do the closest-point queries
//! (a point belongs to a cap only when `|z| > h` strictly).
//!
//! **Franke** (`franke1` … `franke6`, `franke1@scattered` … `franke6@scattered`): the graphs
//! of Franke's six test functions over `[0, 1]²` ([`crate::analytic_franke`]) with exact
//! values, normals and shape tensors, in the two usual samplings (Franke 1982): `frankeK` the
//! `N × N` grid (resolution `N`, default 33, each square split along its rising diagonal
//! `(i, j)–(i+1, j+1)`), `frankeK@scattered` `N` points (default 100: the square's four corners,
//! `s = ⌊√(N − 4)⌋/2` uniform points on each side (4 at the default: four corners alone leave
//! slivers along the sides) and the rest uniform inside, from `rng::SplitMix64` seeded with
//! [`FRANKE_SEED`]) with their
//! Delaunay triangulation ([`crate::delaunay`]). Franke's own 100-point set is not available
//! here, so the scattered sampling is this seeded one, not his. They are height fields:
//! `clough-tocher` and `powell-sabin` fit them with their functional C1 forms. They are not in
//! [`DATASET_NAMES`] (the surfaces the studies iterate over) but in [`FRANKE_NAMES`].
//!
//! **Octa**: Figure 2 as is; its vertices lie on the unit sphere, so they carry the sphere's
//! tensor `−(I − n nᵀ)`.

use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, TAU};
use std::sync::Arc;

use crate::analytic::{sphere_point, torus_point};
use crate::vertex::VertexData;
use nalgebra::{Matrix3, Point3, Vector3};

use crate::mesh::{Mesh, MeshError, Vertex};
use crate::testbed_format::{read_testbed, TestbedError};

/// The names [`dataset_by_name`] knows, in a stable order.
pub const DATASET_NAMES: [&str; 4] = ["sphere", "ring", "capsule", "octa"];

/// The Franke data sets [`dataset_by_name`] knows besides [`DATASET_NAMES`]: `frankeK` on the
/// grid, `frankeK@scattered` on scattered points (module docs).
pub const FRANKE_NAMES: [&str; 12] = [
    "franke1",
    "franke2",
    "franke3",
    "franke4",
    "franke5",
    "franke6",
    "franke1@scattered",
    "franke2@scattered",
    "franke3@scattered",
    "franke4@scattered",
    "franke5@scattered",
    "franke6@scattered",
];

/// Default grid side of the Franke grid data sets (Franke's 33 × 33).
pub const FRANKE_GRID_DEFAULT: usize = 33;
/// Default point count of the scattered Franke data sets (Franke's 100).
pub const FRANKE_SCATTERED_DEFAULT: usize = 100;
/// Largest grid side of the Franke grids (2 · 1024² faces).
pub const FRANKE_GRID_MAX: usize = 1025;
/// The seed of the scattered Franke points ("FRANKE" in ASCII).
pub const FRANKE_SEED: u64 = 0x4652_414E_4B45;

/// Default subdivision level of `sphere`.
pub const SPHERE_DEFAULT_LEVELS: usize = 2;
/// Largest subdivision level of `sphere` (8 · 4⁸ ≈ 5·10⁵ faces).
pub const SPHERE_MAX_LEVELS: usize = 8;
/// Default number of grid steps around the axis of `ring` (16 × 8).
pub const RING_DEFAULT_RESOLUTION: usize = 16;
/// Default number of meridians of `capsule`.
pub const CAPSULE_DEFAULT_RESOLUTION: usize = 16;
/// Largest resolution of `ring` and `capsule`.
pub const MAX_RESOLUTION: usize = 4096;
/// Major radius of the ring (as in the curve layer's tests and samples).
pub const RING_MAJOR_RADIUS: f64 = 1.0;
/// Tube radius of the ring.
pub const RING_TUBE_RADIUS: f64 = 0.4;
/// Radius of the capsule's cylinder and caps.
pub const CAPSULE_RADIUS: f64 = 0.5;
/// Half-length of the capsule's cylinder along z.
pub const CAPSULE_HALF_LENGTH: f64 = 0.5;

/// The octahedron of the testbed's Figure 2, compiled in (the project never reads `../shared`).
pub const OCTA_M: &str = include_str!("../../data/octa.m");

/// The closest point of an analytic surface to a query point, with everything known there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Position, outward unit normal and shape tensor at the closest point.
    pub data: VertexData,
    /// Distance from the query point, positive outside (along `n`).
    pub signed_distance: f64,
    /// Principal curvatures `κ1 ≤ κ2` (docs/conventions.md sign).
    pub principal: [f64; 2],
}

impl SurfacePoint {
    /// Gaussian curvature `K = κ1 κ2`.
    pub fn gaussian(&self) -> f64 {
        self.principal[0] * self.principal[1]
    }

    /// Mean curvature `H = (κ1 + κ2)/2`.
    pub fn mean(&self) -> f64 {
        0.5 * (self.principal[0] + self.principal[1])
    }
}

fn sorted(a: f64, b: f64) -> [f64; 2] {
    if a <= b {
        [a, b]
    } else {
        [b, a]
    }
}

/// A surface with exact closest points, normals and curvatures.
///
/// Queries are exact for any point off the surface's medial axis; on the medial axis (the
/// centre of a sphere, the axis of a torus or capsule, …) the closest point is not unique and a
/// documented one is returned, never NaN.
pub trait AnalyticSurface: std::fmt::Debug + Send + Sync {
    /// The closest point to `q` and the surface's data there.
    fn closest(&self, q: &Point3<f64>) -> SurfacePoint;

    /// The closest point to `q`.
    fn closest_point(&self, q: &Point3<f64>) -> Point3<f64> {
        self.closest(q).data.p
    }

    /// Signed distance of `q`, positive outside.
    fn signed_distance(&self, q: &Point3<f64>) -> f64 {
        self.closest(q).signed_distance
    }

    /// Outward unit normal at the closest point.
    fn normal(&self, q: &Point3<f64>) -> Vector3<f64> {
        self.closest(q).data.n
    }

    /// Principal curvatures `κ1 ≤ κ2` at the closest point.
    fn principal_curvatures(&self, q: &Point3<f64>) -> [f64; 2] {
        self.closest(q).principal
    }

    /// Gaussian curvature at the closest point.
    fn gaussian_curvature(&self, q: &Point3<f64>) -> f64 {
        self.closest(q).gaussian()
    }

    /// Mean curvature at the closest point.
    fn mean_curvature(&self, q: &Point3<f64>) -> f64 {
        self.closest(q).mean()
    }
}

/// A sphere. At its centre the closest point is taken in the +z direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: Point3<f64>,
    /// Radius.
    pub radius: f64,
}

impl Sphere {
    /// The unit sphere about the origin.
    pub fn unit() -> Self {
        Sphere {
            center: Point3::origin(),
            radius: 1.0,
        }
    }
}

impl AnalyticSurface for Sphere {
    fn closest(&self, q: &Point3<f64>) -> SurfacePoint {
        let d = q - self.center;
        let dist = d.norm();
        let dir = if dist > 0.0 { d } else { Vector3::z() };
        let mut data = sphere_point(&dir, self.radius);
        data.p += self.center.coords;
        let k = -1.0 / self.radius;
        SurfacePoint {
            data,
            signed_distance: dist - self.radius,
            principal: [k, k],
        }
    }
}

/// A torus about the z axis through the origin (`crate::analytic::torus_point`'s). On the z
/// axis the closest point is taken at `u = 0`, on the tube's centre circle at `v = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Torus {
    /// Major radius `R`.
    pub big: f64,
    /// Tube radius `r`.
    pub small: f64,
}

impl Torus {
    /// The angles `(u, v)` of the closest point to `q`.
    pub fn angles(&self, q: &Point3<f64>) -> (f64, f64) {
        let rho = q.x.hypot(q.y);
        let u = if rho > 0.0 { q.y.atan2(q.x) } else { 0.0 };
        let (a, b) = (rho - self.big, q.z);
        let v = if a != 0.0 || b != 0.0 {
            b.atan2(a)
        } else {
            0.0
        };
        (u, v)
    }
}

impl AnalyticSurface for Torus {
    fn closest(&self, q: &Point3<f64>) -> SurfacePoint {
        let (u, v) = self.angles(q);
        let rho = q.x.hypot(q.y);
        let tube = (rho - self.big).hypot(q.z);
        let cv = v.cos();
        SurfacePoint {
            data: torus_point(u, v, self.big, self.small),
            signed_distance: tube - self.small,
            principal: sorted(-1.0 / self.small, -cv / (self.big + self.small * cv)),
        }
    }
}

/// A capsule along z: a cylinder of radius `radius` over `|z| ≤ half_length`, closed by
/// hemispheres. On the axis segment the closest point is taken in the +x direction; a point with
/// `|z| ≤ half_length` gets the cylinder's curvature (see the module docs on the seams).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// Radius of cylinder and caps.
    pub radius: f64,
    /// Half-length of the cylinder.
    pub half_length: f64,
}

impl AnalyticSurface for Capsule {
    fn closest(&self, q: &Point3<f64>) -> SurfacePoint {
        let h = self.half_length;
        let c = Point3::new(0.0, 0.0, q.z.clamp(-h, h));
        let d = q - c;
        let dist = d.norm();
        let n = if dist > 0.0 { d / dist } else { Vector3::x() };
        let p = c + n * self.radius;
        let k = -1.0 / self.radius;
        if q.z.abs() > h {
            SurfacePoint {
                data: VertexData::new(p, n, (Matrix3::identity() - n * n.transpose()) * k),
                signed_distance: dist - self.radius,
                principal: [k, k],
            }
        } else {
            let e = Vector3::z().cross(&n);
            SurfacePoint {
                data: VertexData::new(p, n, e * e.transpose() * k),
                signed_distance: dist - self.radius,
                principal: [k, 0.0],
            }
        }
    }
}

/// Why a data set could not be made.
#[derive(Debug, thiserror::Error)]
pub enum DataSetError {
    /// No data set has this name.
    #[error("unknown data set `{name}`; known: {}", DATASET_NAMES.join(", "))]
    UnknownName {
        /// The name asked for.
        name: String,
    },
    /// The resolution is outside what the data set accepts.
    #[error("data set `{name}`: resolution {resolution} is not allowed ({allowed})")]
    BadResolution {
        /// The data set.
        name: &'static str,
        /// The resolution asked for.
        resolution: usize,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The built-in octahedron did not parse (a build defect, reported rather than hidden).
    #[error("built-in octa.m: {0}")]
    Builtin(#[from] TestbedError),
    /// The scattered points could not be triangulated (a defect of this module: the seeded
    /// points are in general position).
    #[error("Delaunay triangulation: {0}")]
    Delaunay(#[from] crate::delaunay::DelaunayError),
    /// A generated mesh was invalid (a defect of this module, reported rather than hidden).
    #[error("generated mesh: {0}")]
    Mesh(#[from] MeshError),
}

/// A named mesh with exact vertex data and the surface it samples.
#[derive(Clone, Debug)]
pub struct DataSet {
    /// Registry name.
    pub name: &'static str,
    /// The resolution used (see the module table for its meaning; 0 for `octa`).
    pub resolution: usize,
    /// The sampled mesh, vertices carrying exact position, normal and shape tensor.
    pub mesh: Mesh,
    /// The true surface.
    pub surface: Arc<dyn AnalyticSurface>,
}

/// Builds a data set by name (`sphere`, `ring`, `capsule`, `octa`; [`DATASET_NAMES`]) at a
/// resolution (`None` for the default; see the module docs for what it means per data set;
/// `octa` takes none).
pub fn dataset_by_name(name: &str, resolution: Option<usize>) -> Result<DataSet, DataSetError> {
    let bad = |name, resolution, allowed| DataSetError::BadResolution {
        name,
        resolution,
        allowed,
    };
    match name {
        "sphere" => {
            let k = resolution.unwrap_or(SPHERE_DEFAULT_LEVELS);
            if k > SPHERE_MAX_LEVELS {
                return Err(bad("sphere", k, "subdivision levels 0..=8"));
            }
            sphere(k)
        }
        "ring" => {
            let n = resolution.unwrap_or(RING_DEFAULT_RESOLUTION);
            if !(3..=MAX_RESOLUTION).contains(&n) {
                return Err(bad("ring", n, "3..=4096 steps around the axis"));
            }
            ring(n, (n / 2).max(3))
        }
        "capsule" => {
            let n = resolution.unwrap_or(CAPSULE_DEFAULT_RESOLUTION);
            if !(3..=MAX_RESOLUTION).contains(&n) {
                return Err(bad("capsule", n, "3..=4096 meridians"));
            }
            capsule(n)
        }
        name if FRANKE_NAMES.contains(&name) => {
            let k = name.as_bytes()[6] - b'0';
            let function = crate::analytic_franke::Franke::by_number(usize::from(k))
                .ok_or(DataSetError::UnknownName { name: name.into() })?;
            let static_name = FRANKE_NAMES
                .iter()
                .find(|n| **n == name)
                .copied()
                .unwrap_or("franke");
            if name.ends_with("@scattered") {
                let n = resolution.unwrap_or(FRANKE_SCATTERED_DEFAULT);
                if !(4..=crate::delaunay::MAX_POINTS).contains(&n) {
                    return Err(bad(static_name, n, "4..=20000 points"));
                }
                franke_scattered(function, static_name, n)
            } else {
                let n = resolution.unwrap_or(FRANKE_GRID_DEFAULT);
                if !(2..=FRANKE_GRID_MAX).contains(&n) {
                    return Err(bad(static_name, n, "2..=1025 points a side"));
                }
                franke_grid(function, static_name, n)
            }
        }
        "octa" => match resolution {
            None => octa(),
            Some(r) => Err(bad("octa", r, "none: Figure 2 has a fixed sampling")),
        },
        _ => Err(DataSetError::UnknownName {
            name: name.to_string(),
        }),
    }
}

/// The octahedron of Figure 2 with the unit sphere's shape tensors.
pub fn octa() -> Result<DataSet, DataSetError> {
    let mut mesh = read_testbed(OCTA_M)?;
    for v in mesh.vertices_mut() {
        let data = sphere_point(&v.data.p.coords, 1.0);
        v.data.shape = data.shape;
        v.curvature_known = true;
    }
    Ok(DataSet {
        name: "octa",
        resolution: 0,
        mesh,
        surface: Arc::new(Sphere::unit()),
    })
}

/// The octahedron split `levels` times and pushed to the unit sphere.
pub fn sphere(levels: usize) -> Result<DataSet, DataSetError> {
    let base = read_testbed(OCTA_M)?;
    let mut dirs: Vec<Vector3<f64>> = base.vertices().iter().map(|v| v.data.p.coords).collect();
    let mut names: Vec<Option<String>> = base
        .vertices()
        .iter()
        .map(|v| v.name().map(str::to_string))
        .collect();
    let mut faces = base.faces().to_vec();
    for _ in 0..levels {
        let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
        let mut split = |a: usize, b: usize, dirs: &mut Vec<Vector3<f64>>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                dirs.push((dirs[a] + dirs[b]).normalize());
                names.push(None);
                dirs.len() - 1
            })
        };
        let mut next = Vec::with_capacity(4 * faces.len());
        for &[a, b, c] in &faces {
            let ab = split(a, b, &mut dirs);
            let bc = split(b, c, &mut dirs);
            let ca = split(c, a, &mut dirs);
            next.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        faces = next;
    }
    let vertices = dirs
        .iter()
        .zip(names)
        .map(|(d, name)| {
            let mut v = Vertex::new(sphere_point(d, 1.0));
            v.set_name(name);
            v
        })
        .collect();
    Ok(DataSet {
        name: "sphere",
        resolution: levels,
        mesh: Mesh::new(vertices, faces)?,
        surface: Arc::new(Sphere::unit()),
    })
}

/// Faces of the quad grid `(i, j)` with `i` periodic over `ni` and rows `j = 0..nj` (row `nj`
/// is row 0 when `wrap_j`), each quad split along `(i,j)–(i+1,j+1)`; `index(i, j)` numbers the
/// vertices.
fn grid_faces(
    ni: usize,
    nj: usize,
    index: impl Fn(usize, usize) -> usize,
    out: &mut Vec<[usize; 3]>,
) {
    for i in 0..ni {
        for j in 0..nj {
            let a = index(i, j);
            let b = index((i + 1) % ni, j);
            let c = index((i + 1) % ni, j + 1);
            let d = index(i, j + 1);
            out.push([a, b, c]);
            out.push([a, c, d]);
        }
    }
}

/// The torus `R = 1`, `r = 0.4` on an `nu × nv` grid.
pub fn ring(nu: usize, nv: usize) -> Result<DataSet, DataSetError> {
    let (du, dv) = (TAU / nu as f64, TAU / nv as f64);
    let mut vertices = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let v = torus_point(
                i as f64 * du,
                j as f64 * dv,
                RING_MAJOR_RADIUS,
                RING_TUBE_RADIUS,
            );
            vertices.push(Vertex::new(v));
        }
    }
    let mut faces = Vec::with_capacity(2 * nu * nv);
    grid_faces(nu, nv, |i, j| i * nv + j % nv, &mut faces);
    Ok(DataSet {
        name: "ring",
        resolution: nu,
        mesh: Mesh::new(vertices, faces)?,
        surface: Arc::new(Torus {
            big: RING_MAJOR_RADIUS,
            small: RING_TUBE_RADIUS,
        }),
    })
}

/// The capsule with `n` meridians (profile in the module docs).
pub fn capsule(n: usize) -> Result<DataSet, DataSetError> {
    let surface = Capsule {
        radius: CAPSULE_RADIUS,
        half_length: CAPSULE_HALF_LENGTH,
    };
    let (a, h) = (surface.radius, surface.half_length);
    let m_cap = (n / 4).max(1);
    let m_cyl = ((2.0 * h) / (TAU * a / n as f64)).round().max(1.0) as usize;
    // Profile rings strictly between the poles, as (rho, z).
    let mut rings: Vec<(f64, f64)> = Vec::new();
    for j in 1..=m_cap {
        let alpha = FRAC_PI_2 * j as f64 / m_cap as f64;
        let (rho, z) = if j == m_cap {
            (a, -h)
        } else {
            (a * alpha.sin(), -h - a * alpha.cos())
        };
        rings.push((rho, z));
    }
    for t in 1..=m_cyl {
        rings.push((a, -h + 2.0 * h * (t as f64 / m_cyl as f64)));
    }
    for j in 1..m_cap {
        let alpha = FRAC_PI_2 * (m_cap - j) as f64 / m_cap as f64;
        rings.push((a * alpha.sin(), h + a * alpha.cos()));
    }
    let nr = rings.len();
    let mut points = vec![Point3::new(0.0, 0.0, -h - a)];
    for &(rho, z) in &rings {
        for i in 0..n {
            let theta = TAU * i as f64 / n as f64;
            points.push(Point3::new(rho * theta.cos(), rho * theta.sin(), z));
        }
    }
    points.push(Point3::new(0.0, 0.0, h + a));
    let (south, north) = (0, points.len() - 1);
    let ring_index = |i: usize, j: usize| 1 + j * n + i % n;
    let mut faces = Vec::new();
    for i in 0..n {
        faces.push([south, ring_index(i + 1, 0), ring_index(i, 0)]);
    }
    grid_faces(n, nr - 1, ring_index, &mut faces);
    for i in 0..n {
        faces.push([ring_index(i, nr - 1), ring_index(i + 1, nr - 1), north]);
    }
    let vertices = points
        .iter()
        .map(|p| {
            let mut data = surface.closest(p).data;
            data.p = *p;
            Vertex::new(data)
        })
        .collect();
    Ok(DataSet {
        name: "capsule",
        resolution: n,
        mesh: Mesh::new(vertices, faces)?,
        surface: Arc::new(surface),
    })
}

fn franke_vertex(function: crate::analytic_franke::Franke, x: f64, y: f64) -> Vertex {
    Vertex::new(crate::analytic_franke::graph_data(x, y, &function.jet(x, y)).0)
}

fn franke_set(
    function: crate::analytic_franke::Franke,
    name: &'static str,
    resolution: usize,
    mesh: Mesh,
) -> DataSet {
    DataSet {
        name,
        resolution,
        mesh,
        surface: Arc::new(crate::analytic_franke::FrankeSurface { function }),
    }
}

/// The Franke function's graph on the `n × n` grid of `[0, 1]²` (module docs).
pub fn franke_grid(
    function: crate::analytic_franke::Franke,
    name: &'static str,
    n: usize,
) -> Result<DataSet, DataSetError> {
    let h = 1.0 / (n - 1) as f64;
    let mut vertices = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            vertices.push(franke_vertex(function, i as f64 * h, j as f64 * h));
        }
    }
    let mut faces = Vec::with_capacity(2 * (n - 1) * (n - 1));
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i;
            faces.push([a, a + 1, a + n + 1]);
            faces.push([a, a + n + 1, a + n]);
        }
    }
    Ok(franke_set(function, name, n, Mesh::new(vertices, faces)?))
}

/// The Franke function's graph on `n` scattered points of `[0, 1]²` (the corners, seeded
/// uniform points on the sides and inside) with their Delaunay triangulation (module docs).
pub fn franke_scattered(
    function: crate::analytic_franke::Franke,
    name: &'static str,
    n: usize,
) -> Result<DataSet, DataSetError> {
    let mut rng = rng::SplitMix64::new(FRANKE_SEED);
    let mut points = vec![
        nalgebra::Vector2::new(0.0, 0.0),
        nalgebra::Vector2::new(1.0, 0.0),
        nalgebra::Vector2::new(1.0, 1.0),
        nalgebra::Vector2::new(0.0, 1.0),
    ];
    // `s` points on each side, so that the hull's edges are not the square's whole sides (four
    // corners alone leave slivers along every side).
    let s = (((n - 4) as f64).sqrt() as usize / 2).min((n - 4) / 4);
    for side in 0..4 {
        for _ in 0..s {
            let t = rng.next_f64();
            points.push(match side {
                0 => nalgebra::Vector2::new(t, 0.0),
                1 => nalgebra::Vector2::new(1.0, t),
                2 => nalgebra::Vector2::new(t, 1.0),
                _ => nalgebra::Vector2::new(0.0, t),
            });
        }
    }
    while points.len() < n {
        points.push(nalgebra::Vector2::new(rng.next_f64(), rng.next_f64()));
    }
    let faces = crate::delaunay::delaunay(&points)?;
    let vertices = points
        .iter()
        .map(|p| franke_vertex(function, p.x, p.y))
        .collect();
    Ok(franke_set(function, name, n, Mesh::new(vertices, faces)?))
}
