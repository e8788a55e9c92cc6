//! The seed's `G1` as a filter: every record passes through unchanged; the BezierTriangles
//! are kept aside and, at the end of the stream, measured by the library
//! ([`surface::patch_g1::measure_patches`]).
//!
//! Two patches share a boundary when their boundary curves have the same control points
//! **within a tolerance** ([`surface::patch_g1::MATCH_RELATIVE`] times the diagonal of the
//! patches' bounding box; never bit for bit), in reverse order (the usual case: neighbours
//! traverse their common edge in opposite directions) or in the same order (then the two
//! patches are oppositely oriented: counted, and the normal of the second is flipped before
//! comparing). At `samples` equally spaced parameters (ends included; at least
//! [`surface::patch_g1::MIN_SAMPLES`]) the angle between the normals is measured with the
//! library's G1 sampling ([`surface::g1`]); samples where either normal is undefined (a
//! collapsed corner) are skipped and counted.
//!
//! What could not be measured is counted and reported: edges between two corners that other
//! patch edges also join, along another curve (a C0 defect: *mismatched*), and shared
//! boundaries with no defined normal at any sample. With `--strict` the run fails on a normal
//! angle above [`G1_TOLERANCE`], on anything left unmeasured (a boundary, or a single sample
//! where a normal is undefined), and when nothing was measured. `--samples` runs from
//! [`surface::patch_g1::MIN_SAMPLES`] to [`MAX_SAMPLES`]; the patches held until the end are
//! checked against the memory available as they come ([`PATCH_BYTES`]).

use surface::patch_g1::{self, PatchG1Report};
use surface::BezierTriangle;

use crate::error::FilterError;
use crate::filters::Filter;
use crate::pipe::{Pipe, StreamOptions};
use crate::record;

/// Largest normal angle (radians) along a shared boundary still called G1 by `--strict`:
/// 1e-6 rad is far above the rounding of a patch carried through the text formats and the
/// working frame's way back (about 1e-14 rad measured on `shirman-sequin` on the built-in
/// ring), far below any crease a picture shows (a tenth of a degree is 1.7e-3 rad).
pub const G1_TOLERANCE: f64 = 1e-6;

/// Default samples per boundary (ends included).
pub const DEFAULT_SAMPLES: usize = 9;

/// Most samples per boundary: 4097 put a sample within 1/8192 of every point of a boundary,
/// where a normal angle that is a polynomial of low degree along it (every scheme's) has long
/// shown its maximum; the work is linear in the samples (measured: 10⁶ samples on the 36
/// boundaries of a 24-patch octahedron took over a minute, 4097 take a fifth of a second:
/// docs/hostile-input.md), so a larger count only costs time.
pub const MAX_SAMPLES: usize = 4097;

/// Bytes one patch held by `g1` takes, for the memory check as they accumulate: a quartic's
/// 15 control points (360 bytes), its vector's header and the allocator's slack (about 64),
/// its record number and the matching's corner and edge entries (about 200).
pub const PATCH_BYTES: u128 = 640;

/// `testbed g1`: the seed's G1.
pub struct G1;

/// Options of `g1`.
#[derive(clap::Args, Debug)]
pub struct G1Args {
    /// Exit with an error when the largest angle exceeds the tolerance (1e-6 rad), when a
    /// boundary or a sample could not be measured, or when nothing was measured.
    #[arg(long)]
    pub strict: bool,
    /// Samples per boundary, ends included (3 to 4097: the ends alone say nothing).
    #[arg(long, default_value_t = DEFAULT_SAMPLES, value_parser = samples_option)]
    pub samples: usize,
}

impl Filter for G1 {
    const NAME: &'static str = "g1";
    const SUMMARY: &'static str =
        "Passes records through; measures normal angles along shared patch boundaries";
    const DESCRIPTION: &'static str = "\
        Every record is written unchanged. The BezierTriangles are kept aside and measured at \
        the end of the stream: two patch edges are one boundary when their control points agree \
        within a tolerance relative to the patches' size (never bit for bit), and the angle \
        between the two normals is sampled along it. The report goes to standard error: the \
        largest angle and where, border and mismatched edges (not even C0), boundaries with no \
        defined normal.";
    const SEED: &'static str = "G1";
    type Args = G1Args;

    fn run(args: G1Args, stream: StreamOptions) -> Result<(), FilterError> {
        stream.filter(Self::NAME, &mut |p| g1(p, args.strict, args.samples))
    }
}

/// `g1 --samples N`: a whole number from [`surface::patch_g1::MIN_SAMPLES`] to
/// [`MAX_SAMPLES`] (clap refuses anything else as a usage error, exit status 2).
fn samples_option(s: &str) -> Result<usize, String> {
    let min = patch_g1::MIN_SAMPLES;
    match s.parse::<usize>() {
        Ok(n) if (min..=MAX_SAMPLES).contains(&n) => Ok(n),
        _ => Err(format!(
            "from {min} to {MAX_SAMPLES} samples per boundary (with 2 only the ends are sampled, where every interpolating scheme has the vertex normal on both sides; beyond {MAX_SAMPLES} the work grows and the largest angle does not)"
        )),
    }
}

/// What the G1 measurement found: the library's report, with record numbers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct G1Summary {
    /// The library's figures (patch indices count from 0 in stream order).
    pub report: PatchG1Report,
    /// Record number of each patch.
    pub records: Vec<usize>,
}

/// Where the largest angle was measured, by record.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Worst {
    /// Angle in radians.
    pub angle: f64,
    /// Record number of the first patch.
    pub record_a: usize,
    /// Its edge (0: `w = 0` from `u` to `v`; 1: `u = 0`; 2: `v = 0`).
    pub edge_a: usize,
    /// Record number of the second patch.
    pub record_b: usize,
    /// Its edge.
    pub edge_b: usize,
    /// Parameter along the first patch's edge.
    pub t: f64,
}

impl G1Summary {
    /// Patches read.
    pub fn patches(&self) -> usize {
        self.report.patches
    }

    /// Boundary edges with no partner within the tolerance: the border and the mismatched.
    pub fn unshared(&self) -> usize {
        self.report.border + self.report.mismatched
    }

    /// The record number of patch `i`.
    fn record(&self, i: usize) -> usize {
        self.records.get(i).copied().unwrap_or(i + 1)
    }

    /// The largest angle and where, by record.
    pub fn worst(&self) -> Option<Worst> {
        self.report.worst.map(|w| Worst {
            angle: w.angle,
            record_a: self.record(w.a.0),
            edge_a: w.a.1,
            record_b: self.record(w.b.0),
            edge_b: w.b.1,
            t: w.t,
        })
    }
}

/// Measures `patches`, patch `i` from record `records[i]`, at `samples` points per boundary;
/// `creases[i]` flags the patch edges its record marks as crease edges (left out, counted).
pub fn measure(
    records: &[usize],
    patches: &[BezierTriangle],
    creases: &[[bool; 3]],
    samples: usize,
) -> G1Summary {
    let crease = |(p, e): patch_g1::PatchEdge| creases.get(p).is_some_and(|c| c[e]);
    G1Summary {
        report: patch_g1::measure_patches_with_creases(patches, samples, &crease),
        records: records.to_vec(),
    }
}

/// `g1 [--strict] [--samples N]`: passes every record through, measures the patches at the
/// end, reports on standard error. With `strict`, an angle above [`G1_TOLERANCE`], a boundary
/// or a sample left unmeasured, or nothing measured is an error. A sample count outside
/// [`surface::patch_g1::MIN_SAMPLES`]`..=`[`MAX_SAMPLES`] is a usage error (the ends alone
/// say nothing; more only costs time).
pub fn g1(pipe: &mut Pipe, strict: bool, samples: usize) -> Result<G1Summary, FilterError> {
    if !(patch_g1::MIN_SAMPLES..=MAX_SAMPLES).contains(&samples) {
        return Err(FilterError::Usage(format!(
            "g1 --samples {samples}: from {} to {MAX_SAMPLES} (the ends alone are the vertex normals, equal on both sides for every interpolating scheme; more only costs time)",
            patch_g1::MIN_SAMPLES
        )));
    }
    let mut patches = Vec::new();
    let mut records = Vec::new();
    let mut creases = Vec::new();
    let mut rec = crate::stream::Record::default();
    while pipe.next_good(&mut rec)? {
        if rec.kind() == "BezierTriangle" {
            match record::bezier_triangle(&rec.tape)
                .and_then(|p| Ok((p, record::patch_creases(&rec.tape)?)))
            {
                Ok((p, c)) => {
                    if patches.len() == patches.capacity() {
                        // The vector is about to grow: check the patches it will hold.
                        let next = (patches.len() as u128 * 2).max(64);
                        surface::limits::check_memory(
                            &format!("g1 holding {next} patches until the end of the stream"),
                            next.saturating_mul(PATCH_BYTES),
                        )?;
                    }
                    patches.push(p);
                    creases.push(c);
                    records.push(rec.at.record);
                }
                Err(e) => {
                    pipe.bad_field(&rec, e)?;
                    continue;
                }
            }
        }
        pipe.write(&rec)?;
    }
    pipe.finish()?;
    let summary = measure(&records, &patches, &creases, samples);
    let r = &summary.report;
    eprintln!(
        "g1: {} patches, {} shared boundaries ({} measured), {} unshared ({} border, {} mismatched), {} unmeasurable, {} collapsed edges, {} orientation mismatches, {} samples unmeasured (an undefined normal) (boundaries matched within {:.1e}: {:.0e} of the patches' size)",
        r.patches,
        r.shared,
        r.measured,
        summary.unshared(),
        r.border,
        r.mismatched,
        r.unmeasurable,
        r.collapsed,
        r.orientation_mismatches,
        r.undefined,
        r.tolerance,
        patch_g1::MATCH_RELATIVE,
    );
    if r.creases > 0 {
        eprintln!(
            "g1: {} shared boundaries on creases (marked by their records: C0 by construction, not measured)",
            r.creases
        );
    }
    if r.non_manifold > 0 {
        eprintln!(
            "g1: {} boundaries shared by more than two patches (each measured against the first)",
            r.non_manifold
        );
    }
    if r.unmeasured() > 0 {
        let first = r
            .mismatched_at
            .first()
            .map(|&(p, e)| format!(", the first at record {} edge {}", summary.record(p), e))
            .unwrap_or_default();
        eprintln!(
            "g1: warning: {} boundaries not measured: {} mismatched (patches meeting at both ends along different curves: not even C0{first}), {} with no defined normal at any sample",
            r.unmeasured(),
            r.mismatched,
            r.unmeasurable
        );
    }
    if r.undefined > 0 {
        eprintln!(
            "g1: warning: {} samples not measured: a normal undefined on one side (a collapsed corner or a degenerate patch)",
            r.undefined
        );
    }
    let worst = summary.worst();
    match worst {
        Some(w) => {
            let verdict = if w.angle > G1_TOLERANCE {
                "warning: not G1"
            } else {
                "G1 within tolerance"
            };
            eprintln!(
                "g1: {verdict}: largest normal angle {:.3e} rad ({:.4}°) between record {} edge {} and record {} edge {} at t = {:.3} (tolerance {:.0e} rad)",
                w.angle,
                w.angle.to_degrees(),
                w.record_a,
                w.edge_a,
                w.record_b,
                w.edge_b,
                w.t,
                G1_TOLERANCE
            );
        }
        None => {
            eprintln!("g1: warning: nothing measured (no shared boundary with a defined normal)")
        }
    }
    if strict {
        let exceeded = worst.filter(|w| w.angle > G1_TOLERANCE || w.angle.is_nan());
        let mut problems = Vec::new();
        if r.unmeasured() > 0 {
            problems.push(format!(
                "{} boundaries left unmeasured ({} mismatched, {} with no defined normal)",
                r.unmeasured(),
                r.mismatched,
                r.unmeasurable
            ));
        }
        if r.undefined > 0 {
            problems.push(format!(
                "{} samples left unmeasured (a normal undefined on one side: a collapsed corner or a degenerate patch)",
                r.undefined
            ));
        }
        if r.measured == 0 {
            problems.push(format!(
                "nothing measured: {} patches, no shared boundary with a defined normal",
                r.patches
            ));
        }
        match exceeded {
            Some(w) if problems.is_empty() => {
                return Err(FilterError::G1Exceeded {
                    angle: w.angle,
                    tolerance: G1_TOLERANCE,
                })
            }
            Some(w) => problems.insert(
                0,
                format!(
                    "G1 defect {:.3e} rad exceeds the tolerance {G1_TOLERANCE:.1e} rad",
                    w.angle
                ),
            ),
            None => {}
        }
        if !problems.is_empty() {
            return Err(FilterError::G1Unmeasured(problems.join("; ")));
        }
    }
    Ok(summary)
}
