//! `tess`, the seed's Tess: each `BezierTriangle` to `s²` `Triangle` records, or with
//! `--mesh` to one shared-vertex `TriangleMesh` record; a patch's other fields are carried to
//! its records (`crate::filters` for the pass-through rules), other records pass through.
//!
//! Each patch is differentiated in its own unit frame (`crate::tessellator::UnitFrame`), so
//! its normals and curvatures do not depend on its size or position. Nothing is dropped or
//! made up silently: a patch whose control points are all equal (a point) writes no records
//! and is counted; samples at singular points and triangles collapsed by the weld are
//! counted; all three are reported on standard error at the end. A value that is not finite
//! (a curvature beyond `f64` at an extreme scale) is an error naming the record
//! (`--keep-going` skips the patch and counts it), never a number written.

use crate::error::{FieldError, FilterError};
use crate::filters::Filter;
use crate::pipe::{Pipe, StreamOptions};
use crate::record;
use crate::sample::{carried_fields, CurvatureFields, TriangleTapes};
use crate::stream::Record;
use crate::tessellator::{keeps_table, IndexedPatch, Outcome, PatchTessellator, TessCounts};
use crate::triangle_mesh::MeshTapes;

/// `testbed tess`.
pub struct Tess;

/// Options of `tess`.
#[derive(clap::Args, Debug)]
pub struct TessArgs {
    /// Segments per patch edge, from 1 to 4096 (and within memory: a patch at s takes about
    /// 44 bytes × s² while it is written, 0.5 kB × s² as one TriangleMesh, 44 bytes × s² as Triangles).
    #[arg(short = 's', long = "segments", value_name = "N", default_value_t = 8)]
    pub s: usize,
    /// Write Gaussian curvature `kg` at the vertices.
    #[arg(long)]
    pub kg: bool,
    /// Write mean curvature `km` at the vertices.
    #[arg(long)]
    pub km: bool,
    /// Write the principal curvatures `k1 ≥ k2` (the sign of `km`: k1 + k2 = 2 km) and their
    /// unit directions `d1`, `d2` (d2 = norm × d1) at the vertices, from the patches' exact
    /// second derivatives.
    #[arg(long)]
    pub kp: bool,
    /// Write one TriangleMesh record per patch (its vertices once, its triangles as
    /// indices): the default, accepted for scripts that ask for it.
    #[arg(long, conflicts_with = "triangles")]
    pub mesh: bool,
    /// Write the seed's s² Triangle records per patch instead of one TriangleMesh (every
    /// triangle with its three vertices: about three times the bytes and the work downstream).
    #[arg(long)]
    pub triangles: bool,
}

impl Filter for Tess {
    const NAME: &'static str = "tess";
    const SUMMARY: &'static str = "\
        BezierTriangles to one TriangleMesh per patch or, with --triangles, the seed's Triangles \
        (s² per patch); a patch's other fields go to its records";
    const DESCRIPTION: &'static str = "\
        Each triangle (or TriangleMesh) gets its vertices first, then every field of its patch \
        but `type`, `degree` and `points`, in the patch's order: `face`, `subpatch`, `scheme` \
        and anything added upstream. Records of other types pass through unchanged. Each vertex \
        carries its own patch's normal (and curvature), computed in the patch's unit frame (the \
        same figures at any scale). One patch is held at a time, and an -s whose patch would \
        not fit in memory is refused before it is tessellated. A patch whose control points are \
        all equal writes nothing and is counted; singular samples and collapsed triangles are \
        counted; a curvature beyond the range of a double (a patch 1e-200 across) is an error \
        naming the record (--keep-going skips it).";
    const SEED: &'static str = "Tess";
    type Args = TessArgs;

    fn run(args: TessArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let records = if args.triangles {
            TessRecords::Triangles
        } else {
            TessRecords::Mesh
        };
        let fields = CurvatureFields {
            kg: args.kg,
            km: args.km,
            kp: args.kp,
        };
        check_segments(Self::NAME, args.s)?;
        stream.filter(Self::NAME, &mut |p| tess(p, args.s, fields, records))
    }
}

/// Largest `tess -s` (and `fit -s`): a patch at s = 4096 is 8.4 M samples and 16.8 M
/// triangles, about 0.7 GB held while its `Triangle` records are written (88 bytes a sample,
/// [`tess_bytes`]; measured 0.73 GB), about 5 GB as one `--mesh` record (estimated 8.4 GB),
/// far beyond any picture's need; it keeps
/// every vertex index of a `TriangleMesh` within `u32`. Every `-s` is also checked against
/// the memory available before its first patch ([`check_tess_memory`]).
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

/// `-s N` of `tess` and `fit`: from 1 to [`MAX_SEGMENTS`] (a usage error naming the range
/// otherwise).
pub fn check_segments(filter: &str, s: usize) -> Result<(), FilterError> {
    if s == 0 || s > MAX_SEGMENTS {
        return Err(FilterError::Usage(format!(
            "{filter} -s {s}: from 1 to {MAX_SEGMENTS} segments per patch edge"
        )));
    }
    Ok(())
}

/// `tess -s N [--kg] [--km] [--kp] [--mesh]`: BezierTriangles to Triangles, or to one TriangleMesh
/// each (module docs for what is carried); what was counted (patches, degenerate ones,
/// singular samples, collapsed triangles), also reported on standard error.
pub fn tess(
    pipe: &mut Pipe,
    s: usize,
    fields: CurvatureFields,
    records: TessRecords,
) -> Result<TessCounts, FilterError> {
    check_segments("tess", s)?;
    let mut tessellator = PatchTessellator::new(s)?.with_principal(fields.kp);
    let mut degrees_checked = Vec::new();
    let mut rec = Record::default();
    let mut indexed = IndexedPatch::default();
    let mut tapes = TriangleTapes::new();
    let mut meshes = MeshTapes::default();
    let mut carried = Vec::new();
    let mut first_degenerate = None;
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
            check_tess_memory(s, patch.degree(), records)?;
            degrees_checked.push(patch.degree());
        }
        if tessellator.tessellate_indexed(&patch, &mut indexed)? == Outcome::Degenerate {
            first_degenerate.get_or_insert(rec.at);
            continue;
        }
        if let Some(bad) = indexed.first_non_finite(fields) {
            let what = match bad.field {
                "kg" => "Gaussian curvature",
                "km" => "mean curvature",
                "kp" => "principal curvature or direction",
                "norm" => "normal",
                _ => "position",
            };
            let size = surface::mesh::bounding_size(patch.points());
            pipe.bad_field(
                &rec,
                FieldError::new(
                    "points",
                    format!(
                        "the {what} at sample {} is {} at this patch's size ({size:.1e} across): beyond the range of a double (±{:.1e}); leave `--{}` out or rescale the input",
                        bad.sample,
                        bad.value,
                        f64::MAX,
                        bad.field
                    ),
                ),
            )?;
            continue;
        }
        match records {
            TessRecords::Mesh => {
                carried_fields(&rec.tape, &mut carried);
                let t = meshes.build(&rec.tape, &indexed, fields, &carried);
                match pipe.writer.write_tape(t, rec.at) {
                    Err(e) if e.is_record_error() => pipe.bad(e)?,
                    other => other?,
                }
            }
            TessRecords::Triangles => {
                // Each triangle's record built from the shared samples as it is written: no
                // list of triangles with their vertices is held beside them.
                tapes.start(&rec.tape);
                for k in 0..indexed.triangles.len() {
                    let t = tapes.build(
                        &rec.tape,
                        &indexed.triangle(k),
                        indexed.triangle_principal(k),
                        fields,
                    );
                    match pipe.writer.write_tape(t, rec.at) {
                        Err(e) if e.is_record_error() => pipe.bad(e)?,
                        other => other?,
                    }
                }
            }
        }
    }
    pipe.finish()?;
    report(pipe.name, &tessellator.counts(), first_degenerate);
    Ok(tessellator.counts())
}

/// Says on standard error what was not tessellated as asked: patches that are points, samples
/// at singular points, triangles collapsed by the weld (nothing when all is well).
fn report(name: &str, c: &TessCounts, first_degenerate: Option<crate::Position>) {
    if c.degenerate > 0 {
        let first = first_degenerate
            .map(|at| format!(", the first at {at}"))
            .unwrap_or_default();
        eprintln!(
            "{name}: {} of {} patches not tessellated: all their control points are equal (a point, no surface){first}",
            c.degenerate, c.patches
        );
    }
    if c.singular_samples > 0 {
        eprintln!(
            "{name}: {} samples at singular points (a collapsed edge or a patch with no normal): normal and curvature taken a small step inside, or the corner triangle's normal and zero curvature where the patch has none",
            c.singular_samples
        );
    }
    if c.collapsed_triangles > 0 {
        eprintln!(
            "{name}: {} triangles dropped: two of their corners welded into one vertex (a patch edge collapsed to a point)",
            c.collapsed_triangles
        );
    }
}

/// Bytes one sample of a patch takes while its `Triangle` records are written: the sample
/// (position, normal, K, H: 64 bytes) and its two triangles' indices (24 bytes), nothing else
/// (each triangle's record is built and written on its own). Measured: 86 bytes a sample at
/// `-s 4096` (docs/hostile-input.md).
const TRIANGLES_BYTES_PER_SAMPLE: u128 = 88;

/// Bytes one sample of a patch takes in its `TriangleMesh` record, built whole before it is
/// written: the sample (88 bytes as above), its 16 to 18 tokens (pos, norm, kg, km, two
/// triangles; 24 bytes each: 432) and its text in the output buffer (about 200 bytes of JSON),
/// with room for the buffers' growth by doubling. Measured (peak resident memory of the whole
/// process over the samples of one patch): 1573 bytes a sample at `-s 700` in the binary
/// stream, the default since issue 28 (630 were measured at `-s 1024` over JSON Lines before;
/// a 1024 record is now refused by the record limit instead). Under `ulimit -v` the check
/// counts the room left under the limit (`surface::limits::available_memory`): with 1000 here,
/// `tess -s 700` passed the check at a 360–420 MB limit and then aborted on a failed
/// allocation; with this figure it is refused with the message.
const MESH_BYTES_PER_SAMPLE: u128 = 1700;

/// Estimated bytes `tess -s s` holds for one patch of `degree`: its samples and what its
/// records need ([`TRIANGLES_BYTES_PER_SAMPLE`], [`MESH_BYTES_PER_SAMPLE`]), and the weight
/// table of the degree where one is kept (`crate::tessellator::MAX_TABLE_BYTES`;
/// [`surface::limits::sample_weights_bytes`]).
pub fn tess_bytes(s: usize, degree: usize, records: TessRecords) -> u128 {
    let samples = (s as u128 + 1).saturating_mul(s as u128 + 2) / 2;
    let points = (degree + 1) * (degree + 2) / 2;
    let per_sample = match records {
        TessRecords::Triangles => TRIANGLES_BYTES_PER_SAMPLE,
        TessRecords::Mesh => MESH_BYTES_PER_SAMPLE,
    };
    let table = if keeps_table(points, s) {
        surface::limits::sample_weights_bytes(points, s)
    } else {
        0
    };
    samples.saturating_mul(per_sample).saturating_add(table)
}

/// Refuses `tess -s s` for patches of `degree` when one patch's tessellation and the records
/// built from it ([`tess_bytes`]) would exceed the library's limit
/// ([`surface::limits::check_memory`]). One patch is held at a time, so the stream's length
/// does not count; the check is made when a degree is first met, before anything of it is
/// built.
pub fn check_tess_memory(s: usize, degree: usize, records: TessRecords) -> Result<(), FilterError> {
    let mesh = if records == TessRecords::Mesh {
        " --mesh"
    } else {
        ""
    };
    Ok(surface::limits::check_memory(
        &format!("tess -s {s}{mesh} (patches of degree {degree})"),
        tess_bytes(s, degree, records),
    )?)
}
