//! What a fit job did and measured, whole: serializable (`fit --report FILE.json`), and the
//! source of the terminal summary every front end prints ([`FitReport::summary_lines`]).
//!
//! Angles are in radians, positions in the input's (world) units. Timings are under the
//! `time` key and nowhere else, so two runs' reports compare equal apart from it. A number
//! that could not be computed is `null` in JSON (a NaN), never a plausible value.

use serde::Serialize;

/// How many fallback faces and degenerate edges the terminal summary lists by name (the
/// report holds them all).
pub const FALLBACKS_LISTED: usize = 10;

/// The whole report of one fit job.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct FitReport {
    /// The input as named (a data set's name or a file's path).
    pub input: String,
    /// Vertices, edges and faces of the mesh fitted (after repair).
    pub vertices: usize,
    /// Edges of the mesh fitted.
    pub edges: usize,
    /// Faces of the mesh fitted.
    pub faces: usize,
    /// What was done to a file (repairs, estimation, notes), one line each.
    pub notes: Vec<String>,
    /// Whether the repair changed anything.
    pub repaired: bool,
    /// The scheme's name.
    pub scheme: String,
    /// The continuity the scheme claims (`G1`, `C0 + normal field`, `C0`).
    pub continuity: String,
    /// The boundary-curve construction, when the scheme's boundaries are cubic edge curves.
    pub curves: Option<String>,
    /// The settings as the summary states them (`curves chord, β = 0.333…, c = 1`).
    pub settings: String,
    /// Whether the patches were streamed (built, measured and written a window of faces at a
    /// time, never all held).
    pub streamed: bool,
    /// The G1 measurement (absent for subdivision).
    pub g1: Option<G1Summary>,
    /// Every face fitted with the C0 fallback patch, with its reason.
    pub fallback_faces: Vec<FallbackFace>,
    /// The fold test (`surface::folds`; measured with G1, absent for subdivision).
    pub folds: Option<FoldSummary>,
    /// What the crease detection found (absent for a data set).
    pub creases: Option<estimate::CreaseSummary>,
    /// Every edge whose boundary-curve problem was degenerate (fitted with a straight cubic).
    pub degenerate_edges: Vec<DegenerateEdge>,
    /// The curve construction's counts (when the scheme uses curves).
    pub curve_counts: Option<CurveCounts>,
    /// The per-triangle interior choice's statistics (when one was asked for).
    pub interior: Option<InteriorSummary>,
    /// The tessellation written (when asked for).
    pub tessellation: Option<TessellationSummary>,
    /// The subdivision (for a subdivision scheme, instead of patches).
    pub subdivision: Option<SubdivisionSummary>,
    /// Where the patches were written.
    pub patches_out: Option<String>,
    /// Seconds spent on each stage.
    pub time: Timings,
    /// The process's peak resident memory after each stage, where the system says.
    pub peak_memory: Vec<PeakMemory>,
}

/// The G1 measurement: the largest normal angles between patches, split into edges between
/// regular faces and edges touching a fallback face, and the interpolation of the data.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct G1Summary {
    /// Samples per boundary (ends included).
    pub samples: usize,
    /// Largest angle along interior boundaries of regular faces (inside split triangles).
    pub interior_max: f64,
    /// Largest angle along mesh edges between two regular faces.
    pub exterior_max: f64,
    /// Mesh edges touching a fallback face (shared by two faces).
    pub fallback_edges: usize,
    /// Crease edges: C0 by construction with the data's dihedral kept, not measured.
    pub crease_edges: usize,
    /// Largest angle along interior boundaries of fallback faces.
    pub fallback_interior_max: f64,
    /// Largest angle along edges touching a fallback face.
    pub fallback_exterior_max: f64,
    /// Largest distance between a patch corner and its data vertex (world units).
    pub position_error: f64,
    /// Largest angle between a patch's corner normal and its data vertex normal.
    pub normal_error: f64,
    /// Samples where a patch normal was undefined (degenerate derivatives), skipped.
    pub undefined_normals: usize,
}

/// `F (file vertices a, b, c, file face G)`: a face as the summary names it.
fn face_in_file(face: usize, v: [usize; 3], file_face: Option<usize>) -> String {
    let file_face = file_face
        .map(|g| format!(", file face {g}"))
        .unwrap_or_default();
    format!(
        "{face} (file vertices {}, {}, {}{file_face})",
        v[0], v[1], v[2]
    )
}

/// A face of the fitted mesh, with where it came from in the file.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FaceRef {
    /// The face of the fitted mesh.
    pub face: usize,
    /// Its corners in the file's numbering (0-based; the mesh's for a data set).
    pub file_vertices: [usize; 3],
    /// The file's face it came from (0-based; absent for a data set).
    pub file_face: Option<usize>,
}

/// The fold test (`surface::folds`): faces whose patches' normals turn to or past 90° from the
/// data face's normal somewhere over the face.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct FoldSummary {
    /// Faces tested.
    pub faces_measured: usize,
    /// The folded faces, in face order.
    pub folded_faces: Vec<FaceRef>,
    /// The smallest cosine between a patch normal and its face's normal (≤ 0: folded).
    pub worst_cosine: Option<f64>,
    /// Faces of zero area, which have no normal to test against.
    pub faces_without_normal: usize,
    /// Samples where a patch is singular (no normal there).
    pub singular_samples: usize,
}

/// A face fitted with the C0 fallback patch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FallbackFace {
    /// The face of the fitted mesh.
    pub face: usize,
    /// Its corners in the file's numbering (0-based; the mesh's for a data set).
    pub file_vertices: [usize; 3],
    /// The file's face it came from (0-based; absent for a data set).
    pub file_face: Option<usize>,
    /// Why the scheme could not fit it.
    pub reason: String,
}

/// An edge whose boundary-curve problem was degenerate.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DegenerateEdge {
    /// The mesh edge.
    pub edge: usize,
    /// What was degenerate (names the edge's vertices).
    pub error: String,
}

/// The curve construction's counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct CurveCounts {
    /// Curves that fell back to the chord choice.
    pub fallbacks: usize,
    /// Optimizations that did not converge.
    pub unconverged: usize,
    /// Tangents flipped past 90° (a vertex normal leaning past the chord).
    pub flipped_tangents: usize,
    /// Curve ends whose tangent was turned to the largest angle with the chord allowed
    /// (`curves::problem::MAX_TANGENT_ANGLE`).
    pub clamped_tangents: usize,
    /// Curves whose lengths were shortened so they do not run back along their chord.
    pub shortened_curves: usize,
    /// Crease edges: curves along the crease, in both sectors' tangent planes.
    pub crease_edges: usize,
    /// Crease edges with an end where the crease tangent could not be used (the crease leaves
    /// the edge sideways or folds flat): the bisector plane's tangent there.
    pub crease_ends_off_line: usize,
    /// The corner test before and after the tangent fans (`surface::fit::fan`).
    pub fan: surface::fit::fan::FanCounts,
}

/// The per-triangle interior choice.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct InteriorSummary {
    /// The choice (`thin-plate`, `membrane`).
    pub choice: String,
    /// Faces it ran on.
    pub faces: usize,
    /// Faces whose optimization converged.
    pub converged: usize,
    /// Faces kept at the default parameters.
    pub kept_default: usize,
    /// Total energy at the default parameters.
    pub energy_default: f64,
    /// Total energy at the chosen parameters.
    pub energy_chosen: f64,
}

/// The tessellation written.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TessellationSummary {
    /// Segments per patch edge.
    pub segments: usize,
    /// Vertices of the welded mesh.
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Samples welded across patch seams.
    pub welds: usize,
    /// The file written.
    pub path: String,
}

/// A subdivision scheme's result.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SubdivisionSummary {
    /// Steps applied.
    pub levels: u32,
    /// Vertices of the control mesh after them.
    pub vertices: usize,
    /// Faces of the control mesh after them.
    pub faces: usize,
    /// Largest distance from a data point to its limit position.
    pub approximation_max: f64,
    /// RMS of those distances.
    pub approximation_rms: f64,
    /// The model size (bounding-box diagonal) the distances compare with.
    pub model_size: f64,
}

/// Seconds spent on each stage (the report's only timing fields).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Timings {
    /// Reading, repairing and estimating the input (building a data set).
    pub read: f64,
    /// The fit: the curves when streamed, else the whole fit (or the subdivision).
    pub fit: f64,
    /// The G1 measurement; when streamed, the patches, G1 and writing together.
    pub g1: f64,
    /// The tessellation and its writing.
    pub tessellate: f64,
    /// The part of `tessellate` that samples the patches into the welded mesh, before its
    /// conversion to the output format and writing (what `scripts/compare_tessellation.py`
    /// times).
    pub sample: f64,
}

/// Peak resident memory after a stage.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PeakMemory {
    /// The stage (`read`, `fit and G1`, `tessellate`, …).
    pub stage: String,
    /// Bytes.
    pub bytes: u64,
}

impl FitReport {
    /// What was not as asked, counted: a repaired input, fallback faces, degenerate edges,
    /// curves fallen back to chord, unconverged optimizations (`--strict` fails on any).
    pub fn departures(&self) -> Vec<(usize, &'static str)> {
        let counts = self.curve_counts.unwrap_or_default();
        [
            (usize::from(self.repaired), "repaired input"),
            (self.fallback_faces.len(), "fallback faces"),
            (
                self.folds.as_ref().map_or(0, |f| f.folded_faces.len()),
                "folded faces",
            ),
            (self.degenerate_edges.len(), "degenerate edges"),
            (counts.fallbacks, "curves fallen back to chord"),
            (counts.unconverged, "unconverged optimizations"),
        ]
        .into_iter()
        .filter(|(n, _)| *n > 0)
        .collect()
    }

    /// The report as pretty-printed JSON with a final newline.
    pub fn to_json(&self) -> Result<String, serde_json::Error> {
        let mut text = serde_json::to_string_pretty(self)?;
        text.push('\n');
        Ok(text)
    }

    /// The terminal summary, one line each (the lines every front end prints after the run).
    pub fn summary_lines(&self) -> Vec<String> {
        let mut lines = Vec::new();
        if let Some(s) = &self.subdivision {
            lines.push(format!(
                "fit: {} ({} vertices, {} faces), subdivision {} × {}: {} vertices, {} faces in {:.3} s",
                self.input, self.vertices, self.faces, self.scheme, s.levels, s.vertices, s.faces,
                self.time.fit
            ));
            lines.push(format!(
                "  approximation: data point to limit surface max {:.3e}, RMS {:.3e} ({:.3e} and {:.3e} of the model size)",
                s.approximation_max,
                s.approximation_rms,
                s.approximation_max / s.model_size,
                s.approximation_rms / s.model_size
            ));
            return lines;
        }
        lines.push(format!(
            "fit: {} ({} vertices, {} edges, {} faces), scheme {} ({}), {}",
            self.input,
            self.vertices,
            self.edges,
            self.faces,
            self.scheme,
            self.continuity,
            self.settings
        ));
        let g1 = self.g1.unwrap_or_default();
        lines.push(format!(
            "  {}: interior {:.3e} rad, exterior {:.3e} rad; interpolation: position {:.3e}, normal {:.3e} rad",
            if self.continuity == surface::Continuity::G1.to_string()
                || self.continuity == surface::Continuity::C1.to_string()
            {
                "G1 defect"
            } else {
                "normal jump (the scheme claims only C0)"
            },
            g1.interior_max,
            g1.exterior_max,
            g1.position_error,
            g1.normal_error
        ));
        if g1.crease_edges > 0 {
            lines.push(format!(
                "  creases: {} edges C0 with the data's dihedral (not G1 boundaries; the G1 figures are the smooth edges')",
                g1.crease_edges
            ));
        }
        if !self.fallback_faces.is_empty() {
            lines.push(format!(
                "  fallback: {} faces fitted C0 ({} edges touch them; G1 defect there: interior {:.3e} rad, exterior {:.3e} rad)",
                self.fallback_faces.len(),
                g1.fallback_edges,
                g1.fallback_interior_max,
                g1.fallback_exterior_max
            ));
            for fb in self.fallback_faces.iter().take(FALLBACKS_LISTED) {
                let at = face_in_file(fb.face, fb.file_vertices, fb.file_face);
                lines.push(format!("    face {at}: {}", fb.reason));
            }
            if self.fallback_faces.len() > FALLBACKS_LISTED {
                lines.push(format!("    … ({} in all)", self.fallback_faces.len()));
            }
        }
        if let Some(folds) = self.folds.as_ref().filter(|f| !f.folded_faces.is_empty()) {
            lines.push(format!(
                "  folds: {} of {} faces turn over (a patch normal at or past 90° from its face; worst cosine {:.3})",
                folds.folded_faces.len(),
                folds.faces_measured,
                folds.worst_cosine.unwrap_or(f64::NAN)
            ));
            for f in folds.folded_faces.iter().take(FALLBACKS_LISTED) {
                let at = face_in_file(f.face, f.file_vertices, f.file_face);
                lines.push(format!("    folded face {at}"));
            }
            if folds.folded_faces.len() > FALLBACKS_LISTED {
                lines.push(format!(
                    "    … ({} folded in all)",
                    folds.folded_faces.len()
                ));
            }
        }
        if !self.degenerate_edges.is_empty() {
            lines.push(format!(
                "  degenerate edges: {} fitted with straight cubics",
                self.degenerate_edges.len()
            ));
            for d in self.degenerate_edges.iter().take(FALLBACKS_LISTED) {
                lines.push(format!("    edge {}: {}", d.edge, d.error));
            }
            if self.degenerate_edges.len() > FALLBACKS_LISTED {
                lines.push(format!("    … ({} in all)", self.degenerate_edges.len()));
            }
        }
        if let Some(c) = &self.curve_counts {
            lines.push(format!(
                "  curves: {} fallbacks to chord, {} unconverged optimizations, {} flipped tangents, {} clamped tangents, {} shortened{}",
                c.fallbacks,
                c.unconverged,
                c.flipped_tangents,
                c.clamped_tangents,
                c.shortened_curves,
                if c.crease_edges > 0 {
                    format!(
                        "; {} along creases ({} with an end off the crease line)",
                        c.crease_edges, c.crease_ends_off_line
                    )
                } else {
                    String::new()
                }
            ));
            let f = &c.fan;
            if f.corners_failing_before > 0 {
                lines.push(format!(
                    "  corners: {} not convex with each edge's own tangents, {} after the tangent fans ({} sectors fanned, {} straight crease corners, {} without a convex fan, {} left: a normal facing away from a face)",
                    f.corners_failing_before,
                    f.corners_failing_after,
                    f.sectors_fanned,
                    f.sectors_straight,
                    f.sectors_unfannable,
                    f.sectors_facing_away
                ));
            }
        }
        let t = &self.time;
        if self.streamed {
            lines.push(format!(
                "  time: read {:.3} s, curves {:.3} s, patches, G1{} {:.3} s ({:.0} triangles/s)",
                t.read,
                t.fit,
                if self.patches_out.is_some() {
                    " and writing"
                } else {
                    ""
                },
                t.g1,
                self.faces as f64 / (t.fit + t.g1).max(1e-12),
            ));
        } else {
            lines.push(format!(
                "  time: read {:.3} s, fit {:.3} s ({:.0} triangles/s), G1 {:.3} s",
                t.read,
                t.fit,
                self.faces as f64 / t.fit.max(1e-12),
                t.g1
            ));
        }
        lines.push(format!(
            "  peak memory: {}",
            self.peak_memory
                .iter()
                .map(|p| format!(
                    "{} {:.0} MB ({:.0} bytes/triangle)",
                    p.stage,
                    p.bytes as f64 / 1e6,
                    p.bytes as f64 / self.faces.max(1) as f64
                ))
                .collect::<Vec<_>>()
                .join(", ")
        ));
        lines
    }
}
