//! The record schemas of the pipeline and typed access to their fields: each hot record kind
//! is read from its [`Tape`] straight into a typed struct ([`Vertex`], `BezierTriangle`).
//!
//! ```text
//! {"type": "BezierTriangle", "degree": n, "points": [[x, y, z], …], "face": f,
//!  "subpatch": s, "scheme": "name", …}
//! {"type": "Triangle", "vertex1": V, "vertex2": V, "vertex3": V, …}
//!     V = {"pos": [x, y, z], "norm": [x, y, z], "kg": K?, "km": H?, "color": [r, g, b]?, …}
//! ```
//!
//! `points` lists the `(n+1)(n+2)/2` control points in the net order of
//! `docs/conventions.md` (rows `k = 0 … n`, within a row `i` from `n − k` down). `kg` is the
//! Gaussian and `km` the mean curvature (signs of `docs/conventions.md`: the unit sphere with
//! outward normals has `kg = 1`, `km = −1`). `color` is linear RGB in `[0, 1]`. Triangles
//! are counter-clockwise seen from the side the normals point to. Readers ignore and keep
//! every other field. The shared-vertex `TriangleMesh` (a patch's vertices once, its triangles
//! as indices) has its own module, [`crate::triangle_mesh`].

use nalgebra::{Point3, Vector3};
use serde_json::{Number, Value};
use surface::BezierTriangle;

use crate::error::FieldError;
use crate::tape::{Tape, Tok};

/// Highest patch degree a record may declare: far above any scheme (quartics), low enough
/// that a hostile `degree` cannot make a reader allocate a huge net.
pub const MAX_DEGREE: usize = 32;

/// The names of a triangle's vertex fields.
pub const VERTEX_FIELDS: [&str; 3] = ["vertex1", "vertex2", "vertex3"];

/// The patch edges a `BezierTriangle` record marks as lying on a crease of the fitted mesh
/// (`"creases": [e, …]`, each 0, 1 or 2 as `surface::patch_g1::PatchEdge`; written by `fit`
/// where the mesh has creases): as three flags, all false when the field is absent.
pub fn patch_creases(t: &Tape) -> Result<[bool; 3], FieldError> {
    let mut out = [false; 3];
    let Some(at) = t.get(0, "creases") else {
        return Ok(out);
    };
    let items = t
        .items(at)
        .ok_or_else(|| FieldError::new("creases", "expected an array of patch edges 0, 1, 2"))?;
    for (i, it) in items.enumerate() {
        match t.toks.get(it) {
            Some(Tok::Int(e)) if (0..3).contains(e) => out[*e as usize] = true,
            _ => {
                return Err(FieldError::new(
                    "creases",
                    format!("creases[{i}]: expected a patch edge 0, 1 or 2"),
                ))
            }
        }
    }
    Ok(out)
}

/// A field of the record (the top-level object).
pub fn field(t: &Tape, name: &str) -> Result<usize, FieldError> {
    t.get(0, name)
        .ok_or_else(|| FieldError::new(name, "missing"))
}

/// A finite number at token `at`; `path` names it in the error.
pub fn number(t: &Tape, at: usize, path: &dyn Fn() -> String) -> Result<f64, FieldError> {
    t.number(at).filter(|x| x.is_finite()).ok_or_else(|| {
        FieldError::new(path(), format!("expected a number, found {}", brief(t, at)))
    })
}

/// Three finite numbers at token `at`.
pub fn vec3(t: &Tape, at: usize, path: &dyn Fn() -> String) -> Result<[f64; 3], FieldError> {
    let bad = || {
        FieldError::new(
            path(),
            format!("expected [x, y, z], found {}", brief(t, at)),
        )
    };
    let mut items = t.items(at).ok_or_else(bad)?;
    if items.len() != 3 {
        return Err(bad());
    }
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let i = items.next().ok_or_else(bad)?;
        *o = number(t, i, &|| format!("{}[{k}]", path()))?;
    }
    Ok(out)
}

/// A short description of a value for messages (at most ~40 characters).
fn brief(t: &Tape, at: usize) -> String {
    let s = t.value(at).to_string();
    if s.len() > 40 {
        let cut = (0..=37).rev().find(|&i| s.is_char_boundary(i)).unwrap_or(0);
        format!("{}…", &s[..cut])
    } else {
        s
    }
}

/// A JSON number from an `f64` (`null` for a non-finite value, which no writer should
/// produce).
pub fn num(x: f64) -> Value {
    Number::from_f64(x).map_or(Value::Null, Value::Number)
}

/// `[x, y, z]` as a JSON array.
pub fn arr3(a: [f64; 3]) -> Value {
    Value::Array(a.iter().map(|&x| num(x)).collect())
}

/// The patch of a `BezierTriangle` record.
pub fn bezier_triangle(t: &Tape) -> Result<BezierTriangle, FieldError> {
    let d = field(t, "degree")?;
    let degree = match t.toks.get(d) {
        Some(Tok::Int(x)) if *x >= 1 && *x as usize <= MAX_DEGREE => *x as usize,
        _ => {
            return Err(FieldError::new(
                "degree",
                format!("expected an integer from 1 to {MAX_DEGREE}"),
            ))
        }
    };
    let p = field(t, "points")?;
    let items = t
        .items(p)
        .ok_or_else(|| FieldError::new("points", "expected an array of [x, y, z]"))?;
    let want = (degree + 1) * (degree + 2) / 2;
    if items.len() != want {
        return Err(FieldError::new(
            "points",
            format!(
                "degree {degree} needs {want} control points, found {}",
                items.len()
            ),
        ));
    }
    let points = items
        .enumerate()
        .map(|(i, at)| vec3(t, at, &|| format!("points[{i}]")).map(Point3::from))
        .collect::<Result<Vec<_>, _>>()?;
    BezierTriangle::new(degree, points).map_err(|e| FieldError::new("points", e.to_string()))
}

/// A triangle vertex as the pipeline's filters use it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    /// Position.
    pub pos: Point3<f64>,
    /// Unit normal, when given.
    pub norm: Option<Vector3<f64>>,
    /// Gaussian curvature, when given.
    pub kg: Option<f64>,
    /// Mean curvature, when given.
    pub km: Option<f64>,
    /// Linear RGB colour, when given.
    pub color: Option<[f32; 3]>,
}

/// The vertex object `name` of a Triangle record (only `pos` is required).
pub fn vertex(t: &Tape, name: &str) -> Result<Vertex, FieldError> {
    let at = field(t, name)?;
    if !matches!(t.toks.get(at), Some(Tok::Obj { .. })) {
        return Err(FieldError::new(
            name,
            "expected a list of (name . value) pairs",
        ));
    }
    let mut v = Vertex {
        pos: Point3::origin(),
        norm: None,
        kg: None,
        km: None,
        color: None,
    };
    let mut pos = false;
    for (key, i) in t.fields(at) {
        match key {
            b"pos" => {
                v.pos = Point3::from(vec3(t, i, &|| format!("{name}.pos"))?);
                pos = true;
            }
            b"norm" => v.norm = Some(Vector3::from(vec3(t, i, &|| format!("{name}.norm"))?)),
            b"kg" => v.kg = Some(number(t, i, &|| format!("{name}.kg"))?),
            b"km" => v.km = Some(number(t, i, &|| format!("{name}.km"))?),
            b"color" => v.color = Some(vec3(t, i, &|| format!("{name}.color"))?.map(|c| c as f32)),
            _ => {}
        }
    }
    if !pos {
        return Err(FieldError::new(format!("{name}.pos"), "missing"));
    }
    Ok(v)
}

/// The three vertices of a Triangle record.
pub fn triangle(t: &Tape) -> Result<[Vertex; 3], FieldError> {
    Ok([
        vertex(t, VERTEX_FIELDS[0])?,
        vertex(t, VERTEX_FIELDS[1])?,
        vertex(t, VERTEX_FIELDS[2])?,
    ])
}

/// A colour component rounded to 1e-4 (far below an 8-bit step, 1/255): short to write.
pub fn color_component(x: f32) -> f64 {
    (f64::from(x) * 1e4).round() / 1e4
}
