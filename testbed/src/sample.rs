//! Tessellated vertices (*samples*) and the `Triangle` records built from them: the vertex
//! objects and records of `fit`'s sampled output, the patch fields a patch's triangles carry
//! (every field but [`TESS_CONSUMES`]), and the tapes `tess` writes its triangles with.

use nalgebra::{Point3, Vector3};
use serde_json::{Map, Value};

use crate::record::{self, VERTEX_FIELDS};
use crate::tape::{Span, Tape, Tok};

/// Which curvatures a tessellation writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CurvatureFields {
    /// Gaussian curvature `kg`.
    pub kg: bool,
    /// Mean curvature `km`.
    pub km: bool,
    /// Principal curvatures `k1 ≥ k2` and their unit directions `d1`, `d2` (`tess --kp`).
    pub kp: bool,
}

/// The principal curvatures and directions at one sample, in the pipeline's sign (that of
/// `km`: `k1 + k2 = 2 km`, the unit sphere with outward normals has `k1 = k2 = −1`), `k1 ≥ k2`,
/// `d2 = n × d1`. From the patch's exact shape tensor: `estimate::principal_frame` gives them
/// in the exported sign (`κ′1 ≥ κ′2`, directions `d′1`, `d′2`), whose negation reverses the
/// order: `k1 = −κ′2` along `d′2`, `k2 = −κ′1` along `d′1`, and `n × d′2 = −d′1` keeps the
/// frame right-handed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Principal {
    /// `[k1, k2]`, `k1 ≥ k2`.
    pub k: [f64; 2],
    /// `[d1, d2]`, unit.
    pub d: [Vector3<f64>; 2],
}

impl Principal {
    /// The principal frame of shape tensor `s` at normal `n` (the pipeline's sign).
    pub fn of(s: &nalgebra::Matrix3<f64>, n: &Vector3<f64>) -> Self {
        let p = estimate::principal_frame(s, n);
        Principal {
            k: [-p.k2, -p.k1],
            d: [p.d2, -p.d1],
        }
    }
}

/// One tessellated vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Position.
    pub pos: Point3<f64>,
    /// Unit normal.
    pub norm: Vector3<f64>,
    /// Gaussian curvature.
    pub kg: f64,
    /// Mean curvature.
    pub km: f64,
}

/// The vertex object of a sample (fit's slow path).
pub fn sample_value(s: &Sample, fields: CurvatureFields) -> Value {
    let mut v = Map::with_capacity(4);
    v.insert("pos".into(), record::arr3([s.pos.x, s.pos.y, s.pos.z]));
    v.insert("norm".into(), record::arr3([s.norm.x, s.norm.y, s.norm.z]));
    if fields.kg {
        v.insert("kg".into(), record::num(s.kg));
    }
    if fields.km {
        v.insert("km".into(), record::num(s.km));
    }
    Value::Object(v)
}

/// A Triangle record: the three vertices, then `carried` fields in order (fit's slow path).
pub fn triangle_value<'v>(
    tri: &[Sample; 3],
    fields: CurvatureFields,
    carried: impl Iterator<Item = (&'v String, &'v Value)>,
) -> Value {
    let mut m = Map::new();
    m.insert("type".into(), Value::from("Triangle"));
    for (name, s) in VERTEX_FIELDS.iter().zip(tri) {
        m.insert((*name).into(), sample_value(s, fields));
    }
    for (k, v) in carried {
        m.insert(k.clone(), v.clone());
    }
    Value::Object(m)
}

/// Fields of a patch record that tess consumes (the rest are carried to its triangles).
pub const TESS_CONSUMES: [&str; 3] = ["type", "degree", "points"];

/// The token ranges (key and value) of the fields of a patch record that tess carries to its
/// triangles: every field but [`TESS_CONSUMES`], in order. `out` is cleared first.
pub fn carried_fields(patch: &Tape, out: &mut Vec<std::ops::Range<usize>>) {
    out.clear();
    for (key, v) in patch.fields(0) {
        if !TESS_CONSUMES.iter().any(|c| c.as_bytes() == key) {
            let w = patch.toks.get(v).map_or(1, Tok::width);
            out.push(v - 1..v + w);
        }
    }
}

/// Builds Triangle tapes over one patch record's text (so carried fields are copied as
/// tokens, their strings not at all): `tess`'s records.
pub(crate) struct TriangleTapes {
    tape: Tape,
    /// Spans of `type`, `Triangle`, `vertex1..3`, `pos`, `norm`, `kg`, `km`, `k1`, `k2`, `d1`,
    /// `d2`.
    names: [Span; 13],
    /// Token ranges (key and value) of the carried fields.
    carried: Vec<std::ops::Range<usize>>,
}

impl TriangleTapes {
    /// An empty builder.
    pub(crate) fn new() -> Self {
        TriangleTapes {
            tape: Tape::default(),
            names: [Span { start: 0, len: 0 }; 13],
            carried: Vec::new(),
        }
    }

    /// Starts the triangles of `patch`.
    pub(crate) fn start(&mut self, patch: &Tape) {
        self.tape.clear();
        self.tape.text.extend_from_slice(&patch.text);
        for (k, n) in [
            "type", "Triangle", "vertex1", "vertex2", "vertex3", "pos", "norm", "kg", "km", "k1",
            "k2", "d1", "d2",
        ]
        .iter()
        .enumerate()
        {
            self.names[k] = self.tape.push_text(n.as_bytes());
        }
        carried_fields(patch, &mut self.carried);
    }

    /// The tape of one triangle (`principal`: its vertices' frames, written when `fields.kp`).
    pub(crate) fn build(
        &mut self,
        patch: &Tape,
        tri: &[Sample; 3],
        principal: Option<[Principal; 3]>,
        fields: CurvatureFields,
    ) -> &Tape {
        let n = self.names;
        let toks = &mut self.tape.toks;
        toks.clear();
        toks.push(Tok::Obj { fields: 0, len: 0 });
        toks.push(Tok::Key(n[0]));
        toks.push(Tok::Str(n[1]));
        for (vi, smp) in tri.iter().enumerate() {
            toks.push(Tok::Key(n[2 + vi]));
            let obj = toks.len();
            toks.push(Tok::Obj { fields: 0, len: 0 });
            toks.push(Tok::Key(n[5]));
            toks.push(Tok::Arr { items: 3, len: 3 });
            toks.extend(smp.pos.iter().map(|&x| Tok::Float(x)));
            toks.push(Tok::Key(n[6]));
            toks.push(Tok::Arr { items: 3, len: 3 });
            toks.extend(smp.norm.iter().map(|&x| Tok::Float(x)));
            let mut count = 2;
            if fields.kg {
                toks.push(Tok::Key(n[7]));
                toks.push(Tok::Float(smp.kg));
                count += 1;
            }
            if fields.km {
                toks.push(Tok::Key(n[8]));
                toks.push(Tok::Float(smp.km));
                count += 1;
            }
            if let (true, Some(p)) = (fields.kp, principal) {
                let p = p[vi];
                toks.push(Tok::Key(n[9]));
                toks.push(Tok::Float(p.k[0]));
                toks.push(Tok::Key(n[10]));
                toks.push(Tok::Float(p.k[1]));
                for (key, d) in [(n[11], p.d[0]), (n[12], p.d[1])] {
                    toks.push(Tok::Key(key));
                    toks.push(Tok::Arr { items: 3, len: 3 });
                    toks.extend(d.iter().map(|&x| Tok::Float(x)));
                }
                count += 4;
            }
            toks[obj] = Tok::Obj {
                fields: count,
                len: (toks.len() - obj - 1) as u32,
            };
        }
        for r in &self.carried {
            toks.extend_from_slice(&patch.toks[r.clone()]);
        }
        toks[0] = Tok::Obj {
            fields: 4 + self.carried.len() as u32,
            len: (toks.len() - 1) as u32,
        };
        &self.tape
    }
}
