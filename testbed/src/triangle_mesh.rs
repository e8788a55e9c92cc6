//! The shared-vertex record `TriangleMesh`: one patch's tessellation (or any block of
//! triangles) as columns of vertex data and a list of triangles indexing them.
//!
//! ```text
//! {"type": "TriangleMesh", "pos": [[x, y, z], …], "norm": [[x, y, z], …]?, "kg": [K, …]?,
//!  "km": [H, …]?, "color": [[r, g, b], …]?, "dist": [d, …]?, "triangles": [[a, b, c], …], …}
//! ```
//!
//! Each column holds one entry per vertex, in the order of `pos`, with the meaning of the
//! `Triangle` vertex field of the same name (`crate::record`); only `pos` and `triangles`
//! are required, and a column that is present has exactly as many entries as `pos`.
//! `triangles` lists each triangle's three vertices as 0-based indices into the columns,
//! counter-clockwise seen from the side the normals point to. At `tess -s 8` a quartic patch
//! is 45 vertices and 64 triangles: one record instead of 64 `Triangle`s, each vertex written,
//! read and converted once instead of about four times.
//!
//! Filters treat a `TriangleMesh` as the triangles it lists: the colour filters set the
//! `color` (and `dist`) column in place or append it after the last field; every other field
//! (known or not, including columns no filter knows) passes through in order. Readers check
//! the lengths of the columns and the range of every index, and name the field at fault.

use std::ops::Range;

use nalgebra::{Point3, Vector3};

use crate::error::FieldError;
use crate::record::{self, Vertex};
use crate::sample::CurvatureFields;
use crate::tape::{Span, Tape, Tok};
use crate::tessellator::IndexedPatch;

/// The record's `type`.
pub const KIND: &str = "TriangleMesh";

/// The field of the triangles' vertex indices.
pub const TRIANGLES: &str = "triangles";

/// A `TriangleMesh` record read into typed columns (absent columns are empty). Reading into
/// the same value again reuses its storage.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Positions, one per vertex.
    pub pos: Vec<Point3<f64>>,
    /// Unit normals (empty: not given).
    pub norm: Vec<Vector3<f64>>,
    /// Gaussian curvature (empty: not given).
    pub kg: Vec<f64>,
    /// Mean curvature (empty: not given).
    pub km: Vec<f64>,
    /// Linear RGB colours (empty: not given).
    pub color: Vec<[f32; 3]>,
    /// Triangles: indices into the columns, each checked to be in range.
    pub triangles: Vec<[u32; 3]>,
}

/// Calls `each` with the three numbers of every item of the array at `at` (field `name`).
fn column3(
    t: &Tape,
    at: usize,
    name: &str,
    mut each: impl FnMut([f64; 3]),
) -> Result<usize, FieldError> {
    let items = t
        .items(at)
        .ok_or_else(|| FieldError::new(name, "expected an array of [x, y, z]"))?;
    let n = items.len();
    for (k, i) in items.enumerate() {
        // The common case read directly; anything else through the checked reader, which
        // names what is wrong.
        let fast = match t.toks.get(i..i + 4) {
            Some([Tok::Arr { items: 3, len: 3 }, a, b, c]) => match (num(a), num(b), num(c)) {
                (Some(a), Some(b), Some(c)) => Some([a, b, c]),
                _ => None,
            },
            _ => None,
        };
        let v = match fast {
            Some(v) => v,
            None => record::vec3(t, i, &|| format!("{name}[{k}]"))?,
        };
        each(v);
    }
    Ok(n)
}

/// A finite number token's value.
fn num(t: &Tok) -> Option<f64> {
    let x = match *t {
        Tok::Float(x) | Tok::Text(x, _) => x,
        Tok::Int(x) => x as f64,
        Tok::UInt(x) => x as f64,
        _ => return None,
    };
    x.is_finite().then_some(x)
}

/// Calls `each` with every number of the array at `at` (field `name`).
fn column1(
    t: &Tape,
    at: usize,
    name: &str,
    mut each: impl FnMut(f64),
) -> Result<usize, FieldError> {
    let items = t
        .items(at)
        .ok_or_else(|| FieldError::new(name, "expected an array of numbers"))?;
    let n = items.len();
    for (k, i) in items.enumerate() {
        let x = match t.toks.get(i).and_then(num) {
            Some(x) => x,
            None => record::number(t, i, &|| format!("{name}[{k}]"))?,
        };
        each(x);
    }
    Ok(n)
}

impl TriangleMesh {
    /// Reads a `TriangleMesh` record's columns and triangles (every other field is left to
    /// pass through). Errors name the field: a column that is not an array of the right
    /// items, a column whose length is not `pos`'s, an index out of range.
    pub fn read(&mut self, t: &Tape) -> Result<(), FieldError> {
        self.pos.clear();
        self.norm.clear();
        self.kg.clear();
        self.km.clear();
        self.color.clear();
        self.triangles.clear();
        let mut lengths: [Option<usize>; 5] = [None; 5];
        let mut tris = None;
        for (key, at) in t.fields(0) {
            match key {
                b"pos" => {
                    lengths[0] = Some(column3(t, at, "pos", |v| self.pos.push(Point3::from(v)))?)
                }
                b"norm" => {
                    lengths[1] = Some(column3(t, at, "norm", |v| {
                        self.norm.push(Vector3::from(v))
                    })?)
                }
                b"kg" => lengths[2] = Some(column1(t, at, "kg", |x| self.kg.push(x))?),
                b"km" => lengths[3] = Some(column1(t, at, "km", |x| self.km.push(x))?),
                b"color" => {
                    lengths[4] = Some(column3(t, at, "color", |c| {
                        self.color.push(c.map(|x| x as f32))
                    })?)
                }
                b"triangles" => tris = Some(at),
                _ => {}
            }
        }
        let n = lengths[0].ok_or_else(|| FieldError::new("pos", "missing"))?;
        for (name, len) in ["norm", "kg", "km", "color"].iter().zip(&lengths[1..]) {
            if let Some(len) = *len {
                if len != n {
                    return Err(FieldError::new(
                        *name,
                        format!("{len} entries for {n} vertices (one per entry of `pos`)"),
                    ));
                }
            }
        }
        let at = tris.ok_or_else(|| FieldError::new(TRIANGLES, "missing"))?;
        let items = t.items(at).ok_or_else(|| {
            FieldError::new(TRIANGLES, "expected an array of [a, b, c] vertex indices")
        })?;
        for (k, i) in items.enumerate() {
            let corners = match t.toks.get(i..i + 4) {
                Some([Tok::Arr { items: 3, len: 3 }, a, b, c]) => [*a, *b, *c],
                _ => {
                    return Err(FieldError::new(
                        format!("{TRIANGLES}[{k}]"),
                        "expected [a, b, c] vertex indices",
                    ))
                }
            };
            let mut tri = [0u32; 3];
            for (c, (slot, tok)) in tri.iter_mut().zip(corners).enumerate() {
                *slot = match tok {
                    Tok::Int(x) if (0..n as i64).contains(&x) => x as u32,
                    Tok::Int(_) | Tok::UInt(_) => {
                        return Err(FieldError::new(
                            format!("{TRIANGLES}[{k}][{c}]"),
                            format!("index {} out of range ({n} vertices)", t.value(i + 1 + c)),
                        ))
                    }
                    _ => {
                        return Err(FieldError::new(
                            format!("{TRIANGLES}[{k}][{c}]"),
                            "expected a vertex index (an integer from 0)",
                        ))
                    }
                };
            }
            self.triangles.push(tri);
        }
        Ok(())
    }

    /// Vertex `i` (in range: the columns were checked) with the columns present.
    pub fn vertex(&self, i: usize) -> Vertex {
        Vertex {
            pos: self.pos[i],
            norm: self.norm.get(i).copied(),
            kg: self.kg.get(i).copied(),
            km: self.km.get(i).copied(),
            color: self.color.get(i).copied(),
        }
    }

    /// The vertices of triangle `k`.
    pub fn triangle(&self, k: usize) -> [Vertex; 3] {
        self.triangles[k].map(|i| self.vertex(i as usize))
    }
}

/// Builds `TriangleMesh` tapes over one patch record's text, so the fields it carries are
/// copied as tokens (their strings not at all): `tess --mesh`.
#[derive(Debug)]
pub struct MeshTapes {
    tape: Tape,
    /// Spans of `type`, `TriangleMesh`, `pos`, `norm`, `kg`, `km`, `triangles`, `k1`, `k2`,
    /// `d1`, `d2`.
    names: [Span; 11],
}

impl Default for MeshTapes {
    fn default() -> Self {
        MeshTapes {
            tape: Tape::default(),
            names: [Span { start: 0, len: 0 }; 11],
        }
    }
}

impl MeshTapes {
    /// The record of `mesh`: the vertex columns (`kg`, `km`, `k1 k2 d1 d2` as `fields` asks), the
    /// triangles, then the token ranges `carried` of `patch` (key and value each) in order.
    pub fn build(
        &mut self,
        patch: &Tape,
        mesh: &IndexedPatch,
        fields: CurvatureFields,
        carried: &[Range<usize>],
    ) -> &Tape {
        self.tape.clear();
        self.tape.text.extend_from_slice(&patch.text);
        for (k, n) in [
            "type", KIND, "pos", "norm", "kg", "km", TRIANGLES, "k1", "k2", "d1", "d2",
        ]
        .iter()
        .enumerate()
        {
            self.names[k] = self.tape.push_text(n.as_bytes());
        }
        let n = self.names;
        let toks = &mut self.tape.toks;
        let v = mesh.samples.len() as u32;
        let column3 = |toks: &mut Vec<Tok>, key: Span, xs: &mut dyn Iterator<Item = [f64; 3]>| {
            toks.push(Tok::Key(key));
            toks.push(Tok::Arr {
                items: v,
                len: 4 * v,
            });
            for x in xs {
                toks.push(Tok::Arr { items: 3, len: 3 });
                toks.extend(x.map(Tok::Float));
            }
        };
        let column1 = |toks: &mut Vec<Tok>, key: Span, xs: &mut dyn Iterator<Item = f64>| {
            toks.push(Tok::Key(key));
            toks.push(Tok::Arr { items: v, len: v });
            toks.extend(xs.map(Tok::Float));
        };
        toks.push(Tok::Obj { fields: 0, len: 0 });
        toks.push(Tok::Key(n[0]));
        toks.push(Tok::Str(n[1]));
        let smp = &mesh.samples;
        column3(toks, n[2], &mut smp.iter().map(|s| s.pos.coords.into()));
        column3(toks, n[3], &mut smp.iter().map(|s| s.norm.into()));
        let mut count = 4;
        if fields.kg {
            column1(toks, n[4], &mut smp.iter().map(|s| s.kg));
            count += 1;
        }
        if fields.km {
            column1(toks, n[5], &mut smp.iter().map(|s| s.km));
            count += 1;
        }
        if fields.kp && mesh.principal.len() == smp.len() {
            let p = &mesh.principal;
            column1(toks, n[7], &mut p.iter().map(|p| p.k[0]));
            column1(toks, n[8], &mut p.iter().map(|p| p.k[1]));
            column3(toks, n[9], &mut p.iter().map(|p| p.d[0].into()));
            column3(toks, n[10], &mut p.iter().map(|p| p.d[1].into()));
            count += 4;
        }
        let m = mesh.triangles.len() as u32;
        toks.push(Tok::Key(n[6]));
        toks.push(Tok::Arr {
            items: m,
            len: 4 * m,
        });
        for t in &mesh.triangles {
            toks.push(Tok::Arr { items: 3, len: 3 });
            toks.extend(t.map(|i| Tok::Int(i64::from(i))));
        }
        for r in carried {
            toks.extend_from_slice(&patch.toks[r.clone()]);
        }
        toks[0] = Tok::Obj {
            fields: count + carried.len() as u32,
            len: (toks.len() - 1) as u32,
        };
        &self.tape
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn tape(v: serde_json::Value) -> Tape {
        Tape::from_value(&v)
    }

    #[test]
    fn columns_and_triangles_are_read_and_checked() {
        let good = json!({"type": KIND, "pos": [[0, 0, 0], [1.5, 0, 0], [0, 1, 0]],
            "kg": [0.5, -0.25, 0], "uv": [[0, 0], [1, 0], [0, 1]],
            "triangles": [[0, 1, 2], [2, 1, 0]], "face": 3});
        let mut m = TriangleMesh::default();
        m.read(&tape(good.clone())).expect("reads");
        assert_eq!(m.pos[1], Point3::new(1.5, 0.0, 0.0));
        assert_eq!(m.kg, [0.5, -0.25, 0.0]);
        assert!(m.norm.is_empty() && m.color.is_empty());
        assert_eq!(m.triangles, [[0, 1, 2], [2, 1, 0]]);
        assert_eq!(m.triangle(1)[0].kg, Some(0.0));
        assert_eq!(m.triangle(1)[2].pos, Point3::origin());
        let cases = [
            ("pos", json!(null), "pos", "missing"),
            ("kg", json!([0.5, 1]), "kg", "2 entries for 3 vertices"),
            (
                "norm",
                json!([[0, 0, 1]]),
                "norm",
                "1 entries for 3 vertices",
            ),
            (
                "pos",
                json!([[0, 0, 0], [1, 0]]),
                "pos[1]",
                "expected [x, y, z]",
            ),
            (
                "triangles",
                json!([[0, 1, 3]]),
                "triangles[0][2]",
                "index 3 out of range (3 vertices)",
            ),
            (
                "triangles",
                json!([[0, -1, 2]]),
                "triangles[0][1]",
                "index -1 out of range",
            ),
            (
                "triangles",
                json!([[0, 1.5, 2]]),
                "triangles[0][1]",
                "expected a vertex index",
            ),
            (
                "triangles",
                json!([[0, 1]]),
                "triangles[0]",
                "expected [a, b, c]",
            ),
            ("triangles", json!(null), "triangles", "missing"),
            ("kg", json!([0, "x", 1]), "kg[1]", "expected a number"),
        ];
        for (field, value, path, message) in cases {
            let mut bad = good.clone();
            if value.is_null() {
                bad.as_object_mut().expect("object").remove(field);
            } else {
                bad[field] = value;
            }
            let e = m.read(&tape(bad)).expect_err(path);
            assert_eq!(e.field, path);
            assert!(e.message.contains(message), "{path}: {}", e.message);
        }
    }

    #[test]
    fn built_records_read_back_exactly() {
        let patch = tape(json!({"type": "BezierTriangle", "degree": 1, "face": 7, "note": "n"}));
        let sample = |x: f64| crate::sample::Sample {
            pos: Point3::new(x, 2.0 * x, 0.1),
            norm: Vector3::new(0.0, 0.6, 0.8),
            kg: x - 1.0,
            km: -x,
        };
        let mesh = IndexedPatch {
            samples: vec![sample(0.0), sample(1.0), sample(0.5)],
            triangles: vec![[0, 1, 2]],
            principal: Vec::new(),
        };
        let mut carried = Vec::new();
        crate::sample::carried_fields(&patch, &mut carried);
        // `face` and `note`: key and value tokens 5..7 and 7..9 of the patch.
        assert_eq!(carried, [5..7, 7..9]);
        let mut b = MeshTapes::default();
        let fields = CurvatureFields {
            kg: true,
            km: false,
            kp: false,
        };
        let t = b.build(&patch, &mesh, fields, &carried).clone();
        let v = t.to_value();
        let keys: Vec<&String> = v.as_object().expect("object").keys().collect();
        assert_eq!(
            keys,
            ["type", "pos", "norm", "kg", TRIANGLES, "face", "note"]
        );
        assert_eq!(v["type"], KIND);
        assert_eq!(v["note"], "n");
        let mut m = TriangleMesh::default();
        m.read(&t).expect("reads");
        assert_eq!(
            m.pos,
            mesh.samples.iter().map(|s| s.pos).collect::<Vec<_>>()
        );
        assert_eq!(m.kg, [-1.0, 0.0, -0.5]);
        assert!(m.km.is_empty());
        assert_eq!(m.triangles, mesh.triangles);
        // The tape's lengths are consistent: it survives a round trip through values.
        assert_eq!(Tape::from_value(&v).to_value(), v);
    }
}
