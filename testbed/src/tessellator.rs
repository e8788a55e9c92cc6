//! The patch tessellator of `tess` (and of the one-process benchmark): patches one at a time
//! at `s` segments per edge, as `surface::tessellate` does for the patch alone, **in the
//! patch's own unit frame** ([`UnitFrame`]: every patch is differentiated at unit size and its
//! normals and curvatures mapped back, so a patch 1e-200 or 1e200 across gets the normals and
//! curvatures a unit patch of its shape gets), with the Bernstein weights of the samples
//! computed once per degree and shared by every patch while they fit in
//! [`MAX_TABLE_BYTES`] (beyond, each sample is evaluated by de Casteljau's algorithm with no
//! table: [`Casteljau`]).
//!
//! What cannot be tessellated is said, never dropped silently: a patch whose control points
//! are all equal is a point ([`Outcome::Degenerate`]); samples at singular points and
//! triangles the general path collapses are counted ([`TessCounts`]); a value that is not
//! finite after the way back (a curvature beyond `f64` at an extreme scale) is found by
//! [`IndexedPatch::first_non_finite`] before anything is written.

use std::collections::HashMap;

use nalgebra::{Point3, Vector3};
use surface::beztri::{Derivatives, SampleWeights};
use surface::BezierTriangle;

use crate::sample::{CurvatureFields, Principal, Sample};

/// One patch's tessellation with shared vertices: its samples, and its triangles as indices
/// into them (counter-clockwise, in the order of `surface::tessellate`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IndexedPatch {
    /// The samples (vertices), each once.
    pub samples: Vec<Sample>,
    /// The triangles: indices into `samples`.
    pub triangles: Vec<[u32; 3]>,
    /// Each sample's principal curvatures and directions, when the tessellator was asked for
    /// them ([`PatchTessellator::with_principal`]); empty otherwise.
    pub principal: Vec<Principal>,
}

/// A value of a tessellated patch that is not finite ([`IndexedPatch::first_non_finite`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NonFinite {
    /// The sample (vertex) index.
    pub sample: usize,
    /// The field: `pos`, `norm`, `kg` or `km`.
    pub field: &'static str,
    /// The value (infinite or NaN).
    pub value: f64,
}

impl IndexedPatch {
    /// The triangles with their vertices, appended to `out` after clearing it.
    pub fn expand(&self, out: &mut Vec<[Sample; 3]>) {
        out.clear();
        out.extend((0..self.triangles.len()).map(|k| self.triangle(k)));
    }

    /// Triangle `k`'s three samples (`k` in range).
    pub fn triangle(&self, k: usize) -> [Sample; 3] {
        self.triangles[k].map(|i| self.samples[i as usize])
    }

    /// Triangle `k`'s principal frames, when they were computed.
    pub fn triangle_principal(&self, k: usize) -> Option<[Principal; 3]> {
        let t = self.triangles.get(k)?;
        Some([
            *self.principal.get(t[0] as usize)?,
            *self.principal.get(t[1] as usize)?,
            *self.principal.get(t[2] as usize)?,
        ])
    }

    /// The first value that is not finite among the positions, the normals and the curvatures
    /// `fields` asks for (`None`: every value written is finite).
    pub fn first_non_finite(&self, fields: CurvatureFields) -> Option<NonFinite> {
        self.samples.iter().enumerate().find_map(|(i, s)| {
            let bad = |field, value: f64| {
                (!value.is_finite()).then_some(NonFinite {
                    sample: i,
                    field,
                    value,
                })
            };
            s.pos
                .iter()
                .find_map(|&x| bad("pos", x))
                .or_else(|| s.norm.iter().find_map(|&x| bad("norm", x)))
                .or_else(|| fields.kg.then(|| bad("kg", s.kg)).flatten())
                .or_else(|| fields.km.then(|| bad("km", s.km)).flatten())
                .or_else(|| {
                    let p = self.principal.get(i).filter(|_| fields.kp)?;
                    p.k.iter().find_map(|&k| bad("kp", k)).or_else(|| {
                        p.d.iter()
                            .flat_map(|d| d.iter())
                            .find_map(|&x| bad("kp", x))
                    })
                })
        })
    }
}

/// Multiplies `x` by `2^e` (an exact scaling, unless the result leaves the normal range),
/// for any `e`: in steps the binary exponent can hold.
pub fn scale_pow2(mut x: f64, mut e: i32) -> f64 {
    /// The largest step: `2^±1000` is a normal number, `2^1024` is not.
    const STEP: i32 = 1000;
    let pow2 = |k: i32| f64::from_bits(((k + 1023) as u64) << 52);
    while e > STEP {
        x *= pow2(STEP);
        e -= STEP;
    }
    while e < -STEP {
        x *= pow2(-STEP);
        e += STEP;
    }
    x * pow2(e)
}

/// A patch's unit frame: its control net's bounding-box centre `c` and a power of two
/// `σ = 2^k` at least half the box's largest side, so that the unit net `q = (b − c)/σ` lies
/// in `[−1, 1]³` whatever the patch's size or position (a net 1e-200 across, or 1e200).
///
/// **Why.** The curvature formulas square and multiply the partials (`E G − F²` is fourth
/// order in the coordinates): on a net 1e-100 across it underflows to 0 and on a net 1e100
/// across it overflows, and the normal and curvature come out undefined or wrong, although
/// the patch is an ordinary surface at another scale. Differentiated in its unit frame, every
/// intermediate is of order 1.
///
/// **The way back.** With `r(u, v) = c + σ q(u, v)`: `r_u = σ q_u`, `r_v = σ q_v`, and the
/// second partials are `σ` times `q`'s. The normal `(r_u × r_v)/|r_u × r_v|` is
/// `σ²(q_u × q_v)/(σ²|q_u × q_v|)`, `q`'s normal, unchanged (`σ > 0`). The first fundamental
/// form scales by `σ²` (`E = σ² E_q`, …), the second by `σ` (`L = r_uu · n = σ L_q`, …), so
/// (do Carmo §3-3; `surface::beztri` for the formulas)
/// `K = (LN − M²)/(EG − F²) = σ²(L_qN_q − M_q²)/(σ⁴(E_qG_q − F_q²)) = K_q/σ²` and
/// `H = (EN − 2FM + GL)/(2(EG − F²)) = σ³(…)/(2σ⁴(…)) = H_q/σ`; positions are `c + σ q`.
/// `σ` being a power of two, `K_q/σ²` and `H_q/σ` are exact unless they leave the range of
/// `f64`, which [`IndexedPatch::first_non_finite`] then reports (a Gaussian curvature of a
/// patch 1e-200 across is about 1e400).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitFrame {
    /// The bounding-box centre.
    pub center: Vector3<f64>,
    /// `k` of `σ = 2^k`.
    pub exponent: i32,
}

impl UnitFrame {
    /// The frame of a finite net, `None` when its points are all equal (a point: no surface).
    /// Computed without overflow: the centre as `min/2 + max/2`, the half side as
    /// `max/2 − min/2`.
    pub fn of(points: &[Point3<f64>]) -> Option<UnitFrame> {
        let first = points.first()?;
        let (mut lo, mut hi) = (first.coords, first.coords);
        for p in points {
            lo = lo.inf(&p.coords);
            hi = hi.sup(&p.coords);
        }
        let half = (hi * 0.5 - lo * 0.5).max();
        if !(half > 0.0 && half.is_finite()) {
            return None;
        }
        let mut exponent = half.log2().ceil() as i32;
        if scale_pow2(1.0, exponent) < half {
            exponent += 1;
        }
        Some(UnitFrame {
            center: lo * 0.5 + hi * 0.5,
            exponent,
        })
    }

    /// `σ`, the frame's scale (may overflow to infinity for nets near `f64::MAX`: use the
    /// mapping functions, which do not form it).
    pub fn scale(&self) -> f64 {
        scale_pow2(1.0, self.exponent)
    }

    /// A world point in the unit frame, `(p − c)/σ`.
    pub fn to_unit(&self, p: &Point3<f64>) -> Point3<f64> {
        Point3::from((p.coords - self.center).map(|x| scale_pow2(x, -self.exponent)))
    }

    /// A unit-frame point in the world, `c + σ q`.
    pub fn to_world(&self, q: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.center + q.coords.map(|x| scale_pow2(x, self.exponent)))
    }

    /// A unit-frame principal frame in the world: curvatures `k_q/σ`, directions unchanged.
    pub fn principal_to_world(&self, p: &Principal) -> Principal {
        Principal {
            k: p.k.map(|k| scale_pow2(k, -self.exponent)),
            d: p.d,
        }
    }

    /// A unit-frame sample in the world: position `c + σ q`, normal unchanged, `K_q/σ²`,
    /// `H_q/σ` (the type's docs).
    pub fn sample_to_world(&self, s: &Sample) -> Sample {
        Sample {
            pos: self.to_world(&s.pos),
            norm: s.norm,
            kg: scale_pow2(s.kg, -2 * self.exponent),
            km: scale_pow2(s.km, -self.exponent),
        }
    }
}

/// What [`PatchTessellator::tessellate_indexed`] made of a patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Tessellated.
    Tessellated,
    /// Every control point is the same point: no surface, no samples (counted in
    /// [`TessCounts::degenerate`]).
    Degenerate,
}

/// What a tessellator has counted over the patches it was given.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TessCounts {
    /// Patches given.
    pub patches: usize,
    /// Patches whose control points are all equal: no triangles written.
    pub degenerate: usize,
    /// Patches tessellated by the general path (`surface::tessellate`: a singular sample or
    /// boundary samples close enough to be welded).
    pub general: usize,
    /// Samples at a singular point (a collapsed edge; a net collapsed to a curve): their
    /// normal and curvature taken a small step inside, or, where the patch has no normal
    /// anywhere, its corner triangle's normal (`+z` if that has no area either) and zero
    /// curvature (`surface::tessellate`'s rule).
    pub singular_samples: usize,
    /// Triangles dropped because welding made two of their corners one vertex (a patch edge
    /// collapsed to a point).
    pub collapsed_triangles: usize,
}

/// Largest table of Bernstein weights a tessellator keeps for a degree
/// (`surface::limits::sample_weights_bytes`: a quartic's is 1.6 kB a sample, 64 MiB is a
/// quartic at `s` ≈ 280, far above the pictures' `s = 8`); beyond it each sample is evaluated
/// by de Casteljau's algorithm ([`Casteljau`]), which needs no table and takes about as long
/// per sample (measured: docs/hostile-input.md), so the memory of a large `-s` is the samples'
/// alone.
pub const MAX_TABLE_BYTES: u128 = 64 << 20;

/// Whether a tessellator at `s` keeps the weight table of patches with `points` control
/// points ([`MAX_TABLE_BYTES`]).
pub fn keeps_table(points: usize, s: usize) -> bool {
    surface::limits::sample_weights_bytes(points, s) <= MAX_TABLE_BYTES
}

/// Position and partials of a net by de Casteljau's algorithm with no table and no
/// allocation per sample: `n − 2` steps at the point reduce the net to degree 2 (six points
/// `Q`), and with `e_u = (1, 0, −1)`, `e_v = (0, 1, −1)` the partials are
/// `r_uu = n(n − 1) Q[e_u, e_u]`, `r_uv = n(n − 1) Q[e_u, e_v]`, `r_vv = n(n − 1) Q[e_v, e_v]`;
/// one more step at the point gives three points `R`, and `r = R[p]`, `r_u = n R[e_u]`,
/// `r_v = n R[e_v]` (the blossom's symmetry: `surface::beztri`'s module docs). The same
/// numbers as `BezierTriangle::derivatives` up to rounding (the steps are taken in another
/// order).
#[derive(Clone, Debug)]
pub struct Casteljau {
    degree: usize,
    /// Per step from degree `m` to `m − 1` (`m = n, …, 3`): for each point of the lower net,
    /// the indices of `b_{i+1,j,k}`, `b_{i,j+1,k}`, `b_{i,j,k+1}` in the upper one.
    sources: Vec<Vec<[usize; 3]>>,
    a: Vec<Vector3<f64>>,
    b: Vec<Vector3<f64>>,
}

impl Casteljau {
    /// The evaluator of degree-`degree` nets (at least 1).
    pub fn new(degree: usize) -> Self {
        let sources = surface::beztri::casteljau_steps(degree, 3);
        Casteljau {
            degree,
            sources,
            a: Vec::new(),
            b: Vec::new(),
        }
    }

    /// Position and partials of `net` (net order, of the evaluator's degree) at `(u, v)`.
    pub fn derivatives(&mut self, net: &[Point3<f64>], u: f64, v: f64) -> Derivatives {
        let at = [u, v, 1.0 - u - v];
        let n = self.degree as f64;
        self.a.clear();
        self.a.extend(net.iter().map(|p| p.coords));
        if self.degree < 2 {
            // Degree 1 (degree 0 has no partials): r = Σ at_i b_i, r_u = b_u − b_w.
            let g = |k: usize| self.a.get(k).copied().unwrap_or_else(Vector3::zeros);
            let (bu, bv, bw) = (g(0), g(1), g(2));
            let d = if self.degree == 1 {
                [bu - bw, bv - bw]
            } else {
                [Vector3::zeros(); 2]
            };
            let p = if self.degree == 1 {
                bu * at[0] + bv * at[1] + bw * at[2]
            } else {
                bu
            };
            return Derivatives {
                p: Point3::from(p),
                du: d[0] * n,
                dv: d[1] * n,
                duu: Vector3::zeros(),
                duv: Vector3::zeros(),
                dvv: Vector3::zeros(),
            };
        }
        for src in &self.sources {
            self.b.clear();
            self.b.extend(
                src.iter()
                    .map(|s| self.a[s[0]] * at[0] + self.a[s[1]] * at[1] + self.a[s[2]] * at[2]),
            );
            std::mem::swap(&mut self.a, &mut self.b);
        }
        // Q in net order: b200, b110, b020, b101, b011, b002.
        let q = &self.a;
        let (q200, q110, q020, q101, q011, q002) = (q[0], q[1], q[2], q[3], q[4], q[5]);
        // One step along e_u and along e_v, then the second direction.
        let ru = [q200 - q101, q110 - q011, q101 - q002];
        let rv = [q110 - q101, q020 - q011, q011 - q002];
        let second = n * (n - 1.0);
        let r = [
            q200 * at[0] + q110 * at[1] + q101 * at[2],
            q110 * at[0] + q020 * at[1] + q011 * at[2],
            q101 * at[0] + q011 * at[1] + q002 * at[2],
        ];
        Derivatives {
            p: Point3::from(r[0] * at[0] + r[1] * at[1] + r[2] * at[2]),
            du: (r[0] - r[2]) * n,
            dv: (r[1] - r[2]) * n,
            duu: (ru[0] - ru[2]) * second,
            duv: (ru[1] - ru[2]) * second,
            dvv: (rv[1] - rv[2]) * second,
        }
    }
}

/// How a degree's samples are evaluated.
#[derive(Debug)]
enum Evaluator {
    /// The shared table of weights (bit for bit `surface::tessellate`'s numbers).
    Table(Vec<SampleWeights>),
    /// De Casteljau per sample (no table).
    Direct(Casteljau),
}

/// Tessellates patches one at a time at `s` segments per edge, each in its unit frame
/// ([`UnitFrame`]), as `surface::tessellate` does for the unit patch alone, mapped back; with
/// the Bernstein weights of the samples computed once per degree and shared by every patch
/// while the table fits [`MAX_TABLE_BYTES`] (`surface::tessellate` computes them per call,
/// which is 90% of its time for one patch), by de Casteljau's algorithm per sample beyond. A
/// patch with a singular sample or two boundary samples close enough to be welded goes
/// through `surface::tessellate` itself (on the unit patch).
#[derive(Debug)]
pub struct PatchTessellator {
    s: usize,
    /// Compute each sample's principal frame too ([`PatchTessellator::with_principal`]).
    principal: bool,
    evaluators: HashMap<usize, Evaluator>,
    indexed: IndexedPatch,
    counts: TessCounts,
}

/// Boundary samples closer than this many weld tolerances (`surface::tessellate`'s
/// `WELD_RELATIVE` times the net's size) send a patch to the general path: a margin of 4
/// keeps the fast path away from the welder's own comparisons.
const WELD_MARGIN: f64 = 4.0;

impl PatchTessellator {
    /// A tessellator at `s ≥ 1` segments per edge.
    pub fn new(s: usize) -> Result<Self, surface::TessError> {
        if s == 0 {
            return Err(surface::TessError::ZeroDensity);
        }
        Ok(PatchTessellator {
            s,
            principal: false,
            evaluators: HashMap::new(),
            indexed: IndexedPatch::default(),
            counts: TessCounts::default(),
        })
    }

    /// This tessellator, computing each sample's principal curvatures and directions as well
    /// (into [`IndexedPatch::principal`]) when `on` (`tess --kp`): one 2 × 2 eigenproblem a
    /// sample, skipped otherwise.
    pub fn with_principal(mut self, on: bool) -> Self {
        self.principal = on;
        self
    }

    /// What has been counted so far.
    pub fn counts(&self) -> TessCounts {
        self.counts
    }

    /// The `s²` triangles of `patch` (fewer where the general path collapses some, none for a
    /// degenerate patch), appended to `out` after clearing it:
    /// [`PatchTessellator::tessellate_indexed`] with each triangle's vertices copied out.
    pub fn tessellate(
        &mut self,
        patch: &BezierTriangle,
        out: &mut Vec<[Sample; 3]>,
    ) -> Result<Outcome, surface::TessError> {
        let mut indexed = std::mem::take(&mut self.indexed);
        let result = self.tessellate_indexed(patch, &mut indexed);
        indexed.expand(out);
        self.indexed = indexed;
        result
    }

    /// The tessellation of `patch` with shared vertices: `(s + 1)(s + 2)/2` samples and `s²`
    /// triangles on the fast path; on the general path the welded vertices and triangles of
    /// `surface::tessellate` for the unit patch alone; nothing for a patch whose points are
    /// all equal ([`Outcome::Degenerate`]). `out` is cleared first. The values are mapped
    /// back from the unit frame and may hold a curvature that is not finite (check with
    /// [`IndexedPatch::first_non_finite`] before writing).
    pub fn tessellate_indexed(
        &mut self,
        patch: &BezierTriangle,
        out: &mut IndexedPatch,
    ) -> Result<Outcome, surface::TessError> {
        out.samples.clear();
        out.triangles.clear();
        out.principal.clear();
        self.counts.patches += 1;
        let Some(frame) = UnitFrame::of(patch.points()) else {
            self.counts.degenerate += 1;
            return Ok(Outcome::Degenerate);
        };
        let unit = unit_patch(patch, &frame)?;
        let s = self.s;
        let degree = patch.degree();
        let points = unit.points().len();
        let evaluator = self.evaluators.entry(degree).or_insert_with(|| {
            if keeps_table(points, s) {
                Evaluator::Table(SampleWeights::grid(degree, s))
            } else {
                Evaluator::Direct(Casteljau::new(degree))
            }
        });
        let mut regular = true;
        let principal = self.principal;
        let mut push = |d: Option<Derivatives>| {
            let Some((d, c)) = d.and_then(|d| surface::beztri::curvature_of(&d).map(|c| (d, c)))
            else {
                return false;
            };
            out.samples.push(Sample {
                pos: d.p,
                norm: c.normal,
                kg: c.gaussian,
                km: c.mean,
            });
            if principal {
                out.principal.push(Principal::of(&c.shape, &c.normal));
            }
            true
        };
        match evaluator {
            Evaluator::Table(table) => {
                for w in table.iter() {
                    if !push(unit.derivatives_with(w)) {
                        regular = false;
                        break;
                    }
                }
            }
            Evaluator::Direct(casteljau) => {
                'grid: for j in 0..=s {
                    for i in 0..=s - j {
                        let (u, v) = (i as f64 / s as f64, j as f64 / s as f64);
                        if !push(Some(casteljau.derivatives(unit.points(), u, v))) {
                            regular = false;
                            break 'grid;
                        }
                    }
                }
            }
        }
        if !regular {
            return self.general(&unit, &frame, out);
        }
        let local = |i: usize, j: usize| j * (s + 1) - j * j.saturating_sub(1) / 2 + i;
        // Would the welder join two boundary samples? (In the unit frame, as the general path
        // welds.)
        let tol = surface::tessellate::WELD_RELATIVE
            * surface::mesh::bounding_size(unit.points()).max(f64::MIN_POSITIVE)
            * WELD_MARGIN;
        let mut boundary = Vec::with_capacity(3 * s);
        for j in 0..=s {
            for i in 0..=s - j {
                if i == 0 || j == 0 || i + j == s {
                    boundary.push(out.samples[local(i, j)].pos);
                }
            }
        }
        for (a, p) in boundary.iter().enumerate() {
            if boundary[a + 1..].iter().any(|q| (p - q).norm() <= tol) {
                return self.general(&unit, &frame, out);
            }
        }
        for smp in &mut out.samples {
            *smp = frame.sample_to_world(smp);
        }
        for p in &mut out.principal {
            *p = frame.principal_to_world(p);
        }
        // Sample indices fit u32 for any s whose samples fit in memory (and `tess` allows at
        // most MAX_SEGMENTS).
        let at = |i: usize, j: usize| local(i, j) as u32;
        out.triangles.reserve(s * s);
        for j in 0..s {
            for i in 0..s - j {
                // Upward triangle: corners towards u, v, w; then the downward one (the order
                // of `surface::tessellate`).
                out.triangles.push([at(i + 1, j), at(i, j + 1), at(i, j)]);
                if i + j + 2 <= s {
                    out.triangles
                        .push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
        Ok(Outcome::Tessellated)
    }

    /// The general path on the unit patch, mapped back, its counts added.
    fn general(
        &mut self,
        unit: &BezierTriangle,
        frame: &UnitFrame,
        out: &mut IndexedPatch,
    ) -> Result<Outcome, surface::TessError> {
        let counts = general(unit, frame, self.s, self.principal, out)?;
        self.counts.general += 1;
        self.counts.singular_samples += counts.singular_samples;
        self.counts.collapsed_triangles += counts.collapsed_triangles;
        Ok(Outcome::Tessellated)
    }
}

/// `patch` in its unit frame (its points are finite and so are theirs: should the net be
/// refused all the same, the error says so).
fn unit_patch(
    patch: &BezierTriangle,
    frame: &UnitFrame,
) -> Result<BezierTriangle, surface::TessError> {
    let points = patch.points().iter().map(|p| frame.to_unit(p)).collect();
    BezierTriangle::new(patch.degree(), points)
        .map_err(|e| surface::TessError::Rebuild(format!("the patch in its unit frame: {e}")))
}

/// `surface::tessellate` on the unit patch `unit` alone, mapped back by `frame`; the samples'
/// singular and collapsed counts returned.
fn general(
    unit: &BezierTriangle,
    frame: &UnitFrame,
    s: usize,
    principal: bool,
    out: &mut IndexedPatch,
) -> Result<TessCounts, surface::TessError> {
    out.samples.clear();
    out.triangles.clear();
    out.principal.clear();
    let t = surface::tessellate(std::slice::from_ref(unit), s)?;
    if principal {
        out.principal.extend(
            t.shapes
                .iter()
                .zip(&t.normals)
                .map(|(sh, n)| frame.principal_to_world(&Principal::of(sh, n))),
        );
    }
    out.samples.extend((0..t.positions.len()).map(|i| {
        frame.sample_to_world(&Sample {
            pos: t.positions[i],
            norm: t.normals[i],
            kg: t.gaussian[i],
            km: t.mean[i],
        })
    }));
    out.triangles
        .extend(t.faces.iter().map(|f| f.map(|i| i as u32)));
    Ok(TessCounts {
        singular_samples: t.singular_samples,
        collapsed_triangles: t.collapsed_faces,
        ..TessCounts::default()
    })
}

/// The `s²` triangles of one patch at `s` segments per patch edge (`surface::tessellate` on
/// the patch alone in its unit frame, mapped back, so every vertex carries its own patch's
/// normal and curvature); none for a patch whose points are all equal. For many patches use a
/// [`PatchTessellator`], which shares the sample weights.
pub fn tessellate_patch(
    patch: &BezierTriangle,
    s: usize,
) -> Result<Vec<[Sample; 3]>, surface::TessError> {
    let mut indexed = IndexedPatch::default();
    if let Some(frame) = UnitFrame::of(patch.points()) {
        general(&unit_patch(patch, &frame)?, &frame, s, false, &mut indexed)?;
    } else if s == 0 {
        return Err(surface::TessError::ZeroDensity);
    }
    let mut out = Vec::new();
    indexed.expand(&mut out);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use nalgebra::Point3;

    use super::*;

    /// De Casteljau in another order than the blossom of `BezierTriangle::derivatives`: a few
    /// roundings apart on these unit-size nets.
    const REORDERED: f64 = 1e-12;

    fn quartic() -> BezierTriangle {
        BezierTriangle::from_fn(4, |i, j, k| {
            let (u, v) = (i as f64 / 4.0, j as f64 / 4.0);
            Point3::new(
                u,
                v,
                0.3 * u * u - 0.2 * u * v + 0.1 * v * v + 0.05 * k as f64,
            )
        })
    }

    /// The shared-weights path gives exactly (bit for bit) what `surface::tessellate` gives
    /// for the unit patch alone mapped back, on regular patches and on a degenerate one (a
    /// collapsed edge: its samples are welded and some triangles dropped there, so it takes
    /// the general path).
    #[test]
    fn patch_tessellator_equals_surface_tessellate() {
        let quad = quartic();
        let collapsed = BezierTriangle::from_fn(2, |i, j, _| {
            // Corners (2,0,0) and (0,2,0) coincide: edge w = 0 is a point.
            Point3::new(
                (i * j) as f64 * 0.5,
                (i + j) as f64 * 0.25,
                (i as f64 - 1.0).abs(),
            )
        });
        for s in [1, 3, 8] {
            let mut t = PatchTessellator::new(s).expect("s ≥ 1");
            let mut out = Vec::new();
            for patch in [&quad, &collapsed, &quad] {
                t.tessellate(patch, &mut out).expect("tessellates");
                let expected = tessellate_patch(patch, s).expect("tessellates");
                assert_eq!(out, expected, "s = {s}");
            }
            // Shared vertices: each sample once, s² triangles on the fast path (the quartic),
            // fewer vertices where the general path welds (the collapsed edge).
            let mut indexed = IndexedPatch::default();
            t.tessellate_indexed(&quad, &mut indexed)
                .expect("tessellates");
            assert_eq!(indexed.samples.len(), (s + 1) * (s + 2) / 2);
            assert_eq!(indexed.triangles.len(), s * s);
            t.tessellate_indexed(&collapsed, &mut indexed)
                .expect("tessellates");
            assert!(indexed.samples.len() < (s + 1) * (s + 2) / 2, "s = {s}");
            indexed.expand(&mut out);
            assert_eq!(out, tessellate_patch(&collapsed, s).expect("tessellates"));
            assert_eq!(t.counts().general, 2, "the collapsed patch, twice");
        }
        assert!(PatchTessellator::new(0).is_err());
    }

    /// De Casteljau with no table gives `BezierTriangle::derivatives`' partials (degrees 1 to
    /// 6, inside, on edges and at corners).
    #[test]
    fn casteljau_gives_the_partials() {
        for degree in 1..=6 {
            let patch = BezierTriangle::from_fn(degree, |i, j, k| {
                let (x, y, z) = (i as f64, j as f64, k as f64);
                Point3::new(
                    x + 0.3 * y * z,
                    y - 0.2 * x * x,
                    0.1 * x * y + 0.05 * z * z * x,
                )
            });
            let mut c = Casteljau::new(degree);
            for (u, v) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.25, 0.5), (0.1, 0.7)] {
                let want = patch.derivatives(u, v);
                let got = c.derivatives(patch.points(), u, v);
                let pairs = [
                    (got.p.coords, want.p.coords),
                    (got.du, want.du),
                    (got.dv, want.dv),
                    (got.duu, want.duu),
                    (got.duv, want.duv),
                    (got.dvv, want.dvv),
                ];
                for (k, (g, w)) in pairs.iter().enumerate() {
                    assert!(
                        (g - w).norm() <= REORDERED * (1.0 + w.norm()),
                        "degree {degree} at ({u}, {v}), partial {k}: {g:?} vs {w:?}"
                    );
                }
            }
        }
    }

    /// Without a table (an `s` whose table would exceed `MAX_TABLE_BYTES`) the tessellation is
    /// the table's up to rounding.
    #[test]
    fn the_direct_path_agrees_with_the_table() {
        let quad = quartic();
        let s = 300;
        assert!(!keeps_table(15, s), "s = {s} is beyond the table");
        let mut direct = IndexedPatch::default();
        PatchTessellator::new(s)
            .expect("s ≥ 1")
            .tessellate_indexed(&quad, &mut direct)
            .expect("tessellates");
        let mut table = PatchTessellator::new(s).expect("s ≥ 1");
        table
            .evaluators
            .insert(4, Evaluator::Table(SampleWeights::grid(4, s)));
        let mut tabled = IndexedPatch::default();
        table
            .tessellate_indexed(&quad, &mut tabled)
            .expect("tessellates");
        assert_eq!(direct.triangles, tabled.triangles);
        for (a, b) in direct.samples.iter().zip(&tabled.samples) {
            assert!((a.pos - b.pos).norm() < REORDERED);
            assert!((a.norm - b.norm).norm() < REORDERED);
            assert!((a.kg - b.kg).abs() < REORDERED && (a.km - b.km).abs() < REORDERED);
        }
    }

    /// The unit frame maps a net into `[−1, 1]³` and back exactly for powers of two, and
    /// refuses a point.
    #[test]
    fn unit_frame_round_trip() {
        let pts = [Point3::new(3.0, -1.0, 0.5), Point3::new(7.0, 1.0, 0.5)];
        let f = UnitFrame::of(&pts).expect("not a point");
        assert_eq!(f.center, Vector3::new(5.0, 0.0, 0.5));
        assert_eq!(f.exponent, 1);
        assert_eq!(f.to_unit(&pts[1]), Point3::new(1.0, 0.5, 0.0));
        assert_eq!(f.to_world(&f.to_unit(&pts[0])), pts[0]);
        assert_eq!(UnitFrame::of(&[pts[0], pts[0]]), None);
        let huge = [
            Point3::new(-f64::MAX, 0.0, 0.0),
            Point3::new(f64::MAX, 0.0, 0.0),
        ];
        let f = UnitFrame::of(&huge).expect("finite");
        let q = f.to_unit(&huge[1]);
        assert!(q.x > 0.99 && q.x <= 1.0);
        assert_eq!(f.to_world(&q).x, f64::MAX);
        assert_eq!(scale_pow2(1.0, -1074), f64::from_bits(1));
        assert_eq!(scale_pow2(f64::from_bits(1), 1074), 1.0);
    }
}
