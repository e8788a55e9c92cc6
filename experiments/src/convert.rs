//! `experiments -- convert`: read a mesh in any supported format, repair it, estimate what it
//! lacks, and write it in the format its output extension names.
//!
//! `.m` output (the testbed format) carries the normals in `norm` and the shape tensors in
//! `shape`, so `fit --data OUT.m --estimate none` reads them back as exact data (the
//! workbench's own sign convention). `.ply` and `.glb` output carry the normals and, when the
//! curvature is known, the curvature in libigl's, trimesh's and MeshLab's convention (`H > 0`
//! on a sphere with outward normals: `meshio::convention`): PLY `quality` (K),
//! `gaussian_curvature`, `mean_curvature`, `k1`, `k2` and the principal directions `pd1x …
//! pd2z`; glTF `_GAUSSIAN_CURVATURE`, `_MEAN_CURVATURE`, `_PRINCIPAL_CURVATURE_1/2`,
//! `_PRINCIPAL_DIRECTION_1/2` (`--up` says which axis is up; glTF is y up). `.obj`, `.off` carry the
//! normals; `.stl` carries positions and facets only (the format has no more).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use crate::error::ExperimentError;
use crate::input::{load, InputArgs};

/// Options of the `convert` experiment.
#[derive(clap::Args, Debug)]
pub struct ConvertArgs {
    /// The input mesh and how to complete it.
    #[command(flatten)]
    input: InputArgs,
    /// The output file; its extension names the format (.m, .obj, .ply, .off, .stl, .glb).
    #[arg(short = 'o', long)]
    output: PathBuf,
    /// Write text instead of binary where the format offers both (PLY, STL).
    #[arg(long)]
    ascii: bool,
    /// How the mesh file is written.
    #[command(flatten)]
    mesh_options: fitjob::output::MeshOutputOptions,
}

/// The PLY vertex properties the curvature is written as (`meshio::ply`).
const CURVATURE_PROPERTY_NAMES: [&str; 11] = [
    "quality",
    "gaussian_curvature",
    "mean_curvature",
    "k1",
    "k2",
    "pd1x",
    "pd1y",
    "pd1z",
    "pd2x",
    "pd2y",
    "pd2z",
];

/// Runs the conversion.
pub fn run(args: &ConvertArgs) -> Result<ExitCode, ExperimentError> {
    let t0 = Instant::now();
    let format = crate::output::mesh_format_for("--output", &args.output)?;
    let loaded = load(&args.input)?;
    crate::output::refuse_overwriting_input("--output", &args.output, &args.input.data)?;
    // The loaded mesh itself is mapped to world coordinates (a copy of it was the largest
    // single allocation of the conversion: 0.2 GB at 10⁶ faces).
    // What the file does not need (the maps back to the input's faces and vertices: 12 bytes
    // a face at 10⁶ faces) goes at once.
    let fitjob::input::Loaded {
        mesh: mut world,
        frame,
        notes,
        ..
    } = loaded;
    frame.mesh_to_world(&mut world);
    let mesh = &world;
    let (num_vertices, num_faces) = (mesh.num_vertices(), mesh.num_faces());
    // The shape tensors only for a format that stores them (72 bytes a vertex).
    let mut raw = surface::repair::mesh_to_raw_with(mesh, true, format.writes_shapes());
    if format.writes_curvature() && mesh.vertices().iter().all(|v| v.curvature_known) {
        // The workbench's sign internally; the file gets the exported one (H > 0 on a sphere).
        let (k, h): (Vec<f64>, Vec<f64>) = mesh
            .vertices()
            .iter()
            .map(|v| {
                let [a, b] = estimate::principal_curvatures(&v.data.shape, &v.data.n);
                (a * b, 0.5 * (a + b))
            })
            .unzip();
        let directions = mesh
            .vertices()
            .iter()
            .map(|v| {
                let p = estimate::principal_frame(&v.data.shape, &v.data.n);
                [p.d1, p.d2]
            })
            .collect();
        // Properties of the input under the names the curvature is written as give way to it.
        for name in CURVATURE_PROPERTY_NAMES {
            if raw.properties.remove(name).is_some() {
                say!("  the input's vertex property `{name}` is replaced by the curvature");
            }
        }
        raw.curvature = Some(meshio::Curvature::from_internal(k, h).with_directions(directions));
    }
    // Everything the file needs is in `raw` now: the mesh is let go before the write.
    drop(world);
    let mut options = args.mesh_options.write_options();
    if args.ascii {
        options = options.ascii();
    }
    fitjob::output::write_mesh_result(&args.output, format, &raw, &options).map_err(
        |e| match e {
            fitjob::JobError::MeshWrite { path, source } => {
                ExperimentError::MeshWrite { path, source }
            }
            other => ExperimentError::from(other),
        },
    )?;
    // The size as written (the file was streamed, not held in memory).
    let written = std::fs::metadata(&args.output).map_or(0, |m| m.len());
    for note in &notes {
        say!("  {note}");
    }
    say!(
        "convert: {} ({} vertices, {} faces) → {} ({} bytes, {}) in {:.3} s",
        args.input.data,
        num_vertices,
        num_faces,
        args.output.display(),
        written,
        format.name(),
        t0.elapsed().as_secs_f64()
    );
    Ok(ExitCode::SUCCESS)
}
