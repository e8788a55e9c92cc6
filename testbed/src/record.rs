//! The record schemas of the pipeline and typed access to their fields.
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
//! every other field.

use nalgebra::{Point3, Vector3};
use serde_json::{Map, Number, Value};
use surface::BezierTriangle;

use crate::error::FieldError;

/// Highest patch degree a record may declare: far above any scheme (quartics), low enough
/// that a hostile `degree` cannot make a reader allocate a huge net.
pub const MAX_DEGREE: usize = 32;

/// The names of a triangle's vertex fields.
pub const VERTEX_FIELDS: [&str; 3] = ["vertex1", "vertex2", "vertex3"];

/// A field of an object.
pub fn field<'a>(obj: &'a Map<String, Value>, name: &str) -> Result<&'a Value, FieldError> {
    obj.get(name)
        .ok_or_else(|| FieldError::new(name, "missing"))
}

/// A finite number.
pub fn number(v: &Value, path: &str) -> Result<f64, FieldError> {
    v.as_f64()
        .filter(|x| x.is_finite())
        .ok_or_else(|| FieldError::new(path, format!("expected a number, found {}", brief(v))))
}

/// Three finite numbers.
pub fn vec3(v: &Value, path: &str) -> Result<[f64; 3], FieldError> {
    let a = v
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| FieldError::new(path, format!("expected [x, y, z], found {}", brief(v))))?;
    Ok([
        number(&a[0], &format!("{path}[0]"))?,
        number(&a[1], &format!("{path}[1]"))?,
        number(&a[2], &format!("{path}[2]"))?,
    ])
}

/// A short description of a value for messages (at most ~40 characters).
fn brief(v: &Value) -> String {
    let s = v.to_string();
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

/// A colour component rounded to 1e-4 (far below an 8-bit step, 1/255): short to write.
pub fn color_value(c: [f32; 3]) -> Value {
    Value::Array(
        c.iter()
            .map(|&x| num((f64::from(x) * 1e4).round() / 1e4))
            .collect(),
    )
}

/// The patch of a `BezierTriangle` record.
pub fn bezier_triangle(obj: &Map<String, Value>) -> Result<BezierTriangle, FieldError> {
    let degree = field(obj, "degree")?
        .as_u64()
        .filter(|&d| d >= 1 && d as usize <= MAX_DEGREE)
        .ok_or_else(|| {
            FieldError::new(
                "degree",
                format!("expected an integer from 1 to {MAX_DEGREE}"),
            )
        })? as usize;
    let pts = field(obj, "points")?
        .as_array()
        .ok_or_else(|| FieldError::new("points", "expected an array of [x, y, z]"))?;
    let want = (degree + 1) * (degree + 2) / 2;
    if pts.len() != want {
        return Err(FieldError::new(
            "points",
            format!(
                "degree {degree} needs {want} control points, found {}",
                pts.len()
            ),
        ));
    }
    let points = pts
        .iter()
        .enumerate()
        .map(|(i, p)| vec3(p, &format!("points[{i}]")).map(Point3::from))
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
pub fn vertex(obj: &Map<String, Value>, name: &str) -> Result<Vertex, FieldError> {
    let v = field(obj, name)?
        .as_object()
        .ok_or_else(|| FieldError::new(name, "expected a list of (name . value) pairs"))?;
    let pos = Point3::from(vec3(
        v.get("pos")
            .ok_or_else(|| FieldError::new(format!("{name}.pos"), "missing"))?,
        &format!("{name}.pos"),
    )?);
    let norm = v
        .get("norm")
        .map(|n| vec3(n, &format!("{name}.norm")).map(Vector3::from))
        .transpose()?;
    let kg = v
        .get("kg")
        .map(|x| number(x, &format!("{name}.kg")))
        .transpose()?;
    let km = v
        .get("km")
        .map(|x| number(x, &format!("{name}.km")))
        .transpose()?;
    let color = v
        .get("color")
        .map(|c| vec3(c, &format!("{name}.color")).map(|c| c.map(|x| x as f32)))
        .transpose()?;
    Ok(Vertex {
        pos,
        norm,
        kg,
        km,
        color,
    })
}

/// The three vertices of a Triangle record.
pub fn triangle(obj: &Map<String, Value>) -> Result<[Vertex; 3], FieldError> {
    Ok([
        vertex(obj, VERTEX_FIELDS[0])?,
        vertex(obj, VERTEX_FIELDS[1])?,
        vertex(obj, VERTEX_FIELDS[2])?,
    ])
}

/// Sets `name` in `obj`: in place if present (keeping the field order), appended otherwise.
pub fn set(obj: &mut Map<String, Value>, name: &str, value: Value) {
    match obj.get_mut(name) {
        Some(slot) => *slot = value,
        None => {
            obj.insert(name.to_string(), value);
        }
    }
}

/// Sets `field` of every vertex object of a Triangle record to `values[i]`.
pub fn set_vertex_field(
    obj: &mut Map<String, Value>,
    field_name: &str,
    values: [Value; 3],
) -> Result<(), FieldError> {
    for (name, value) in VERTEX_FIELDS.iter().zip(values) {
        let v = obj
            .get_mut(*name)
            .and_then(Value::as_object_mut)
            .ok_or_else(|| FieldError::new(*name, "expected a list of (name . value) pairs"))?;
        set(v, field_name, value);
    }
    Ok(())
}
