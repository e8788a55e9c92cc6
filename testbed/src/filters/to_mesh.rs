//! `to-mesh`: the stream's triangles as a mesh file, welded by position within a tolerance
//! (the library's weld), the format by the file's extension.

use std::path::Path;

use nalgebra::{Point3, Vector3};

use crate::draw;
use crate::error::FilterError;
use crate::filters::Filter;
use crate::pipe::StreamOptions;
use crate::record::Vertex;

/// `testbed to-mesh`.
pub struct ToMesh;

/// Options of `to-mesh` (the mesh file is the filter's `-o, --output FILE`).
#[derive(clap::Args, Debug)]
pub struct ToMeshArgs {
    /// How the mesh file is written.
    #[command(flatten)]
    pub mesh_options: fitjob::output::MeshOutputOptions,
}

impl Filter for ToMesh {
    const NAME: &'static str = "to-mesh";
    const SUMMARY: &'static str = "\
        The triangles as a mesh file (welded by position within a tolerance: the library's \
        weld), format by extension";
    const DESCRIPTION: &'static str = "\
        Reads every Triangle and every triangle of a TriangleMesh; other records are ignored. \
        Corners closer than a tolerance relative to the triangles' size are one vertex (the weld \
        surface::tessellate uses, so patches tessellated one by one close up); triangles the \
        weld collapses are dropped and counted on standard error. Normals and colours are \
        written when every vertex has them (colours sRGB-encoded in PLY, OBJ and OFF, linear in \
        glTF), and kg and km, in .ply and .glb, when every vertex has both: in libigl's, \
        trimesh's and MeshLab's convention (H > 0 on a sphere with outward normals; the \
        stream's km has the opposite sign). The mesh file is -o, --output FILE, its extension \
        naming the format; it is written atomically, and nothing goes to standard output.";
    type Args = ToMeshArgs;

    fn run(args: ToMeshArgs, stream: StreamOptions) -> Result<(), FilterError> {
        // The mesh file is the output; its format is checked before anything is read.
        let Some(path) = stream.output.clone() else {
            return Err(FilterError::Usage(format!(
                "to-mesh needs -o, --output FILE: the mesh file, its extension naming the format ({})",
                fitjob::output::writable_extensions()
            )));
        };
        let format = mesh_format(&path)?;
        meshio::outfile::writable_target(&path).map_err(render::RenderError::from)?;
        let tris = stream.read(Self::NAME, &mut draw::collect_triangles)?;
        if tris.is_empty() {
            eprintln!("{}: no triangles in the input", Self::NAME);
        }
        write_mesh(&tris, &path, format, &args.mesh_options)
    }
}

/// The writable mesh format `path`'s extension names, or the usage error listing them.
pub fn mesh_format(path: &Path) -> Result<&'static dyn meshio::MeshFormat, FilterError> {
    meshio::format_for_path(path)
        .filter(|f| f.can_write())
        .ok_or_else(|| {
            FilterError::Usage(format!(
                "to-mesh: --output {} names no writable mesh format ({})",
                path.display(),
                fitjob::output::writable_extensions()
            ))
        })
}

/// Triangles welded by position with the library's weld ([`surface::weld::weld_triangles`]:
/// corners closer than [`surface::tessellate::WELD_RELATIVE`] times the diagonal of the
/// triangles' bounding box are one vertex, so patches tessellated one by one, whose shared
/// boundary samples differ by rounding, close up), into a raw mesh with normals (the first
/// seen at a vertex) and colours (when every vertex has one); triangles the weld collapses are
/// dropped (counted in the second value).
pub fn to_raw(tris: &[[Vertex; 3]]) -> (meshio::RawMesh, surface::weld::WeldedTriangles) {
    let corners: Vec<[Point3<f64>; 3]> = tris.iter().map(|t| t.each_ref().map(|v| v.pos)).collect();
    let welded = surface::weld::weld_triangles(&corners);
    drop(corners);
    let all_normals = tris.iter().flatten().all(|v| v.norm.is_some());
    let all_colors = tris.iter().flatten().all(|v| v.color.is_some());
    let corner = |c: usize| tris.get(c / 3).and_then(|t| t.get(c % 3));
    let mut raw = meshio::RawMesh::from_triangles(welded.positions.clone(), &welded.faces);
    if all_normals {
        raw.normals = Some(
            welded
                .source
                .iter()
                .map(|&c| corner(c).and_then(|v| v.norm).unwrap_or_else(Vector3::z))
                .collect(),
        );
    }
    if all_colors {
        raw.colors = Some(
            welded
                .source
                .iter()
                .map(|&c| {
                    corner(c)
                        .and_then(|v| v.color)
                        .unwrap_or(render::colors::MATERIAL)
                })
                .collect(),
        );
    }
    (raw, welded)
}

/// Writes triangles as a mesh file of `format`, atomically; the curvature (`kg`, `km`, when
/// every vertex has both) where `format` stores it, in the exported convention.
pub fn write_mesh(
    tris: &[[Vertex; 3]],
    path: &Path,
    format: &dyn meshio::MeshFormat,
    mesh_options: &fitjob::output::MeshOutputOptions,
) -> Result<(), FilterError> {
    let (mut raw, welded) = to_raw(tris);
    if format.writes_curvature() {
        raw.curvature = curvature(tris, &welded);
    }
    meshio::outfile::write_atomic_mesh(path, format, &raw, &mesh_options.write_options()).map_err(
        |e| match e {
            meshio::outfile::MeshOutputError::Encode { path, source } => FilterError::MeshWrite {
                path,
                message: source.to_string(),
            },
            meshio::outfile::MeshOutputError::File(e) => render::RenderError::from(e).into(),
        },
    )?;
    eprintln!(
        "to-mesh: {} triangles, {} vertices ({} corners welded within {:.1e}: {:.0e} of the size; {} collapsed triangles dropped){} → {}",
        raw.num_faces(),
        raw.num_vertices(),
        welded.welds,
        welded.tolerance,
        surface::tessellate::WELD_RELATIVE,
        welded.collapsed,
        if raw.curvature.is_some() { ", with curvature" } else { "" },
        path.display()
    );
    Ok(())
}

/// The welded vertices' curvature from the stream's `kg` and `km` (the workbench's sign:
/// `km = −1` on the unit sphere) in the exported convention, when every corner has both.
fn curvature(
    tris: &[[Vertex; 3]],
    welded: &surface::weld::WeldedTriangles,
) -> Option<meshio::Curvature> {
    if !tris
        .iter()
        .flatten()
        .all(|v| v.kg.is_some() && v.km.is_some())
    {
        return None;
    }
    let corner = |c: usize| tris.get(c / 3).and_then(|t| t.get(c % 3));
    let (k, h): (Vec<f64>, Vec<f64>) = welded
        .source
        .iter()
        .map(|&c| {
            let v = corner(c);
            (
                v.and_then(|v| v.kg).unwrap_or(0.0),
                v.and_then(|v| v.km).unwrap_or(0.0),
            )
        })
        .unzip();
    Some(meshio::Curvature::from_internal(k, h))
}
