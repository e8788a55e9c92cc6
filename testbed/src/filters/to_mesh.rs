//! `to-mesh`: the stream's triangles as a mesh file, welded by position within a tolerance
//! (the library's weld), the format by the file's extension.

use std::path::{Path, PathBuf};

use nalgebra::{Point3, Vector3};

use crate::draw;
use crate::error::FilterError;
use crate::filters::Filter;
use crate::pipe::StreamOptions;
use crate::record::Vertex;

/// `testbed to-mesh`.
pub struct ToMesh;

/// Options of `to-mesh`.
#[derive(clap::Args, Debug)]
pub struct ToMeshArgs {
    /// The mesh file (.ply, .obj, .glb, .off, .stl, .m).
    #[arg(long)]
    pub out: PathBuf,
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
        written when every vertex has them. The file is written atomically.";
    type Args = ToMeshArgs;

    fn run(args: ToMeshArgs, stream: StreamOptions) -> Result<(), FilterError> {
        // The mesh is its own file: an --output would be written empty (a file that looks
        // like a result and holds nothing), so it is refused before anything is read.
        if let Some(o) = &stream.output {
            return Err(FilterError::Usage(format!(
                "--output {}: to-mesh writes its mesh to --out and nothing else (leave --output out)",
                o.display()
            )));
        }
        let tris = stream.read(Self::NAME, &mut draw::collect_triangles)?;
        if tris.is_empty() {
            eprintln!("{}: no triangles in the input", Self::NAME);
        }
        // Nothing goes to the output (standard output or --output): the mesh is its own file.
        stream.with_output(&mut |_| write_mesh(&tris, &args.out))
    }
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

/// Writes triangles as a mesh file, the format by `path`'s extension, atomically.
pub fn write_mesh(tris: &[[Vertex; 3]], path: &Path) -> Result<(), FilterError> {
    let format = meshio::format_for_path(path)
        .filter(|f| f.can_write())
        .ok_or_else(|| {
            FilterError::Usage(format!(
                "to-mesh: {} names no writable mesh format (.ply, .obj, .glb, .stl, .off, .m)",
                path.display()
            ))
        })?;
    let (raw, welded) = to_raw(tris);
    let bytes = meshio::write_bytes(&raw, format, &meshio::WriteOptions::new()).map_err(|e| {
        FilterError::MeshWrite {
            path: path.to_path_buf(),
            message: e.to_string(),
        }
    })?;
    meshio::outfile::write_atomic(path, &bytes).map_err(render::RenderError::from)?;
    eprintln!(
        "to-mesh: {} triangles, {} vertices ({} corners welded within {:.1e}: {:.0e} of the size; {} collapsed triangles dropped) → {}",
        raw.num_faces(),
        raw.num_vertices(),
        welded.welds,
        welded.tolerance,
        surface::tessellate::WELD_RELATIVE,
        welded.collapsed,
        path.display()
    );
    Ok(())
}
