//! `experiments -- view FILE… --output PAGE.html`: one self-contained interactive page
//! (the `viewer` crate) with one view per file, side by side, cameras linked.
//!
//! A file is read by its extension: `.jsonl` (patch records, `surface::patch_io`'s JSON Lines)
//! and `.bzp` (its binary form, Bézier nets only) are tessellated at `--density` segments per
//! patch edge and shown with curvature (`K`, `H`, `κ1`, `κ2`), patch boundaries and control
//! nets; any other file is read as a mesh (`meshio::read_file`, every readable format) and shown
//! with its own normals or area-weighted ones, its curvature when the file carries it, and its
//! edges as the data mesh.
//!
//! A directory (a study's result directory) stands for its viewable files, sorted by name:
//! mesh files by extension, `.bzp` patch files, and `.jsonl` files whose first record is a
//! patch (a sweep's `results.jsonl` is not); the others are named on stderr as skipped.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::error::ExperimentError;
use crate::output::write_result;

/// Options of the `view` experiment.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// Mesh files (any readable format), patch files (.jsonl, .bzp) or directories (their
    /// viewable files), one view a file.
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
    /// The axis the camera keeps up and the reflection lines turn about: z (the workbench's
    /// data) or y (most scanned models); the page's `#up=` overrides it.
    #[arg(long, default_value_t = meshio::UpAxis::Z)]
    up: meshio::UpAxis,
}

/// Copies of a tessellation a page holds at its peak: the view's vertex and index arrays, their
/// base64 in the page's JSON data block (4/3 of the bytes) and the HTML text around it: three
/// times the tessellation's estimate covers them.
const PAGE_COPIES: u128 = 3;

/// Writes the page.
pub fn run(args: &ViewArgs) -> Result<ExitCode, ExperimentError> {
    // The tessellation's range, as `fit --segments` (4096 aborted on the memory it asked for).
    fitjob::limits::check_usize("density", args.density, &fitjob::limits::SAMPLING_RANGE)?;
    let mut files = Vec::new();
    for arg in &args.files {
        files.extend(expand(arg)?);
    }
    let names: Vec<String> = files
        .iter()
        .map(|f| {
            f.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| f.display().to_string())
        })
        .collect();
    let title = args.title.clone().unwrap_or_else(|| names.join(" · "));
    let mut page = viewer::Page::new(title);
    page.set_up(args.up);
    for (file, name) in files.iter().zip(&names) {
        let view = view_of(file, name, args.density)?;
        say!(
            "  {name}: {} vertices, {} triangles",
            view.mesh.positions.len(),
            view.mesh.indices.len()
        );
        page.add_view(view)
            .map_err(|source| ExperimentError::Page {
                path: file.clone(),
                source,
            })?;
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
    if viewer::is_patch_file(file) {
        let patches = viewer::read_patch_file(file).map_err(|e| ExperimentError::Read {
            path: file.to_path_buf(),
            source: std::io::Error::other(e),
        })?;
        // The page's memory before it is built, as every other output's.
        let points = patches
            .iter()
            .map(|p| {
                p.degree()
                    .saturating_add(1)
                    .saturating_mul(p.degree().saturating_add(2))
                    / 2
            })
            .max()
            .unwrap_or(0);
        let bytes = surface::limits::tessellation_bytes(patches.len() as u128, density)
            .saturating_add(surface::limits::sample_weights_bytes(points, density))
            .saturating_mul(PAGE_COPIES);
        fitjob::limits::check_memory(
            &format!("the page of {} at --density {density}", file.display()),
            bytes,
        )?;
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

/// Most bytes of a `.jsonl` file's first line read to tell a patch file from other JSON Lines.
const FIRST_LINE_LIMIT: u64 = 1 << 20;

/// The files `arg` stands for: itself, or a directory's viewable files sorted by name.
fn expand(arg: &Path) -> Result<Vec<PathBuf>, ExperimentError> {
    if !arg.is_dir() {
        return Ok(vec![arg.to_path_buf()]);
    }
    let read = |source| ExperimentError::Read {
        path: arg.to_path_buf(),
        source,
    };
    let mut entries: Vec<PathBuf> = std::fs::read_dir(arg)
        .map_err(read)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()
        .map_err(read)?;
    entries.sort();
    let mut kept = Vec::new();
    let mut skipped = Vec::new();
    for p in entries {
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        if !p.is_file() {
            continue;
        }
        let ext = p
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let viewable = match ext.as_deref() {
            Some("bzp") => true,
            Some("jsonl") => first_record_is_a_patch(&p),
            _ => meshio::format_for_path(&p).is_some(),
        };
        if viewable {
            kept.push(p);
        } else if let Some(n) = name {
            skipped.push(n);
        }
    }
    if !skipped.is_empty() {
        say!(
            "  {}: skipped {} files that are neither meshes nor patches ({})",
            arg.display(),
            skipped.len(),
            skipped.join(", ")
        );
    }
    if kept.is_empty() {
        return Err(ExperimentError::Usage(format!(
            "{}: the directory holds no mesh or patch file",
            arg.display()
        )));
    }
    Ok(kept)
}

/// Whether the first line of a JSON Lines file is a patch record (`"type": "BezierTriangle"`).
fn first_record_is_a_patch(path: &Path) -> bool {
    use std::io::{BufRead, Read};
    let Ok(f) = std::fs::File::open(path) else {
        return false;
    };
    let mut line = String::new();
    if std::io::BufReader::new(f.take(FIRST_LINE_LIMIT))
        .read_line(&mut line)
        .is_err()
    {
        return false;
    }
    serde_json::from_str::<serde_json::Value>(&line).is_ok_and(|r| r["type"] == "BezierTriangle")
}
