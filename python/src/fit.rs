//! `fit(…)` and the [`Fit`] it returns: the library's fit job ([`fitjob::run`]) on arrays, a
//! mesh file or a data set, with every net kept; the nets, the report, the G1 measurement and
//! tessellations read from the kept fit.

use std::path::PathBuf;
use std::str::FromStr;
use std::sync::OnceLock;

use mesh::{Frame, Mesh};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use surface::G1Report;

use crate::arrays;
use crate::errors::{failed, job_error, usage};
use crate::input::{crease_rule, raw_from_arrays};

/// A finished fit: the fitted mesh, every patch's control net, the report and the G1
/// measurement, all in the input's coordinates.
///
/// `nets` is one float64 array of shape (patches, points per patch, 3): patch `s` of face `f`
/// is row `f · layout["patches_per_face"] + s`, each net in the row order of the workbench's
/// conventions (docs/conventions.md, "Bézier triangles"). `report` is the dict the command
/// line's `fit --report` writes (G1 split, fallback faces with their reasons, curve
/// statistics, timings). `V`, `F` are the mesh that was fitted (after the repair:
/// `face_source` and `vertex_source` map it back to the input's numbering).
#[pyclass(module = "triwb", frozen)]
pub struct Fit {
    report_json: String,
    mesh: Option<Mesh>,
    frame: Frame,
    fit: Option<surface::Fit>,
    g1: Option<G1Report>,
    face_source: Option<Vec<usize>>,
    vertex_source: Option<Vec<usize>>,
    /// The job's progress lines (what the command line prints before its summary).
    #[pyo3(get)]
    log: Vec<String>,
    /// Wall seconds of the library job alone (`fitjob::run`, timed inside the call): what the
    /// Python call adds is its wall time less this.
    #[pyo3(get)]
    job_seconds: f64,
    nets: OnceLock<Py<PyAny>>,
    report: OnceLock<Py<PyAny>>,
}

/// The arguments `fit` takes besides the input (keyword only), as the command line's options.
pub struct JobArgs<'a> {
    /// `--scheme`.
    pub scheme: &'a str,
    /// `--curves`.
    pub curves: &'a str,
    /// `--solver`.
    pub solver: &'a str,
    /// `--dbhs-pick`.
    pub dbhs_pick: Option<&'a str>,
    /// `--tweak-t`.
    pub tweak_t: f64,
    /// `--four-ninths`.
    pub four_ninths: bool,
    /// `--tangents`: `star` or `per-edge`.
    pub tangents: &'a str,
    /// `--heightfield` (`Some(true)`), `--no-heightfield` (`Some(false)`), or detected (`None`).
    pub heightfield: Option<bool>,
    /// `--interior`.
    pub interior: &'a str,
    /// Samples per boundary of the G1 measurement.
    pub g1_samples: usize,
    /// `--segments`, of the tessellation written to `mesh_out`.
    pub segments: usize,
    /// `--output`.
    pub patches_out: Option<PathBuf>,
    /// `--mesh-output`.
    pub mesh_out: Option<PathBuf>,
    /// `--up`.
    pub up: &'a str,
    /// The scheme's parameters, by keyword.
    pub params: Option<&'a Bound<'a, PyDict>>,
}

/// The scheme options of `params` (keyword arguments named as the registry's parameters, `-`
/// written `_`: `beta`, `c`, `phong_alpha`), refused when the scheme does not read one.
fn scheme_options(
    scheme: &str,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<surface::SchemeOptions> {
    let mut options = surface::SchemeOptions::default();
    let Some(params) = params else {
        return Ok(options);
    };
    let all = surface::scheme::parameters_of(surface::scheme::REGISTRY);
    let entry = surface::scheme::entry_by_name(scheme).ok();
    for (k, v) in params.iter() {
        let key: String = k.extract()?;
        let Some((spec, owners)) = all.iter().find(|(p, _)| p.key() == key || p.name == key) else {
            let known: Vec<String> = all.iter().map(|(p, _)| p.key()).collect();
            return Err(usage(format!(
                "unknown argument `{key}` (scheme parameters: {}; see schemes())",
                known.join(", ")
            )));
        };
        if let Some(e) = entry {
            if !e.parameters.iter().any(|p| p.name == spec.name) {
                return Err(usage(format!(
                    "scheme {} does not read {} (read by {})",
                    e.name,
                    spec.key(),
                    owners.join(", ")
                )));
            }
        }
        let value: f64 = v
            .extract()
            .map_err(|_| usage(format!("{} must be a number", spec.key())))?;
        options.set(spec, value);
    }
    Ok(options)
}

/// The job options of `args` on `input`.
pub fn job_options(
    input: fitjob::InputOptions,
    args: &JobArgs<'_>,
) -> PyResult<fitjob::FitOptions> {
    let method_options = ::curves::MethodOptions {
        tangents: ::curves::TangentRule::from_str(args.tangents)
            .map_err(|e| usage(format!("tangents: {e}")))?,
        ..crate::curve::method_options(args.solver, args.dbhs_pick, args.tweak_t, args.four_ninths)?
    };
    let interior = surface::fairing::InteriorChoice::from_str(args.interior).map_err(usage)?;
    let range = &fitjob::limits::G1_SAMPLES_RANGE;
    if !range.contains(&args.g1_samples) {
        return Err(usage(format!(
            "g1_samples={}: outside its valid range [{}, {}] (samples per boundary of the G1 measure, both ends included)",
            args.g1_samples,
            range.start(),
            range.end()
        )));
    }
    let up = meshio::UpAxis::from_str(args.up).map_err(usage)?;
    Ok(fitjob::FitOptions {
        input,
        scheme: args.scheme.to_string(),
        scheme_options: scheme_options(args.scheme, args.params)?,
        curves: args.curves.to_string(),
        method_options,
        interior,
        heightfield: match args.heightfield {
            None => surface::scheme::functional::HeightFieldMode::Auto,
            Some(true) => surface::scheme::functional::HeightFieldMode::On,
            Some(false) => surface::scheme::functional::HeightFieldMode::Off,
        },
        tess: args.segments,
        g1_samples: args.g1_samples,
        measure_g1: true,
        patches_out: args.patches_out.clone(),
        mesh_out: args.mesh_out.clone(),
        mesh_options: fitjob::output::MeshOutputOptions { up },
        keep: true,
        ..fitjob::FitOptions::default()
    })
}

/// Whether `obj` names a file or data set (a `str` or an `os.PathLike`) rather than holding
/// positions.
fn is_name(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<pyo3::types::PyString>() || obj.hasattr("__fspath__").unwrap_or(false)
}

/// Fits a surface through a triangle mesh with the workbench's fit job, the same job the
/// command line's `fit` runs.
///
/// The input is either arrays — `V` (n × 3), `F` (m × 3) and optionally `normals` (n × 3),
/// `shape` (n × 3 × 3, the workbench's convention) and `creases` (k × 2 vertex pairs marked
/// sharp), repaired and completed by `estimate` like a mesh file — or a name: a mesh file's
/// path, or a data set (`"ring"`, `"sphere"`, `"capsule"`, `"octa"`, at `resolution`), which
/// is fitted exactly as `experiments fit --data NAME` fits it.
///
/// Options, with the command line's defaults: `scheme` (`schemes()`), `curves`
/// (`curve_methods()`), `solver` (`solvers()`, for `optimized`), `dbhs_pick`, `tweak_t` (for
/// `tweak`), `four_ninths` (the projection family's five-ninths point), `tangents` (`star`:
/// a vertex's end tangents chosen together from its star where each edge's own leave a face
/// corner that is not convex; `per-edge`: each edge's own, as the seeds build them; as
/// `--tangents`), `heightfield` (`True`:
/// the functional form required, as `--heightfield`; `False`: never, `--no-heightfield`;
/// `None`: detected), `interior`
/// (`default`, `thin-plate`, `membrane`), `estimate` (`estimators()`, or `none`),
/// `replace_normals`, `crease_angle` / `no_creases`, `g1_samples`, and the scheme's own
/// parameters as keyword arguments (`beta=0.3, c=1.0`, `phong_alpha=0.75`). `patches_out` and
/// `mesh_out` write the patches and a tessellation at `segments` (as `--output` and
/// `--mesh-output`), `up` the data's up axis for glTF. The work runs without the GIL, on the
/// process's shared thread pool, or with `threads=n` on a pool of its own (`threads=1` for
/// fits run side by side from several Python threads).
#[pyfunction]
#[pyo3(signature = (V, F=None, *, normals=None, shape=None, creases=None, resolution=None,
    scheme="shirman-sequin", curves="chord", solver="exact-penalty", dbhs_pick=None,
    tweak_t=::curves::tweak::DEFAULT_TWEAK_T, four_ninths=false, tangents="star",
    heightfield=None, interior="default", estimate="hybrid", replace_normals=false, crease_angle=None,
    no_creases=false, g1_samples=fitjob::options::DEFAULT_G1_SAMPLES,
    segments=fitjob::options::DEFAULT_TESS, patches_out=None, mesh_out=None, up="z",
    label=None, threads=None, **params))]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn fit(
    py: Python<'_>,
    V: &Bound<'_, PyAny>,
    F: Option<&Bound<'_, PyAny>>,
    normals: Option<&Bound<'_, PyAny>>,
    shape: Option<&Bound<'_, PyAny>>,
    creases: Option<&Bound<'_, PyAny>>,
    resolution: Option<usize>,
    scheme: &str,
    curves: &str,
    solver: &str,
    dbhs_pick: Option<&str>,
    tweak_t: f64,
    four_ninths: bool,
    tangents: &str,
    heightfield: Option<bool>,
    interior: &str,
    estimate: &str,
    replace_normals: bool,
    crease_angle: Option<f64>,
    no_creases: bool,
    g1_samples: usize,
    segments: usize,
    patches_out: Option<PathBuf>,
    mesh_out: Option<PathBuf>,
    up: &str,
    label: Option<String>,
    threads: Option<usize>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<Fit> {
    let source = if is_name(V) {
        if F.is_some() || normals.is_some() || shape.is_some() || creases.is_some() {
            return Err(usage(
                "a file or data set is fitted with its own faces and data: give F, normals, shape and creases only with arrays",
            ));
        }
        let path: PathBuf = V.extract()?;
        fitjob::Source::Data {
            data: path.to_string_lossy().into_owned(),
            resolution,
        }
    } else {
        let Some(F) = F else {
            return Err(usage(
                "fit(V, F): F is missing (or give a file's path or a data set's name)",
            ));
        };
        if resolution.is_some() {
            return Err(usage("resolution is a data set's: arrays have theirs"));
        }
        fitjob::Source::Raw {
            label: label.unwrap_or_else(|| "arrays".into()),
            raw: Box::new(raw_from_arrays(V, F, normals, shape, creases)?),
        }
    };
    let input = fitjob::InputOptions {
        source,
        estimate: estimate.to_string(),
        radius: None,
        replace_normals,
        creases: crease_rule(crease_angle, no_creases)?,
    };
    let options = job_options(
        input,
        &JobArgs {
            scheme,
            curves,
            solver,
            dbhs_pick,
            tweak_t,
            four_ninths,
            tangents,
            heightfield,
            interior,
            g1_samples,
            segments,
            patches_out,
            mesh_out,
            up,
            params,
        },
    )?;
    run_job(py, options, threads)
}

/// Runs the job without the GIL and keeps what it gives.
pub fn run_job(
    py: Python<'_>,
    options: fitjob::FitOptions,
    threads: Option<usize>,
) -> PyResult<Fit> {
    let (outcome, log, job_seconds) = crate::threads::run(py, threads, move || {
        let mut log = Vec::new();
        let t = std::time::Instant::now();
        let outcome = fitjob::run(options, &mut |line| log.push(line.to_string()));
        (outcome, log, t.elapsed().as_secs_f64())
    })?;
    let outcome = outcome.map_err(job_error)?;
    let report_json = outcome
        .report
        .to_json()
        .map_err(|e| failed(format!("the report could not be written as JSON: {e}")))?;
    let kept = outcome.kept;
    Ok(Fit {
        report_json,
        mesh: kept.mesh,
        frame: kept.frame.unwrap_or_else(Frame::identity),
        fit: kept.fit,
        g1: kept.g1,
        face_source: kept.face_source,
        vertex_source: kept.vertex_source,
        log,
        job_seconds,
        nets: OnceLock::new(),
        report: OnceLock::new(),
    })
}

impl Fit {
    /// The kept mesh and fit, or the error a subdivision scheme's fit gives (it keeps no
    /// patches).
    fn kept(&self) -> PyResult<(&Mesh, &surface::Fit)> {
        match (&self.mesh, &self.fit) {
            (Some(m), Some(f)) => Ok((m, f)),
            _ => Err(usage(
                "a subdivision scheme's fit has no patches: ask for mesh_out to have its limit mesh written",
            )),
        }
    }

    fn world(&self, p: &nalgebra::Point3<f64>) -> [f64; 3] {
        let q = self.frame.to_world(p);
        [q.x, q.y, q.z]
    }
}

/// A tessellation of `fit` at `segments` per patch edge, in world coordinates, as arrays:
/// what `Fit.tessellate` gives.
fn tessellation_dict<'py>(
    py: Python<'py>,
    tess: &surface::Tessellation,
) -> PyResult<Bound<'py, PyDict>> {
    let n = tess.positions.len();
    let mut k1 = Vec::with_capacity(n);
    let mut k2 = Vec::with_capacity(n);
    let mut d1 = Vec::with_capacity(n);
    let mut d2 = Vec::with_capacity(n);
    for (s, nrm) in tess.shapes.iter().zip(&tess.normals) {
        let p = ::estimate::principal_frame(s, nrm);
        k1.push(p.k1);
        k2.push(p.k2);
        d1.push([p.d1.x, p.d1.y, p.d1.z]);
        d2.push([p.d2.x, p.d2.y, p.d2.z]);
    }
    let out = PyDict::new(py);
    out.set_item(
        "V",
        arrays::points_out(py, tess.positions.iter().map(|p| [p.x, p.y, p.z]))?,
    )?;
    out.set_item("F", arrays::indices_out(py, &tess.faces)?)?;
    out.set_item(
        "normals",
        arrays::points_out(py, tess.normals.iter().map(|v| [v.x, v.y, v.z]))?,
    )?;
    // The exported convention (libigl's): K as it is, H with its sign turned.
    let curvature = meshio::Curvature::from_internal(tess.gaussian.clone(), tess.mean.clone());
    out.set_item("K", arrays::floats_out(py, curvature.gaussian)?)?;
    out.set_item("H", arrays::floats_out(py, curvature.mean)?)?;
    out.set_item("k1", arrays::floats_out(py, k1)?)?;
    out.set_item("k2", arrays::floats_out(py, k2)?)?;
    out.set_item("d1", arrays::points_out(py, d1.into_iter())?)?;
    out.set_item("d2", arrays::points_out(py, d2.into_iter())?)?;
    let patch: Vec<i64> = tess.patch_of_face.iter().map(|&p| p as i64).collect();
    out.set_item(
        "patch",
        arrays::shaped(py, patch, &[tess.patch_of_face.len()])?,
    )?;
    out.set_item("welds", tess.welds)?;
    out.set_item("singular_samples", tess.singular_samples)?;
    out.set_item("collapsed_faces", tess.collapsed_faces)?;
    Ok(out)
}

/// Where a G1 maximum is, as a dict.
fn boundary_dict<'py>(
    py: Python<'py>,
    at: Option<(surface::g1::Boundary, f64)>,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    use surface::g1::Boundary;
    let Some((b, t)) = at else { return Ok(None) };
    let d = PyDict::new(py);
    match b {
        Boundary::Interior { face, boundary } => {
            d.set_item("kind", "interior")?;
            d.set_item("face", face)?;
            d.set_item("boundary", boundary)?;
        }
        Boundary::Exterior { edge } => {
            d.set_item("kind", "exterior")?;
            d.set_item("edge", edge)?;
        }
    }
    d.set_item("t", t)?;
    Ok(Some(d))
}

#[pymethods]
impl Fit {
    /// Every patch's control net, (patches, points per patch, 3) float64, in the input's
    /// coordinates (built once, on first access).
    #[getter]
    fn nets(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        if let Some(n) = self.nets.get() {
            return Ok(n.clone_ref(py));
        }
        let (_, fit) = self.kept()?;
        let np = fit.layout.points_per_patch();
        // The one copy: each point moved to world coordinates straight into the buffer numpy
        // takes over (memory-bound: the fresh pages' faults are most of it, and a parallel
        // copy measured slower, the two threads' faults serialized in the kernel).
        let frame = self.frame;
        let flat = py.detach(|| {
            let mut flat = Vec::with_capacity(3 * fit.points.len());
            flat.extend(fit.points.iter().flat_map(|p| {
                let q = frame.to_world(p);
                [q.x, q.y, q.z]
            }));
            flat
        });
        let a = arrays::shaped(py, flat, &[fit.num_patches(), np, 3])?.unbind();
        Ok(self.nets.get_or_init(|| a).clone_ref(py))
    }

    /// How the patches are laid out per face: `degree`, `form` (`"bezier"`, or the sampled
    /// form's name), `patches_per_face`, `points_per_patch`, and `subs` (each patch's domain
    /// as three corners in barycentric coordinates of its face).
    #[getter]
    fn layout<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (_, fit) = self.kept()?;
        let l = &fit.layout;
        let d = PyDict::new(py);
        d.set_item("degree", l.degree)?;
        d.set_item(
            "form",
            match l.form {
                surface::scheme::Form::Bezier => "bezier".to_string(),
                surface::scheme::Form::Sampled(s) => s.name().to_string(),
            },
        )?;
        d.set_item("patches_per_face", l.patches_per_face())?;
        d.set_item("points_per_patch", l.points_per_patch())?;
        let subs: Vec<Vec<[f64; 3]>> = l.subs.iter().map(|s| s.to_vec()).collect();
        d.set_item("subs", subs)?;
        d.set_item("scheme", fit.scheme)?;
        d.set_item("continuity", fit.continuity.to_string())?;
        Ok(d)
    }

    /// The whole report, as the command line's `fit --report` writes it.
    #[getter]
    fn report(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        if let Some(r) = self.report.get() {
            return Ok(r.clone_ref(py));
        }
        let json = py.import("json")?;
        let r = json.call_method1("loads", (&self.report_json,))?.unbind();
        Ok(self.report.get_or_init(|| r).clone_ref(py))
    }

    /// The report as JSON text.
    #[getter]
    fn report_json(&self) -> &str {
        &self.report_json
    }

    /// The fitted mesh's vertex positions (n × 3), in the input's coordinates.
    #[getter(V)]
    fn vertices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (mesh, _) = self.kept()?;
        arrays::points_out(py, mesh.vertices().iter().map(|v| self.world(&v.data.p)))
    }

    /// The fitted mesh's triangles (m × 3).
    #[getter(F)]
    fn faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (mesh, _) = self.kept()?;
        arrays::indices_out(py, mesh.faces())
    }

    /// For each fitted face, the input face it came from (None for a data set).
    #[getter]
    fn face_source<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.face_source
            .as_ref()
            .map(|s| {
                arrays::shaped(
                    py,
                    s.iter().map(|&i| i as i64).collect::<Vec<_>>(),
                    &[s.len()],
                )
            })
            .transpose()
    }

    /// For each fitted vertex, the input vertex it came from (None for a data set).
    #[getter]
    fn vertex_source<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.vertex_source
            .as_ref()
            .map(|s| {
                arrays::shaped(
                    py,
                    s.iter().map(|&i| i as i64).collect::<Vec<_>>(),
                    &[s.len()],
                )
            })
            .transpose()
    }

    /// The mesh's edges (E × 2 vertex indices), in the order of `edge_curves`.
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (mesh, _) = self.kept()?;
        let e: Vec<[usize; 2]> = mesh.edges().map(|e| e.vertices).collect();
        arrays::indices_out(py, &e)
    }

    /// Each edge's cubic boundary curve (E × 4 × 3 Bézier points, from `edges[:, 0]` to
    /// `edges[:, 1]`); empty for schemes that make their own boundaries.
    #[getter]
    fn edge_curves<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (_, fit) = self.kept()?;
        let mut flat = Vec::with_capacity(12 * fit.curves.len());
        for c in &fit.curves {
            for p in &c.points {
                flat.extend_from_slice(&self.world(p));
            }
        }
        arrays::shaped(py, flat, &[fit.curves.len(), 4, 3])
    }

    /// Each edge curve's end-derivative lengths `[α0, α1]` in the unit-chord form (E × 2).
    #[getter]
    fn alphas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (_, fit) = self.kept()?;
        let flat: Vec<f64> = fit.alphas.iter().flat_map(|a| a.iter().copied()).collect();
        arrays::shaped(py, flat, &[fit.alphas.len(), 2])
    }

    /// Tessellates the patches at `segments` per patch edge (the testbed's `Tess -s`), welded,
    /// in the input's coordinates: a dict of `V`, `F`, `normals`, `K`, `H`, `k1 ≥ k2`, `d1`,
    /// `d2` (libigl's curvature convention, from the patches' exact second derivatives),
    /// `patch` (each triangle's patch), and the weld counts.
    #[pyo3(signature = (segments=fitjob::options::DEFAULT_TESS))]
    fn tessellate<'py>(&self, py: Python<'py>, segments: usize) -> PyResult<Bound<'py, PyDict>> {
        let tess = self.tessellation(py, segments)?;
        tessellation_dict(py, &tess)
    }

    /// The G1 measurement: the largest normal angles (radians) across interior and exterior
    /// boundaries and where they are, the interpolation errors, the fallback and crease edges.
    /// `samples` per boundary: the fit's measurement when None, otherwise measured again.
    #[pyo3(signature = (samples=None))]
    fn g1<'py>(&self, py: Python<'py>, samples: Option<usize>) -> PyResult<Bound<'py, PyDict>> {
        let (mesh, fit) = self.kept()?;
        let g = match (samples, self.g1) {
            (None, Some(g)) => g,
            (s, _) => {
                let s = s.unwrap_or(fitjob::options::DEFAULT_G1_SAMPLES);
                fitjob::limits::check_usize("samples", s, &fitjob::limits::SAMPLING_RANGE)
                    .map_err(job_error)?;
                py.detach(|| surface::measure_g1(mesh, fit, s))
            }
        };
        let d = PyDict::new(py);
        d.set_item("interior_max", g.interior_max)?;
        d.set_item("interior_at", boundary_dict(py, g.interior_at)?)?;
        d.set_item("exterior_max", g.exterior_max)?;
        d.set_item("exterior_at", boundary_dict(py, g.exterior_at)?)?;
        d.set_item("max", g.max_angle())?;
        d.set_item("position_error", g.position_error * self.frame.scale)?;
        d.set_item("normal_error", g.normal_error)?;
        d.set_item("undefined_normals", g.undefined_normals)?;
        d.set_item("fallback_interior_max", g.fallback_interior_max)?;
        d.set_item("fallback_exterior_max", g.fallback_exterior_max)?;
        d.set_item("fallback_edges", g.fallback_edges)?;
        d.set_item("crease_edges", g.crease_edges)?;
        Ok(d)
    }

    /// Writes a tessellation at `segments` to `path`, in the format its extension names, as the
    /// command line's `--mesh-output` writes it (normals, colours by Gaussian curvature, and the
    /// curvature where the format stores it). Returns the path.
    #[pyo3(signature = (path, segments=fitjob::options::DEFAULT_TESS, up="z"))]
    fn to_mesh(
        &self,
        py: Python<'_>,
        path: PathBuf,
        segments: usize,
        up: &str,
    ) -> PyResult<PathBuf> {
        let up = meshio::UpAxis::from_str(up).map_err(usage)?;
        let format = fitjob::output::mesh_format_for("path", &path).map_err(job_error)?;
        fitjob::output::refuse_unstorable_curvature("path", &path, format, self.frame.scale)
            .map_err(job_error)?;
        let tess = self.tessellation(py, segments)?;
        let written = py.detach(|| -> Result<(), fitjob::JobError> {
            let raw = fitjob::output::tessellation_mesh(&tess, format);
            let options = fitjob::output::MeshOutputOptions { up }.write_options();
            // Streamed into the file as it is encoded (no copy of the file's bytes in memory).
            fitjob::output::write_mesh_result(&path, format, &raw, &options)
        });
        written.map_err(job_error)?;
        Ok(path)
    }

    /// The fallback faces with their reasons (from the report).
    #[getter]
    fn fallback_faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let r = self.report(py)?;
        let list = r.bind(py).get_item("fallback_faces")?;
        Ok(list.cast_into::<PyList>()?.into_any())
    }

    fn __repr__(&self) -> String {
        let scheme = self.fit.as_ref().map(|f| f.scheme).unwrap_or("subdivision");
        match &self.mesh {
            Some(m) => format!(
                "Fit({scheme}: {} faces, {} patches)",
                m.num_faces(),
                self.fit.as_ref().map_or(0, |f| f.num_patches())
            ),
            None => format!("Fit({scheme})"),
        }
    }
}

impl Fit {
    /// The kept fit tessellated at `segments` in world coordinates (memory checked first).
    fn tessellation(&self, py: Python<'_>, segments: usize) -> PyResult<surface::Tessellation> {
        let (mesh, fit) = self.kept()?;
        fitjob::limits::check_usize("segments", segments, &fitjob::limits::SAMPLING_RANGE)
            .map_err(job_error)?;
        fitjob::limits::check_memory(
            &format!("segments={segments}"),
            fitjob::limits::tessellation_bytes(fit.num_patches() as u128, segments),
        )
        .map_err(job_error)?;
        let frame = self.frame;
        let tess = py.detach(|| surface::tessellate_fit(mesh, fit, segments));
        let mut tess = tess.map_err(|e| failed(format!("tessellation failed: {e}")))?;
        tess.to_world(&frame);
        Ok(tess)
    }
}
