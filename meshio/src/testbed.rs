//! The testbed's mesh format (`.m`): the "semi-dstruct" input of Lounsbery et al. (1990).
//!
//! ```text
//! % The mesh description for an octahedron.
//! px = (Point . (pos . [1,0,0]) (norm . [1,0,0]));
//! ...
//! PPP = [px,py,pz];
//! ...
//! mesh = {PPP,PMP,MPP,MMP,PPM,PMM,MPM,MMM};
//! ```
//!
//! # Reading
//!
//! Whitespace (line breaks included) is free between tokens; `%` starts a comment running to
//! the end of the line. Statements end with `;`:
//!
//! * **point** `NAME = (Point . FIELD*);` with `FIELD = (KEY . VALUE)`, `VALUE` a number or a
//!   (possibly nested, at most [`MAX_NESTING_DEPTH`] deep) array of numbers, flattened.
//!   `pos` (3 numbers, required) → positions; `norm` (3 numbers) → normals, normalized (a zero
//!   normal is an error); `shape` (9 numbers, row by row, the shape tensor `S` with
//!   `κn(d) = dᵀ S d`) → shapes, checked symmetric within [`SHAPE_SYMMETRY_TOLERANCE`] and then
//!   symmetrized. `norm` and `shape` must be given for every point or for none. Any other
//!   field → [`RawMesh::properties`]: a field of one number keeps its key, a field of `k > 1`
//!   numbers becomes the properties `KEY[0]` … `KEY[k-1]`; every point must have the field with
//!   the same number of values. The point's name → [`RawMesh::vertex_names`].
//! * **face** `NAME = [V1, V2, …];` naming 3 or more points (kept as a polygon).
//! * **mesh** `mesh = {F1, F2, …};` exactly once: the faces of the mesh, in this order, named
//!   in [`RawMesh::face_names`]. Faces not listed are not part of the mesh (a note counts
//!   them).
//! * **mesh field** `NAME = NUMBER;` or `NAME = [numbers…];` → [`RawMesh::mesh_fields`].
//!
//! Names may be used before they are defined, and must be unique. Refused, naming the line:
//! syntax errors, unknown or duplicate names, strings as field values, non-finite numbers,
//! fields with the wrong number of values, partial `norm`/`shape`/property fields (naming the
//! point), faces with fewer than 3 corners, nesting deeper than [`MAX_NESTING_DEPTH`].
//!
//! # Writing
//!
//! The same format: one point statement per vertex (`pos`, `norm` when present, `shape` when
//! present, then the properties, `KEY[i]` properties regrouped into one array field), one face
//! statement per polygon, the `mesh` statement, mesh fields. Names are the mesh's, or `v0…`,
//! `f0…` when absent; they must be identifiers, unique, and not `mesh`. Numbers are written in
//! Rust's shortest round-trip form, so reading back gives identical values.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt::Write as _;

use nalgebra::{Matrix3, Point3, Vector3};

use crate::error::{ReadError, WriteError};
use crate::format::{MeshFormat, WriteOptions};
use crate::hash::FxBuildHasher;
use crate::raw::{Polygons, RawMesh};
use crate::util::{show, validate_for_write};

const NAME: &str = "testbed";

/// How far from symmetric (largest `|S_ij − S_ji|`, relative to the largest entry) a `shape`
/// field may be: hand-typed or printed tensors carry rounding, anything larger is a mistake.
pub const SHAPE_SYMMETRY_TOLERANCE: f64 = 1e-9;

/// Deepest nesting of arrays in a field value (`[[1,2],[3,4]]` is 2 deep). Real files use 2;
/// the cap keeps the recursive parser's stack bounded on hostile input.
pub const MAX_NESTING_DEPTH: usize = 16;

/// The testbed format (`.m`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Testbed;

impl MeshFormat for Testbed {
    fn writes_shapes(&self) -> bool {
        true
    }

    fn name(&self) -> &'static str {
        NAME
    }

    fn extensions(&self) -> &'static [&'static str] {
        &["m"]
    }

    fn sniff(&self, bytes: &[u8]) -> bool {
        let mut lx = Lexer::new(bytes);
        matches!(
            (lx.next(), lx.next(), lx.next()),
            (
                Ok((Tok::Ident(_), _)),
                Ok((Tok::Punct(b'='), _)),
                Ok((Tok::Punct(b'(' | b'[' | b'{') | Tok::Num(_), _))
            )
        )
    }

    fn read(&self, bytes: &[u8]) -> Result<RawMesh, ReadError> {
        read_testbed(bytes).map_err(|e| *e)
    }

    fn size_hint(&self, mesh: &RawMesh, _: &WriteOptions) -> usize {
        // About 80 characters a point line and 40 a face line.
        80 * mesh.positions.len() + 40 * mesh.polygons.len()
    }

    fn write_to(
        &self,
        mesh: &RawMesh,
        _: &WriteOptions,
        out: &mut dyn std::io::Write,
    ) -> Result<(), WriteError> {
        write_testbed(mesh, out)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Tok<'a> {
    Ident(&'a [u8]),
    Num(f64),
    Str,
    Punct(u8),
    Eof,
}

impl Tok<'_> {
    fn describe(&self) -> String {
        match self {
            Tok::Ident(s) => format!("`{}`", show(s)),
            Tok::Num(x) => format!("number {x}"),
            Tok::Str => "a string".to_string(),
            Tok::Punct(c) => format!("`{}`", char::from(*c)),
            Tok::Eof => "end of file".to_string(),
        }
    }
}

/// The reader's error, boxed while parsing: results stay two words wide, which every token
/// passes through (the unboxed error is 64 bytes).
type Failure = Box<ReadError>;

fn err(line: usize, m: impl Into<String>) -> Failure {
    Box::new(ReadError::line(NAME, line, m))
}

/// A streaming lexer (no token list: memory stays proportional to what the mesh keeps).
struct Lexer<'a> {
    b: &'a [u8],
    i: usize,
    line: usize,
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_' || c >= 0x80
}

impl<'a> Lexer<'a> {
    fn new(b: &'a [u8]) -> Self {
        Lexer { b, i: 0, line: 1 }
    }

    fn at(&self, k: usize) -> Option<u8> {
        self.b.get(k).copied()
    }

    /// The next token and its line.
    fn next(&mut self) -> Result<(Tok<'a>, usize), Failure> {
        loop {
            match self.at(self.i) {
                None => return Ok((Tok::Eof, self.line)),
                Some(b'\n') => {
                    self.line += 1;
                    self.i += 1;
                }
                Some(c) if c.is_ascii_whitespace() => self.i += 1,
                Some(b'%') => {
                    while self.at(self.i).is_some_and(|c| c != b'\n') {
                        self.i += 1;
                    }
                }
                Some(_) => break,
            }
        }
        let line = self.line;
        let start = self.i;
        let c = self.at(start).unwrap_or(0);
        let next = self.at(start + 1);
        let digitish = |d: Option<u8>| d.is_some_and(|d| d.is_ascii_digit() || d == b'.');
        if c.is_ascii_digit()
            || ((c == b'-' || c == b'+') && digitish(next))
            || (c == b'.' && next.is_some_and(|d| d.is_ascii_digit()))
        {
            self.i += 1;
            while let Some(d) = self.at(self.i) {
                let prev = self.at(self.i - 1);
                let exp_sign = (d == b'-' || d == b'+') && matches!(prev, Some(b'e' | b'E'));
                if d.is_ascii_digit() || d == b'.' || d == b'e' || d == b'E' || exp_sign {
                    self.i += 1;
                } else {
                    break;
                }
            }
            let tok = self.b.get(start..self.i).unwrap_or(&[]);
            let x = crate::util::parse_f64(tok).map_err(|m| err(line, m))?;
            Ok((Tok::Num(x), line))
        } else if is_ident(c) {
            while self.at(self.i).is_some_and(is_ident) {
                self.i += 1;
            }
            Ok((Tok::Ident(self.b.get(start..self.i).unwrap_or(&[])), line))
        } else if c == b'"' {
            self.i += 1;
            loop {
                match self.at(self.i) {
                    None => return Err(err(line, "unterminated string")),
                    Some(b'"') => break,
                    Some(b'\n') => self.line += 1,
                    Some(_) => {}
                }
                self.i += 1;
            }
            self.i += 1;
            Ok((Tok::Str, line))
        } else if b"=().[]{},;".contains(&c) {
            self.i += 1;
            Ok((Tok::Punct(c), line))
        } else {
            Err(err(
                line,
                format!("unexpected character `{}`", char::from(c).escape_default()),
            ))
        }
    }
}

struct Parser<'a> {
    lx: Lexer<'a>,
    tok: Tok<'a>,
    line: usize,
}

impl<'a> Parser<'a> {
    fn new(b: &'a [u8]) -> Result<Self, Failure> {
        let mut lx = Lexer::new(b);
        let (tok, line) = lx.next()?;
        Ok(Parser { lx, tok, line })
    }

    fn bump(&mut self) -> Result<Tok<'a>, Failure> {
        let (t, l) = self.lx.next()?;
        self.line = l;
        Ok(std::mem::replace(&mut self.tok, t))
    }

    fn fail<T>(&self, expected: &str) -> Result<T, Failure> {
        Err(err(
            self.line,
            format!("expected {expected}, found {}", self.tok.describe()),
        ))
    }

    fn punct(&mut self, c: u8, expected: &str) -> Result<(), Failure> {
        self.punct_or(c, || expected.to_string())
    }

    /// [`Parser::punct`] with the message built only on failure (no allocation per token).
    fn punct_or(&mut self, c: u8, expected: impl FnOnce() -> String) -> Result<(), Failure> {
        if self.tok == Tok::Punct(c) {
            self.bump()?;
            Ok(())
        } else {
            self.fail(&expected())
        }
    }

    fn eat(&mut self, c: u8) -> Result<bool, Failure> {
        let hit = self.tok == Tok::Punct(c);
        if hit {
            self.bump()?;
        }
        Ok(hit)
    }

    /// An identifier, borrowed from the input, and its line.
    fn ident(&mut self, expected: &str) -> Result<(&'a [u8], usize), Failure> {
        self.ident_or(|| expected.to_string())
    }

    fn ident_or(
        &mut self,
        expected: impl FnOnce() -> String,
    ) -> Result<(&'a [u8], usize), Failure> {
        match self.tok {
            Tok::Ident(s) => {
                let out = (s, self.line);
                self.bump()?;
                Ok(out)
            }
            _ => self.fail(&expected()),
        }
    }

    /// A number or a (nested) array of numbers, flattened into `out`.
    fn numbers(&mut self, key: &[u8], out: &mut Vec<f64>, depth: usize) -> Result<(), Failure> {
        match self.tok {
            Tok::Num(x) => {
                out.push(x);
                self.bump()?;
                Ok(())
            }
            Tok::Punct(b'[') => {
                if depth >= MAX_NESTING_DEPTH {
                    return Err(err(
                        self.line,
                        format!(
                            "arrays in `{}` nested deeper than {MAX_NESTING_DEPTH}",
                            text(key)
                        ),
                    ));
                }
                self.bump()?;
                if self.eat(b']')? {
                    return Ok(());
                }
                loop {
                    self.numbers(key, out, depth + 1)?;
                    if self.eat(b']')? {
                        return Ok(());
                    }
                    self.punct_or(b',', || {
                        format!("`,` or `]` in the array of `{}`", text(key))
                    })?;
                }
            }
            Tok::Str => Err(err(
                self.line,
                format!(
                    "field `{}` holds a string; only numeric fields are kept",
                    text(key)
                ),
            )),
            _ => self.fail(&format!("a number or `[` for the value of `{}`", text(key))),
        }
    }

    /// A list of names up to `close`, appended to `out` (borrowed from the input, with lines).
    fn name_list(
        &mut self,
        close: u8,
        what: &str,
        out: &mut Vec<(&'a [u8], usize)>,
    ) -> Result<(), Failure> {
        if self.eat(close)? {
            return Ok(());
        }
        loop {
            out.push(self.ident_or(|| format!("a {what} name"))?);
            if self.eat(close)? {
                return Ok(());
            }
            self.punct_or(b',', || {
                format!("`,` or `{}` in the list of {what}s", char::from(close))
            })?;
        }
    }
}

/// A name or key as text for messages and outputs (as the names were always read: invalid
/// UTF-8 replaced).
fn text(s: &[u8]) -> std::borrow::Cow<'_, str> {
    String::from_utf8_lossy(s)
}

struct Point<'a> {
    name: &'a [u8],
    line: usize,
    pos: [f64; 3],
    /// Whether the point has `norm` (the normals of the points that have one are in a list
    /// of their own, in point order: a point costs no room for what it lacks).
    norm: bool,
    /// Whether the point has `shape` (likewise).
    shape: bool,
    /// Its other fields, boxed (most points have none: a point then costs 8 bytes for them).
    fields: Option<Box<Fields>>,
}

/// A point's fields other than `pos`, `norm` and `shape`: key and values.
type Fields = Vec<(String, Vec<f64>)>;

/// The normals and shape tensors of the points that have them, in point order.
#[derive(Default)]
struct Given {
    normals: Vec<Vector3<f64>>,
    shapes: Vec<Matrix3<f64>>,
}

fn parse_point<'a>(
    p: &mut Parser<'a>,
    name: &'a [u8],
    line: usize,
    v: &mut Vec<f64>,
    given: &mut Given,
) -> Result<Point<'a>, Failure> {
    p.punct(b'(', "`(`")?;
    let (head, hl) = p.ident("`Point`")?;
    if head != b"Point" {
        return Err(err(
            hl,
            format!("expected `Point` after `(`, found `{}`", text(head)),
        ));
    }
    p.punct(b'.', "`.` after `Point`")?;
    let mut pos = None;
    let mut norm = None;
    let mut shape = None;
    let mut fields: Vec<(String, Vec<f64>)> = Vec::new();
    while !p.eat(b')')? {
        let fl = p.line;
        p.punct(b'(', "`(` to open a field or `)` to close the point")?;
        let (key, _) = p.ident("a field name")?;
        p.punct_or(b'.', || format!("`.` after field name `{}`", text(key)))?;
        v.clear();
        p.numbers(key, v, 0)?;
        let dup = match key {
            b"pos" | b"norm" | b"shape" => {
                let want = if key == b"shape" { 9 } else { 3 };
                if v.len() != want {
                    return Err(err(
                        fl,
                        format!(
                            "`{}` of `{}` has {} numbers, expected {want}",
                            text(key),
                            text(name),
                            v.len()
                        ),
                    ));
                }
                match key {
                    b"pos" => pos.replace([v[0], v[1], v[2]]).is_some(),
                    b"norm" => {
                        let n = Vector3::new(v[0], v[1], v[2]);
                        let Some(unit) = n.try_normalize(0.0) else {
                            return Err(err(
                                fl,
                                format!("point `{}` has a zero normal", text(name)),
                            ));
                        };
                        norm.replace(unit).is_some()
                    }
                    _ => {
                        let s = Matrix3::from_row_slice(v);
                        let scale = s.amax().max(f64::MIN_POSITIVE);
                        if (s - s.transpose()).amax() > SHAPE_SYMMETRY_TOLERANCE * scale {
                            return Err(err(
                                fl,
                                format!("`shape` of `{}` is not symmetric", text(name)),
                            ));
                        }
                        shape.replace((s + s.transpose()) * 0.5).is_some()
                    }
                }
            }
            _ => {
                let key = text(key).into_owned();
                let dup = fields.iter().any(|(k, _)| *k == key);
                fields.push((key, v.clone()));
                dup
            }
        };
        if dup {
            return Err(err(
                fl,
                format!("field `{}` of `{}` is given twice", text(key), text(name)),
            ));
        }
        p.punct_or(b')', || format!("`)` to close field `{}`", text(key)))?;
    }
    let pos = pos.ok_or_else(|| err(line, format!("point `{}` has no `pos` field", text(name))))?;
    if let Some(n) = norm {
        given.normals.push(n);
    }
    if let Some(s) = shape {
        given.shapes.push(s);
    }
    Ok(Point {
        name,
        line,
        pos,
        norm: norm.is_some(),
        shape: shape.is_some(),
        fields: (!fields.is_empty()).then(|| Box::new(fields)),
    })
}

/// What a name was defined as, and where.
#[derive(Clone, Copy)]
enum Def {
    /// Point number `i`.
    Point(usize),
    /// Face statement number `i`.
    Face(usize),
    /// A mesh field.
    Field,
}

/// The defined names: hashed with the workbench's one fast hasher, seeded per read so that
/// collisions cannot be planted in a file ([`crate::hash`]): a million names hash in
/// milliseconds.
type Names<'a> = HashMap<&'a [u8], (Def, usize), FxBuildHasher>;

/// A name in the input and the line it is on.
type NameAt<'a> = (&'a [u8], usize);

fn read_testbed(bytes: &[u8]) -> Result<RawMesh, Failure> {
    use std::hash::BuildHasher as _;
    let seed = std::collections::hash_map::RandomState::new().hash_one(0x07e5_7bed_u64);
    let mut p = Parser::new(bytes)?;
    let mut points: Vec<Point<'_>> = Vec::new();
    // Every defined name (but `mesh`): what it is and its line.
    let mut defined: Names<'_> = HashMap::with_hasher(FxBuildHasher::with_seed(seed));
    // Face corners as point indices, resolved as the face is read when the name is a point's
    // own number (`v17`), [`UNRESOLVED`] otherwise, with the name kept in `deferred`.
    let mut corners: Vec<usize> = Vec::new();
    let mut deferred: Vec<(usize, NameAt<'_>)> = Vec::new();
    let mut corner_names: Vec<NameAt<'_>> = Vec::new();
    let mut n_faces = 0usize;
    let mut mesh_fields: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let mut mesh_stmt: Option<(usize, MeshList<'_>)> = None;
    let mut scratch: Vec<f64> = Vec::new();
    // A point and a face named `mesh` (not in `defined`, as `mesh` may be redefined).
    let mut mesh_named: (Option<usize>, Option<usize>) = (None, None);
    let mut face_defs: Vec<FaceDef<'_>> = Vec::new();
    let mut given = Given::default();
    while p.tok != Tok::Eof {
        let (name, line) = p.ident("a name at the start of a statement")?;
        p.punct_or(b'=', || format!("`=` after `{}`", text(name)))?;
        if name != b"mesh" {
            if let Some(first) = names_so_far(&points, &face_defs, &defined, name) {
                return Err(err(
                    line,
                    format!("`{}` is already defined (line {first})", text(name)),
                ));
            }
        }
        // Names that end in their own statement's number (`v17` for point 17, `f3` for face 3,
        // as writers number them) are found by that number and stay out of the map: a million
        // points cost no hashing and no scattered lookups.
        let index = trailing_index(name);
        let mut define = |def: Def| {
            let own_number = match def {
                Def::Point(i) | Def::Face(i) => index == Some(i),
                Def::Field => false,
            };
            if !own_number {
                defined.insert(name, (def, line));
            }
        };
        match p.tok {
            Tok::Punct(b'(') => {
                let point = parse_point(&mut p, name, line, &mut scratch, &mut given)?;
                if name == b"mesh" {
                    // `mesh` is not a reserved name for a point (the last one counts).
                    mesh_named.0 = Some(points.len());
                } else {
                    define(Def::Point(points.len()));
                }
                points.push(point);
            }
            Tok::Punct(b'[') => {
                p.bump()?;
                if matches!(p.tok, Tok::Ident(_)) {
                    let start = corners.len();
                    corner_names.clear();
                    p.name_list(b']', "vertex", &mut corner_names)?;
                    for &(vname, vline) in &corner_names {
                        match trailing_index(vname) {
                            Some(i) if points.get(i).is_some_and(|pt| pt.name == vname) => {
                                corners.push(i);
                            }
                            _ => {
                                deferred.push((corners.len(), (vname, vline)));
                                corners.push(UNRESOLVED);
                            }
                        }
                    }
                    let len = corners.len() - start;
                    if len < 3 {
                        return Err(err(
                            line,
                            format!("face `{}` has {len} corners, at least 3 needed", text(name)),
                        ));
                    }
                    let k = face_defs.len();
                    if name == b"mesh" {
                        // Nor for a face (the last one counts).
                        if mesh_named.1.is_none() {
                            n_faces += 1;
                        }
                        mesh_named.1 = Some(k);
                    } else {
                        define(Def::Face(k));
                        n_faces += 1;
                    }
                    face_defs.push(FaceDef { name, line, start });
                } else {
                    // A mesh field: re-read the array from its first element.
                    let mut v = Vec::new();
                    if !p.eat(b']')? {
                        loop {
                            p.numbers(name, &mut v, 1)?;
                            if p.eat(b']')? {
                                break;
                            }
                            p.punct_or(b',', || {
                                format!("`,` or `]` in the array of `{}`", text(name))
                            })?;
                        }
                    }
                    define(Def::Field);
                    mesh_fields.insert(text(name).into_owned(), v);
                }
            }
            Tok::Num(x) => {
                p.bump()?;
                define(Def::Field);
                mesh_fields.insert(text(name).into_owned(), vec![x]);
            }
            Tok::Punct(b'{') => {
                if name != b"mesh" {
                    return Err(err(
                        line,
                        format!(
                            "a face list in braces must be `mesh = {{…}};`, found `{}`",
                            text(name)
                        ),
                    ));
                }
                if let Some((first, _)) = mesh_stmt {
                    return Err(err(
                        line,
                        format!("second `mesh` statement (the first is at line {first})"),
                    ));
                }
                p.bump()?;
                // Faces already defined under their own number (`f3` as face 3) are resolved
                // as read (a name is defined once, so this is what the end would find); the
                // rest wait for the end of the file, with their names.
                let mut list = MeshList::default();
                if !p.eat(b'}')? {
                    loop {
                        let (fname, fline) = p.ident_or(|| "a face name".to_string())?;
                        match trailing_index(fname) {
                            Some(k)
                                if fname != b"mesh"
                                    && face_defs.get(k).is_some_and(|f| f.name == fname) =>
                            {
                                list.faces.push(k);
                            }
                            _ => {
                                list.late.push((list.faces.len(), (fname, fline)));
                                list.faces.push(UNRESOLVED);
                            }
                        }
                        if p.eat(b'}')? {
                            break;
                        }
                        p.punct_or(b',', || "`,` or `}` in the list of faces".to_string())?;
                    }
                }
                mesh_stmt = Some((line, list));
            }
            _ => {
                return p.fail(&format!(
                    "`(Point . …)`, `[` (a face), `{{` (the mesh) or a number after `{} =`",
                    text(name)
                ))
            }
        }
        if !p.eat(b';')? {
            return p.fail("`;` at the end of the statement");
        }
    }
    let Some((_, mesh_faces)) = mesh_stmt else {
        return Err(err(
            p.line,
            "no `mesh = {…};` statement: the mesh has no faces",
        ));
    };
    let names = Lookup {
        defined: &defined,
        points: &points,
        faces: &face_defs,
        mesh_named,
        corners: corners.len(),
    };
    let corners = Corners {
        index: &corners,
        deferred: &deferred,
    };
    assemble(
        &points,
        given,
        &names,
        &corners,
        n_faces,
        mesh_faces,
        mesh_fields,
    )
}

/// The faces of the `mesh` statement: a face index each, or [`UNRESOLVED`] with the name and
/// line in `late` (by position, increasing).
#[derive(Default)]
struct MeshList<'a> {
    faces: Vec<usize>,
    late: Vec<(usize, NameAt<'a>)>,
}

/// A face corner whose point is found only once the whole file is read.
const UNRESOLVED: usize = usize::MAX;

/// The corners of every face statement.
struct Corners<'m, 'a> {
    /// Point index per corner, or [`UNRESOLVED`].
    index: &'m [usize],
    /// The unresolved corners' positions in `index` (increasing), names and lines.
    deferred: &'m [(usize, NameAt<'a>)],
}

/// A face statement: its name, line and the start of its corners (they run to the next face
/// statement's, or to the end: [`Lookup::range`]).
struct FaceDef<'a> {
    name: &'a [u8],
    line: usize,
    start: usize,
}

/// The number a name ends in (`v17` → 17; `v017`, `v` and `17` end in none): a name that is
/// its statement's own number is found by it ([`read_testbed`]).
fn trailing_index(name: &[u8]) -> Option<usize> {
    let digits = name.iter().rev().take_while(|c| c.is_ascii_digit()).count();
    let (prefix, number) = name.split_at(name.len() - digits);
    if prefix.is_empty() || number.is_empty() || number.len() > 18 {
        return None;
    }
    if number.len() > 1 && number[0] == b'0' {
        return None;
    }
    Some(
        number
            .iter()
            .fold(0usize, |n, d| n * 10 + usize::from(d - b'0')),
    )
}

/// The line of the definition of `name` so far, if any (points and faces by their own number,
/// everything else by the map).
fn names_so_far(
    points: &[Point<'_>],
    faces: &[FaceDef<'_>],
    defined: &Names<'_>,
    name: &[u8],
) -> Option<usize> {
    if let Some(i) = trailing_index(name) {
        if let Some(pt) = points.get(i).filter(|pt| pt.name == name) {
            return Some(pt.line);
        }
        if let Some(f) = faces.get(i).filter(|f| f.name == name) {
            return Some(f.line);
        }
    }
    if defined.is_empty() {
        return None;
    }
    defined.get(name).map(|(_, line)| *line)
}

/// Name resolution for [`assemble`].
struct Lookup<'m, 'a> {
    defined: &'m Names<'a>,
    points: &'m [Point<'a>],
    faces: &'m [FaceDef<'a>],
    mesh_named: (Option<usize>, Option<usize>),
    /// The number of corners of all face statements.
    corners: usize,
}

impl Lookup<'_, '_> {
    fn point(&self, name: &[u8]) -> Option<usize> {
        if name == b"mesh" {
            return self.mesh_named.0;
        }
        if let Some(i) = trailing_index(name) {
            if self.points.get(i).is_some_and(|pt| pt.name == name) {
                return Some(i);
            }
        }
        match self.defined.get(name) {
            Some((Def::Point(i), _)) => Some(*i),
            _ => None,
        }
    }

    /// A face's corner range.
    fn face(&self, name: &[u8]) -> Option<(usize, usize)> {
        let k = if name == b"mesh" {
            self.mesh_named.1?
        } else {
            match trailing_index(name) {
                Some(i) if self.faces.get(i).is_some_and(|f| f.name == name) => i,
                _ => match self.defined.get(name) {
                    Some((Def::Face(k), _)) => *k,
                    _ => return None,
                },
            }
        };
        self.range(k)
    }

    /// Face statement `k`'s corner range `(start, len)`.
    fn range(&self, k: usize) -> Option<(usize, usize)> {
        let f = self.faces.get(k)?;
        let end = self.faces.get(k + 1).map_or(self.corners, |g| g.start);
        Some((f.start, end - f.start))
    }
}

fn assemble(
    points: &[Point<'_>],
    given: Given,
    names: &Lookup<'_, '_>,
    corners: &Corners<'_, '_>,
    n_faces: usize,
    mesh_faces: MeshList<'_>,
    mesh_fields: BTreeMap<String, Vec<f64>>,
) -> Result<RawMesh, Failure> {
    let n = points.len();
    let listed_faces = mesh_faces.faces.len();
    let mut polys = Polygons::with_capacity(listed_faces, 3 * listed_faces);
    // Each listed face's name and line (of the `mesh` statement for a late one, of its own
    // statement otherwise: only messages use it).
    let mut late = mesh_faces.late.iter().peekable();
    let mut entries = mesh_faces.faces.iter().enumerate().map(|(j, &k)| {
        if k != UNRESOLVED {
            let f = &names.faces[k];
            return (f.name, f.line);
        }
        match late.next_if(|(at, _)| *at == j) {
            Some((_, at)) => *at,
            None => (&b"?"[..], 0),
        }
    });
    // Names that are what the writer emits for a mesh without names (`v<i>`, `f<k>`, by
    // position) are implied rather than stored ([`RawMesh::implied_vertex_names`]).
    let implied_vertex_names = points
        .iter()
        .enumerate()
        .all(|(i, pt)| is_positional_name(pt.name, b'v', i));
    let implied_face_names = mesh_faces
        .faces
        .iter()
        .enumerate()
        .all(|(j, &k)| k != UNRESOLVED && is_positional_name(names.faces[k].name, b'f', j));
    let mut face_names = Vec::with_capacity(if implied_face_names { 0 } else { listed_faces });
    let mut face_corners = Vec::new();
    // Faces listed, flagged at the start of their corners (each face's range is its own).
    let mut listed = vec![false; corners.index.len()];
    let mut listed_count = 0usize;
    for &k in &mesh_faces.faces {
        let Some((fname, fline)) = entries.next() else {
            break;
        };
        let resolved = if k == UNRESOLVED {
            names.face(fname)
        } else {
            names.range(k)
        };
        let Some((start, len)) = resolved else {
            let what = if names.point(fname).is_some() {
                "a point, not a face"
            } else {
                "not defined"
            };
            return Err(err(
                fline,
                format!("mesh refers to unknown face `{}` ({what})", text(fname)),
            ));
        };
        face_corners.clear();
        for q in start..start + len {
            let i = match corners.index.get(q) {
                Some(&i) if i != UNRESOLVED => i,
                _ => {
                    let at = corners.deferred.binary_search_by_key(&q, |d| d.0);
                    let (vname, vline) = at.map_or((&b"?"[..], fline), |k| corners.deferred[k].1);
                    let Some(i) = names.point(vname) else {
                        return Err(err(
                            vline,
                            format!(
                                "face `{}` refers to unknown vertex `{}`",
                                text(fname),
                                text(vname)
                            ),
                        ));
                    };
                    i
                }
            };
            face_corners.push(i);
        }
        polys.push(&face_corners);
        if !implied_face_names {
            face_names.push(text(fname).into_owned());
        }
        if let Some(flag) = listed.get_mut(start) {
            listed_count += usize::from(!*flag);
            *flag = true;
        }
    }
    let mut notes = Vec::new();
    let unlisted = n_faces.saturating_sub(listed_count);
    if unlisted > 0 {
        notes.push(format!(
            "{unlisted} faces are defined but not listed in `mesh`: not part of the mesh"
        ));
    }
    // All or none: `norm`, `shape`, and each other field.
    let all_or_none = |what: &str, has: &dyn Fn(&Point) -> bool| -> Result<bool, Failure> {
        let k = points.iter().filter(|pt| has(pt)).count();
        if k == 0 || k == n {
            return Ok(k > 0);
        }
        let missing = points.iter().find(|pt| !has(pt));
        let (name, line) = missing.map_or(("?".into(), 0), |pt| (text(pt.name), pt.line));
        Err(err(
            line,
            format!(
                "point `{}` has no `{what}` field, but {k} of the {n} points have one",
                name
            ),
        ))
    };
    let has_norm = all_or_none("norm", &|pt| pt.norm)?;
    let has_shape = all_or_none("shape", &|pt| pt.shape)?;
    let mut keys: Vec<String> = Vec::new();
    for pt in points {
        for (k, _) in pt.fields.iter().flat_map(|f| f.iter()) {
            if !keys.contains(k) {
                keys.push(k.clone());
            }
        }
    }
    let mut properties = BTreeMap::new();
    for key in &keys {
        let len = points
            .iter()
            .find_map(|pt| {
                pt.fields
                    .iter()
                    .flat_map(|f| f.iter())
                    .find(|(k, _)| k == key)
                    .map(|(_, v)| v.len())
            })
            .unwrap_or(0);
        let mut cols: Vec<Vec<f64>> = vec![Vec::with_capacity(n); len];
        for pt in points {
            let Some((_, v)) = pt
                .fields
                .iter()
                .flat_map(|f| f.iter())
                .find(|(k, _)| k == key)
            else {
                return Err(err(
                    pt.line,
                    format!(
                        "point `{}` has no `{key}` field, but other points have one",
                        text(pt.name)
                    ),
                ));
            };
            if v.len() != len {
                return Err(err(
                    pt.line,
                    format!(
                        "field `{key}` of point `{}` has {} values, other points have {len}",
                        text(pt.name),
                        v.len()
                    ),
                ));
            }
            for (c, x) in cols.iter_mut().zip(v) {
                c.push(*x);
            }
        }
        if len == 1 {
            properties.insert(key.clone(), cols.pop().unwrap_or_default());
        } else {
            for (i, c) in cols.into_iter().enumerate() {
                properties.insert(format!("{key}[{i}]"), c);
            }
        }
    }
    let mut mesh = RawMesh {
        positions: points.iter().map(|pt| Point3::from(pt.pos)).collect(),
        // Every point has one (or none does): the lists are one per point, in point order.
        normals: has_norm.then_some(given.normals),
        shapes: has_shape.then_some(given.shapes),
        properties,
        polygons: polys,
        face_names: (!implied_face_names).then_some(face_names),
        implied_face_names,
        implied_vertex_names,
        mesh_fields,
        notes,
        ..RawMesh::default()
    };
    if !implied_vertex_names {
        mesh.vertex_names = Some(points.iter().map(|pt| text(pt.name).into_owned()).collect());
    }
    Ok(mesh)
}

/// Whether `name` is `letter` followed by the decimal `i` (no leading zeros): the name the
/// writer gives the `i`-th point (`v`) or face (`f`) of a mesh without names.
fn is_positional_name(name: &[u8], letter: u8, i: usize) -> bool {
    name.len() >= 2
        && name[0] == letter
        && name[1..].iter().all(u8::is_ascii_digit)
        && trailing_index(name) == Some(i)
}

fn is_identifier(s: &str) -> bool {
    let b = s.as_bytes();
    b.first()
        .is_some_and(|&c| c.is_ascii_alphabetic() || c == b'_' || c >= 0x80)
        && b.iter().all(|&c| is_ident(c))
}

fn fmt_list(s: &mut crate::util::Sink<'_>, v: &[f64]) {
    s.push('[');
    for (i, x) in v.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        let _ = write!(s, "{x:?}");
    }
    s.push(']');
}

/// Splits a property name `KEY[i]` into `(KEY, i)`.
fn indexed(name: &str) -> Option<(&str, usize)> {
    let (key, rest) = name.split_once('[')?;
    let i = rest.strip_suffix(']')?.parse().ok()?;
    Some((key, i))
}

fn write_testbed(mesh: &RawMesh, out: &mut dyn std::io::Write) -> Result<(), WriteError> {
    validate_for_write(mesh, NAME)?;
    let bad = |m: String| WriteError::invalid(NAME, m);
    let vnames: Vec<String> = match &mesh.vertex_names {
        Some(v) => v.clone(),
        None => (0..mesh.positions.len()).map(|i| format!("v{i}")).collect(),
    };
    let fnames: Vec<String> = match &mesh.face_names {
        Some(f) => f.clone(),
        None => (0..mesh.polygons.len()).map(|i| format!("f{i}")).collect(),
    };
    let mut seen = HashSet::new();
    for n in vnames.iter().chain(&fnames) {
        if !is_identifier(n) || n == "mesh" {
            return Err(bad(format!(
                "`{n}` is not a usable name (an identifier other than `mesh`)"
            )));
        }
        if !seen.insert(n.as_str()) {
            return Err(bad(format!("the name `{n}` is used twice")));
        }
    }
    for k in mesh.mesh_fields.keys() {
        if !is_identifier(k) || k == "mesh" || seen.contains(k.as_str()) {
            return Err(bad(format!("mesh field `{k}` is not a usable name")));
        }
    }
    // Fields: KEY[i] regrouped (in index order), other keys alone.
    let mut groups: BTreeMap<&str, Vec<(usize, &Vec<f64>)>> = BTreeMap::new();
    for (k, v) in &mesh.properties {
        match indexed(k) {
            Some((key, i)) => groups.entry(key).or_default().push((i, v)),
            None => groups.entry(k.as_str()).or_default().push((0, v)),
        }
    }
    for (key, cols) in groups.iter_mut() {
        if !is_identifier(key) || matches!(*key, "pos" | "norm" | "shape") {
            return Err(bad(format!("property `{key}` is not a usable field name")));
        }
        cols.sort_by_key(|c| c.0);
        let single = cols.len() == 1 && mesh.properties.contains_key(*key);
        let contiguous = cols.iter().enumerate().all(|(j, (i, _))| *i == j);
        if !single && !contiguous {
            return Err(bad(format!(
                "properties `{key}[…]` are not numbered 0, 1, … without gaps"
            )));
        }
    }
    let mut s = crate::util::Sink::new(out);
    s.push_str("% written by meshio\n");
    let mut vals = Vec::new();
    for (i, p) in mesh.positions.iter().enumerate() {
        let name = vnames.get(i).map_or("", String::as_str);
        let _ = write!(s, "{name} = (Point . (pos . ");
        fmt_list(&mut s, &[p.x, p.y, p.z]);
        s.push(')');
        if let Some(n) = mesh.normals.as_ref().and_then(|n| n.get(i)) {
            s.push_str(" (norm . ");
            fmt_list(&mut s, &[n.x, n.y, n.z]);
            s.push(')');
        }
        if let Some(m) = mesh.shapes.as_ref().and_then(|m| m.get(i)) {
            s.push_str(" (shape . ");
            let rows: Vec<f64> = (0..3)
                .flat_map(|r| (0..3).map(move |c| m[(r, c)]))
                .collect();
            fmt_list(&mut s, &rows);
            s.push(')');
        }
        for (key, cols) in &groups {
            vals.clear();
            vals.extend(cols.iter().map(|(_, v)| v.get(i).copied().unwrap_or(0.0)));
            let _ = write!(s, " ({key} . ");
            match (vals.as_slice(), mesh.properties.contains_key(*key)) {
                ([x], true) => {
                    let _ = write!(s, "{x:?}");
                }
                _ => fmt_list(&mut s, &vals),
            }
            s.push(')');
        }
        s.push_str(");\n");
    }
    for (f, poly) in mesh.polygons.iter().enumerate() {
        let _ = write!(s, "{} = [", fnames.get(f).map_or("", String::as_str));
        for (k, &i) in poly.iter().enumerate() {
            if k > 0 {
                s.push_str(", ");
            }
            s.push_str(vnames.get(i).map_or("", String::as_str));
        }
        s.push_str("];\n");
    }
    s.push_str("mesh = {");
    for (f, name) in fnames.iter().enumerate() {
        if f > 0 {
            s.push_str(", ");
        }
        s.push_str(name);
    }
    s.push_str("};\n");
    for (k, v) in &mesh.mesh_fields {
        let _ = write!(s, "{k} = ");
        fmt_list(&mut s, v);
        s.push_str(";\n");
    }
    s.finish(NAME)
}
