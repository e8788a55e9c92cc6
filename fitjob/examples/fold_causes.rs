//! Why the faces of a fit fold: a diagnostic, not a test.
//!
//! `cargo run --release -p fitjob --example fold_causes -- MESH [CURVES]` fits `MESH` the way
//! `experiments fit` does (the fit job: read, repair, estimate, `shirman-sequin` on the curves
//! `CURVES`, default `optimized`), measures the folds (`surface::folds`) and classifies every
//! folded face by the causes below; the table counts each cause once per face, and a face may
//! have several. `FOLD_CAUSES_VERBOSE=1` prints each face's causes; `FOLD_CAUSES_DUMP=f` also
//! prints face `f` projected onto its plane (its curves, nets and the cosines of its patch
//! normals on a grid), with `FOLD_CAUSES_FALLBACK=1` the fallback patch on its curves instead
//! of the fitted one.
//!
//! * `regular` / `fallback:<reason>`: whether the face got the fallback patch, and why.
//! * `needle`: its smallest angle is below [`NEEDLE_DEG`]; `cap`: its largest above [`CAP_DEG`].
//! * `lean>60`, `lean>90`: a corner's vertex normal makes more than 60° (90°) with the face
//!   normal; `regular-normal≥90`: such a face fitted regularly (the patch interpolates that
//!   normal, so it folds at that corner).
//! * `steep`: an end tangent of one of its edge curves makes more than [`STEEP_DEG`] with the
//!   chord (where the tangent clamp of `curves::problem` acts).
//! * `backtrack`: an edge curve runs backwards along its chord somewhere (`B'(t)·d ≤ 0`: α too
//!   long for the tangent's angle, `curves::UnitProblem::bounded_alpha`).
//! * `slab-out`, `slab-across`: an inner control point of an edge curve, projected onto the
//!   face plane, lies outside the triangle by more than [`SLAB`] of the height beyond its own
//!   edge (the curve bulges out of the face) or beyond another edge's line (across the face).
//! * `corner-cross:<why>`: at a corner the projected edge tangents turn the wrong way
//!   (`(a × b)·N_f ≤ 0`, `a` leaving, `b` arriving reversed), with why: `sharp` (a corner
//!   below twice the needle angle), `normal≥90` (the vertex normal at or past 90° from the
//!   face: tangents perpendicular to it project with their orientation reversed), `steep` (a
//!   steep tangent there) or `other`.
//! * `forced:<why>`: `surface::fallback::forced_fold` — the projected boundary does not turn
//!   once, or stops: no patch on these curves can avoid folding.
//! * `worst@corner`, `worst@edge`, `worst@inside`: where the most folded sample of the fold
//!   measure's grid lies (a data vertex, an exterior edge, elsewhere).
//!
//! The last line counts the clamped tangent ends and the α the monotone-polygon bound shortens
//! on the mesh's edges.

use std::collections::BTreeMap;
use std::error::Error;

use nalgebra::{Point3, Vector3};
use surface::fallback::{fallback_patch, forced_fold, jacobian_coefficients, ForcedFold};
use surface::patch::eval_at;
use surface::{FaceFallbackReason, Fit, Mesh, QuarticNet, SchemeError};

/// Smallest angle of a needle, degrees.
const NEEDLE_DEG: f64 = 5.0;
/// Largest angle of a cap, degrees.
const CAP_DEG: f64 = 170.0;
/// End tangent angle to the chord counted as steep, degrees (the clamp's bound).
const STEEP_DEG: f64 = 60.0;
/// How far outside the triangle, in barycentric coordinates (fractions of the height over the
/// edge crossed), an inner control point's projection must lie to count as leaving it: a
/// quarter keeps the slight outward bulge of every curved surface's edges out of the count.
const SLAB: f64 = 0.25;

type Res<T> = Result<T, Box<dyn Error>>;

/// A face's corners, unit vertex normals and unit normal.
type FaceFrame = ([Point3<f64>; 3], [Vector3<f64>; 3], Vector3<f64>);

fn angle(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b)).to_degrees()
}

fn project(v: &Vector3<f64>, n: &Vector3<f64>) -> Vector3<f64> {
    v - n * v.dot(n)
}

/// [`FaceFrame`] of face `f`.
fn face_frame(mesh: &Mesh, f: usize) -> Res<FaceFrame> {
    let face = mesh.face(f)?;
    let v = face.map(|i| mesh.vertices()[i].data.p);
    let nv = face.map(|i| mesh.vertices()[i].data.n.normalize());
    let nf = mesh
        .face_area_normal(f)?
        .try_normalize(0.0)
        .ok_or_else(|| format!("face {f} has no normal"))?;
    Ok((v, nv, nf))
}

fn quartic(fit: &Fit, patch: usize) -> Res<QuarticNet> {
    fit.quartic_net(patch)
        .ok_or_else(|| format!("patch {patch} is not a quartic").into())
}

fn classify(mesh: &Mesh, fit: &Fit, f: usize, reason: Option<&str>) -> Res<Vec<String>> {
    let mut tags = Vec::new();
    let (v, nv, nf) = face_frame(mesh, f)?;
    let edges = fit.face_curves(mesh, f)?;
    tags.push(reason.map_or("regular".into(), |r| format!("fallback:{r}")));
    let corner_angles: [f64; 3] =
        std::array::from_fn(|i| angle(&(v[(i + 1) % 3] - v[i]), &(v[(i + 2) % 3] - v[i])));
    if corner_angles.iter().copied().fold(f64::INFINITY, f64::min) < NEEDLE_DEG {
        tags.push("needle".into());
    }
    if corner_angles.iter().copied().fold(0.0, f64::max) > CAP_DEG {
        tags.push("cap".into());
    }
    let lean = nv.iter().map(|n| angle(n, &nf)).fold(0.0, f64::max);
    if lean > 60.0 {
        tags.push("lean>60".into());
    }
    if lean > 90.0 {
        tags.push("lean>90".into());
    }
    if reason.is_none() && nv.iter().any(|n| n.dot(&nf) <= 0.0) {
        tags.push("regular-normal≥90".into());
    }
    let area = (v[1] - v[0]).cross(&(v[2] - v[0])).dot(&nf);
    for (e, c) in edges.iter().enumerate() {
        let p = c.points;
        let d = p[3] - p[0];
        if angle(&(p[1] - p[0]), &d) > STEEP_DEG || angle(&(p[3] - p[2]), &d) > STEEP_DEG {
            tags.push("steep".into());
        }
        // B'·d is the quadratic with the Bernstein coefficients l0, l1, l2 (times 3).
        let (l0, l1, l2) = (
            (p[1] - p[0]).dot(&d),
            (p[2] - p[1]).dot(&d),
            (p[3] - p[2]).dot(&d),
        );
        if l0 <= 0.0 || l2 <= 0.0 || l1 <= -(l0 * l2).sqrt() {
            tags.push("backtrack".into());
        }
        for q in [p[1], p[2]] {
            // λ_k: the barycentric coordinate of the projection over the edge opposite k.
            let lam: [f64; 3] = std::array::from_fn(|k| {
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                (b - a).cross(&(q - a)).dot(&nf) / area
            });
            // Edge e runs from corner e to e + 1, opposite corner e + 2.
            let own = (e + 2) % 3;
            if lam[own] < -SLAB {
                tags.push("slab-out".into());
            }
            if (0..3).any(|k| k != own && lam[k] < -SLAB) {
                tags.push("slab-across".into());
            }
        }
    }
    for i in 0..3 {
        let leaving = edges[i].points[1] - edges[i].points[0];
        let arriving = edges[(i + 2) % 3].points[2] - edges[(i + 2) % 3].points[3];
        if project(&leaving, &nf)
            .cross(&project(&arriving, &nf))
            .dot(&nf)
            <= 0.0
        {
            let steep_here = angle(&leaving, &(v[(i + 1) % 3] - v[i])) > STEEP_DEG
                || angle(&arriving, &(v[(i + 2) % 3] - v[i])) > STEEP_DEG;
            tags.push(
                if corner_angles[i] < 2.0 * NEEDLE_DEG {
                    "corner-cross:sharp"
                } else if nv[i].dot(&nf) <= 0.0 {
                    "corner-cross:normal≥90"
                } else if steep_here {
                    "corner-cross:steep"
                } else {
                    "corner-cross:other"
                }
                .into(),
            );
        }
    }
    if let Some(why) = forced_fold(&edges) {
        tags.push(match why {
            ForcedFold::StoppedEdge { .. } => "forced:stopped-edge".into(),
            ForcedFold::Cusp { .. } => "forced:cusp".into(),
            ForcedFold::Turning { turns } => format!("forced:turning={turns}"),
        });
    }
    // Where the most folded sample of the fold measure's grid is.
    let s = surface::folds::FOLD_SEGMENTS;
    let mut worst = (f64::INFINITY, "worst@inside");
    for sub in 0..3 {
        let net = quartic(fit, 3 * f + sub)?;
        for i in 0..=s {
            for j in 0..=s - i {
                let (a, b) = (i as f64 / s as f64, j as f64 / s as f64);
                let d = eval_at(&fit.layout, &net, [a, b, 1.0 - a - b]);
                let Some(n) = d.du.cross(&d.dv).try_normalize(0.0) else {
                    continue;
                };
                let at = if i == s || j == s {
                    "worst@corner"
                } else if i + j == s {
                    "worst@edge"
                } else {
                    "worst@inside"
                };
                if n.dot(&nf) < worst.0 {
                    worst = (n.dot(&nf), at);
                }
            }
        }
    }
    tags.push(worst.1.into());
    tags.sort();
    tags.dedup();
    Ok(tags)
}

/// Prints face `f` in a frame of its plane (`x` along its first edge, heights along its
/// normal, lengths in first-edge lengths): corners, curves, nets, the projected Jacobian's
/// smallest Bernstein coefficient and the patch normals' cosines with the face normal on an
/// 8-segment grid of each sub-patch.
fn dump(mesh: &Mesh, fit: &Fit, f: usize, fallback: bool) -> Res<()> {
    let face = mesh.face(f)?;
    let (v, nv, nf) = face_frame(mesh, f)?;
    let ex = (v[1] - v[0]).normalize();
    let ey = nf.cross(&ex);
    let scale = (v[1] - v[0]).norm();
    let at = |p: &Point3<f64>| {
        let d = p - v[0];
        format!(
            "({:.3}, {:.3}, h {:.3})",
            d.dot(&ex) / scale,
            d.dot(&ey) / scale,
            d.dot(&nf) / scale
        )
    };
    for i in 0..3 {
        println!(
            "  V{i} (vertex {}) {}  n·N {:.3}",
            face[i],
            at(&v[i]),
            nv[i].dot(&nf)
        );
    }
    let edges = fit.face_curves(mesh, f)?;
    for (e, c) in edges.iter().enumerate() {
        let pts: Vec<String> = c.points.iter().map(at).collect();
        println!("  edge {e}: {}", pts.join(" "));
    }
    let replaced = fallback_patch(&edges);
    for (sub, other) in replaced.iter().enumerate() {
        let net = if fallback {
            *other
        } else {
            quartic(fit, 3 * f + sub)?
        };
        println!("  sub-patch {sub}:");
        for rows in [0..5, 5..9, 9..12, 12..14, 14..15] {
            let row: Vec<String> = net[rows].iter().map(at).collect();
            println!("    {}", row.join(" "));
        }
        let lowest = jacobian_coefficients(&net, &nf)
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        println!(
            "    smallest Jacobian coefficient {:.3e}",
            lowest / (scale * scale)
        );
        let s = 8;
        for i in (0..=s).rev() {
            let mut line = String::new();
            for j in 0..=s - i {
                let (a, b) = (i as f64 / s as f64, j as f64 / s as f64);
                let d = eval_at(&fit.layout, &net, [a, b, 1.0 - a - b]);
                let cos =
                    d.du.cross(&d.dv)
                        .try_normalize(0.0)
                        .map_or(f64::NAN, |n| n.dot(&nf));
                line += &format!("{cos:6.2}");
            }
            println!("      {line}");
        }
    }
    Ok(())
}

fn reason_name(reason: FaceFallbackReason) -> &'static str {
    match reason {
        FaceFallbackReason::ZeroArea => "zero-area",
        FaceFallbackReason::Scheme(SchemeError::NoCrossComponent { .. }) => "no-cross",
        FaceFallbackReason::Scheme(SchemeError::NormalAgainstFace { .. }) => "normal-against-face",
        FaceFallbackReason::Scheme(SchemeError::TangentOffPlane { .. }) => "clamped-tangent",
        FaceFallbackReason::Scheme(SchemeError::FoldsOverFace) => "folds-over-face",
        FaceFallbackReason::Scheme(_) => "scheme",
        FaceFallbackReason::NonFinite => "non-finite",
        FaceFallbackReason::Folded { .. } => "folded-corner",
        FaceFallbackReason::FoldedEdge { .. } => "folded-edge",
    }
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        return Err("usage: fold_causes MESH [CURVES]".into());
    };
    let curves = args.get(1).cloned().unwrap_or_else(|| "optimized".into());
    let verbose = std::env::var_os("FOLD_CAUSES_VERBOSE").is_some();
    let dump_face = std::env::var("FOLD_CAUSES_DUMP")
        .ok()
        .and_then(|x| x.parse::<usize>().ok());
    let dump_fallback = std::env::var_os("FOLD_CAUSES_FALLBACK").is_some();
    let outcome = fitjob::run(
        fitjob::FitOptions {
            input: fitjob::InputOptions {
                source: fitjob::Source::Data {
                    data: path.clone(),
                    resolution: None,
                },
                ..fitjob::InputOptions::default()
            },
            curves: curves.clone(),
            keep: true,
            ..fitjob::FitOptions::default()
        },
        &mut |_| {},
    )?;
    let mesh = outcome.kept.mesh.ok_or("no mesh kept")?;
    let fit = outcome.kept.fit.ok_or("no fit kept")?;
    let g1 = outcome.kept.g1.ok_or("no G1 kept")?;
    let folds = surface::folds::measure(&mesh, &fit);
    let reasons: BTreeMap<usize, &str> = fit
        .face_fallbacks
        .iter()
        .map(|fb| (fb.face, reason_name(fb.reason)))
        .collect();
    let mut table: BTreeMap<String, usize> = BTreeMap::new();
    for &f in &folds.folded {
        let tags = classify(&mesh, &fit, f, reasons.get(&f).copied())?;
        if verbose {
            println!("face {f}: {}", tags.join(" "));
        }
        if dump_face == Some(f) {
            dump(&mesh, &fit, f, dump_fallback)?;
        }
        for t in tags {
            *table.entry(t).or_default() += 1;
        }
    }
    println!(
        "{path} ({curves}): {} of {} faces folded, {} fallback faces; G1 between regular faces: exterior {:.3e} rad, interior {:.3e} rad",
        folds.folded.len(),
        folds.faces,
        fit.face_fallbacks.len(),
        g1.exterior_max,
        g1.interior_max
    );
    for (tag, n) in &table {
        println!("  {tag:<28} {n}");
    }
    let method = curves::method_by_name(&curves, &curves::MethodOptions::default())?;
    let verts = mesh.vertices();
    let (mut clamped, mut shortened) = (0, 0);
    for e in mesh.edges() {
        let [a, b] = e.vertices;
        if let Ok(p) = curves::BoundaryProblem::new((a, b), &verts[a].data, &verts[b].data) {
            clamped += p.clamped.iter().filter(|c| **c).count();
            shortened += usize::from(p.unit.bounded_alpha(method.construct(&p.unit).alpha).1);
        }
    }
    println!("  clamped tangent ends {clamped}, α shortened on {shortened} edges");
    Ok(())
}
