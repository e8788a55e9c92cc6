//! The head of the pipeline: a mesh in, patches (or, sampled, triangles) out — the seed's
//! Fitter0, Piper, Nielson, … with the workbench's schemes standing in.
//!
//! The mesh is read from bytes in any `meshio` format, the format sniffed from the content
//! (so `fit < octa.m` works), repaired and completed by an estimator (`estimate::prepare`:
//! normals kept when the file has them, curvature estimated), fitted in the working frame,
//! and written back in the file's coordinates.
//!
//! Records: `{"type":"BezierTriangle","degree":n,"points":[…],"face":f,"subpatch":s,
//! "creases":[e, …] (only on a patch with an edge on a crease of the mesh: its patch edges
//! there, which `g1` leaves out),
//! "scheme":"name"}`; with `segments = Some(N)` (`-s N`) the fit is tessellated here
//! (`surface::tessellate_fit`) and `Triangle`s are written instead, with `face`, `subpatch`
//! and `scheme` after the vertices — the shape of the seed's Example 5, where a fitter
//! samples its own surface. A scheme whose patches are not Bézier nets (`nielson`,
//! `discrete-side-vertex`: `surface::patch`) is always sampled here, at
//! [`SAMPLED_DENSITY`] unless `-s` says otherwise, as the seed's non-Bézier fitters were.
//!
//! The input is standard input or `--input FILE` (the format sniffed from the content), or
//! `--data NAME|FILE` with `--resolution N` as `experiments fit` takes them. A sampled value
//! that is not finite (a curvature beyond `f64` on a mesh 1e-200 across) is an error naming
//! the patch, never written.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde_json::{Map, Value};

use crate::error::{FilterError, Position, StreamError};
use crate::filters::Filter;
use crate::pipe::StreamOptions;
use crate::record;
use crate::sample::{triangle_value, CurvatureFields, Sample};
use crate::stream::{Format, RecordWriter};

/// The density a non-Bézier scheme is sampled at when `-s` is not given (the seed's
/// Example 5: `Nielson -s 8`).
pub const SAMPLED_DENSITY: usize = 8;

/// `testbed fit`: the head of the pipeline.
pub struct Fit;

/// Options of `fit`.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// The surface scheme and the schemes' parameters (generated from the registry).
    #[command(flatten)]
    pub scheme: fitjob::cli::SchemeArgs<fitjob::cli::PatchesOnly>,
    /// Boundary-curve construction (the registry's).
    #[arg(long, default_value = "chord", value_parser = fitjob::cli::curve_method_names())]
    pub curves: String,
    /// The curve constructions' options (`--solver`, `--dbhs-pick`, `--tweak-t`,
    /// `--four-ninths`), as `experiments fit` takes them.
    #[command(flatten)]
    pub curve: fitjob::cli::CurveOptions,
    /// `--heightfield`, `--no-heightfield` (the functional Clough–Tocher and Powell–Sabin).
    #[command(flatten)]
    pub heightfield: fitjob::cli::HeightFieldArgs,
    /// Estimator for what the mesh lacks (the registry's, or `none`).
    #[arg(long, default_value = estimate::DEFAULT_ESTIMATOR, value_parser = fitjob::cli::estimator_names())]
    pub estimate: String,
    /// Estimate on Euclidean balls of this many mean edge lengths (the degree-2 jet at one
    /// radius, Huber-weighted) instead of the estimator's own neighbourhoods: wider for noisier
    /// scans.
    #[arg(long, value_name = "R")]
    pub radius: Option<f64>,
    /// Estimate normals even where the mesh has them.
    #[arg(long)]
    pub replace_normals: bool,
    /// How creases are found (`--crease-angle DEG`, `--no-creases`).
    #[command(flatten)]
    pub creases: fitjob::cli::CreaseArgs,
    /// A data set (ring, sphere, capsule, octa) or a mesh file (the format by extension,
    /// checked against the content), instead of the input stream.
    #[arg(long, value_name = "NAME|FILE")]
    pub data: Option<String>,
    /// Resolution of a named data set (its default when absent).
    #[arg(long, value_name = "N")]
    pub resolution: Option<usize>,
    /// Tessellate here at N segments per patch edge (1 to 4096, as `tess -s`) and write
    /// triangles (Example 5).
    #[arg(short = 's', long = "segments", value_name = "N")]
    pub segments: Option<usize>,
    /// With -s: write Gaussian curvature.
    #[arg(long)]
    pub kg: bool,
    /// With -s: write mean curvature.
    #[arg(long)]
    pub km: bool,
    /// With -s (or an evaluated scheme): one shared-vertex TriangleMesh record per
    /// patch (as `tess`): the default, accepted for scripts that ask for it.
    #[arg(long, conflicts_with = "triangles")]
    pub mesh: bool,
    /// With -s (or an evaluated scheme): the seed's Triangle records instead of one
    /// TriangleMesh per patch (as `tess --triangles`).
    #[arg(long)]
    pub triangles: bool,
}

impl Filter for Fit {
    const NAME: &'static str = "fit";
    const SUMMARY: &'static str = "\
        A mesh (any format, sniffed; `.m` included) to BezierTriangle records, or with `-s N` \
        straight to triangles (one TriangleMesh a patch; --triangles: the seed's Triangles)";
    const DESCRIPTION: &'static str = "\
        The mesh (--input, standard input, or --data NAME|FILE with --resolution N) is read \
        whole, its format sniffed from the content, repaired and completed by --estimate (the file's normals kept unless \
        --replace-normals), fitted by --scheme and written back in its own coordinates: one \
        BezierTriangle per patch with `face`, `subpatch` and `scheme` after the points. A scheme \
        whose patches are not Bézier nets is always sampled here, as with -s 8 unless -s says \
        otherwise; a sampled value that is not finite is an error naming the patch. The output is JSON Lines unless --format says otherwise; \
        --keep-going has nothing to skip.";
    const SEED: &'static str =
        "Fitter0, Shirman–Séquin, … (Piper not recovered); Nielson, a sampling fitter (Herron not recovered)";
    type Args = FitArgs;

    fn run(args: FitArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let mut input = match &args.data {
            Some(d) => {
                if stream.input.is_some() {
                    return Err(FilterError::Usage(format!(
                        "--data {d} and --input: one input (--data NAME|FILE, or --input FILE, or standard input)"
                    )));
                }
                data_input(d, args.resolution, &args.estimate, args.replace_normals)?
            }
            None => {
                if let Some(r) = args.resolution {
                    return Err(FilterError::Usage(format!(
                        "--resolution {r} is a data set's: give --data NAME"
                    )));
                }
                let (name, bytes) = match stream.input.as_deref().and_then(fitjob::destination) {
                    Some(p) => (
                        p.to_path_buf(),
                        std::fs::read(p)
                            .map_err(|e| StreamError::io(format!("reading {}", p.display()), e))?,
                    ),
                    None => {
                        let mut b = Vec::new();
                        std::io::Read::read_to_end(&mut std::io::stdin().lock(), &mut b)
                            .map_err(|e| StreamError::io("reading the input", e))?;
                        (PathBuf::from("<standard input>"), b)
                    }
                };
                input_from_bytes(&name, &bytes, &args.estimate, args.replace_normals)?
            }
        };
        input.creases = args.creases.rule();
        input.radius = args.radius;
        if let Some(s) = args.segments {
            crate::filters::tess::check_segments(Self::NAME, s)?;
        }
        let options = FitOptions {
            scheme: args.scheme.scheme,
            scheme_options: args.scheme.options,
            curves: args.curves,
            method_options: args.curve.method_options(),
            heightfield: args.heightfield.mode(),
            estimate: args.estimate,
            replace_normals: args.replace_normals,
            segments: args.segments,
            fields: CurvatureFields {
                kg: args.kg,
                km: args.km,
                kp: false,
            },
            mesh: match (args.mesh, args.triangles) {
                (true, _) => Some(true),
                (_, true) => Some(false),
                _ => None,
            },
        };
        let mut input = Some(input);
        stream.with_output(&mut |out| {
            let mut w = RecordWriter::new(
                out,
                Some(stream.format.unwrap_or_else(|| default_format(&stream))),
            );
            match input.take() {
                Some(input) => fit(input, &options, &mut w),
                None => Ok(()),
            }
        })
    }
}

/// The record format `fit` writes when `--format` is not given: the binary patch file for an
/// output named `.bzp`, JSON Lines for one named `.jsonl` or `.json` and on a terminal (where
/// a person reads it), the self-describing binary form otherwise (into a pipe or a file: the
/// fast form, which every filter reads and follows).
pub fn default_format(stream: &StreamOptions) -> Format {
    use std::io::IsTerminal;
    let output = stream.output.as_deref().and_then(fitjob::destination);
    let ext = output
        .and_then(|p| p.extension())
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("bzp") => Format::Bzp,
        Some("jsonl" | "json") => Format::Json,
        _ if output.is_none() && std::io::stdout().is_terminal() => Format::Json,
        _ => Format::Binary,
    }
}

/// How to fit.
#[derive(Clone, Debug, PartialEq)]
pub struct FitOptions {
    /// Scheme name (`surface::scheme_names`).
    pub scheme: String,
    /// The schemes' parameters.
    pub scheme_options: surface::SchemeOptions,
    /// Boundary-curve construction (`curves::REGISTRY`).
    pub curves: String,
    /// The constructions' options.
    pub method_options: curves::MethodOptions,
    /// Whether to fit as a height field.
    pub heightfield: surface::scheme::functional::HeightFieldMode,
    /// Estimator for what the file lacks (`none` or an estimator's name).
    pub estimate: String,
    /// Estimate normals even where the file has them.
    pub replace_normals: bool,
    /// Tessellate here at this many segments per patch edge and write triangles.
    pub segments: Option<usize>,
    /// Curvatures written with sampled triangles.
    pub fields: CurvatureFields,
    /// Sampled output as one shared-vertex `TriangleMesh` record per patch (`None`, the
    /// default, and `Some(true)`, asked for by `--mesh`: an error without sampling) or as the
    /// seed's `Triangle` records (`Some(false)`, `--triangles`).
    pub mesh: Option<bool>,
}

/// The fit job's input from bytes (`path` names it and may pick the format by extension; the
/// content decides when it is recognisably another format): read here, repaired and completed
/// by the job.
pub fn input_from_bytes(
    path: &Path,
    bytes: &[u8],
    estimate: &str,
    replace_normals: bool,
) -> Result<fitjob::InputOptions, FilterError> {
    let raw = meshio::read_bytes(path, bytes)?;
    Ok(fitjob::InputOptions {
        source: fitjob::Source::Raw {
            label: path.display().to_string(),
            raw: Box::new(raw),
        },
        estimate: estimate.to_string(),
        radius: None,
        replace_normals,
        creases: mesh::features::CreaseRule::Auto,
    })
}

/// `--data NAME|FILE [--resolution N]` as the fit job's input, as `experiments fit` takes
/// them (`fitjob::Source::Data`: an existing file, or a name with a mesh extension, is read;
/// otherwise the name is a data set). A resolution is a data set's: with a file it is a usage
/// error.
pub fn data_input(
    data: &str,
    resolution: Option<usize>,
    estimate: &str,
    replace_normals: bool,
) -> Result<fitjob::InputOptions, FilterError> {
    if let Some(r) = resolution {
        if fitjob::input::is_file_input(data) {
            return Err(FilterError::Usage(format!(
                "--resolution {r} is a data set's; --data {data} is a file"
            )));
        }
    }
    Ok(fitjob::InputOptions {
        source: fitjob::Source::Data {
            data: data.to_string(),
            resolution,
        },
        estimate: estimate.to_string(),
        radius: None,
        replace_normals,
        creases: mesh::features::CreaseRule::Auto,
    })
}

/// Fits `input` with the fit job (`fitjob::run`, the fit every front end calls; G1 is left to
/// the pipeline's `g1` filter) and writes its records.
pub fn fit<W: std::io::Write>(
    input: fitjob::InputOptions,
    options: &FitOptions,
    out: &mut RecordWriter<W>,
) -> Result<(), FilterError> {
    let scheme = surface::scheme_by_name(&options.scheme, &options.scheme_options)
        .map_err(|e| FilterError::Usage(e.to_string()))?;
    curves::method_by_name(&options.curves, &options.method_options)
        .map_err(|e| FilterError::Usage(e.to_string()))?;
    let layout = scheme.layout();
    let sample = match options.segments {
        None if !layout.is_bezier() => {
            eprintln!(
                "fit: `{}` is evaluated, not a Bézier patch: sampled here at s = {SAMPLED_DENSITY} (-s N to change)",
                scheme.name()
            );
            Some(SAMPLED_DENSITY)
        }
        s => s,
    };
    if options.mesh == Some(true) && sample.is_none() {
        return Err(FilterError::Usage(
            "fit --mesh writes sampled triangles: give -s N (tess --mesh does it for patches)"
                .into(),
        ));
    }
    if let Some(s) = sample {
        crate::filters::tess::check_segments("fit", s)?;
    }
    let job = fitjob::FitOptions {
        input,
        scheme: options.scheme.clone(),
        scheme_options: options.scheme_options.clone(),
        curves: options.curves.clone(),
        method_options: options.method_options,
        heightfield: options.heightfield,
        measure_g1: false,
        keep: true,
        ..fitjob::FitOptions::default()
    };
    let outcome = fitjob::run(job, &mut |line| eprintln!("fit: {}", line.trim_start()))
        .map_err(FilterError::from)?;
    let (Some(mesh), Some(frame), Some(fitted)) =
        (outcome.kept.mesh, outcome.kept.frame, outcome.kept.fit)
    else {
        return Err(FilterError::Usage(
            "the fit job kept no fit (a subdivision scheme is not a fitter of the pipeline)".into(),
        ));
    };
    if !fitted.face_fallbacks.is_empty() {
        eprintln!(
            "fit: {} face(s) fitted with the C0 fallback patch",
            fitted.face_fallbacks.len()
        );
    }
    // The tessellation's memory, checked before it allocates (the fit is within the job's own
    // estimates).
    if sample.is_some() {
        check_memory(mesh.num_faces(), &layout, sample)?;
    }
    let per_face = fitted.layout.patches_per_face().max(1);
    let scheme_name = Value::from(fitted.scheme);
    let mut at = Position::default();
    if let Some(s) = sample {
        let mut t = surface::tessellate_fit(&mesh, &fitted, s)?;
        t.to_world(&frame);
        check_finite(&t, per_face, options.fields, frame.scale)?;
        if options.mesh != Some(false) {
            for v in patch_meshes(&t, per_face, &scheme_name, options.fields) {
                at.record += 1;
                out.write(&v, at)?;
            }
            out.finish()?;
            return Ok(());
        }
        for (fi, f) in t.faces.iter().enumerate() {
            let sample = |i: usize| Sample {
                pos: t.positions[i],
                norm: t.normals[i],
                kg: t.gaussian[i],
                km: t.mean[i],
            };
            let patch = t.patch_of_face.get(fi).copied().unwrap_or(0);
            let mut carried = Map::new();
            carried.insert("face".into(), Value::from(patch / per_face));
            carried.insert("subpatch".into(), Value::from(patch % per_face));
            carried.insert("scheme".into(), scheme_name.clone());
            let v = triangle_value(
                &[sample(f[0]), sample(f[1]), sample(f[2])],
                options.fields,
                carried.iter(),
            );
            at.record += 1;
            out.write(&v, at)?;
        }
    } else {
        // The workspace's one patch record (`surface::patch_io::patch_record`, the record of
        // `experiments fit --out`), then the scheme's name.
        let to_world = |p: &nalgebra::Point3<f64>| frame.to_world(p);
        if out.format() == Some(Format::Bzp) {
            // The workspace's binary patch file, as `experiments fit --out FILE.bzp` writes it.
            let raw = out.raw()?;
            surface::patch_io::write_binary(&fitted, &to_world, raw)
                .map_err(|e| StreamError::io("writing the output", e))?;
            out.finish()?;
            return Ok(());
        }
        for (i, net) in fitted.nets().enumerate() {
            let mut m = surface::patch_io::patch_record(&fitted.layout, i, net, &to_world);
            m.insert("scheme".into(), scheme_name.clone());
            // The patch edges on the mesh's creases, for the pipeline's `g1` (which sees no
            // mesh): C0 there by construction.
            let flags =
                surface::fit::patch_crease_edges(&mesh, &fitted.layout, i / per_face, i % per_face);
            if flags.iter().any(|&c| c) {
                let edges: Vec<Value> = (0..3).filter(|&k| flags[k]).map(Value::from).collect();
                m.insert("creases".into(), Value::Array(edges));
            }
            at.record += 1;
            out.write(&Value::Object(m), at)?;
        }
    }
    out.finish()?;
    Ok(())
}

/// Refuses a fit of `faces` faces with `layout` (tessellated at `sample` segments per patch
/// edge, if given) whose estimated memory exceeds the library's limit
/// ([`surface::limits::check_memory`]): the estimates of `experiments fit`,
/// [`surface::limits::FIT_BYTES_PER_FACE`] per face and [`surface::limits::tessellation_bytes`],
/// with the tessellator's weight table ([`surface::limits::sample_weights_bytes`]), checked
/// before the fit allocates anything.
pub fn check_memory(
    faces: usize,
    layout: &surface::Layout,
    sample: Option<usize>,
) -> Result<(), FilterError> {
    let fit = (faces as u128).saturating_mul(surface::limits::FIT_BYTES_PER_FACE as u128);
    let Some(s) = sample else {
        return Ok(surface::limits::check_memory(
            &format!("fitting {faces} faces"),
            fit,
        )?);
    };
    let patches = (faces as u128).saturating_mul(layout.patches_per_face() as u128);
    Ok(surface::limits::check_memory(
        &format!("fit -s {s} ({faces} faces, {patches} patches)"),
        fit.saturating_add(surface::limits::tessellation_bytes(patches, s))
            .saturating_add(surface::limits::sample_weights_bytes(
                layout.points_per_patch(),
                s,
            )),
    )?)
}

/// Refuses a tessellation with a value it would write that is not finite (positions,
/// normals, and the curvatures `fields` asks for): a curvature mapped back from the working
/// frame (`K / scale²`, `H / scale`) leaves the range of `f64` on a mesh about 1e-154 across
/// or smaller. The error names the patch (face and subpatch) and the vertex.
fn check_finite(
    t: &surface::Tessellation,
    per_face: usize,
    fields: CurvatureFields,
    scale: f64,
) -> Result<(), FilterError> {
    let bad = (0..t.positions.len()).find_map(|i| {
        let p = t.positions[i];
        let n = t.normals[i];
        let checks = [
            ("position", p.x, true),
            ("position", p.y, true),
            ("position", p.z, true),
            ("normal", n.x, true),
            ("normal", n.y, true),
            ("normal", n.z, true),
            ("Gaussian curvature", t.gaussian[i], fields.kg),
            ("mean curvature", t.mean[i], fields.km),
        ];
        checks
            .into_iter()
            .find(|(_, x, asked)| *asked && !x.is_finite())
            .map(|(what, x, _)| (i, what, x))
    });
    let Some((vertex, what, value)) = bad else {
        return Ok(());
    };
    let patch = t
        .faces
        .iter()
        .position(|f| f.contains(&vertex))
        .and_then(|k| t.patch_of_face.get(k).copied())
        .unwrap_or(0);
    Err(FilterError::NotFinite(format!(
        "face {} subpatch {}, vertex {vertex}: the {what} is {value} on a mesh {scale:.1e} across, beyond the range of a double (±{:.1e}); leave --kg/--km out or rescale the mesh",
        patch / per_face,
        patch % per_face,
        f64::MAX
    )))
}

/// The welded tessellation `t` cut back into one `TriangleMesh` record per patch, in patch
/// order: each patch's vertices (in the order its triangles first use them) as columns, its
/// triangles as indices into them, then `face`, `subpatch` and `scheme` as the `Triangle`
/// records carry them. The triangles of a patch are consecutive in `t` (`tessellate_fit`
/// writes them patch by patch).
fn patch_meshes<'a>(
    t: &'a surface::Tessellation,
    per_face: usize,
    scheme: &'a Value,
    fields: CurvatureFields,
) -> impl Iterator<Item = Value> + 'a {
    let mut start = 0;
    std::iter::from_fn(move || {
        t.faces.get(start)?;
        let patch = t.patch_of_face.get(start).copied().unwrap_or(0);
        let end = start
            + t.patch_of_face[start..]
                .iter()
                .take_while(|p| **p == patch)
                .count()
                .max(1);
        // Each vertex's index in the patch, in the order its triangles first use it (a map,
        // not a search of the list: a patch at s = 1000 has half a million vertices).
        let mut local: Vec<usize> = Vec::new();
        let mut index_of: HashMap<usize, usize> = HashMap::new();
        let mut triangles = Vec::with_capacity(end - start);
        for f in &t.faces[start..end] {
            let tri: Vec<Value> = f
                .iter()
                .map(|g| {
                    let i = *index_of.entry(*g).or_insert_with(|| {
                        local.push(*g);
                        local.len() - 1
                    });
                    Value::from(i)
                })
                .collect();
            triangles.push(Value::Array(tri));
        }
        start = end;
        let column3 = |xs: &dyn Fn(usize) -> [f64; 3]| {
            Value::Array(local.iter().map(|&g| record::arr3(xs(g))).collect())
        };
        let column1 =
            |xs: &[f64]| Value::Array(local.iter().map(|&g| record::num(xs[g])).collect());
        let mut m = Map::new();
        m.insert("type".into(), Value::from("TriangleMesh"));
        m.insert(
            "pos".into(),
            column3(&|g| {
                let p = t.positions[g];
                [p.x, p.y, p.z]
            }),
        );
        m.insert(
            "norm".into(),
            column3(&|g| {
                let n = t.normals[g];
                [n.x, n.y, n.z]
            }),
        );
        if fields.kg {
            m.insert("kg".into(), column1(&t.gaussian));
        }
        if fields.km {
            m.insert("km".into(), column1(&t.mean));
        }
        m.insert("triangles".into(), Value::Array(triangles));
        m.insert("face".into(), Value::from(patch / per_face));
        m.insert("subpatch".into(), Value::from(patch % per_face));
        m.insert("scheme".into(), scheme.clone());
        Some(Value::Object(m))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The help's description names the density an evaluated scheme is sampled at.
    #[test]
    fn the_description_names_the_sampled_density() {
        assert!(Fit::DESCRIPTION.contains(&format!("-s {SAMPLED_DENSITY} ")));
    }
}
