//! `tess`, the seed's Tess: each `BezierTriangle` to `s²` `Triangle` records, or with
//! `--mesh` to one shared-vertex `TriangleMesh` record; a patch's other fields are carried to
//! its records (`crate::filters` for the pass-through rules), other records pass through.

use crate::error::FilterError;
use crate::filters::Filter;
use crate::pipe::{Pipe, StreamOptions};
use crate::record;
use crate::sample::{carried_fields, CurvatureFields, TriangleTapes};
use crate::stream::Record;
use crate::tessellator::{IndexedPatch, PatchTessellator};
use crate::triangle_mesh::MeshTapes;

/// `testbed tess`.
pub struct Tess;

/// Options of `tess`.
#[derive(clap::Args, Debug)]
pub struct TessArgs {
    /// Segments per patch edge.
    #[arg(short = 's', default_value_t = 8)]
    pub s: usize,
    /// Write Gaussian curvature `kg` at the vertices.
    #[arg(long)]
    pub kg: bool,
    /// Write mean curvature `km` at the vertices.
    #[arg(long)]
    pub km: bool,
    /// Write one TriangleMesh record per patch (its vertices once, its triangles as
    /// indices) instead of s² Triangle records.
    #[arg(long)]
    pub mesh: bool,
}

impl Filter for Tess {
    const NAME: &'static str = "tess";
    const SUMMARY: &'static str = "\
        BezierTriangles to Triangles (s² per patch) or, with --mesh, one TriangleMesh per patch; \
        a patch's other fields go to its records";
    const DESCRIPTION: &'static str = "\
        Each triangle (or TriangleMesh) gets its vertices first, then every field of its patch \
        but `type`, `degree` and `points`, in the patch's order: `face`, `subpatch`, `scheme` \
        and anything added upstream. Records of other types pass through unchanged. Each vertex \
        carries its own patch's normal (and curvature); one patch is held at a time, and an -s \
        whose patch would not fit in memory is refused before it is tessellated.";
    const SEED: &'static str = "Tess";
    type Args = TessArgs;

    fn run(args: TessArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let records = if args.mesh {
            TessRecords::Mesh
        } else {
            TessRecords::Triangles
        };
        let fields = CurvatureFields {
            kg: args.kg,
            km: args.km,
        };
        stream.filter(Self::NAME, &mut |p| tess(p, args.s, fields, records))
    }
}

/// Largest `tess -s`: a patch at s = 4096 is 8.4 M samples (about half a GB with their weights),
/// far beyond any picture's need, while a larger `-s` would only exhaust memory (or overflow
/// the sample table's size) instead of failing with a message; it also keeps every vertex
/// index of a `TriangleMesh` within `u32`.
pub const MAX_SEGMENTS: usize = 4096;

/// What `tess` writes for each patch.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TessRecords {
    /// `s²` `Triangle` records (the seed's record, the default).
    #[default]
    Triangles,
    /// One `TriangleMesh` record: the patch's vertices once, its triangles as indices
    /// (`crate::triangle_mesh`).
    Mesh,
}

/// `tess -s N [--kg] [--km] [--mesh]`: BezierTriangles to Triangles, or to one TriangleMesh
/// each (module docs for what is carried).
pub fn tess(
    pipe: &mut Pipe,
    s: usize,
    fields: CurvatureFields,
    records: TessRecords,
) -> Result<(), FilterError> {
    if s == 0 || s > MAX_SEGMENTS {
        return Err(FilterError::Usage(format!(
            "tess: -s {s}: from 1 to {MAX_SEGMENTS} segments per edge"
        )));
    }
    let mut tessellator = PatchTessellator::new(s)?;
    let mut degrees_checked = Vec::new();
    let mut rec = Record::default();
    let mut indexed = IndexedPatch::default();
    let mut tris = Vec::new();
    let mut tapes = TriangleTapes::new();
    let mut meshes = MeshTapes::default();
    let mut carried = Vec::new();
    while pipe.next_good(&mut rec)? {
        if rec.kind() != "BezierTriangle" {
            pipe.write(&rec)?;
            continue;
        }
        let patch = match record::bezier_triangle(&rec.tape) {
            Ok(p) => p,
            Err(e) => {
                pipe.bad_field(&rec, e)?;
                continue;
            }
        };
        if !degrees_checked.contains(&patch.degree()) {
            check_tess_memory(s, patch.degree())?;
            degrees_checked.push(patch.degree());
        }
        match records {
            TessRecords::Mesh => {
                tessellator.tessellate_indexed(&patch, &mut indexed)?;
                carried_fields(&rec.tape, &mut carried);
                let t = meshes.build(&rec.tape, &indexed, fields, &carried);
                match pipe.writer.write_tape(t, rec.at) {
                    Err(e) if e.is_record_error() => pipe.bad(e)?,
                    other => other?,
                }
            }
            TessRecords::Triangles => {
                tessellator.tessellate(&patch, &mut tris)?;
                tapes.start(&rec.tape);
                for tri in &tris {
                    let t = tapes.build(&rec.tape, tri, fields);
                    match pipe.writer.write_tape(t, rec.at) {
                        Err(e) if e.is_record_error() => pipe.bad(e)?,
                        other => other?,
                    }
                }
            }
        }
    }
    pipe.finish()?;
    Ok(())
}

/// Bytes per sample of the record `tess` builds for one patch before writing it: a
/// `TriangleMesh` tape holds each sample's coordinates, normal and its two triangles' indices
/// as tokens with their text (measured: binary `--mesh` at `-s 1024` peaks at 1.7 GB, of which
/// 0.86 GB the weight table and 0.12 GB the tessellation, 1.4 KB a sample for the rest); a
/// `Triangle` stream holds the patch's triangles with their vertices (2 × 168 bytes a sample).
const TESS_RECORD_BYTES_PER_SAMPLE: u128 = 1500;

/// Refuses `tess -s s` for patches of `degree` when one patch's tessellation, the weight table
/// kept for the degree and the record built from it would exceed the library's limit
/// ([`surface::limits::check_memory`], the estimates of `experiments`:
/// [`surface::limits::tessellation_bytes`], [`surface::limits::sample_weights_bytes`]). One
/// patch is held at a time, so the stream's length does not count; the check is made when a
/// degree is first met, before its table is built.
pub fn check_tess_memory(s: usize, degree: usize) -> Result<(), FilterError> {
    let samples = (s as u128 + 1) * (s as u128 + 2) / 2;
    let points = (degree + 1) * (degree + 2) / 2;
    let bytes = surface::limits::tessellation_bytes(1, s)
        .saturating_add(surface::limits::sample_weights_bytes(points, s))
        .saturating_add(samples.saturating_mul(TESS_RECORD_BYTES_PER_SAMPLE));
    Ok(surface::limits::check_memory(
        &format!("tess -s {s} (patches of degree {degree})"),
        bytes,
    )?)
}
