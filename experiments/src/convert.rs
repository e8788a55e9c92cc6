//! `experiments -- convert`: read a mesh in any supported format, repair it, estimate what it
//! lacks, and write it in the format its output extension names.
//!
//! `.m` output (the testbed format) carries the normals in `norm` and the shape tensors in
//! `shape`, so `fit --data OUT.m --estimate none` reads them back as exact data. `.ply` output
//! carries the normals, and the Gaussian and mean curvature as vertex properties `gaussian` and
//! `mean` when the curvature is known; `.obj`, `.off`, `.glb` carry the normals; `.stl` carries
//! positions and facets only (the format has no more).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use meshio::WriteOptions;

use crate::error::ExperimentError;
use crate::input::{load, InputArgs};
use crate::output::write_result;

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
}

/// Runs the conversion.
pub fn run(args: &ConvertArgs) -> Result<ExitCode, ExperimentError> {
    let t0 = Instant::now();
    let format = crate::output::mesh_format_for("--output", &args.output)?;
    let loaded = load(&args.input)?;
    crate::output::refuse_overwriting_input("--output", &args.output, &args.input.data)?;
    let mut world = loaded.mesh.clone();
    loaded.frame.mesh_to_world(&mut world);
    let mesh = &world;
    let mut raw = surface::repair::mesh_to_raw(mesh, true);
    if format.writes_properties() && mesh.vertices().iter().all(|v| v.curvature_known) {
        let (k, h): (Vec<f64>, Vec<f64>) = mesh
            .vertices()
            .iter()
            .map(|v| {
                let [a, b] = estimate::principal_curvatures(&v.data.shape, &v.data.n);
                (a * b, 0.5 * (a + b))
            })
            .unzip();
        raw.properties.insert("gaussian".into(), k);
        raw.properties.insert("mean".into(), h);
    }
    let options = if args.ascii {
        WriteOptions::new().ascii()
    } else {
        WriteOptions::new()
    };
    let bytes = meshio::write_bytes(&raw, format, &options).map_err(|source| {
        ExperimentError::MeshWrite {
            path: args.output.clone(),
            source,
        }
    })?;
    write_result(Some(&args.output), &bytes)?;
    for note in &loaded.notes {
        say!("  {note}");
    }
    say!(
        "convert: {} ({} vertices, {} faces) → {} ({} bytes, {}) in {:.3} s",
        args.input.data,
        mesh.num_vertices(),
        mesh.num_faces(),
        args.output.display(),
        bytes.len(),
        format.name(),
        t0.elapsed().as_secs_f64()
    );
    Ok(ExitCode::SUCCESS)
}
