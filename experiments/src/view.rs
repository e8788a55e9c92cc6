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
    /// The axis the camera keeps up and the reflection lines turn about: z (the workbench's
    /// data) or y (most scanned models); the page's `#up=` overrides it.
    #[arg(long, default_value_t = meshio::UpAxis::Z)]
    up: meshio::UpAxis,
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
    page.set_up(args.up);
    for (file, name) in args.files.iter().zip(&names) {
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
