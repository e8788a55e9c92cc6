//! `experiments -- view FILE… --output PAGE.html`: one self-contained interactive page
//! (the `viewer` crate) with one view per file, side by side, cameras linked.
//!
//! A file is read by its extension: `.jsonl` (patch records, `surface::patch_io`'s JSON Lines)
//! and `.bzp` (its binary form, Bézier nets only) are tessellated at `--density` segments per
//! patch edge and shown with curvature (`K`, `H`, `κ1`, `κ2`), patch boundaries and control
//! nets; any other file is read as a mesh (`meshio::read_file`, every readable format) and shown
//! with its own normals or area-weighted ones, its curvature when the file carries it, and its
//! edges as the data mesh.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use nalgebra::Point3;
use surface::BezierTriangle;

use crate::error::ExperimentError;
use crate::output::write_result;

/// Options of the `view` experiment.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// Mesh files (any readable format) or patch files (.jsonl, .bzp), one view each.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// The page to write (one self-contained HTML file, works offline).
    #[arg(short = 'o', long)]
    output: PathBuf,
    /// The page's title (default: the file names).
    #[arg(long)]
    title: Option<String>,
    /// Segments per patch edge when tessellating patch files.
    #[arg(long, default_value_t = 8)]
    density: usize,
}

/// Writes the page.
pub fn run(args: &ViewArgs) -> Result<ExitCode, ExperimentError> {
    let names: Vec<String> = args
        .files
        .iter()
        .map(|f| {
            f.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| f.display().to_string())
        })
        .collect();
    let title = args.title.clone().unwrap_or_else(|| names.join(" · "));
    let mut page = viewer::Page::new(title);
    for (file, name) in args.files.iter().zip(&names) {
        let view = view_of(file, name, args.density)?;
        say!(
            "  {name}: {} vertices, {} triangles",
            view.mesh.positions.len(),
            view.mesh.indices.len()
        );
        page.add_view(view)
            .map_err(|e| ExperimentError::Usage(format!("{}: {e}", file.display())))?;
    }
    let html = page.to_html();
    write_result(Some(&args.output), html.as_bytes())?;
    say!(
        "wrote {} ({} bytes, data {} bytes)",
        args.output.display(),
        html.len(),
        page.data_json().len()
    );
    Ok(ExitCode::SUCCESS)
}

/// One file's view.
fn view_of(file: &Path, name: &str, density: usize) -> Result<viewer::View, ExperimentError> {
    let ext = file
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if ext == "jsonl" || ext == "bzp" {
        let bytes = std::fs::read(file).map_err(|source| ExperimentError::Read {
            path: file.to_path_buf(),
            source,
        })?;
        let patches = if ext == "bzp" {
            binary_patches(file, &bytes)?
        } else {
            jsonl_patches(file, &bytes)?
        };
        if patches.is_empty() {
            return Err(ExperimentError::Usage(format!("{}: no patches", file.display())));
        }
        return viewer::view_from_patches(name, &patches, density).map_err(|source| {
            ExperimentError::Tessellate {
                subject: file.display().to_string(),
                source,
            }
        });
    }
    let raw = meshio::read_file(file).map_err(|e| ExperimentError::Read {
        path: file.to_path_buf(),
        source: std::io::Error::other(e),
    })?;
    viewer::view_from_raw(name, &raw)
        .map_err(|e| ExperimentError::Usage(format!("{}: {e}", file.display())))
}

/// The Bézier nets of a `.bzp` file.
fn binary_patches(file: &Path, bytes: &[u8]) -> Result<Vec<BezierTriangle>, ExperimentError> {
    let bad = |e: String| ExperimentError::Usage(format!("{}: {e}", file.display()));
    let (degree, _, points) =
        surface::patch_io::read_binary(bytes).map_err(|e| bad(e.to_string()))?;
    let per = surface::beztri::num_points(degree);
    points
        .chunks(per)
        .enumerate()
        .map(|(k, net)| {
            BezierTriangle::new(degree, net.to_vec()).map_err(|e| bad(format!("patch {k}: {e}")))
        })
        .collect()
}

/// The patches of a JSON Lines file: `{"type":"BezierTriangle","degree":n,"points":[[x,y,z],…]}`
/// a line (other fields ignored; blank lines skipped).
fn jsonl_patches(file: &Path, bytes: &[u8]) -> Result<Vec<BezierTriangle>, ExperimentError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| ExperimentError::Usage(format!("{}: not UTF-8: {e}", file.display())))?;
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let bad = |e: String| {
            ExperimentError::Usage(format!("{}:{}: {e}", file.display(), n + 1))
        };
        let record: serde_json::Value =
            serde_json::from_str(line).map_err(|e| bad(format!("not JSON: {e}")))?;
        if record["type"] != "BezierTriangle" {
            return Err(bad(format!(
                "a record of type {} (only BezierTriangle patches are shown)",
                record["type"]
            )));
        }
        let degree = record["degree"]
            .as_u64()
            .and_then(|d| usize::try_from(d).ok())
            .ok_or_else(|| bad("no `degree`".into()))?;
        let points = record["points"]
            .as_array()
            .ok_or_else(|| bad("no `points`".into()))?
            .iter()
            .map(|p| match p.as_array().map(|c| c.iter().map(|x| x.as_f64()).collect::<Vec<_>>()) {
                Some(c) if c.len() == 3 => match (c[0], c[1], c[2]) {
                    (Some(x), Some(y), Some(z)) => Ok(Point3::new(x, y, z)),
                    _ => Err(bad("a point with a non-number coordinate".into())),
                },
                _ => Err(bad("a point that is not [x, y, z]".into())),
            })
            .collect::<Result<Vec<_>, _>>()?;
        out.push(BezierTriangle::new(degree, points).map_err(|e| bad(e.to_string()))?);
    }
    Ok(out)
}
