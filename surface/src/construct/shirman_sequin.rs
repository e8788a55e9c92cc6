//! The modified Shirman–Séquin split-domain scheme (Shirman & Séquin 1987; Mann 1994 §2):
//! three quartic triangular Bézier patches per data triangle, meeting at a split point `S`, with
//! cubic exterior boundaries built by any boundary-curve construction of the `curves` crate.
//!
//! The seed's formulas are inconsistent with its own Appendix A (see "Where the seed differs"),
//! so the construction is rebuilt here from the G1 conditions; a reader can follow it without
//! the seed.
//!
//! # Notation
//!
//! The data triangle has corners `V_0, V_1, V_2` (counter-clockwise about the normals) with unit
//! normals `n_i`. Exterior edge `e` runs from `V_e` to `V_{e+1}` (indices mod 3) and carries the
//! cubic `V_e, E_e¹, E_e², V_{e+1}` (shared with the neighbouring triangle). Sub-patch `e` is the
//! quartic over the domain triangle `(V_e, V_{e+1}, S)` of the centroid split; its net, in rows
//! parallel to the exterior edge (the row order of docs/conventions.md, corners `b400 = V_e`, `b040 = V_{e+1}`,
//! `b004 = S`):
//!
//! ```text
//! row 0:  V_e      q1      q2      q3      V_{e+1}     (the exterior cubic, degree-raised)
//! row 1:  I¹_e     C¹_e    C²_e    I¹_{e+1}
//! row 2:  I²_e     N_e     I²_{e+1}
//! row 3:  I³_e     I³_{e+1}
//! row 4:  S
//! ```
//!
//! The interior boundary from corner `i` to `S` is the cubic `V_i, J¹_i, J²_i, S`, whose
//! degree-raised points are `I¹_i = (V_i + 3J¹_i)/4`, `I²_i = (J¹_i + J²_i)/2`,
//! `I³_i = (3J²_i + S)/4`. Free parameters: `α` (in the exterior cubics), `β_i > 0` per corner,
//! and Jensen's `c_e > 0` per exterior edge **of each triangle** (see below).
//!
//! # G1 across an exterior edge: Chiyokura–Kimura with Jensen's parameter
//!
//! For the edge cubic `B(t)` from `V_a` to `V_b` with control points `V_a, E¹, E², V_b`, let
//! `Ĉ_0 = (n_a × (E¹ − V_a))/|…|` and `Ĉ_1 = (n_b × (V_b − E²))/|…|` (unit, in the tangent
//! planes, perpendicular to the curve, to the left of the direction of travel: into a
//! counter-clockwise face, and reversed for the neighbour, which travels the edge the other way;
//! the seed's "sign chosen to make k positive" is the same thing on valid data, and on folded
//! data it would hide a cusp). The corner cross vectors
//! of the patch lie in the tangent planes and decompose as
//! `I¹_a − V_a = k_0 Ĉ_0 + h_0 (E¹ − V_a)` and `I¹_b − V_b = k_1 Ĉ_1 + h_1 (V_b − E²)` (eqs 4–5).
//! The cross-boundary derivative along `V_S − V_a` of a quartic is the cubic
//! `D(t) = 4 Σ B³_m(t) (row1_m − row0_m)`. Chiyokura–Kimura choose
//! `D(t) = 4 K(t) Ĉ(t) + (4/3) h(t) B'(t)` with `Ĉ(t) = (1−t)Ĉ_0 + tĈ_1` and `h` linear
//! (`h(0) = h_0`, `h(1) = h_1 + 3/4`, the shift because the derivative is taken from `V_a`).
//! Every such `D` lies in `span(Ĉ(t), B'(t))`, and `Ĉ(t)` depends only on the edge's curve and
//! end normals, so both triangles on the edge get the same normal `B' × Ĉ` along it: G1. Matching
//! the Bernstein coefficients gives (eqs 2–3 of the seed):
//!
//! ```text
//! C¹ = E¹ + ⅓ { c (k_0 + k_1) Ĉ_0 + k_0 Ĉ_1 + 2h_0 (E² − E¹) + h_1 (E¹ − V_a) }
//! C² = E² + ⅓ { k_1 Ĉ_0 + c (k_0 + k_1) Ĉ_1 + h_0 (V_b − E²) + 2h_1 (E² − E¹) }
//! ```
//!
//! with `K(t) = k_0(1−t)(1 − t + ct) + k_1 t(t + c(1−t))`: Chiyokura–Kimura for `c = 1` (then
//! `K` is linear), Jensen's generalization otherwise. The Ĉ-part of `D` factors as
//! `K(t)·[(1−t)Ĉ_0 + tĈ_1]` for **every** `c`, so `c` never affects the neighbour: it is free
//! per (triangle, edge), and the two triangles on an edge may use different values. It cannot
//! vary between the two ends of one edge (the middle coefficients must equal `2K_1/3` in both
//! the `Ĉ_0` and `Ĉ_1` parts). `K > 0` on `[0, 1]` needs `c > 0` and `k_0, k_1 > 0`.
//!
//! # G1 inside the triangle
//!
//! Across the interior boundary from `V_i` to `S` the two sub-patches `L` (edge `i`) and `R`
//! (edge `i−1`) have cross-boundary derivatives `D_L`, `D_R` along the domain directions
//! `V_{i+1} − V_i` and `V_{i−1} − V_i`, whose sum is `3(S − V_i)` in the centroid split. The
//! scheme imposes `D_L(t) + D_R(t) = μ(t) P'(t)` with `P` the boundary and `μ` linear (degrees:
//! `D` cubic, `P'` quadratic): coplanarity, hence G1 (C1 when `μ ≡ 3`). With `P'` written in the
//! cubic's differences `Δ_m = J^{m+1} − J^m` (`J⁰ = V_i`, `J³ = S`), the degree-3 coefficients
//! of `μ P'` are `3μ_0Δ_0`, `2μ_0Δ_1 + μ_1Δ_0`, `μ_0Δ_2 + 2μ_1Δ_1`, `3μ_1Δ_2`, and the condition
//! `4[(l_m − p_m) + (r_m − p_m)] = coefficient m` gives, for `m = 0 … 3`:
//!
//! * `m = 0`: `J¹_i = V_i + β_i (E_a + E_b − 2V_i)` with `β_i = 1/μ_0` and `E_a, E_b` the
//!   cubic points next to `V_i` on its two edges; equivalently
//!   `I¹_i = V_i + β_i (E⁴_a + E⁴_b − 2V_i)` with the quartic points. `β = ⅓` gives C1.
//! * `m = 3`: with `S = (J²_0 + J²_1 + J²_2)/3` the condition holds with `μ_1 = 3` on every
//!   interior boundary (and `S` is C1).
//! * `m = 1`: `J²_i = J¹_i + β_i [4(C_L + C_R − 2I¹_i) − 3(J¹_i − V_i)]/2`, where `C_L = C¹_i`
//!   and `C_R = C²_{i−1}` are the cross-boundary points next to `V_i`.
//! * `m = 2`: `N_i + N_{i−1} = R_i := 2I²_i + [(S − J²_i)/β_i + 6(J²_i − J¹_i)]/4` for each
//!   corner: three equations, three unknowns, `N_e = (R_e + R_{e+1} − R_{e+2})/2`.
//!
//! Any `β_i > 0` gives a G1 surface, as the seed says.
//!
//! # Every free parameter
//!
//! What the construction leaves free once G1 is imposed, derived from the conditions above
//! (tests: `surface/tests/suite/free_parameters.rs`: each keeps G1 over its range, and the
//! Jacobian of a face's 45 control points in all of them has full rank on generic data):
//!
//! | parameter | where | count | range | set by |
//! |---|---|---|---|---|
//! | end-derivative lengths `α_0, α_1` | each mesh edge, shared | 2 per edge | `> 0` | the curve construction (`--curves`) |
//! | end-tangent directions | each edge end, shared by the edges of a vertex's sector | 1 angle per edge end | in the tangent plane, every face corner convex | the tangent rule (`--tangents`, `surface::fit::fan`) |
//! | `β_i = 1/μ_0` | each corner of each face | 3 per face | `BETA`: 0.01–10 | `--beta`, `--interior` (fairing) |
//! | Jensen's `c` — or the middle vector `x` of a quadratic field `W` | `c`: each (face, edge); `x`: each edge, shared | 3 per face, or 3 per edge | `C`: 0.01–100; `x` any | `--c`, `--interior`; `x` by the data in `shirman-sequin-curvature` ([`crate::curvature_cross`]) |
//!
//! Everything else is forced:
//!
//! * **The cross-boundary weight functions.** The quartic's cross-boundary derivative `D` is
//!   cubic and `B'` quadratic, so `h` is linear, fixed at both ends by the corner cross vectors
//!   (`h_0, h_1`); `K` and the field `W` share the cubic's degree: `deg K + deg W ≤ 3`, with
//!   `W` shared by both faces and `K` per face. `K` quadratic with `W` linear is Jensen's form
//!   (its middle coefficient, `c`, is the free number); `K` linear with `W` quadratic is the
//!   quadratic-field form (`W`'s middle vector, three numbers, is free and shared). `K`
//!   constant with `W` cubic would need `k_0/k_1` equal on both faces, which the corners do not
//!   give; `W` constant needs equal perpendiculars at both ends. The two free forms cannot be
//!   combined (degree 4).
//! * **The interior-boundary function** `μ(t)` is linear (`D_L + D_R` cubic, `P'` quadratic):
//!   `μ_0 = 1/β_i` is free, and `μ_1 = 3` is forced. With `I³_j = (3J²_j + S)/4`, the `m = 3`
//!   condition on boundary `i` reads `J²_{i+1} + J²_{i−1} − 2J²_i = μ_{1,i}(S − J²_i)`: `S` lies
//!   on the line from `J²_i` through the centroid `G` of the three `J²` for every `i`, and the
//!   three medians of a triangle meet only at `G`. So `S = G` and `μ_1 = 3` (C1 at the split
//!   point), unless the three `J²` are collinear.
//! * **The interior points**: `J¹_i` by `m = 0`, `J²_i` by `m = 1`, the row-2 middles `N_e` by
//!   the three `m = 2` equations (a regular 3 × 3 system, `N_e = (R_e + R_{e+1} − R_{e+2})/2`).
//! * **The domain split point** is the centroid of the data triangle's domain: fixed by the
//!   layout every tessellation, file and measure reads (`crate::scheme::CENTROID_SPLIT`); another
//!   split point changes the relation `D_L + D_R = 3(S − V_i)` of the domain directions and is
//!   a different layout, not a parameter.
//! * **The interior boundaries are cubics** (degree-raised): a quartic interior boundary would
//!   free `I¹, I², I³` and change every condition above (the testbed's variant,
//!   [`crate::ss_variants`], makes that choice).
//!
//! # Straight crease corners
//!
//! A corner `V_i` whose two edges are both crease lines there (a single face between two
//! crease edges: its sector has no other face) carries the crease's tangents, which lie in both
//! sectors' tangent planes and so on their common line: opposite, `a = −b` for the cubic legs
//! `a = E_a − V_i`, `b = E_b − V_i` once the fit gives them equal lengths
//! (`surface::fit::fan`, a crease C1 through the vertex). Then `m = 0` above,
//! `3(a + b) = 3μ_0(J¹_i − V_i)`, leaves `J¹_i` on the crease line for every `β_i`: the two
//! sub-patches at the corner would have a corner of zero angle, and the Chiyokura–Kimura cross
//! vector has no component across the edges ([`SchemeError::NoCrossComponent`]). The face is
//! still fitted G1 by taking `μ_0 = 0` there (`β_i = ∞`), which `m = 0` allows exactly when
//! `a + b = 0`:
//!
//! * `J¹_i = V_i + u`, `u = ℓ ĉ` with `ĉ = n_i × â` the unit perpendicular into the face in
//!   the tangent plane and `ℓ = ĉ · (V_{i+1} + V_{i−1} − 2V_i)/9` (the C1 construction's
//!   `β(a + b)` for chords in thirds, `β = ⅓`, measured across the crease): sub-patch `i` has
//!   the corner tangents `a` and `¾u`, sub-patch `i − 1` has `¾u` and `b = −a`, and both have
//!   the normal `a × u ∥ n_i` there;
//! * `m = 1` reads `4[(C_L − I¹_i) + (C_R − I¹_i)] = μ_1 Δ_0 = 3u`: no longer a condition on
//!   `J²_i` but on the two cross-boundary points next to the corner. Both lie on crease edges,
//!   across which no G1 is owed, so Chiyokura–Kimura's `C_L`, `C_R` are each moved by half of
//!   the defect `¾u − (C_L − I¹_i) − (C_R − I¹_i)`;
//! * `J²_i = V_i + 2u` (free now; the interior cubic leaves the corner at even steps);
//! * `m = 2` with `μ_0 = 0`: `R_i = 2I²_i + 6(J²_i − J¹_i)/4`; `m = 3` is unchanged.
//!
//! Every coefficient of `D_L + D_R = μP'` still holds (`μ(t) = 3t`), and `D_L`, `D_R` lie on
//! opposite sides of `P'` wherever they are not along it: G1 across the interior boundaries,
//! Chiyokura–Kimura (untouched) across the face's third edge, and the crease edges C0 as every
//! crease. [`macro_patch_creased`] builds it; [`macro_patch`] (no creases known) refuses such a
//! corner as before.
//!
//! # Where the seed differs
//!
//! Mann's eq 1, `I_i2` and `N_i` formulas are mutually consistent and equal to the above with
//! `β_here = 3 β_seed / 8` (eq 1 must be read with its left side as the cubic point `J¹`). But
//! Appendix A's nets — the Shirman–Séquin default — are the C1 construction `β_here = ⅓`, i.e.
//! `β_seed = 8/9`, not the `β_seed = ⅓` the text states. The tests reproduce Appendix A with
//! `β = ⅓` in this module's parametrization.

use curves::{CubicBez3, VertexData};
use nalgebra::{Point3, Vector3};

/// A quartic triangular Bézier net in the row order of docs/conventions.md (15 points).
pub type QuarticNet = [Point3<f64>; 15];

/// Below this sine the construction's perpendiculars are undefined (a zero-length end
/// derivative or a corner cross vector along the edge): the same threshold as the curve layer.
pub const DEGENERATE: f64 = curves::DEGENERATE_SINE;

/// The Shirman–Séquin defaults: `β = ⅓` at every corner (C1 inside the triangle, Appendix A),
/// `c = 1` on every edge (Chiyokura–Kimura).
pub const DEFAULT_BETA: f64 = 1.0 / 3.0;
/// Jensen's parameter of Chiyokura–Kimura's cross-boundary construction.
pub const DEFAULT_C: f64 = 1.0;

/// The free interior parameters of one macro-patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InteriorParameters {
    /// `β_i` for corners `0, 1, 2` of the triangle; any positive value gives G1.
    pub beta: [f64; 3],
    /// Jensen's `c_e` for exterior edges `0, 1, 2` (edge `e` from corner `e` to `e + 1`) of this
    /// triangle; independent of the neighbouring triangle's value on the same edge.
    pub c: [f64; 3],
}

impl Default for InteriorParameters {
    fn default() -> Self {
        InteriorParameters {
            beta: [DEFAULT_BETA; 3],
            c: [DEFAULT_C; 3],
        }
    }
}

/// Why a macro-patch could not be built.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SchemeError {
    /// A β or c is not positive and finite.
    #[error("{name}[{index}] = {value} must be positive and finite")]
    BadParameter {
        /// `"beta"` or `"c"`.
        name: &'static str,
        /// Corner or edge index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// An exterior curve has a zero end derivative at a corner.
    #[error("edge {edge}: zero end derivative at corner {corner}")]
    ZeroEndDerivative {
        /// Edge index in the triangle.
        edge: usize,
        /// Corner index in the triangle.
        corner: usize,
    },
    /// The vertex normal at a corner makes 90° or more with the face normal. The patch
    /// interpolates that normal at the corner (its tangent plane there is spanned by the two
    /// edge tangents, both perpendicular to it), so it would fold over the face there
    /// (`surface::folds`): the face is left to the fallback, which need not interpolate it.
    #[error("the vertex normal at corner {corner} makes 90° or more with the face normal")]
    NormalAgainstFace {
        /// Corner index in the triangle.
        corner: usize,
    },
    /// An exterior curve's end tangent is not perpendicular to the vertex normal (its boundary
    /// problem clamped the tangent towards the chord, `curves::BoundaryProblem::clamped`): no
    /// G1 surface through the vertex has that normal and that tangent.
    #[error("edge {edge}: the tangent at corner {corner} leaves the tangent plane (clamped)")]
    TangentOffPlane {
        /// Edge index in the triangle.
        edge: usize,
        /// Corner index in the triangle.
        corner: usize,
    },
    /// The macro-patch turns over its face (a patch normal at 90° or more from the face normal
    /// at a sample of the fold measure, `surface::folds`) and the fallback patch on the same
    /// curves does not: the scheme ([`crate::scheme::shirman_sequin`]) then prefers the
    /// fallback. Not returned by [`macro_patch`], whose nets are what the construction gives.
    #[error("the patch turns over its face, and the fallback on the same curves does not")]
    FoldsOverFace,
    /// The corner cross vector has no component across the edge (`k ≤ 0`): the
    /// Chiyokura–Kimura decomposition fails and G1 cannot be guaranteed.
    #[error("edge {edge}: cross-boundary vector at corner {corner} does not point into the patch")]
    NoCrossComponent {
        /// Edge index in the triangle.
        edge: usize,
        /// Corner index in the triangle.
        corner: usize,
    },
}

fn mid(a: &Point3<f64>, b: &Point3<f64>, t: f64) -> Point3<f64> {
    a + (b - a) * t
}

/// The unit perpendicular `Ĉ = n × t / |n × t|` (left of the direction of travel `t`, i.e. into a
/// counter-clockwise face) and the decomposition `a = k Ĉ + h t`. The sign of `Ĉ` is fixed by the
/// geometry, not chosen to make `k` positive: the neighbouring face, travelling the edge the
/// other way, gets `−Ĉ`, as G1 needs. `k ≤ 0` means the corner cross vector folds over the edge
/// and no G1 surface of this form exists: `None`.
fn decompose(
    n: &Vector3<f64>,
    t: &Vector3<f64>,
    a: &Vector3<f64>,
) -> Option<(Vector3<f64>, f64, f64)> {
    let perp = n.cross(t);
    let len = perp.norm();
    let tt = t.norm_squared();
    if len <= DEGENERATE * t.norm() || tt == 0.0 {
        return None;
    }
    let c_hat = perp / len;
    let k = a.dot(&c_hat);
    if k <= DEGENERATE * a.norm().max(f64::MIN_POSITIVE) {
        return None;
    }
    Some((c_hat, k, a.dot(t) / tt))
}

/// Data at one end of an exterior edge for the cross-boundary construction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossEnd {
    /// Unit normal at the end vertex.
    pub normal: Vector3<f64>,
    /// The patch's corner cross vector there: the row-1 point next to the vertex minus the
    /// vertex (`I¹ − V`), in the tangent plane.
    pub cross: Vector3<f64>,
}

/// Why the cross-boundary construction failed at an end (0: start, 1: end).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CrossFailure {
    /// The curve's end derivative is zero.
    ZeroDerivative(usize),
    /// The corner cross vector has no component across the edge.
    NoCrossComponent(usize),
}

impl CrossFailure {
    /// The macro-patch's error for this failure on face edge `edge` from corner `corners[0]`
    /// (end 0) to corner `corners[1]` (end 1).
    pub fn on_edge(self, edge: usize, corners: [usize; 2]) -> SchemeError {
        match self {
            CrossFailure::ZeroDerivative(end) => SchemeError::ZeroEndDerivative {
                edge,
                corner: corners[usize::from(end != 0)],
            },
            CrossFailure::NoCrossComponent(end) => SchemeError::NoCrossComponent {
                edge,
                corner: corners[usize::from(end != 0)],
            },
        }
    }
}

/// Chiyokura–Kimura's cross-boundary construction with Jensen's parameter `c` (module docs):
/// the two interior row-1 points `[C¹, C²]` of the quartic patch whose boundary is the cubic
/// `curve` (degree-raised), given the end normals and corner cross vectors.
pub fn chiyokura_kimura(
    curve: &CubicBez3,
    ends: &[CrossEnd; 2],
    c: f64,
) -> Result<[Point3<f64>; 2], CrossFailure> {
    chiyokura_kimura_with_k(curve, ends, c).map(|(points, _)| points)
}

/// [`chiyokura_kimura`] with the decomposition's `[k_0, k_1]` (the corner cross vectors'
/// components across the edge), which the quadratic-field form scales its middle vector by.
pub(crate) fn chiyokura_kimura_with_k(
    curve: &CubicBez3,
    ends: &[CrossEnd; 2],
    c: f64,
) -> Result<([Point3<f64>; 2], [f64; 2]), CrossFailure> {
    let [va, e1, e2, vb] = curve.points;
    let t0 = e1 - va;
    let t1 = vb - e2;
    if t0.norm() == 0.0 {
        return Err(CrossFailure::ZeroDerivative(0));
    }
    if t1.norm() == 0.0 {
        return Err(CrossFailure::ZeroDerivative(1));
    }
    let (ch0, k0, h0) =
        decompose(&ends[0].normal, &t0, &ends[0].cross).ok_or(CrossFailure::NoCrossComponent(0))?;
    let (ch1, k1, h1) =
        decompose(&ends[1].normal, &t1, &ends[1].cross).ok_or(CrossFailure::NoCrossComponent(1))?;
    Ok((
        [
            e1 + (ch0 * (c * (k0 + k1)) + ch1 * k0 + (e2 - e1) * (2.0 * h0) + (e1 - va) * h1) / 3.0,
            e2 + (ch0 * k1 + ch1 * (c * (k0 + k1)) + (vb - e2) * h0 + (e2 - e1) * (2.0 * h1)) / 3.0,
        ],
        [k0, k1],
    ))
}

/// The faces the construction would fold or could not make G1 whatever its parameters, found
/// before it starts: a vertex normal at 90° or more from the face normal (the patch
/// interpolates it: [`SchemeError::NormalAgainstFace`]; only for a face with a normal, i.e.
/// `|(V1 − V0) × (V2 − V0)|` above [`DEGENERATE`] times the two edges' lengths), and an end
/// tangent off the vertex's tangent plane, `|t̂ · n| >` [`DEGENERATE`] (a clamped tangent:
/// [`SchemeError::TangentOffPlane`]; unclamped tangents are perpendicular to rounding, 10⁻¹⁶,
/// and a tangent within 10⁻⁸ of the plane moves the normal by no more than that).
pub(crate) fn refuse_folding(
    v: &[Point3<f64>; 3],
    n: &[Vector3<f64>; 3],
    edges: &[CubicBez3; 3],
) -> Result<(), SchemeError> {
    let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
    let area = e1.cross(&e2);
    if area.norm() > DEGENERATE * e1.norm() * e2.norm() {
        if let Some(corner) = (0..3).find(|&i| n[i].dot(&area) <= 0.0) {
            return Err(SchemeError::NormalAgainstFace { corner });
        }
    }
    for (edge, c) in edges.iter().enumerate() {
        let [va, e1, e2, vb] = c.points;
        let corner_b = (edge + 1) % 3;
        for (corner, t) in [(edge, e1 - va), (corner_b, vb - e2)] {
            if t.dot(&n[corner]).abs() > DEGENERATE * t.norm() {
                return Err(SchemeError::TangentOffPlane { edge, corner });
            }
        }
    }
    Ok(())
}

/// Builds the three quartic sub-patches of one data triangle.
///
/// `vertices` are the corners `V_0, V_1, V_2`; `edges[e]` is the exterior cubic from `V_e` to
/// `V_{e+1}` (the caller orients the shared curve); its end points must be the vertex positions.
/// Returns the nets of sub-patches `0, 1, 2` (sub-patch `e` over `(V_e, V_{e+1}, S)`).
///
/// Refused before anything is built: a face whose vertex normal makes 90° or more with the
/// face normal ([`SchemeError::NormalAgainstFace`]: the patch interpolates that normal, so it
/// would fold there) and a face with a clamped end tangent ([`SchemeError::TangentOffPlane`]).
pub fn macro_patch(
    vertices: [&VertexData; 3],
    edges: &[CubicBez3; 3],
    params: &InteriorParameters,
) -> Result<[QuarticNet; 3], SchemeError> {
    macro_patch_creased(vertices, edges, params, [false; 3])
}

/// The largest `|a + b| / max(|a|, |b|)` of a corner's two cubic legs for the corner to be
/// built as a straight crease corner (module docs): the same `√ε`-size threshold as the rest
/// of the construction. The `m = 0` condition is then off by `3(a + b)`, which turns the two
/// sub-patches' normals at the corner apart by about `|a + b| / |a|`; the fit gives the legs
/// of a straight crease corner exactly opposite directions and equal lengths, so that is the
/// rounding of `E − V`.
pub const STRAIGHT_SINE: f64 = DEGENERATE;

/// [`macro_patch`] on a face whose crease edges are known: `creased[i]` says that both edges at
/// corner `i` are crease lines there. Such a corner whose legs are opposite and of one length
/// (within [`STRAIGHT_SINE`]) is built as a straight crease corner (module docs), G1 where
/// [`macro_patch`] refuses it; every other corner, and every face without one, gets
/// [`macro_patch`]'s nets bit for bit.
pub fn macro_patch_creased(
    vertices: [&VertexData; 3],
    edges: &[CubicBez3; 3],
    params: &InteriorParameters,
    creased: [bool; 3],
) -> Result<[QuarticNet; 3], SchemeError> {
    macro_patch_with(vertices, edges, params, creased, &|e, ends| {
        chiyokura_kimura(&edges[e], ends, params.c[e])
    })
}

/// The cross-boundary rule of an exterior edge: the two interior row-1 points `[C¹, C²]` of
/// face edge `e` from the end normals and corner cross vectors. Chiyokura–Kimura with Jensen's
/// `c` in [`macro_patch_creased`]; the curvature-matched field of
/// [`crate::curvature_cross`] in its variant. The rest of the construction (module docs,
/// "G1 inside the triangle") holds for any rule whose cross-boundary derivative lies in a
/// span both faces on the edge share.
pub(crate) type CrossRule<'a> =
    dyn Fn(usize, &[CrossEnd; 2]) -> Result<[Point3<f64>; 2], CrossFailure> + 'a;

/// [`macro_patch_creased`] with the exterior edges' cross-boundary points from `cross`.
pub(crate) fn macro_patch_with(
    vertices: [&VertexData; 3],
    edges: &[CubicBez3; 3],
    params: &InteriorParameters,
    creased: [bool; 3],
    cross: &CrossRule<'_>,
) -> Result<[QuarticNet; 3], SchemeError> {
    for (name, values) in [("beta", params.beta), ("c", params.c)] {
        for (index, value) in values.into_iter().enumerate() {
            if !(value > 0.0 && value.is_finite()) {
                return Err(SchemeError::BadParameter { name, index, value });
            }
        }
    }
    let v: [Point3<f64>; 3] = std::array::from_fn(|i| vertices[i].p);
    let n: [Vector3<f64>; 3] = std::array::from_fn(|i| vertices[i].n.normalize());
    let prev = |i: usize| (i + 2) % 3;
    let next = |i: usize| (i + 1) % 3;
    let beta = params.beta;
    refuse_folding(&v, &n, edges)?;

    // Straight crease corners: the step `u` of the interior cubic leaving them.
    let straight: [Option<Vector3<f64>>; 3] = std::array::from_fn(|i| {
        creased[i]
            .then(|| straight_step(&v, &n, edges, i))
            .flatten()
    });

    // m = 0: first interior-boundary points.
    let j1: [Point3<f64>; 3] = std::array::from_fn(|i| {
        if let Some(u) = straight[i] {
            return v[i] + u;
        }
        let ea = edges[i].points[1];
        let eb = edges[prev(i)].points[2];
        v[i] + ((ea - v[i]) + (eb - v[i])) * beta[i]
    });
    let i1: [Point3<f64>; 3] = std::array::from_fn(|i| mid(&v[i], &j1[i], 0.75));

    // Chiyokura–Kimura cross-boundary points of every exterior edge.
    let mut c1 = [Point3::origin(); 3];
    let mut c2 = [Point3::origin(); 3];
    for e in 0..3 {
        let (a, b) = (e, next(e));
        let ends = [
            CrossEnd {
                normal: n[a],
                cross: i1[a] - v[a],
            },
            CrossEnd {
                normal: n[b],
                cross: i1[b] - v[b],
            },
        ];
        [c1[e], c2[e]] = cross(e, &ends).map_err(|end| end.on_edge(e, [a, b]))?;
    }

    // m = 1 at a straight corner: the two cross-boundary points next to it (on crease edges)
    // share the defect of 4[(C_L − I¹) + (C_R − I¹)] = 3u.
    for (i, u) in straight.iter().enumerate() {
        if let Some(u) = u {
            let defect = u * 0.75 - ((c1[i] - i1[i]) + (c2[prev(i)] - i1[i]));
            c1[i] += defect / 2.0;
            c2[prev(i)] += defect / 2.0;
        }
    }

    // m = 1: second interior-boundary points; m = 3: the split point.
    let j2: [Point3<f64>; 3] = std::array::from_fn(|i| {
        if let Some(u) = straight[i] {
            return v[i] + u * 2.0;
        }
        let cl = c1[i];
        let cr = c2[prev(i)];
        let sum = (cl - i1[i]) + (cr - i1[i]);
        j1[i] + (sum * 4.0 - (j1[i] - v[i]) * 3.0) * (beta[i] / 2.0)
    });
    let s = Point3::from((j2[0].coords + j2[1].coords + j2[2].coords) / 3.0);
    let i2: [Point3<f64>; 3] = std::array::from_fn(|i| mid(&j1[i], &j2[i], 0.5));
    let i3: [Point3<f64>; 3] = std::array::from_fn(|i| mid(&j2[i], &s, 0.25));

    // m = 2: the row-2 middle points.
    let r: [Vector3<f64>; 3] = std::array::from_fn(|i| {
        if straight[i].is_some() {
            // μ_0 = 0.
            return i2[i].coords * 2.0 + (j2[i] - j1[i]) * (6.0 / 4.0);
        }
        i2[i].coords * 2.0 + ((s - j2[i]) / beta[i] + (j2[i] - j1[i]) * 6.0) / 4.0
    });
    let nmid: [Point3<f64>; 3] =
        std::array::from_fn(|e| Point3::from((r[e] + r[next(e)] - r[prev(e)]) / 2.0));

    Ok(std::array::from_fn(|e| {
        let (a, b) = (e, next(e));
        let q = edges[e].elevate().points;
        [
            q[0], q[1], q[2], q[3], q[4], //
            i1[a], c1[e], c2[e], i1[b], //
            i2[a], nmid[e], i2[b], //
            i3[a], i3[b], //
            s,
        ]
    }))
}

/// The step `u = ℓ ĉ` of the interior cubic at straight crease corner `i` (module docs), or
/// `None` where the corner is not straight (legs not opposite and of one length within
/// [`STRAIGHT_SINE`]) or the face does not reach across the crease line (`ℓ` not above
/// [`DEGENERATE`] times the legs: a face folded over its corner, left to the refusals).
fn straight_step(
    v: &[Point3<f64>; 3],
    n: &[Vector3<f64>; 3],
    edges: &[CubicBez3; 3],
    i: usize,
) -> Option<Vector3<f64>> {
    let (next, prev) = ((i + 1) % 3, (i + 2) % 3);
    let a = edges[i].points[1] - v[i];
    let b = edges[prev].points[2] - v[i];
    let scale = a.norm().max(b.norm());
    if !(scale > 0.0 && (a + b).norm() <= STRAIGHT_SINE * scale) {
        return None;
    }
    let c_hat = n[i].cross(&a).try_normalize(0.0)?;
    let ell = c_hat.dot(&((v[next] - v[i]) + (v[prev] - v[i]))) / 9.0;
    (ell > DEGENERATE * scale).then(|| c_hat * ell)
}

/// Derivatives of a macro-patch's control points with respect to its six interior parameters
/// `p = (β_0, β_1, β_2, c_0, c_1, c_2)`: `[sub-patch][net index][parameter]`.
pub type NetDerivatives = [[[Vector3<f64>; 6]; 15]; 3];

/// [`macro_patch`] together with the exact derivatives of every control point with respect to
/// `(β_0, β_1, β_2, c_0, c_1, c_2)`.
///
/// Each step of the construction is differentiated as written (module docs): with
/// `A_i = E_a + E_b − 2V_i`, `∂J¹_i/∂β_i = A_i`; the Chiyokura–Kimura coefficients are
/// `k = β k̂`, `h = β ĥ` (the cross vector `I¹ − V = ¾ β A` scales with β, `Ĉ` does not), so
/// `∂C¹/∂β_a = ⅓{c k̂_0 Ĉ_0 + k̂_0 Ĉ_1 + 2ĥ_0 (E² − E¹)}`, `∂C¹/∂β_b = ⅓{c k̂_1 Ĉ_0 + ĥ_1 (E¹ − V_a)}`,
/// `∂C¹/∂c = ⅓ (k_0 + k_1) Ĉ_0`, and likewise for `C²`; then the product and quotient rules
/// through `J²`, `S`, `I²`, `I³` and `N` (whose `R_i` has the term `(S − J²_i)/β_i`).
pub fn macro_patch_with_derivatives(
    vertices: [&VertexData; 3],
    edges: &[CubicBez3; 3],
    params: &InteriorParameters,
) -> Result<([QuarticNet; 3], NetDerivatives), SchemeError> {
    let nets = macro_patch(vertices, edges, params)?;
    type D = [Vector3<f64>; 6];
    let zero: D = [Vector3::zeros(); 6];
    let v: [Point3<f64>; 3] = std::array::from_fn(|i| vertices[i].p);
    let n: [Vector3<f64>; 3] = std::array::from_fn(|i| vertices[i].n.normalize());
    let prev = |i: usize| (i + 2) % 3;
    let next = |i: usize| (i + 1) % 3;
    let beta = params.beta;
    let add = |a: &D, b: &D, s: f64| -> D { std::array::from_fn(|k| a[k] + b[k] * s) };

    let a_vec: [Vector3<f64>; 3] =
        std::array::from_fn(|i| (edges[i].points[1] - v[i]) + (edges[prev(i)].points[2] - v[i]));
    let j1: [Point3<f64>; 3] = std::array::from_fn(|i| v[i] + a_vec[i] * beta[i]);
    let i1: [Point3<f64>; 3] = std::array::from_fn(|i| mid(&v[i], &j1[i], 0.75));
    let dj1: [D; 3] = std::array::from_fn(|i| {
        let mut d = zero;
        d[i] = a_vec[i];
        d
    });
    let di1: [D; 3] = std::array::from_fn(|i| dj1[i].map(|x| x * 0.75));

    let mut c1v = [Point3::origin(); 3];
    let mut c2v = [Point3::origin(); 3];
    let mut dc1 = [zero; 3];
    let mut dc2 = [zero; 3];
    for e in 0..3 {
        let (a, b) = (e, next(e));
        let [va, e1, e2, vb] = edges[e].points;
        let (t0, t1) = (e1 - va, vb - e2);
        let fail0 = SchemeError::NoCrossComponent { edge: e, corner: a };
        let fail1 = SchemeError::NoCrossComponent { edge: e, corner: b };
        let (ch0, k0, h0) = decompose(&n[a], &t0, &(i1[a] - v[a])).ok_or(fail0)?;
        let (ch1, k1, h1) = decompose(&n[b], &t1, &(i1[b] - v[b])).ok_or(fail1)?;
        let (kh0, hh0, kh1, hh1) = (k0 / beta[a], h0 / beta[a], k1 / beta[b], h1 / beta[b]);
        let c = params.c[e];
        c1v[e] =
            e1 + (ch0 * (c * (k0 + k1)) + ch1 * k0 + (e2 - e1) * (2.0 * h0) + (e1 - va) * h1) / 3.0;
        c2v[e] =
            e2 + (ch0 * k1 + ch1 * (c * (k0 + k1)) + (vb - e2) * h0 + (e2 - e1) * (2.0 * h1)) / 3.0;
        dc1[e][a] += (ch0 * (c * kh0) + ch1 * kh0 + (e2 - e1) * (2.0 * hh0)) / 3.0;
        dc1[e][b] += (ch0 * (c * kh1) + (e1 - va) * hh1) / 3.0;
        dc1[e][3 + e] = ch0 * ((k0 + k1) / 3.0);
        dc2[e][a] += (ch1 * (c * kh0) + (vb - e2) * hh0) / 3.0;
        dc2[e][b] += (ch0 * kh1 + ch1 * (c * kh1) + (e2 - e1) * (2.0 * hh1)) / 3.0;
        dc2[e][3 + e] = ch1 * ((k0 + k1) / 3.0);
    }

    // J² = J¹ + (β/2) G, G = 4(C_L + C_R − 2I¹) − 3(J¹ − V).
    let mut j2 = [Point3::origin(); 3];
    let mut dj2 = [zero; 3];
    for i in 0..3 {
        let (cl, cr) = (c1v[i], c2v[prev(i)]);
        let g = ((cl - i1[i]) + (cr - i1[i])) * 4.0 - (j1[i] - v[i]) * 3.0;
        j2[i] = j1[i] + g * (beta[i] / 2.0);
        let dg: D = std::array::from_fn(|k| {
            (dc1[i][k] + dc2[prev(i)][k] - di1[i][k] * 2.0) * 4.0 - dj1[i][k] * 3.0
        });
        dj2[i] = add(&dj1[i], &dg, beta[i] / 2.0);
        dj2[i][i] += g / 2.0;
    }
    let s = Point3::from((j2[0].coords + j2[1].coords + j2[2].coords) / 3.0);
    let ds: D = std::array::from_fn(|k| (dj2[0][k] + dj2[1][k] + dj2[2][k]) / 3.0);
    let di2: [D; 3] =
        std::array::from_fn(|i| std::array::from_fn(|k| (dj1[i][k] + dj2[i][k]) * 0.5));
    let di3: [D; 3] =
        std::array::from_fn(|i| std::array::from_fn(|k| dj2[i][k] * 0.75 + ds[k] * 0.25));
    // R_i = 2I² + [(S − J²)/β + 6(J² − J¹)]/4.
    let dr: [D; 3] = std::array::from_fn(|i| {
        let mut d: D = std::array::from_fn(|k| {
            di2[i][k] * 2.0 + ((ds[k] - dj2[i][k]) / beta[i] + (dj2[i][k] - dj1[i][k]) * 6.0) / 4.0
        });
        d[i] -= (s - j2[i]) / (4.0 * beta[i] * beta[i]);
        d
    });
    let dn: [D; 3] = std::array::from_fn(|e| {
        std::array::from_fn(|k| (dr[e][k] + dr[next(e)][k] - dr[prev(e)][k]) / 2.0)
    });
    let derivs: NetDerivatives = std::array::from_fn(|e| {
        let (a, b) = (e, next(e));
        [
            zero, zero, zero, zero, zero, //
            di1[a], dc1[e], dc2[e], di1[b], //
            di2[a], dn[e], di2[b], //
            di3[a], di3[b], //
            ds,
        ]
    });
    Ok((nets, derivs))
}
