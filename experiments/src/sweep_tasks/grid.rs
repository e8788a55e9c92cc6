//! The sweep's parameter grid and its task list: every mesh of `--data` (data sets at each
//! `--resolution`, mesh files as they are) × every `--scheme` × every value of each scheme
//! parameter that scheme reads (`--beta`, `--c`, `--phong-alpha`, …: generated from the scheme
//! registry) × every `--curves` construction for schemes on cubic edge curves × every
//! `--solver` for the construction that takes one × every `-s, --segments` tessellation
//! density (not for subdivision schemes, measured at the limit of three levels).
//!
//! An axis a task does not read collapses for it: a scheme without edge curves runs once
//! (curves `none`), a construction without a solver once (solver `null`), a subdivision scheme
//! once per mesh. The lists come from the command line (comma-separated or the option
//! repeated), a TOML file (`--grid FILE.toml`, one key an axis, a value or an array) or a JSON
//! object of the same keys and values (the library's callers, [`axes_from_json`]); an
//! axis given on the command line replaces the file's. No list may hold an item twice, and an
//! axis no task of the grid reads (a `--solver` list without `optimized`, `--beta` without a
//! scheme that reads β) is refused: the options record what was run, exactly.
//!
//! The task order is data × resolution × scheme × parameter values (in the registry's order
//! of parameters) × curves (registry order) × solver × segments, so the default grid holds the
//! twenty tasks of the ring study's sweep in their old order (with the constructions added to
//! the registry since between them). A task's id names its data and
//! construction and only the parameters that differ from their defaults (`ring/optimized/lm`,
//! `sphere@3/phong/alpha=0.5`, `bunny.ply/chord/s=8`): a function of the task alone, the same
//! in every grid that holds it.

use std::path::{Path, PathBuf};

use serde_json::{json, Map, Value};
use solver::SolverKind;
use surface::fairing::InteriorChoice;
use surface::scheme::ParameterSpec;

use crate::study::StudyError;

/// Whether the grid runs construction `c` once per `--solver` (it takes a solver:
/// [`curves::CurveMethod::takes_solver`]) or once.
fn solved(c: &str) -> bool {
    curves::takes_solver(c)
}

/// Default tessellation density of the sweep's measurements (segments per patch edge).
pub const DEFAULT_SEGMENTS: usize = 4;

/// The curve name of a task without edge curves (a subdivision scheme, a scheme on none).
pub const NO_CURVES: &str = "none";

/// Most tasks a grid may have: the manifest and a merge hold every task's record (about 1 kB
/// each), so 100 000 tasks stay near 100 MB; a longer grid is a mistake or a job for several
/// sweeps.
pub const MAX_TASKS: usize = 100_000;

/// Most bytes of a grid file: a grid is a few lines; a larger file is not one.
pub const MAX_GRID_BYTES: u64 = 1 << 20;

/// The axes of a grid, as given (`None`: not given, the default applies).
#[derive(Clone, Debug, Default)]
pub struct Axes {
    /// Data sets and mesh files.
    pub data: Option<Vec<String>>,
    /// Resolutions of the named data sets.
    pub resolution: Option<Vec<usize>>,
    /// Schemes.
    pub scheme: Option<Vec<String>>,
    /// Curve constructions.
    pub curves: Option<Vec<String>>,
    /// Solvers of the constructions that take one ([`solved`]).
    pub solver: Option<Vec<String>>,
    /// Segments per patch edge.
    pub segments: Option<Vec<usize>>,
    /// Values of each scheme parameter, by its name (`beta`, `phong-alpha`).
    pub parameters: Vec<(&'static ParameterSpec, Vec<f64>)>,
    /// How every task sets its interior parameters.
    pub interior: Option<InteriorChoice>,
    /// The estimator completing mesh files.
    pub estimate: Option<String>,
}

impl Axes {
    /// These axes over `base` (a grid file's): every axis given here replaces `base`'s.
    pub fn over(self, base: Axes) -> Axes {
        let mut parameters = base.parameters;
        for (p, values) in self.parameters {
            parameters.retain(|(q, _)| q.name != p.name);
            parameters.push((p, values));
        }
        Axes {
            data: self.data.or(base.data),
            resolution: self.resolution.or(base.resolution),
            scheme: self.scheme.or(base.scheme),
            curves: self.curves.or(base.curves),
            solver: self.solver.or(base.solver),
            segments: self.segments.or(base.segments),
            parameters,
            interior: self.interior.or(base.interior),
            estimate: self.estimate.or(base.estimate),
        }
    }
}

/// A grid with every axis settled and checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Data sets and mesh files, in order.
    pub data: Vec<String>,
    /// Resolutions of the named data sets (`None`: each its default).
    pub resolution: Vec<Option<usize>>,
    /// Schemes.
    pub schemes: Vec<String>,
    /// Curve constructions.
    pub curves: Vec<String>,
    /// Solvers.
    pub solvers: Vec<SolverKind>,
    /// Every parameter some scheme of the grid reads, with its values.
    pub parameters: Vec<(&'static ParameterSpec, Vec<f64>)>,
    /// Segments per patch edge.
    pub segments: Vec<usize>,
    /// The interior choice.
    pub interior: InteriorChoice,
    /// The estimator of mesh files.
    pub estimate: String,
}

/// One task of a grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Task {
    /// Its position in the grid's order.
    pub index: usize,
    /// Its id (`data[@resolution]/[scheme/][name=value/…]curves[/solver][/s=N]`).
    pub id: String,
    /// The data set's name or the mesh file's path, as given.
    pub data: String,
    /// Whether `data` is a mesh file (no true surface, no resolution).
    pub file: bool,
    /// The data set's resolution (`None`: its default, or a file).
    pub resolution: Option<usize>,
    /// The scheme.
    pub scheme: String,
    /// Whether it is a subdivision scheme.
    pub subdivision: bool,
    /// The values of the parameters the scheme reads, in registry order.
    pub parameters: Vec<(&'static ParameterSpec, f64)>,
    /// The curve construction (`None`: the scheme takes no edge curves).
    pub curves: Option<String>,
    /// The solver (only for a construction that takes one, [`solved`]).
    pub solver: Option<SolverKind>,
    /// Segments per patch edge (`None` for subdivision, measured at its limit).
    pub segments: Option<usize>,
    /// The interior choice.
    pub interior: InteriorChoice,
}

impl Task {
    /// The task's identity as JSON: what the manifest lists and every result line repeats, so
    /// `merge` can check a line is the task it claims to be.
    pub fn identity(&self) -> Value {
        let mut parameters = Map::new();
        for (p, v) in &self.parameters {
            parameters.insert(p.key(), json!(v));
        }
        json!({
            "index": self.index,
            "task": self.id,
            "dataset": self.data,
            "file": self.file,
            "resolution": self.resolution,
            "scheme": self.scheme,
            "subdivision": self.subdivision,
            "parameters": parameters,
            "curves": self.curves.as_deref().unwrap_or(NO_CURVES),
            "solver": self.solver.map(SolverKind::name),
            "segments": self.segments,
            "interior": self.interior.to_string(),
        })
    }
}

/// Whether `scheme` is a subdivision scheme (`subdiv::SCHEMES`), not a Bézier or sampled
/// surface scheme.
pub fn is_subdivision(scheme: &str) -> bool {
    !surface::scheme_names().contains(&scheme) && subdiv::scheme_by_name(scheme).is_ok()
}

/// Whether `data` names a mesh file (an existing file; any other name is a data set, the fit
/// job's rule).
pub fn is_file(data: &str) -> bool {
    Path::new(data).is_file()
}

/// A number as ids and messages write it: the shortest form that reads back the same.
fn shown(x: f64) -> String {
    format!("{x}")
}

/// A task's id: `data[@resolution]/[scheme/][name=value/…]curves[/solver][/s=N]`, with the
/// scheme only when it is not the default, each parameter only when it is not its default,
/// and the segments only when not [`DEFAULT_SEGMENTS`].
#[allow(clippy::too_many_arguments)]
fn task_id(
    data: &str,
    resolution: Option<usize>,
    scheme: &str,
    parameters: &[(&'static ParameterSpec, f64)],
    curves: Option<&str>,
    solver: Option<SolverKind>,
    segments: Option<usize>,
) -> String {
    let mut parts = vec![match resolution {
        Some(r) => format!("{data}@{r}"),
        None => data.to_string(),
    }];
    if scheme != surface::DEFAULT_SCHEME {
        parts.push(scheme.to_string());
    }
    for (p, v) in parameters {
        if *v != p.default {
            parts.push(format!("{}={}", p.name, shown(*v)));
        }
    }
    parts.push(curves.unwrap_or(NO_CURVES).to_string());
    if let Some(s) = solver {
        parts.push(s.name().to_string());
    }
    if let Some(s) = segments.filter(|s| *s != DEFAULT_SEGMENTS) {
        parts.push(format!("s={s}"));
    }
    parts.join("/")
}

/// Whether a scheme builds its patches on edge curves.
fn uses_curves(scheme: &str) -> bool {
    surface::scheme_by_name(scheme, &surface::SchemeOptions::default())
        .is_ok_and(|s| s.uses_curves())
}

fn bad(option: &str, value: impl std::fmt::Display, why: impl Into<String>) -> StudyError {
    StudyError::BadValue {
        option: option.to_string(),
        value: value.to_string(),
        why: why.into(),
    }
}

impl Grid {
    /// Settles `axes` (defaults where not given) and checks them: known names, values in
    /// range, no item twice, no axis that no task reads, at most [`MAX_TASKS`] tasks.
    pub fn new(axes: Axes) -> Result<Grid, StudyError> {
        use crate::study::{refuse_duplicate_names, refuse_duplicate_numbers};
        let data = axes.data.unwrap_or_else(|| {
            crate::datasets::all()
                .iter()
                .map(|s| s.to_string())
                .collect()
        });
        let data: Vec<String> = data.iter().map(|d| d.trim().to_string()).collect();
        refuse_duplicate_names("--data", &data)?;
        if data.is_empty() {
            return Err(bad("--data", "", "an empty list"));
        }
        let named = data.iter().filter(|d| !is_file(d)).count();
        let resolution = match axes.resolution {
            None => vec![None],
            Some(r) => {
                refuse_duplicate_numbers("--resolution", &r)?;
                if named == 0 {
                    return Err(bad(
                        "--resolution",
                        r.iter()
                            .map(|x| x.to_string())
                            .collect::<Vec<_>>()
                            .join(","),
                        "no data set in --data (mesh files have no resolution)",
                    ));
                }
                r.into_iter().map(Some).collect()
            }
        };
        let schemes: Vec<String> = axes
            .scheme
            .unwrap_or_else(|| vec![surface::DEFAULT_SCHEME.to_string()])
            .iter()
            .map(|s| s.trim().to_string())
            .collect();
        refuse_duplicate_names("--scheme", &schemes)?;
        for s in &schemes {
            if !surface::scheme_names().contains(&s.as_str()) && !is_subdivision(s) {
                let known: Vec<&str> = surface::scheme_names()
                    .into_iter()
                    .chain(subdiv::SCHEMES.iter().map(|e| e.name))
                    .collect();
                return Err(bad(
                    "--scheme",
                    s,
                    format!("not a scheme; known: {}", known.join(", ")),
                ));
            }
        }
        let with_curves = schemes.iter().any(|s| !is_subdivision(s) && uses_curves(s));
        let curves_given = axes.curves.is_some();
        let curves: Vec<String> = axes
            .curves
            .unwrap_or_else(|| {
                curves::REGISTRY
                    .iter()
                    .map(|e| e.name.to_string())
                    .collect()
            })
            .iter()
            .map(|s| s.trim().to_string())
            .collect();
        refuse_duplicate_names("--curves", &curves)?;
        for c in &curves {
            if !curves::REGISTRY.iter().any(|e| e.name == c) {
                return Err(bad(
                    "--curves",
                    c,
                    format!(
                        "not a construction; known: {}",
                        crate::curve_args::all_methods()
                    ),
                ));
            }
        }
        if curves_given && !with_curves {
            return Err(bad(
                "--curves",
                curves.join(","),
                "no scheme of the grid builds on edge curves",
            ));
        }
        let solver_names = axes.solver.clone();
        let solvers: Vec<SolverKind> = match &axes.solver {
            None => SolverKind::ALL.to_vec(),
            Some(names) => {
                let names: Vec<String> = names.iter().map(|s| s.trim().to_string()).collect();
                refuse_duplicate_names("--solver", &names)?;
                names
                    .iter()
                    .map(|n| {
                        n.parse()
                            .map_err(|e: solver::UnknownSolver| bad("--solver", n, e.to_string()))
                    })
                    .collect::<Result<_, _>>()?
            }
        };
        if solver_names.is_some() && !(with_curves && curves.iter().any(|c| solved(c))) {
            let takers: Vec<&str> = curves::REGISTRY
                .iter()
                .map(|e| e.name)
                .filter(|n| solved(n))
                .collect();
            return Err(bad(
                "--solver",
                solvers
                    .iter()
                    .map(|s| s.name())
                    .collect::<Vec<_>>()
                    .join(","),
                format!(
                    "no task of the grid runs a construction that takes a solver ({})",
                    takers.join(", ")
                ),
            ));
        }
        // Parameters: every one a scheme of the grid reads, at its default unless given; one
        // given that no scheme reads is refused.
        let read: Vec<&'static ParameterSpec> =
            surface::scheme::parameters_of(surface::scheme::REGISTRY)
                .into_iter()
                .filter(|(_, owners)| owners.iter().any(|o| schemes.iter().any(|s| s == o)))
                .map(|(p, _)| p)
                .collect();
        for (p, values) in &axes.parameters {
            if !read.iter().any(|q| q.name == p.name) {
                let owners: Vec<&str> = surface::scheme::parameters_of(surface::scheme::REGISTRY)
                    .into_iter()
                    .find(|(q, _)| q.name == p.name)
                    .map(|(_, o)| o)
                    .unwrap_or_default();
                return Err(bad(
                    &format!("--{}", p.name),
                    values
                        .iter()
                        .map(|v| shown(*v))
                        .collect::<Vec<_>>()
                        .join(","),
                    format!(
                        "no scheme of the grid reads it (read by {})",
                        owners.join(", ")
                    ),
                ));
            }
            refuse_duplicate_numbers(&format!("--{}", p.name), values)?;
            if values.is_empty() {
                return Err(bad(&format!("--{}", p.name), "", "an empty list"));
            }
            if let Some(v) = values.iter().find(|v| !p.accepts(**v)) {
                return Err(bad(
                    &format!("--{}", p.name),
                    shown(*v),
                    format!(
                        "outside its valid range [{}, {}] ({})",
                        p.range.0, p.range.1, p.range_reason
                    ),
                ));
            }
        }
        let parameters: Vec<(&'static ParameterSpec, Vec<f64>)> = read
            .into_iter()
            .map(|p| {
                let values = axes
                    .parameters
                    .iter()
                    .find(|(q, _)| q.name == p.name)
                    .map(|(_, v)| v.clone())
                    .unwrap_or_else(|| vec![p.default]);
                (p, values)
            })
            .collect();
        let segments = axes.segments.unwrap_or_else(|| vec![DEFAULT_SEGMENTS]);
        refuse_duplicate_numbers("--segments", &segments)?;
        if let Some(s) = segments
            .iter()
            .find(|s| !crate::limits::SAMPLING_RANGE.contains(s))
        {
            return Err(bad(
                "--segments",
                s,
                format!(
                    "outside its valid range [{}, {}]",
                    crate::limits::SAMPLING_RANGE.start(),
                    crate::limits::SAMPLING_RANGE.end()
                ),
            ));
        }
        if segments.is_empty() {
            return Err(bad("--segments", "", "an empty list"));
        }
        let estimate = axes
            .estimate
            .unwrap_or_else(|| estimate::DEFAULT_ESTIMATOR.to_string());
        estimate::EstimateChoice::parse(&estimate)
            .map_err(|e| bad("--estimate", &estimate, e.to_string()))?;
        let grid = Grid {
            data,
            resolution,
            schemes,
            curves,
            solvers,
            parameters,
            segments,
            interior: axes.interior.unwrap_or_default(),
            estimate,
        };
        let n = grid.count();
        if n > MAX_TASKS as u128 {
            return Err(StudyError::TooManyTasks {
                tasks: n,
                max: MAX_TASKS,
            });
        }
        Ok(grid)
    }

    /// The values of every parameter `scheme` reads, each combination once (the product, in
    /// registry order; the first parameter varies slowest).
    fn parameter_sets(&self, scheme: &str) -> Vec<Vec<(&'static ParameterSpec, f64)>> {
        let Ok(entry) = surface::scheme::entry_by_name(scheme) else {
            return vec![Vec::new()];
        };
        let mut sets: Vec<Vec<(&'static ParameterSpec, f64)>> = vec![Vec::new()];
        for (p, values) in &self.parameters {
            if !entry.parameters.iter().any(|q| q.name == p.name) {
                continue;
            }
            sets = sets
                .into_iter()
                .flat_map(|set| {
                    values.iter().map(move |v| {
                        let mut s = set.clone();
                        s.push((*p, *v));
                        s
                    })
                })
                .collect();
        }
        sets
    }

    /// The number of tasks, counted without making them (saturating).
    pub fn count(&self) -> u128 {
        let mut per_mesh: u128 = 0;
        for scheme in &self.schemes {
            let sets = self.parameter_sets_count(scheme);
            let runs: u128 = if is_subdivision(scheme) {
                1
            } else if uses_curves(scheme) {
                let constructions: u128 = self
                    .curves
                    .iter()
                    .map(|c| {
                        if solved(c) {
                            self.solvers.len() as u128
                        } else {
                            1
                        }
                    })
                    .sum();
                constructions.saturating_mul(self.segments.len() as u128)
            } else {
                self.segments.len() as u128
            };
            per_mesh = per_mesh.saturating_add(sets.saturating_mul(runs));
        }
        let named = self.data.iter().filter(|d| !is_file(d)).count() as u128;
        let files = self.data.len() as u128 - named;
        let meshes = named
            .saturating_mul(self.resolution.len() as u128)
            .saturating_add(files);
        meshes.saturating_mul(per_mesh)
    }

    fn parameter_sets_count(&self, scheme: &str) -> u128 {
        let Ok(entry) = surface::scheme::entry_by_name(scheme) else {
            return 1;
        };
        self.parameters
            .iter()
            .filter(|(p, _)| entry.parameters.iter().any(|q| q.name == p.name))
            .fold(1u128, |n, (_, v)| n.saturating_mul(v.len() as u128))
    }

    /// Every task, in the grid's order ([`Grid::count`] of them, at most [`MAX_TASKS`]);
    /// refused when two would have the same id (two files of the same path spelled apart).
    pub fn tasks(&self) -> Result<Vec<Task>, StudyError> {
        let mut out: Vec<Task> = Vec::new();
        for data in &self.data {
            let file = is_file(data);
            let resolutions: Vec<Option<usize>> = if file {
                vec![None]
            } else {
                self.resolution.clone()
            };
            for resolution in resolutions {
                for scheme in &self.schemes {
                    let subdivision = is_subdivision(scheme);
                    for parameters in self.parameter_sets(scheme) {
                        let mut push = |curves: Option<&str>, solver, segments| {
                            out.push(Task {
                                index: out.len(),
                                id: task_id(
                                    data,
                                    resolution,
                                    scheme,
                                    &parameters,
                                    curves,
                                    solver,
                                    segments,
                                ),
                                data: data.clone(),
                                file,
                                resolution,
                                scheme: scheme.clone(),
                                subdivision,
                                parameters: parameters.clone(),
                                curves: curves.map(str::to_string),
                                solver,
                                segments,
                                interior: self.interior,
                            })
                        };
                        if subdivision {
                            push(None, None, None);
                        } else if uses_curves(scheme) {
                            for c in &self.curves {
                                let solvers: Vec<Option<SolverKind>> = if solved(c) {
                                    self.solvers.iter().copied().map(Some).collect()
                                } else {
                                    vec![None]
                                };
                                for solver in solvers {
                                    for s in &self.segments {
                                        push(Some(c), solver, Some(*s));
                                    }
                                }
                            }
                        } else {
                            for s in &self.segments {
                                push(None, None, Some(*s));
                            }
                        }
                    }
                }
            }
        }
        let mut seen = std::collections::HashMap::new();
        for t in &out {
            if let Some(first) = seen.insert(t.id.clone(), t.index) {
                return Err(StudyError::SameId {
                    id: t.id.clone(),
                    first,
                    second: t.index,
                });
            }
        }
        Ok(out)
    }

    /// The grid as the options JSON of its reports, shard lines and manifest: every axis as
    /// run (the parameters some scheme of the grid reads, under their JSON keys).
    pub fn json(&self) -> Value {
        let mut v = json!({
            "data": self.data,
            "resolution": self.resolution,
            "scheme": self.schemes,
            "curves": self.curves,
            "solver": self.solvers.iter().map(|s| s.name()).collect::<Vec<_>>(),
        });
        for (p, values) in &self.parameters {
            v[p.key()] = json!(values);
        }
        v["segments"] = json!(self.segments);
        v["interior"] = json!(self.interior.to_string());
        v["estimate"] = json!(self.estimate);
        v
    }
}

/// The line (1-based) of byte `offset` of `text`.
fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|b| **b == b'\n')
        .count()
        + 1
}

/// Reads a grid file: TOML, one key an axis (`data`, `resolution`, `scheme`, `curves`,
/// `solver`, `segments`, a scheme parameter's name such as `beta` or `phong-alpha` — or with
/// `_` —, `interior`, `estimate`), each a value or an array of values. Unknown keys, wrong
/// types and tables are refused with the line.
pub fn read_grid_file(path: &Path) -> Result<Axes, StudyError> {
    let err = |message: String| StudyError::Grid {
        path: path.to_path_buf(),
        message,
    };
    // The type first: a FIFO would block the read forever.
    let meta = std::fs::metadata(path).map_err(|e| err(format!("cannot read: {e}")))?;
    if let Some(kind) =
        crate::study::special_kind(meta.file_type()).or(meta.is_dir().then_some("a directory"))
    {
        return Err(err(format!("not a regular file ({kind})")));
    }
    if meta.len() > MAX_GRID_BYTES {
        return Err(err(format!(
            "{} bytes: longer than the {MAX_GRID_BYTES} a grid file may have",
            meta.len()
        )));
    }
    let text = std::fs::read_to_string(path).map_err(|e| err(format!("cannot read: {e}")))?;
    parse_grid(&text).map_err(err)
}

/// One item of a grid key's value, a grid file's or a JSON grid's: what the axes read of it.
#[derive(Clone, Copy)]
enum Item<'a> {
    /// A string.
    Str(&'a str),
    /// An integer (TOML's are `i64`, JSON's `i64` or `u64`).
    Int(i128),
    /// A floating-point number.
    Float(f64),
    /// Anything else (a boolean, a date, an array in an array, an inline table, JSON's null).
    Other,
}

/// A grid key's value as given: a table, one value, or an array of values.
enum Given<'a> {
    /// A table (a TOML `[key]`, a JSON object): never an axis.
    Table,
    /// One value, not in an array.
    One(Item<'a>),
    /// An array of values.
    Array(Vec<Item<'a>>),
}

/// Sets axis `key` of `axes` from its value as `given`: the one reading of a grid's keys, for
/// grid files ([`parse_grid`]) and JSON grids ([`axes_from_json`]) alike. `at` puts where the
/// key is (a grid file's line) before a message.
fn set_axis(
    axes: &mut Axes,
    key: &str,
    given: Given<'_>,
    at: impl Fn(String) -> String,
) -> Result<(), String> {
    let params = surface::scheme::parameters_of(surface::scheme::REGISTRY);
    let (values, one): (Vec<Item<'_>>, Option<&str>) = match given {
        Given::Table => {
            return Err(at(
                "expected a value or an array of values, not a table".into()
            ))
        }
        Given::One(v @ Item::Str(s)) => (vec![v], Some(s)),
        Given::One(v) => (vec![v], None),
        Given::Array(a) => (a, None),
    };
    let strings = || -> Result<Vec<String>, String> {
        values
            .iter()
            .map(|v| match v {
                Item::Str(s) => Ok(s.to_string()),
                _ => Err(at("expected strings".into())),
            })
            .collect()
    };
    let counts = || -> Result<Vec<usize>, String> {
        values
            .iter()
            .map(|v| match v {
                Item::Int(i) => usize::try_from(*i).ok(),
                _ => None,
            })
            .map(|c| c.ok_or_else(|| at("expected non-negative integers".into())))
            .collect()
    };
    let one = |what: &str| -> Result<String, String> {
        one.map(str::to_string)
            .ok_or_else(|| at(format!("expected one string ({what})")))
    };
    match key {
        "data" => axes.data = Some(strings()?),
        "resolution" => axes.resolution = Some(counts()?),
        "scheme" => axes.scheme = Some(strings()?),
        "curves" => axes.curves = Some(strings()?),
        "solver" => axes.solver = Some(strings()?),
        "segments" => axes.segments = Some(counts()?),
        "interior" => {
            axes.interior = Some(
                one("default, thin-plate or membrane")?
                    .parse()
                    .map_err(&at)?,
            )
        }
        "estimate" => axes.estimate = Some(one("an estimator's name")?),
        _ => {
            let Some((p, _)) = params.iter().find(|(p, _)| p.name == key || p.key() == key) else {
                let mut known = vec![
                    "data",
                    "resolution",
                    "scheme",
                    "curves",
                    "solver",
                    "segments",
                    "interior",
                    "estimate",
                ];
                known.extend(params.iter().map(|(p, _)| p.name));
                return Err(at(format!("not a grid key; known: {}", known.join(", "))));
            };
            // Both spellings of one parameter (`phong-alpha`, `phong_alpha`) are one axis.
            if axes.parameters.iter().any(|(q, _)| q.name == p.name) {
                return Err(at(format!(
                    "`{}` is given twice (a grid names each parameter once, as `{}` or `{}`)",
                    p.name,
                    p.name,
                    p.key()
                )));
            }
            let numbers: Vec<f64> = values
                .iter()
                .map(|v| match v {
                    Item::Float(x) => Ok(*x),
                    Item::Int(i) => Ok(*i as f64),
                    _ => Err(at("expected numbers".into())),
                })
                .collect::<Result<_, _>>()?;
            axes.parameters.push((*p, numbers));
        }
    }
    Ok(())
}

/// A TOML value as a grid item.
fn toml_item(v: &toml_edit::Value) -> Item<'_> {
    match v {
        toml_edit::Value::String(s) => Item::Str(s.value()),
        toml_edit::Value::Integer(i) => Item::Int(i128::from(*i.value())),
        toml_edit::Value::Float(x) => Item::Float(*x.value()),
        _ => Item::Other,
    }
}

/// A JSON value as a grid item (`4` is an integer, `4.0` a float, as in TOML).
fn json_item(v: &Value) -> Item<'_> {
    match v {
        Value::String(s) => Item::Str(s),
        Value::Number(n) => match (n.as_i64(), n.as_u64(), n.as_f64()) {
            (Some(i), _, _) => Item::Int(i128::from(i)),
            (None, Some(u), _) => Item::Int(i128::from(u)),
            (None, None, Some(x)) => Item::Float(x),
            (None, None, None) => Item::Other,
        },
        _ => Item::Other,
    }
}

/// A grid file's text read as [`Axes`] (the message names the line and key on failure).
pub fn parse_grid(text: &str) -> Result<Axes, String> {
    let doc: toml_edit::Document<String> = text
        .parse()
        .map_err(|e: toml_edit::TomlError| format!("not TOML: {}", e.to_string().trim_end()))?;
    let mut axes = Axes::default();
    for (key, item) in doc.iter() {
        let line = item
            .span()
            .or_else(|| doc.key(key).and_then(|k| k.span()))
            .map_or(0, |s| line_of(text, s.start));
        let given = match item {
            toml_edit::Item::Value(toml_edit::Value::Array(a)) => {
                Given::Array(a.iter().map(toml_item).collect())
            }
            toml_edit::Item::Value(v) => Given::One(toml_item(v)),
            _ => Given::Table,
        };
        set_axis(&mut axes, key, given, |m| {
            format!("line {line}: `{key}`: {m}")
        })?;
    }
    Ok(axes)
}

/// A grid given as a JSON object read as [`Axes`]: the keys and values of a grid file
/// ([`parse_grid`]; `{"data": ["octa"], "beta": [0.2, 0.5], "segments": 4}`), read by the same
/// code, so a bad key or value gets the grid file's message (without a line: `` `betta`: not a
/// grid key; known: … ``).
pub fn axes_from_json(v: &Value) -> Result<Axes, String> {
    let Some(object) = v.as_object() else {
        let kind = match v {
            Value::Null => "null",
            Value::Bool(_) => "a boolean",
            Value::Number(_) => "a number",
            Value::String(_) => "a string",
            Value::Array(_) => "an array",
            Value::Object(_) => "an object",
        };
        return Err(format!(
            "expected a JSON object of axes (the keys of a grid file), not {kind}"
        ));
    };
    let mut axes = Axes::default();
    for (key, value) in object {
        let given = match value {
            Value::Object(_) => Given::Table,
            Value::Array(a) => Given::Array(a.iter().map(json_item).collect()),
            v => Given::One(json_item(v)),
        };
        set_axis(&mut axes, key, given, |m| format!("`{key}`: {m}"))?;
    }
    Ok(axes)
}

/// The manifest of `tasks` of `grid`: what `sweep --list-tasks` writes and `merge` checks
/// every result line against.
pub fn manifest(grid: &Grid, tasks: &[Task]) -> Value {
    json!({
        "experiment": "sweep",
        "options": grid.json(),
        "tasks_total": tasks.len(),
        "tasks": tasks.iter().map(Task::identity).collect::<Vec<_>>(),
    })
}

/// The manifest file of a sweep's directory.
pub fn manifest_path(dir: &Path) -> PathBuf {
    dir.join(MANIFEST)
}

/// The name of the manifest file a sweep writes into its directory.
pub const MANIFEST: &str = "tasks.json";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_grid_is_every_construction_on_every_data_set() {
        let grid = Grid::new(Axes::default()).unwrap();
        let tasks = grid.tasks().unwrap();
        // Four data sets × every registered construction, those that take a solver once per
        // solver (3): the twenty tasks of old (chord, dbhs, optimized) and the rest.
        let per_set = curves::REGISTRY
            .iter()
            .map(|e| if curves::takes_solver(e.name) { 3 } else { 1 })
            .sum::<usize>();
        assert_eq!(tasks.len(), 4 * per_set);
        assert_eq!(grid.count(), 4 * per_set as u128);
        let ids: Vec<&str> = tasks.iter().map(|t| t.id.as_str()).collect();
        assert_eq!(
            &ids[..5],
            [
                "ring/chord",
                "ring/dbhs",
                "ring/optimized/exact-penalty",
                "ring/optimized/lbfgs",
                "ring/optimized/lm"
            ]
        );
        assert_eq!(ids[3 * per_set + 4], "octa/optimized/lm");
        assert_eq!(ids[4 * per_set - 1], "octa/quadric");
        // The options record the axes run: β and c (read by the scheme), not φ's α.
        let o = grid.json();
        assert!(o.get("beta").is_some() && o.get("c").is_some(), "{o}");
        assert!(o.get("phong_alpha").is_none(), "{o}");
    }

    #[test]
    fn axes_multiply_and_collapse_where_a_task_does_not_read_them() {
        let axes = Axes {
            data: Some(vec!["octa".into()]),
            scheme: Some(vec!["shirman-sequin".into(), "phong".into(), "loop".into()]),
            curves: Some(vec!["chord".into(), "optimized".into()]),
            solver: Some(vec!["lm".into()]),
            segments: Some(vec![2, 4]),
            parameters: vec![(&surface::scheme::shirman_sequin::BETA, vec![0.2, 1.0 / 3.0])],
            ..Axes::default()
        };
        let grid = Grid::new(axes).unwrap();
        let tasks = grid.tasks().unwrap();
        // shirman-sequin: 2 β × 2 constructions × 2 segments; phong: 2 segments; loop: 1.
        assert_eq!(tasks.len(), 8 + 2 + 1);
        assert_eq!(grid.count(), 11);
        assert_eq!(tasks[0].id, "octa/beta=0.2/chord/s=2");
        assert_eq!(tasks[3].id, "octa/beta=0.2/optimized/lm");
        assert_eq!(tasks[4].id, "octa/chord/s=2");
        assert_eq!(tasks[8].id, "octa/phong/none/s=2");
        assert_eq!(tasks[10].id, "octa/loop/none");
        assert!(tasks.iter().enumerate().all(|(k, t)| t.index == k));
    }

    #[test]
    fn lists_with_repeats_and_axes_nothing_reads_are_refused() {
        let refused = |axes: Axes| Grid::new(axes).unwrap_err().to_string();
        let e = refused(Axes {
            data: Some(vec!["ring".into(), "ring".into()]),
            ..Axes::default()
        });
        assert!(e.starts_with("--data: `ring` is given twice"), "{e}");
        let e = refused(Axes {
            segments: Some(vec![4, 8, 4]),
            ..Axes::default()
        });
        assert!(e.starts_with("--segments: `4` is given twice"), "{e}");
        let e = refused(Axes {
            curves: Some(vec!["chord".into()]),
            solver: Some(vec!["lm".into()]),
            ..Axes::default()
        });
        assert!(
            e.contains("--solver: `lm`: no task of the grid runs"),
            "{e}"
        );
        let e = refused(Axes {
            parameters: vec![(&surface::scheme::phong::ALPHA, vec![0.5])],
            ..Axes::default()
        });
        assert!(
            e.contains("--phong-alpha: `0.5`: no scheme of the grid reads it"),
            "{e}"
        );
        let e = refused(Axes {
            parameters: vec![(&surface::scheme::shirman_sequin::BETA, vec![1e308])],
            ..Axes::default()
        });
        assert!(e.contains("outside its valid range"), "{e}");
        let e = refused(Axes {
            segments: Some(vec![0]),
            ..Axes::default()
        });
        assert!(
            e.contains("--segments: `0`: outside its valid range [1, 256]"),
            "{e}"
        );
        let e = refused(Axes {
            scheme: Some(vec!["bogus".into()]),
            ..Axes::default()
        });
        assert!(e.contains("not a scheme; known:"), "{e}");
    }

    #[test]
    fn json_grids_are_read_as_grid_files_are() {
        let file = parse_grid(
            "data = [\"octa\", \"sphere\"]\nscheme = \"shirman-sequin\"\nbeta = [0.2, 0.5]\nc = 1\nsegments = [2, 4]\ninterior = \"default\"\n",
        )
        .unwrap();
        let json = axes_from_json(&json!({
            "data": ["octa", "sphere"],
            "scheme": "shirman-sequin",
            "beta": [0.2, 0.5],
            "c": 1,
            "segments": [2, 4],
            "interior": "default",
        }))
        .unwrap();
        let (file, json) = (Grid::new(file).unwrap(), Grid::new(json).unwrap());
        assert_eq!(file, json);
        // 2 data × 2 β × every construction (those that take a solver with 3) × 2 segments.
        assert_eq!(
            json.count(),
            2 * 2
                * (curves::REGISTRY
                    .iter()
                    .map(|e| if curves::takes_solver(e.name) { 3 } else { 1 })
                    .sum::<usize>() as u128)
                * 2
        );
        // Every refusal of a grid file, with its message after the line.
        for (toml, v) in [
            ("betta = 0.2", json!({"betta": 0.2})),
            ("segments = [\"four\"]", json!({"segments": ["four"]})),
            ("segments = 4.0", json!({"segments": 4.0})),
            ("resolution = [-3]", json!({"resolution": [-3]})),
            ("beta = \"x\"", json!({"beta": "x"})),
            ("data = [[\"octa\"]]", json!({"data": [["octa"]]})),
            ("data = true", json!({"data": true})),
            ("interior = [\"default\"]", json!({"interior": ["default"]})),
            ("interior = \"bogus\"", json!({"interior": "bogus"})),
            ("estimate = 3", json!({"estimate": 3})),
            ("[beta]\nx = 1", json!({"beta": {"x": 1}})),
            (
                "phong-alpha = 0.5\nphong_alpha = 0.6",
                json!({"phong-alpha": 0.5, "phong_alpha": 0.6}),
            ),
        ] {
            let from_file = parse_grid(toml).unwrap_err();
            let from_json = axes_from_json(&v).unwrap_err();
            let (_, message) = from_file.split_once(": ").unwrap();
            assert_eq!(message, from_json, "{toml}");
            assert!(from_file.starts_with("line "), "{from_file}");
        }
        let e = axes_from_json(&json!({"phong_alpha": 0.5, "phong-alpha": 0.6})).unwrap_err();
        assert!(
            e.starts_with("`phong-alpha`: `phong-alpha` is given twice"),
            "{e}"
        );
        let e = axes_from_json(&json!(["octa"])).unwrap_err();
        assert_eq!(
            e,
            "expected a JSON object of axes (the keys of a grid file), not an array"
        );
        // JSON's unsigned integers beyond TOML's reach are counts too.
        let big = axes_from_json(&json!({"segments": u64::MAX})).unwrap();
        assert_eq!(big.segments, Some(vec![usize::try_from(u64::MAX).unwrap()]));
    }

    #[test]
    fn a_grid_longer_than_the_limit_is_refused_before_its_tasks_are_made() {
        let axes = Axes {
            resolution: Some((3..3000).collect()),
            segments: Some((1..=256).collect()),
            ..Axes::default()
        };
        let e = Grid::new(axes).unwrap_err();
        assert!(matches!(e, StudyError::TooManyTasks { .. }), "{e}");
    }

    #[test]
    fn grid_files_read_every_axis_and_name_the_line_of_a_bad_key() {
        let axes = parse_grid(
            "# a grid\ndata = [\"octa\", \"sphere\"]\nscheme = \"shirman-sequin\"\nbeta = [0.2, 0.5]\nc = 1\nsegments = [2, 4]\ninterior = \"default\"\n",
        )
        .unwrap();
        assert_eq!(
            axes.data,
            Some(vec!["octa".to_string(), "sphere".to_string()])
        );
        assert_eq!(axes.segments, Some(vec![2, 4]));
        assert_eq!(axes.parameters.len(), 2);
        assert_eq!(axes.parameters[0].1, vec![0.2, 0.5]);
        assert_eq!(axes.parameters[1].1, vec![1.0]);
        let e = parse_grid("data = [\"octa\"]\n\nbetta = 0.2\n").unwrap_err();
        assert!(e.starts_with("line 3: `betta`: not a grid key"), "{e}");
        let e = parse_grid("segments = [\"four\"]\n").unwrap_err();
        assert!(
            e.contains("line 1: `segments`: expected non-negative integers"),
            "{e}"
        );
        let e = parse_grid("data = [\n").unwrap_err();
        assert!(e.starts_with("not TOML"), "{e}");
        let e = parse_grid("[beta]\nx = 1\n").unwrap_err();
        assert!(e.contains("not a table"), "{e}");
        // The command line replaces an axis of the file.
        let file = parse_grid("segments = [2]\nbeta = [0.2]\n").unwrap();
        let cli = Axes {
            segments: Some(vec![8]),
            ..Axes::default()
        };
        let both = cli.over(file);
        assert_eq!(both.segments, Some(vec![8]));
        assert_eq!(both.parameters[0].1, vec![0.2]);
    }
}
