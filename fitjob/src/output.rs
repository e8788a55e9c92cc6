//! Writing the job's outputs: atomically (`meshio::outfile`), to a file or to standard
//! output, and the checks made on every output path before any work is done.

use std::io::Write;
use std::path::Path;

use crate::error::JobError;

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename),
/// The file a stream option names: `-` is the standard stream (`None`: standard input or
/// output), anything else a file (docs/conventions.md, "The command language").
pub fn destination(path: &Path) -> Option<&Path> {
    (path.as_os_str() != "-").then_some(path)
}

/// creating the parent directory if needed; `None` writes to standard output.
pub fn write_result(path: Option<&Path>, bytes: &[u8]) -> Result<(), JobError> {
    match path {
        Some(p) => {
            if let Some(parent) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                ensure_dir(parent)?;
            }
            meshio::outfile::write_atomic(p, bytes).map_err(JobError::from)
        }
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(bytes)
                .and_then(|_| out.flush())
                .map_err(|source| JobError::Write {
                    path: "<stdout>".into(),
                    source,
                })
        }
    }
}

/// Writes to `path` atomically what `produce` writes, piece by piece (no full copy in memory);
/// `None` streams to standard output.
pub fn write_result_with(
    path: Option<&Path>,
    produce: &mut dyn FnMut(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), JobError> {
    match path {
        Some(p) => {
            if let Some(parent) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                ensure_dir(parent)?;
            }
            meshio::outfile::write_atomic_with(p, produce).map_err(JobError::from)
        }
        None => {
            let mut out = std::io::BufWriter::new(std::io::stdout().lock());
            produce(&mut out)
                .and_then(|_| out.flush())
                .map_err(|source| JobError::Write {
                    path: "<stdout>".into(),
                    source,
                })
        }
    }
}

/// Writes `mesh` as `format` to `path` atomically and streaming
/// ([`meshio::outfile::write_atomic_mesh`]: the encoder writes into the temporary file, the
/// file's bytes are never all in memory), creating the parent directory if needed. A mesh the
/// format refuses is [`JobError::MeshWrite`], a file that cannot be written the file's error;
/// both name `path`.
pub fn write_mesh_result(
    path: &Path,
    format: &dyn meshio::MeshFormat,
    mesh: &meshio::RawMesh,
    options: &meshio::WriteOptions,
) -> Result<(), JobError> {
    if let Some(parent) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        ensure_dir(parent)?;
    }
    meshio::outfile::write_atomic_mesh(path, format, mesh, options).map_err(|e| match e {
        meshio::outfile::MeshOutputError::Encode { path, source } => {
            JobError::MeshWrite { path, source }
        }
        meshio::outfile::MeshOutputError::File(e) => JobError::from(e),
    })
}

/// Creates a results directory (and its parents).
pub fn ensure_dir(dir: &Path) -> Result<(), JobError> {
    std::fs::create_dir_all(dir).map_err(|source| JobError::Write {
        path: dir.to_path_buf(),
        source,
    })
}

/// Refuses, before any work is done, an output `out` (given by `option`) that could not be
/// written at the end: a path that exists and is not a regular file or a link to one (a
/// directory, a device …: [`meshio::outfile::writable_target`]), or the input file itself
/// ([`refuse_overwriting_input`]). A run over a large mesh then fails in milliseconds instead
/// of after its whole computation.
pub fn refuse_unwritable(option: &'static str, out: &Path, input: &str) -> Result<(), JobError> {
    meshio::outfile::writable_target(out)?;
    refuse_overwriting_input(option, out, input)
}

/// Refuses to write `out` (given by `option`, such as `--out`) when it is the input file `input`
/// (the same file, by any path): a conversion or fit would otherwise destroy its own input.
pub fn refuse_overwriting_input(
    option: &'static str,
    out: &Path,
    input: &str,
) -> Result<(), JobError> {
    let (Ok(a), Ok(b)) = (std::fs::canonicalize(out), std::fs::canonicalize(input)) else {
        return Ok(());
    };
    if a == b {
        return Err(JobError::OutputIsInput {
            option,
            path: out.to_path_buf(),
        });
    }
    Ok(())
}

/// The writable mesh format `path`'s extension names, or the error naming `option` and the
/// extensions that would do.
pub fn mesh_format_for(
    option: &'static str,
    path: &Path,
) -> Result<&'static dyn meshio::MeshFormat, JobError> {
    meshio::format_for_path(path)
        .filter(|f| f.can_write())
        .ok_or_else(|| JobError::UnsupportedOutputFormat {
            option,
            path: path.to_path_buf(),
            writable: writable_extensions(),
        })
}

/// The extensions of the writable mesh formats as a message lists them (`.obj, .ply, …`;
/// `meshio::writable_extensions`).
pub fn writable_extensions() -> String {
    meshio::writable_extensions()
        .iter()
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// How mesh files are written: the options every command that writes one shares (`--up`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct MeshOutputOptions {
    /// The data's up axis, for mesh formats that fix one: glTF is y up, so the default (z, the
    /// workbench's data) is turned into glTF's y; `y` writes the data unchanged. Recorded in the
    /// file's `extras`.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = meshio::UpAxis::Z))]
    pub up: meshio::UpAxis,
}

impl MeshOutputOptions {
    /// The writer's options these ask for.
    pub fn write_options(&self) -> meshio::WriteOptions {
        meshio::WriteOptions::new().up(self.up)
    }
}

/// A tessellation as the mesh a file of `format` stores: positions, normals, colours by
/// Gaussian curvature (the testbed's KColor: diverging map saturating at the 95th percentile
/// of `|K|`, so a few spikes do not wash the picture out; the range is recorded with the
/// colours), and where `format` stores curvature ([`meshio::MeshFormat::writes_curvature`]),
/// the Gaussian and mean curvature and the principal directions in the exported convention (`H > 0` on a sphere with
/// outward normals; [`meshio::Curvature::from_internal`]). A format that stores no curvature
/// is not given any, so nothing it does not store can stop it.
pub fn tessellation_mesh(
    tess: &surface::Tessellation,
    format: &dyn meshio::MeshFormat,
) -> meshio::RawMesh {
    let extras = TessellationExtras::of(tess, format);
    extras.mesh(
        tess.positions.clone(),
        tess.normals.clone(),
        tess.faces.clone(),
        || (tess.gaussian.clone(), tess.mean.clone()),
    )
}

/// [`tessellation_mesh`] taking the tessellation: its positions, normals and curvature move
/// into the mesh instead of being copied (for a caller that no longer needs it).
pub fn into_tessellation_mesh(
    tess: surface::Tessellation,
    format: &dyn meshio::MeshFormat,
) -> meshio::RawMesh {
    let mut tess = tess;
    let given = std::mem::take(&mut tess.directions);
    let extras = TessellationExtras::of_given(&tess, format, given);
    let surface::Tessellation {
        positions,
        normals,
        gaussian,
        mean,
        faces,
        shapes,
        patch_of_face,
        ..
    } = tess;
    // What the file does not store goes before its mesh is built (the shape tensors, 72 B a
    // vertex, were read by `extras` for the principal directions where the format wants them;
    // the faces' patches, 8 B a triangle); the triangles become the mesh's polygons in place.
    drop(shapes);
    drop(patch_of_face);
    extras.mesh(positions, normals, faces, || (gaussian, mean))
}

/// What [`tessellation_mesh`] derives from a tessellation before taking its arrays: the
/// colours by Gaussian curvature, their map, and the principal directions where the format
/// stores curvature.
struct TessellationExtras {
    colors: Vec<[f32; 3]>,
    color_map: meshio::ColorMap,
    directions: Option<Vec<[nalgebra::Vector3<f64>; 2]>>,
}

impl TessellationExtras {
    fn of(tess: &surface::Tessellation, format: &dyn meshio::MeshFormat) -> Self {
        Self::of_given(tess, format, Vec::new())
    }

    /// [`TessellationExtras::of`], with the tessellation's principal directions taken from
    /// `given` when it has one per vertex (a tessellation that stored them instead of its
    /// shape tensors), from the tensors otherwise ([`principal_directions`]).
    fn of_given(
        tess: &surface::Tessellation,
        format: &dyn meshio::MeshFormat,
        given: Vec<[nalgebra::Vector3<f64>; 2]>,
    ) -> Self {
        let limit = gaussian_colour_limit(&tess.gaussian);
        TessellationExtras {
            colors: tess
                .gaussian
                .iter()
                .map(|k| render::colors::diverging(*k, limit))
                .collect(),
            color_map: meshio::ColorMap {
                quantity: "gaussian_curvature".into(),
                map: "diverging".into(),
                min: -limit,
                max: limit,
            },
            directions: format.writes_curvature().then(|| {
                if !given.is_empty() && given.len() == tess.positions.len() {
                    given
                } else {
                    principal_directions(tess)
                }
            }),
        }
    }

    /// The mesh of these arrays; `curvature` (internal `K`, `H`) is asked for only where the
    /// format stores it.
    fn mesh(
        self,
        positions: Vec<nalgebra::Point3<f64>>,
        normals: Vec<nalgebra::Vector3<f64>>,
        faces: Vec<[usize; 3]>,
        curvature: impl FnOnce() -> (Vec<f64>, Vec<f64>),
    ) -> meshio::RawMesh {
        let mut raw = meshio::RawMesh::from_triangle_vec(positions, faces);
        raw.normals = Some(normals);
        raw.colors = Some(self.colors);
        raw.color_map = Some(self.color_map);
        if let Some(directions) = self.directions {
            let (k, h) = curvature();
            raw.curvature =
                Some(meshio::Curvature::from_internal(k, h).with_directions(directions));
        }
        raw
    }
}

/// The unit principal directions `[d1, d2]` (of `κ1 ≥ κ2`, the exported convention) at every
/// tessellation vertex, from its exact shape tensor and normal (`estimate::principal_frame`);
/// the tessellation's own where it stored them instead of the tensors
/// (`surface::tessellate_fit::Keep::directions`: the same numbers, bit for bit).
pub fn principal_directions(tess: &surface::Tessellation) -> Vec<[nalgebra::Vector3<f64>; 2]> {
    if !tess.directions.is_empty() && tess.directions.len() == tess.positions.len() {
        return tess.directions.clone();
    }
    tess.shapes
        .iter()
        .zip(&tess.normals)
        .map(|(s, n)| {
            let p = estimate::principal_frame(s, n);
            [p.d1, p.d2]
        })
        .collect()
}

/// The colour limit of [`tessellation_mesh`]: the 95th percentile of the finite `|K|` (by the
/// index `⌊(n − 1) · 95/100⌋`), 1 when that is zero or there is none.
pub fn gaussian_colour_limit(gaussian: &[f64]) -> f64 {
    let mut abs: Vec<f64> = gaussian
        .iter()
        .map(|k| k.abs())
        .filter(|k| k.is_finite())
        .collect();
    abs.sort_by(f64::total_cmp);
    abs.get(abs.len().saturating_sub(1) * 95 / 100)
        .copied()
        .filter(|l| *l > 0.0)
        .unwrap_or(1.0)
}

/// Refuses, before a fit, a mesh output (given by `option`) whose format stores curvature as
/// 32-bit floats when the model's `size` (its largest side) puts its curvature outside them
/// ([`meshio::convention::curvature_scale_fits_f32`]). A format without curvature passes
/// whatever the size.
pub fn refuse_unstorable_curvature(
    option: &'static str,
    path: &Path,
    format: &dyn meshio::MeshFormat,
    size: f64,
) -> Result<(), JobError> {
    if !format.writes_curvature() {
        return Ok(());
    }
    meshio::convention::curvature_scale_fits_f32(size).map_err(|message| JobError::MeshWrite {
        path: path.to_path_buf(),
        source: meshio::WriteError::Invalid {
            format: format.name(),
            message: format!("{option}: {message}"),
        },
    })
}
