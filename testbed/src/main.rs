//! `testbed`: the pipeline's filters as subcommands (see the library's docs and
//! `examples/` at the repository root).
//!
//! ```sh
//! testbed fit --scheme shirman-sequin < data/octa.m | testbed tess -s 8 | testbed mat0 \
//!     | testbed render > octa.png
//! ```

use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use testbed::draw::{self, View};
use testbed::filters::{self, CurvatureFields, Pipe};
use testbed::fit::{self, FitOptions};
use testbed::{FilterError, Format, RecordWriter};

/// Filters of the surface-interpolation testbed (Lounsbery et al. 1990), connected by pipes.
#[derive(Parser, Debug)]
#[command(name = "testbed", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Options of every record filter.
#[derive(Args, Debug, Clone)]
struct Common {
    /// Read this file instead of standard input.
    #[arg(long, global = true)]
    input: Option<PathBuf>,
    /// Write this file (atomically) instead of standard output.
    #[arg(long, global = true)]
    output: Option<PathBuf>,
    /// Output format (default: the input's; JSON Lines for fit).
    #[arg(long, global = true, value_enum)]
    format: Option<Format>,
    /// Skip malformed records (counted on standard error) instead of stopping.
    #[arg(long, global = true)]
    keep_going: bool,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// A mesh (any format, sniffed; `.m` included) to BezierTriangle records, or with
    /// `--sample N` straight to Triangle records.
    Fit {
        /// The surface scheme and the schemes' parameters (generated from the registry).
        #[command(flatten)]
        scheme: fitjob::cli::SchemeArgs<fitjob::cli::PatchesOnly>,
        /// Boundary-curve construction (the registry's).
        #[arg(long, default_value = "chord", value_parser = fitjob::cli::curve_method_names())]
        curves: String,
        /// Estimator for what the mesh lacks (the registry's, or `none`).
        #[arg(long, default_value = estimate::DEFAULT_ESTIMATOR, value_parser = fitjob::cli::estimator_names())]
        estimate: String,
        /// Estimate normals even where the mesh has them.
        #[arg(long)]
        replace_normals: bool,
        /// A named data set (ring, sphere, capsule, octa; `NAME:RESOLUTION`) instead of a mesh.
        #[arg(long)]
        dataset: Option<String>,
        /// Tessellate here at N segments per patch edge and write triangles (Example 5).
        #[arg(long)]
        sample: Option<usize>,
        /// With --sample: write Gaussian curvature.
        #[arg(long)]
        kg: bool,
        /// With --sample: write mean curvature.
        #[arg(long)]
        km: bool,
        /// With --sample (or an evaluated scheme): one shared-vertex TriangleMesh record per
        /// patch instead of Triangle records (as `tess --mesh`).
        #[arg(long)]
        mesh: bool,
        #[command(flatten)]
        common: Common,
    },
    /// BezierTriangles to Triangles (s² per patch) or, with --mesh, one TriangleMesh per
    /// patch; a patch's other fields go to its records.
    Tess {
        /// Segments per patch edge.
        #[arg(short = 's', default_value_t = 8)]
        s: usize,
        /// Write Gaussian curvature `kg` at the vertices.
        #[arg(long)]
        kg: bool,
        /// Write mean curvature `km` at the vertices.
        #[arg(long)]
        km: bool,
        /// Write one TriangleMesh record per patch (its vertices once, its triangles as
        /// indices) instead of s² Triangle records.
        #[arg(long)]
        mesh: bool,
        #[command(flatten)]
        common: Common,
    },
    /// Passes records through; measures normal angles along shared patch boundaries.
    G1 {
        /// Exit with an error when the largest angle exceeds the tolerance (1e-6 rad), when a
        /// boundary could not be measured, or when nothing was measured.
        #[arg(long)]
        strict: bool,
        /// Samples per boundary, ends included (at least 3: the ends alone say nothing).
        #[arg(long, default_value_t = testbed::g1::DEFAULT_SAMPLES, value_parser = g1_samples)]
        samples: usize,
        #[command(flatten)]
        common: Common,
    },
    /// The uniform material colour at every vertex.
    Mat0 {
        #[command(flatten)]
        common: Common,
    },
    /// Diverging colours of the curvature (default range ±the 95% quantile of |kg| over the
    /// first --block triangles).
    Kcolor {
        /// Colour range `A:B` (mapped onto blue–grey–red).
        #[arg(long, allow_hyphen_values = true)]
        range: Option<String>,
        /// Without --range: triangles held to fix the range before streaming (0: the whole
        /// stream).
        #[arg(long, default_value_t = filters::DEFAULT_BLOCK)]
        block: usize,
        /// Which curvature: kg (Gaussian) or km (mean).
        #[arg(long, default_value = "kg")]
        field: String,
        #[command(flatten)]
        common: Common,
    },
    /// Sequential colours of the distance to the true surface (and `dist` at each vertex).
    Radial {
        /// The true surface: ring, sphere, capsule (octa lies on the unit sphere).
        #[arg(long)]
        surface: String,
        /// Colour range `A:B` of |distance| (default 0 to its 95% quantile over the first
        /// --block triangles).
        #[arg(long, allow_hyphen_values = true)]
        range: Option<String>,
        /// Without --range: triangles held to fix the range before streaming (0: the whole
        /// stream).
        #[arg(long, default_value_t = filters::DEFAULT_BLOCK)]
        block: usize,
        #[command(flatten)]
        common: Common,
    },
    /// A shaded picture of the triangles, PNG.
    Render {
        #[command(flatten)]
        picture: Picture,
        #[command(flatten)]
        common: Common,
    },
    /// A wire-frame picture of the triangles (every edge), PNG: the seed's XRender.
    Wire {
        #[command(flatten)]
        picture: Picture,
        #[command(flatten)]
        common: Common,
    },
    /// The triangles as a mesh file (welded by position within a tolerance: the library's
    /// weld), format by extension.
    ToMesh {
        /// The mesh file (.ply, .obj, .glb, .off, .stl, .m).
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        common: Common,
    },
}

/// Picture options.
#[derive(Args, Debug, Clone)]
struct Picture {
    /// View direction `AZ,EL` in degrees.
    #[arg(long, allow_hyphen_values = true)]
    view: Option<String>,
    /// Size `WxH` in pixels.
    #[arg(long)]
    size: Option<String>,
}

/// `g1 --samples N`: a whole number of at least [`surface::patch_g1::MIN_SAMPLES`] (clap
/// refuses anything else as a usage error, exit status 2).
fn g1_samples(s: &str) -> Result<usize, String> {
    let min = surface::patch_g1::MIN_SAMPLES;
    match s.parse::<usize>() {
        Ok(n) if n >= min => Ok(n),
        _ => Err(format!(
            "at least {min} samples per boundary (with 2 only the ends are sampled, where every interpolating scheme has the vertex normal on both sides)"
        )),
    }
}

fn pair<T: std::str::FromStr>(s: &str, sep: char, what: &str) -> Result<(T, T), FilterError> {
    let bad = || {
        FilterError::Usage(format!(
            "{what} `{s}`: expected two numbers separated by `{sep}`"
        ))
    };
    let (a, b) = s.split_once(sep).ok_or_else(bad)?;
    Ok((
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    ))
}

fn range(s: &Option<String>) -> Result<Option<(f64, f64)>, FilterError> {
    let Some(s) = s else { return Ok(None) };
    let (a, b): (f64, f64) = pair(s, ':', "--range")?;
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(FilterError::Usage(format!(
            "--range {s}: need finite A < B"
        )));
    }
    Ok(Some((a, b)))
}

fn picture(p: &Picture, wire: bool) -> Result<View, FilterError> {
    let view = match &p.view {
        Some(v) => pair::<f64>(v, ',', "--view")?,
        None => draw::DEFAULT_VIEW,
    };
    if !(view.0.is_finite() && view.1.is_finite()) {
        return Err(FilterError::Usage("--view: finite angles".into()));
    }
    let size = match &p.size {
        Some(s) => pair::<u32>(&s.to_ascii_lowercase(), 'x', "--size")?,
        None => draw::DEFAULT_SIZE,
    };
    Ok(View { view, size, wire })
}

/// Opens the input.
fn open_input(path: &Option<PathBuf>) -> Result<Box<dyn BufRead>, FilterError> {
    Ok(match path {
        Some(p) => Box::new(BufReader::with_capacity(
            1 << 16,
            std::fs::File::open(p)
                .map_err(|e| testbed::StreamError::io(format!("opening {}", p.display()), e))?,
        )),
        None => Box::new(BufReader::with_capacity(1 << 16, std::io::stdin().lock())),
    })
}

/// Runs `f` on the output: standard output, or a file written atomically.
fn with_output(
    path: &Option<PathBuf>,
    f: &mut dyn FnMut(&mut dyn Write) -> Result<(), FilterError>,
) -> Result<(), FilterError> {
    match path {
        None => {
            let stdout = std::io::stdout();
            let mut lock = stdout.lock();
            f(&mut lock)?;
            lock.flush()
                .map_err(|e| testbed::StreamError::io("writing the output", e).into())
        }
        Some(p) => {
            let mut failure = None;
            let result = meshio::outfile::write_atomic_with(p, &mut |w| {
                f(w).map_err(|e| {
                    failure = Some(e);
                    std::io::Error::other("the filter failed")
                })
            });
            match failure {
                Some(e) => Err(e),
                None => result.map_err(|e| FilterError::from(render::RenderError::from(e))),
            }
        }
    }
}

/// Runs a record filter.
fn filter<T>(
    name: &'static str,
    c: &Common,
    f: &mut dyn FnMut(&mut Pipe) -> Result<T, FilterError>,
) -> Result<(), FilterError> {
    let mut input = open_input(&c.input)?;
    with_output(&c.output, &mut |out| {
        let mut pipe = Pipe::new(name, &mut *input, out, c.format, c.keep_going);
        f(&mut pipe).map(|_| ())
    })
}

/// What a sink does with the triangles read.
type SinkFn<'a> =
    dyn FnMut(Vec<[testbed::record::Vertex; 3]>, &mut dyn Write) -> Result<(), FilterError> + 'a;

/// Runs a filter that ends the pipeline (reads triangles, writes something else).
fn sink(name: &'static str, c: &Common, f: &mut SinkFn) -> Result<(), FilterError> {
    let mut input = open_input(&c.input)?;
    let mut nothing = std::io::sink();
    let tris = {
        let mut pipe = Pipe::new(name, &mut *input, &mut nothing, None, c.keep_going);
        draw::collect_triangles(&mut pipe)?
    };
    if tris.is_empty() {
        eprintln!("{name}: no triangles in the input");
    }
    let mut tris = Some(tris);
    with_output(&c.output, &mut |out| {
        f(tris.take().unwrap_or_default(), out)
    })
}

/// Runs a picture filter: the triangles read straight into a render mesh, drawn, PNG out.
fn picture_sink(name: &'static str, c: &Common, view: &View) -> Result<(), FilterError> {
    let mut input = open_input(&c.input)?;
    let mut nothing = std::io::sink();
    let mesh = {
        let mut pipe = Pipe::new(name, &mut *input, &mut nothing, None, c.keep_going);
        draw::collect_mesh(&mut pipe)?
    };
    if mesh.faces.is_empty() {
        eprintln!("{name}: no triangles in the input");
    }
    let image = draw::draw_mesh(&mesh, view)?;
    drop(mesh);
    with_output(&c.output, &mut |out| draw::write_png(&image, out))
}

fn run(cli: Cli) -> Result<(), FilterError> {
    match cli.command {
        Command::Fit {
            scheme,
            curves,
            estimate,
            replace_normals,
            dataset,
            sample,
            kg,
            km,
            mesh,
            common,
        } => {
            let input = match &dataset {
                Some(d) => fit::dataset(d)?,
                None => {
                    let (name, bytes) = match &common.input {
                        Some(p) => (
                            p.clone(),
                            std::fs::read(p).map_err(|e| {
                                testbed::StreamError::io(format!("reading {}", p.display()), e)
                            })?,
                        ),
                        None => {
                            let mut b = Vec::new();
                            std::io::Read::read_to_end(&mut std::io::stdin().lock(), &mut b)
                                .map_err(|e| testbed::StreamError::io("reading the input", e))?;
                            (PathBuf::from("<standard input>"), b)
                        }
                    };
                    fit::input_from_bytes(&name, &bytes, &estimate, replace_normals)?
                }
            };
            let options = FitOptions {
                scheme: scheme.scheme,
                scheme_options: scheme.options,
                curves,
                estimate,
                replace_normals,
                sample,
                fields: CurvatureFields { kg, km },
                mesh,
            };
            let mut input = Some(input);
            with_output(&common.output, &mut |out| {
                let mut w = RecordWriter::new(out, common.format.or(Some(Format::Json)));
                match input.take() {
                    Some(input) => fit::fit(input, &options, &mut w),
                    None => Ok(()),
                }
            })
        }
        Command::Tess {
            s,
            kg,
            km,
            mesh,
            common,
        } => {
            let records = if mesh {
                filters::TessRecords::Mesh
            } else {
                filters::TessRecords::Triangles
            };
            filter("tess", &common, &mut |p| {
                filters::tess(p, s, CurvatureFields { kg, km }, records)
            })
        }
        Command::G1 {
            strict,
            samples,
            common,
        } => filter("g1", &common, &mut |p| testbed::g1::g1(p, strict, samples)),
        Command::Mat0 { common } => filter("mat0", &common, &mut |p| {
            filters::colour(p, &filters::Mat0, "", None, 0)
        }),
        Command::Kcolor {
            range: r,
            block,
            field,
            common,
        } => {
            if field != "kg" && field != "km" {
                return Err(FilterError::Usage(format!(
                    "kcolor --field {field}: kg or km"
                )));
            }
            let r = range(&r)?;
            filter("kcolor", &common, &mut |p| {
                filters::colour(p, &filters::KColor, &field, r, block)
            })
        }
        Command::Radial {
            surface,
            range: r,
            block,
            common,
        } => {
            let name = if surface == "octa" {
                "sphere"
            } else {
                surface.as_str()
            };
            if !["ring", "sphere", "capsule"].contains(&name) {
                return Err(FilterError::Usage(format!(
                    "radial --surface {surface}: ring, sphere or capsule"
                )));
            }
            // The data set's analytic surface (the coarsest sampling: only the surface is used).
            let data = surface::dataset_by_name(name, Some(if name == "sphere" { 0 } else { 4 }))
                .or_else(|_| surface::dataset_by_name(name, None))?;
            let colouring = filters::Radial {
                surface: data.surface,
            };
            let r = range(&r)?;
            filter("radial", &common, &mut |p| {
                filters::colour(p, &colouring, "", r, block)
            })
        }
        Command::Render {
            picture: pic,
            common,
        } => {
            let view = picture(&pic, false)?;
            picture_sink("render", &common, &view)
        }
        Command::Wire {
            picture: pic,
            common,
        } => {
            let view = picture(&pic, true)?;
            picture_sink("wire", &common, &view)
        }
        Command::ToMesh { out, common } => sink("to-mesh", &common, &mut |tris, _| {
            draw::write_mesh(&tris, &out)
        }),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let name = match &cli.command {
        Command::Fit { .. } => "fit",
        Command::Tess { .. } => "tess",
        Command::G1 { .. } => "g1",
        Command::Mat0 { .. } => "mat0",
        Command::Kcolor { .. } => "kcolor",
        Command::Radial { .. } => "radial",
        Command::Render { .. } => "render",
        Command::Wire { .. } => "wire",
        Command::ToMesh { .. } => "to-mesh",
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("testbed {name}: error: {e}");
            ExitCode::FAILURE
        }
    }
}
