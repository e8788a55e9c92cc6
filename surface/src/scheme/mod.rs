//! Surface schemes as a plug-in family: one trait, one registry by name.
//!
//! A scheme turns the data of one face — its three vertices (position, normal, shape tensor)
//! and, for schemes with cubic boundaries, the face's three edge curves from a
//! [`curves::CurveMethod`] — into Bézier triangles laid out by its [`Layout`]: a fixed degree
//! and a fixed split of the face's barycentric domain into sub-triangles (one for a plain patch,
//! three at the centroid for the split-domain schemes, six for Powell–Sabin). Everything
//! downstream (G1 measurement, tessellation, metrics, pictures, output) is driven by the layout,
//! never by a particular scheme.
//!
//! The fit ([`crate::fit::fit_scheme`]) runs in two stages: edge curves (only where
//! [`Scheme::uses_curves`]), shared by the two faces on an edge, then patches per face into one
//! flat buffer of control points.
//!
//! # Adding a scheme
//!
//! One file in `surface/src/scheme/` implementing [`Scheme`], one line in [`REGISTRY`], one test
//! file `surface/tests/scheme_<name>.rs` (closed forms or hand-derived nets, precision,
//! similarity invariance, and the continuity it claims measured on sphere, ring and capsule;
//! `surface/tests/suite/schemes.rs` runs every registered scheme through the common checks).

pub mod clough_tocher;
pub mod discrete_side_vertex;
pub mod flat;
pub mod functional;
pub mod gregory_charrot;
pub mod nielson;
pub mod phong;
pub mod pn_triangles;
pub mod powell_sabin;
pub mod shirman_sequin;
pub mod shirman_sequin_1987;
pub mod shirman_sequin_curvature;
pub mod shirman_sequin_testbed;

use curves::{CubicBez3, VertexData};
use nalgebra::{Point3, Vector3};

use crate::fit::FaceFallbackReason;

/// A point of a face's barycentric domain, `(λ_0, λ_1, λ_2)` with `Σ λ = 1`.
pub type Bary = [f64; 3];

/// The corners of the whole face.
pub const WHOLE: [[Bary; 3]; 1] = [[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]];

const T: f64 = 1.0 / 3.0;

/// The centroid split (Clough–Tocher, Shirman–Séquin): sub-triangle `e` over
/// `(V_e, V_{e+1}, S)`, `S` the centroid.
pub const CENTROID_SPLIT: [[Bary; 3]; 3] = [
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [T, T, T]],
    [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [T, T, T]],
    [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [T, T, T]],
];

/// The six-split (Powell–Sabin): for edge `e`, sub-triangles `(V_e, M_e, S)` and
/// `(M_e, V_{e+1}, S)`, `M_e` the edge midpoint and `S` the centroid.
pub const SIX_SPLIT: [[Bary; 3]; 6] = [
    [[1.0, 0.0, 0.0], [0.5, 0.5, 0.0], [T, T, T]],
    [[0.5, 0.5, 0.0], [0.0, 1.0, 0.0], [T, T, T]],
    [[0.0, 1.0, 0.0], [0.0, 0.5, 0.5], [T, T, T]],
    [[0.0, 0.5, 0.5], [0.0, 0.0, 1.0], [T, T, T]],
    [[0.0, 0.0, 1.0], [0.5, 0.0, 0.5], [T, T, T]],
    [[0.5, 0.0, 0.5], [1.0, 0.0, 0.0], [T, T, T]],
];

/// How a scheme's output is laid out per face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Degree of every patch ([`Form::Bezier`]); for a [`Form::Sampled`] patch the degree of
    /// its boundary curves (informative only).
    pub degree: usize,
    /// The sub-triangles of the face's domain, each as its three corners in barycentric
    /// coordinates of the face, counter-clockwise like the face. Patch `s` of face `f` is the
    /// patch over `subs[s]`; for Bézier patches, its corners `b_{n00}, b_{0n0}, b_{00n}` sit
    /// over `subs[s][0], subs[s][1], subs[s][2]`.
    pub subs: &'static [[Bary; 3]],
    /// What a patch's stored points are: a Bézier net, or the data of a patch evaluated by
    /// its own rule ([`crate::patch`]).
    pub form: Form,
}

/// What the stored points of one patch are (module docs of [`crate::patch`]).
#[derive(Clone, Copy)]
pub enum Form {
    /// A Bézier triangle's control net of the layout's degree, in net order.
    Bezier,
    /// The data of a patch that is evaluated by its own rule (Nielson's side-vertex
    /// interpolant …), [`crate::patch::SampledForm::points_per_patch`] points each.
    Sampled(&'static dyn crate::patch::SampledForm),
}

impl std::fmt::Debug for Form {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Form::Bezier => f.write_str("Bezier"),
            Form::Sampled(s) => write!(f, "Sampled({})", s.name()),
        }
    }
}

impl PartialEq for Form {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (Form::Bezier, Form::Bezier) => true,
            (Form::Sampled(a), Form::Sampled(b)) => a.name() == b.name(),
            _ => false,
        }
    }
}

impl Layout {
    /// Bézier triangles of `degree` over `subs`.
    pub const fn bezier(degree: usize, subs: &'static [[Bary; 3]]) -> Layout {
        Layout {
            degree,
            subs,
            form: Form::Bezier,
        }
    }

    /// True when every patch is a Bézier net.
    pub fn is_bezier(&self) -> bool {
        matches!(self.form, Form::Bezier)
    }

    /// Patches per face.
    pub fn patches_per_face(&self) -> usize {
        self.subs.len()
    }

    /// Points stored per patch.
    pub fn points_per_patch(&self) -> usize {
        match self.form {
            Form::Bezier => crate::beztri::num_points(self.degree),
            Form::Sampled(s) => s.points_per_patch(),
        }
    }

    /// Control points per face.
    pub fn points_per_face(&self) -> usize {
        self.patches_per_face() * self.points_per_patch()
    }
}

/// What a scheme promises across patch boundaries (inside a face and between faces); the G1
/// measurement reports against it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Continuity {
    /// Tangent-plane continuity everywhere (measured below 1e-9 rad).
    G1,
    /// Position continuity, with a separate normal field for shading that is continuous (PN
    /// triangles); the geometric normal jump is measured and reported.
    C0WithNormals,
    /// Position continuity only; the normal jump is measured and reported.
    C0,
    /// On height-field data `z = f(x, y)`: `f` continuously differentiable across every
    /// boundary (value and both partials `z_x`, `z_y`), so G1 too (measured below 1e-9 rad);
    /// the functional schemes ([`functional`]).
    C1,
}

impl std::fmt::Display for Continuity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Continuity::G1 => "G1",
            Continuity::C0WithNormals => "C0 + normal field",
            Continuity::C0 => "C0",
            Continuity::C1 => "C1",
        })
    }
}

/// A scheme's free parameter, declared once (in the scheme's file, listed by its
/// [`SchemeEntry`]): the command lines' options and `--help`, the range check, the sweeps'
/// option records and the reports are all generated from it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParameterSpec {
    /// Option name (`beta`, `phong-alpha` …, without dashes); JSON records use it with `_`
    /// for `-` ([`ParameterSpec::key`]).
    pub name: &'static str,
    /// How reports write it (`β`, `c`, `α`).
    pub symbol: &'static str,
    /// Default value.
    pub default: f64,
    /// The valid values, inclusive.
    pub range: (f64, f64),
    /// Why the range is what it is (shown when a value is refused).
    pub range_reason: &'static str,
    /// What it does.
    pub summary: &'static str,
}

impl ParameterSpec {
    /// The name as a JSON key: `phong-alpha` → `phong_alpha`.
    pub fn key(&self) -> String {
        self.name.replace('-', "_")
    }

    /// Whether `value` lies in [`ParameterSpec::range`] (NaN does not).
    pub fn accepts(&self, value: f64) -> bool {
        value >= self.range.0 && value <= self.range.1
    }
}

/// What one face's construction reads.
#[derive(Clone, Copy, Debug)]
pub struct FaceInput<'a> {
    /// The face index.
    pub face: usize,
    /// The vertex data of its corners `V_0, V_1, V_2`.
    pub vertices: [&'a VertexData; 3],
    /// Its edge curves, `edges[e]` from `V_e` to `V_{e+1}` (the shared curve oriented along the
    /// face). For schemes that do not use curves: the straight cubics at thirds of the edges.
    pub edges: &'a [CubicBez3; 3],
    /// Per face edge `e`, at its start `V_e` (`[0]`) and end `V_{e+1}` (`[1]`): the direction of
    /// the crease line where the edge is a crease at that end ([`crate::fit::edge_ends`]), else
    /// `None` ([`NO_CREASES`] for a face without creases). Filled by the fit for every scheme:
    /// those that make their own boundaries ([`Scheme::uses_curves`] false) project onto these
    /// lines; those on curves find the crease in their edge curves, and `shirman-sequin` reads
    /// which corners lie between two creases (straight crease corners).
    pub creases: [[Option<Vector3<f64>>; 2]; 3],
}

/// [`FaceInput::creases`] of a face with no crease edge.
pub const NO_CREASES: [[Option<Vector3<f64>>; 2]; 3] = [[None; 2]; 3];

impl FaceInput<'_> {
    /// The crease line's direction at corner `corner` of face edge `edge` (one of the corner's
    /// two edges), where the edge is a crease there.
    pub fn crease_line(&self, corner: usize, edge: usize) -> Option<Vector3<f64>> {
        let end = usize::from(edge != corner);
        self.creases.get(edge).and_then(|c| c[end])
    }

    /// Which corners lie between two crease edges (both of a corner's edges are crease lines
    /// there): the corners a construction may build as straight crease corners
    /// ([`crate::shirman_sequin::macro_patch_creased`]).
    pub fn creased_corners(&self) -> [bool; 3] {
        std::array::from_fn(|i| {
            self.crease_line(i, i).is_some() && self.crease_line(i, (i + 2) % 3).is_some()
        })
    }

    /// The direction `d` from corner `corner` along face edge `edge` (one of the two edges at the
    /// corner: `edge == corner` leaves it, `edge == corner + 2 (mod 3)` arrives at it), mapped
    /// into the surface's tangent space there: projected onto the corner's tangent plane
    /// (`d − (d·n) n`, `n` its unit normal), or, where the edge is a crease at that corner, onto
    /// the crease line (`(d·t) t`): the line both sectors' tangent planes share, so the two faces
    /// on the crease build the same boundary from their own normals. The schemes that make their
    /// own boundaries (PN triangles, Phong, Powell–Sabin) project through this.
    pub fn project(&self, corner: usize, edge: usize, d: &Vector3<f64>) -> Vector3<f64> {
        if let Some(t) = self.crease_line(corner, edge) {
            return t * t.dot(d);
        }
        let n = self.vertices[corner]
            .n
            .try_normalize(0.0)
            .unwrap_or_else(Vector3::zeros);
        d - n * d.dot(&n)
    }
}

/// A surface scheme (module docs).
pub trait Scheme: Send + Sync {
    /// The registered name.
    fn name(&self) -> &'static str;

    /// Output layout: degree and domain split.
    fn layout(&self) -> Layout;

    /// What it promises across boundaries.
    fn continuity(&self) -> Continuity;

    /// True if its patch boundaries are the cubic edge curves of a [`curves::CurveMethod`]
    /// (then `--curves` applies); false if the scheme makes its own boundaries.
    fn uses_curves(&self) -> bool;

    /// True if its interior has parameters a per-face optimization can choose
    /// (`surface::fairing`'s thin-plate and membrane choices of β and c).
    fn has_interior_parameters(&self) -> bool {
        false
    }

    /// Builds face `input.face` into `out` (`layout().points_per_face()` points: patch after
    /// patch, each in net order). An error sends the face to [`Scheme::fallback`] and is
    /// reported with the face; [`FaceFallbackReason::Scheme`] with a `BadParameter` stops the
    /// whole fit (a setting, not the data).
    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason>;

    /// This scheme's functional form for `mesh`, when the mesh is a height field
    /// ([`functional::detect`]: the caller has checked) and the scheme has one: the C1
    /// interpolant of `z = f(x, y)` the parametric scheme is named after
    /// (`clough-tocher`, `powell-sabin`). `None` (the default): the scheme fits height fields as
    /// it fits anything.
    fn on_height_field(&self, mesh: &crate::mesh::Mesh) -> Option<Box<dyn Scheme>> {
        let _ = mesh;
        None
    }

    /// The C0 patch of a face [`Scheme::build`] cannot fit, meeting its neighbours along the
    /// shared boundaries. The default is the face's flat triangle over the layout, which is C0
    /// with neighbours whose boundaries are straight; schemes with curved boundaries override.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        flat_over_layout(self.layout(), input.vertices.map(|v| v.p), out);
    }
}

/// Largest `|t̂ · n̂|` of a boundary tangent at a corner for the tangent to be in the corner's
/// tangent plane: the sine of the angle it leaves the plane by; `√ε`-size (a normalized
/// construction's rounding), far below a clamped tangent's (`curves::problem::MAX_TANGENT_ANGLE`
/// turns a tangent out of the plane by at least the excess over the bound).
pub const OFF_PLANE_SINE: f64 = 1e-8;

/// The first corner of a face where its two edge tangents turn against the vertex normal:
/// `(D_{i,i+1} × D_{i,i+2}) · N_i ≤ 0`, with `D_{i,i+1} = 3(c_1 − c_0)` of the edge curve
/// leaving `V_i` and `D_{i,i+2} = −3(c_3 − c_2)` of the curve arriving there. Any patch that
/// interpolates those tangents and the vertex normal is folded at that corner: its normal
/// `r_u × r_v` is the other way round. Also the first corner where a tangent leaves the
/// tangent plane (`|t̂ · n̂| > `[`OFF_PLANE_SINE`]: a clamped tangent, a crease end off its crease
/// line): no patch has that normal and those tangents, so a G1 claim would fail there. The
/// schemes on curves that have no test of their own refuse such faces, which then get their C0
/// fallback ([`FaceFallbackReason::Folded`]).
pub fn folded_corner(input: &FaceInput<'_>) -> Option<usize> {
    (0..3).find(|&i| {
        let leaving = input.edges[i].points[1] - input.edges[i].points[0];
        let k = (i + 2) % 3;
        let arriving = input.edges[k].points[2] - input.edges[k].points[3];
        let n = input.vertices[i].n;
        let off_plane = |t: &Vector3<f64>| {
            let scale = t.norm() * n.norm();
            scale > 0.0 && t.dot(&n).abs() > OFF_PLANE_SINE * scale
        };
        off_plane(&leaving)
            || off_plane(&arriving)
            || leaving.cross(&arriving).dot(&n).partial_cmp(&0.0)
                != Some(std::cmp::Ordering::Greater)
    })
}

/// [`folded_corner`] for schemes that make their own boundaries: the first corner where the
/// face's winding is against the vertex normal, `((V_{i+1} − V_i) × (V_{i+2} − V_i)) · N_i ≤ 0`
/// (a patch through the corner with that normal folds there). Only for schemes whose fallback
/// keeps the boundaries (`powell-sabin`): PN triangles and Phong tessellation are determined by
/// their edges, so the flat fallback of a refused face would break C0 with its neighbours,
/// and they take such faces as they come (the G1 measurement reports the fold).
pub fn folded_winding(input: &FaceInput<'_>) -> Option<usize> {
    let p = input.vertices.map(|v| v.p);
    (0..3).find(|&i| {
        let (a, b) = (p[(i + 1) % 3] - p[i], p[(i + 2) % 3] - p[i]);
        a.cross(&b).dot(&input.vertices[i].n).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
    })
}

/// The affine map of a face's corners, over every sub-triangle of `layout` and raised to its
/// degree: `out` gets `points_per_face` points.
pub fn flat_over_layout(layout: Layout, corners: [Point3<f64>; 3], out: &mut [Point3<f64>]) {
    let n = layout.degree.max(1) as f64;
    let at = |b: Bary| {
        Point3::from(corners[0].coords * b[0] + corners[1].coords * b[1] + corners[2].coords * b[2])
    };
    let np = layout.points_per_patch();
    for (s, sub) in layout.subs.iter().enumerate() {
        for (slot, (i, j, k)) in out[s * np..(s + 1) * np]
            .iter_mut()
            .zip(crate::beztri::multi_indices(layout.degree))
        {
            let b: Bary = std::array::from_fn(|c| {
                (sub[0][c] * i as f64 + sub[1][c] * j as f64 + sub[2][c] * k as f64) / n
            });
            *slot = at(if layout.degree == 0 { sub[0] } else { b });
        }
    }
}

/// The values of the schemes' parameters, by [`ParameterSpec::name`]; a parameter not set
/// has its default. Each scheme reads only its own ([`SchemeEntry::parameters`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SchemeOptions {
    values: std::collections::BTreeMap<&'static str, f64>,
}

impl SchemeOptions {
    /// The value of `spec`: as set, else its default.
    pub fn value(&self, spec: &ParameterSpec) -> f64 {
        self.values.get(spec.name).copied().unwrap_or(spec.default)
    }

    /// Sets the parameter named `spec.name`.
    pub fn set(&mut self, spec: &ParameterSpec, value: f64) {
        self.values.insert(spec.name, value);
    }

    /// These options with `spec` set to `value`.
    pub fn with(mut self, spec: &ParameterSpec, value: f64) -> Self {
        self.set(spec, value);
        self
    }

    /// The first parameter of `entry` whose value is out of its range, with the value.
    pub fn out_of_range(&self, entry: &SchemeEntry) -> Option<(&'static ParameterSpec, f64)> {
        entry
            .parameters
            .iter()
            .map(|p| (p, self.value(p)))
            .find(|(p, v)| !p.accepts(*v))
    }
}

/// One registered scheme.
pub struct SchemeEntry {
    /// Its name on the command line.
    pub name: &'static str,
    /// One line for help texts and reports.
    pub summary: &'static str,
    /// Its free parameters (declared in its file): options, ranges and report fields are
    /// generated from them.
    pub parameters: &'static [ParameterSpec],
    /// Builds it with the given options (its own parameters read through
    /// [`SchemeOptions::value`]).
    pub build: fn(&SchemeOptions) -> Box<dyn Scheme>,
}

/// Every scheme, by name. The default is [`DEFAULT_SCHEME`].
pub const REGISTRY: &[SchemeEntry] = &[
    SchemeEntry {
        name: "flat",
        summary: "the testbed's Fitter0: the data triangle itself (degree 1, C0)",
        parameters: &[],
        build: |_| Box::new(flat::Flat),
    },
    SchemeEntry {
        name: "shirman-sequin",
        summary:
            "Mann's modified Shirman–Séquin: three quartics per face on cubic edge curves (G1)",
        parameters: shirman_sequin::PARAMETERS,
        build: |o| {
            Box::new(shirman_sequin::ShirmanSequin::uniform(
                shirman_sequin::uniform_parameters(o),
            ))
        },
    },
    SchemeEntry {
        name: "pn-triangles",
        summary:
            "Vlachos et al. 2001 curved PN triangles: one cubic per face, quadratic normals (C0)",
        parameters: &[],
        build: |_| Box::new(pn_triangles::PnTriangles),
    },
    SchemeEntry {
        name: "phong",
        summary: "Boubekeur and Alexa 2008 Phong tessellation: one quadratic per face (C0)",
        parameters: phong::PARAMETERS,
        build: |o| {
            Box::new(phong::Phong {
                alpha: o.value(&phong::ALPHA),
            })
        },
    },
    SchemeEntry {
        name: "clough-tocher",
        summary: "parametric Clough–Tocher (Farin 1985): three cubics per face on cubic edge curves, C1 inside, linear cross-boundary derivative (C0; the functional C1 interpolant on height fields)",
        parameters: clough_tocher::PARAMETERS,
        build: |o| {
            Box::new(clough_tocher::CloughTocher {
                cubic_weight: o.value(&clough_tocher::CUBIC_WEIGHT),
            })
        },
    },
    SchemeEntry {
        name: "powell-sabin",
        summary: "parametric Powell–Sabin 1977: six quadratics per face, boundaries from vertex tangent planes (C0; the functional C1 6-split at incentres on height fields)",
        parameters: &[],
        build: |_| Box::new(powell_sabin::PowellSabin),
    },
    SchemeEntry {
        name: "nielson",
        summary: "Nielson 1987 transfinite side-vertex interpolant on cubic edge curves, tangent planes along edges from the vertex normals (G1; evaluated, not Bézier)",
        parameters: &[],
        build: |_| Box::new(nielson::Nielson),
    },
    SchemeEntry {
        name: "discrete-side-vertex",
        summary: "side-vertex interpolant with discrete (vertex-only) cross-boundary data on cubic edge curves (C0; evaluated, not Bézier)",
        parameters: &[],
        build: |_| Box::new(discrete_side_vertex::DiscreteSideVertex),
    },
    SchemeEntry {
        name: "shirman-sequin-1987",
        summary: "the original Shirman–Séquin 1987 construction: three quartics per face on cubic edge curves, parameter α₂ (G1; C1 inside at α₂ = 9/4)",
        parameters: shirman_sequin_1987::PARAMETERS,
        build: |o| {
            Box::new(shirman_sequin_1987::ShirmanSequin1987 {
                alpha2: o.value(&shirman_sequin_1987::ALPHA2),
            })
        },
    },
    SchemeEntry {
        name: "shirman-sequin-testbed",
        summary: "the testbed's modified Shirman–Séquin (UW 1990): split cubic macro patch, Chiyokura–Kimura twists, C1 inside by averaging (G1)",
        parameters: &[],
        build: |_| Box::new(shirman_sequin_testbed::ShirmanSequinTestbed),
    },
    SchemeEntry {
        name: "shirman-sequin-curvature",
        summary: "the modified Shirman–Séquin macro-patch with a quadratic cross-boundary field whose end derivatives carry the vertices' shape tensors (geodesic torsion matched at the vertices; G1)",
        parameters: shirman_sequin_curvature::PARAMETERS,
        build: |o| Box::new(shirman_sequin_curvature::ShirmanSequinCurvature::from_options(o)),
    },
    SchemeEntry {
        name: "gregory-charrot",
        summary: "Gregory–Charrot 1980: three corner interpolants (Boolean sums, rational twist) blended by b_i²/Σb_j² on cubic edge curves, Chiyokura–Kimura cross-boundary data (G1; evaluated, not Bézier)",
        parameters: &[],
        build: |_| Box::new(gregory_charrot::GregoryCharrot),
    },
];

/// The scheme used when none is named.
pub const DEFAULT_SCHEME: &str = "shirman-sequin";

/// A scheme name that is not registered.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown surface scheme `{name}` (known: {known})")]
pub struct UnknownScheme {
    /// The name asked for.
    pub name: String,
    /// The registered names, comma-separated.
    pub known: String,
}

/// The registered entry named `name`.
pub fn entry_by_name(name: &str) -> Result<&'static SchemeEntry, UnknownScheme> {
    REGISTRY
        .iter()
        .find(|e| e.name == name)
        .ok_or_else(|| UnknownScheme {
            name: name.to_string(),
            known: scheme_names().join(", "),
        })
}

/// Every parameter of the schemes of `registry`, each once (by name, in registry order), with
/// the names of the schemes that read it: what a command line offers as options.
pub fn parameters_of(registry: &[SchemeEntry]) -> Vec<(&'static ParameterSpec, Vec<&'static str>)> {
    let mut out: Vec<(&'static ParameterSpec, Vec<&'static str>)> = Vec::new();
    for e in registry {
        for p in e.parameters {
            match out.iter_mut().find(|(q, _)| q.name == p.name) {
                Some((_, owners)) => owners.push(e.name),
                None => out.push((p, vec![e.name])),
            }
        }
    }
    out
}

/// The registered names, in registry order.
pub fn scheme_names() -> Vec<&'static str> {
    REGISTRY.iter().map(|e| e.name).collect()
}

/// The scheme registered as `name`, built with `options`.
pub fn scheme_by_name(
    name: &str,
    options: &SchemeOptions,
) -> Result<Box<dyn Scheme>, UnknownScheme> {
    entry_by_name(name).map(|e| (e.build)(options))
}
