//! The testbed's mesh format: the "semi-dstruct" input of Lounsbery et al. (1990), Figure 2.
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
//! Grammar, as read here (whitespace, including line breaks, is free between tokens; `%` starts
//! a comment that runs to the end of the line):
//!
//! * **point** `NAME = (Point . FIELD*);` with `FIELD = (KEY . VALUE)`. `pos` and `norm` are
//!   required, each exactly three numbers in brackets (the normal is normalized on reading; a
//!   zero normal is an error). The optional field `shape` is the shape
//!   tensor `S` (`κn(d) = dᵀ S d`, DESIGN.md sign), nine numbers row by row, and must be
//!   symmetric (within [`SHAPE_SYMMETRY_TOLERANCE`], then symmetrized). Any other field whose
//!   value is a number or a (possibly nested) array of numbers is kept in
//!   [`crate::Vertex::extra`] (nested arrays flattened) and written back by
//!   [`write_testbed`]; string-valued fields are rejected, since extra fields hold numbers.
//!   A point without `shape` gets a zero shape tensor and
//!   [`crate::Vertex::curvature_known`]` = false`.
//! * **face** `NAME = [V1, V2, V3];` naming three points (triangles only).
//! * **mesh** `mesh = {F1, F2, ...};` naming the faces of the mesh, exactly once. Faces not
//!   listed there are not part of the mesh.
//!
//! The vertices of the resulting [`Mesh`] are all the points, in the order they are defined;
//! its faces are those of the `mesh` statement, in that order, named by their face names. Names
//! may be used before they are defined. Errors give the line and what was expected.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use nalgebra::{Matrix3, Point3, Vector3};

use crate::mesh::{ExtraFields, Mesh, MeshError, Vertex};

/// How far from symmetric (largest `|S_ij − S_ji|`, relative to the largest entry) a `shape`
/// field may be: hand-typed or printed tensors carry rounding, anything larger is a mistake.
pub const SHAPE_SYMMETRY_TOLERANCE: f64 = 1e-9;

/// What went wrong reading or writing a testbed mesh.
#[derive(Debug, thiserror::Error)]
pub enum TestbedError {
    /// A syntax or reference error at a line.
    #[error("line {line}: {message}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// What was expected or wrong.
        message: String,
    },
    /// The mesh is syntactically fine but not a valid mesh.
    #[error("line {line}: {}{source}", face_name.as_ref().map(|n| format!("face `{n}`: ")).unwrap_or_default())]
    Mesh {
        /// Line of the `mesh` statement.
        line: usize,
        /// Name of the face at fault, when the error names a face.
        face_name: Option<String>,
        /// The mesh error.
        source: MeshError,
    },
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// An error in a named file.
    #[error("{}: {source}", path.display())]
    InFile {
        /// The file.
        path: PathBuf,
        /// The error.
        source: Box<TestbedError>,
    },
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Num(f64),
    Str(String),
    Punct(char),
}

impl Tok {
    fn describe(&self) -> String {
        match self {
            Tok::Ident(s) => format!("`{s}`"),
            Tok::Num(x) => format!("number {x}"),
            Tok::Str(s) => format!("string \"{s}\""),
            Tok::Punct(c) => format!("`{c}`"),
        }
    }
}

fn syntax(line: usize, message: impl Into<String>) -> TestbedError {
    TestbedError::Syntax {
        line,
        message: message.into(),
    }
}

fn lex(text: &str) -> Result<(Vec<(Tok, usize)>, usize), TestbedError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut line = 1;
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '%' {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push((Tok::Ident(chars[start..i].iter().collect()), line));
        } else if c.is_ascii_digit()
            || ((c == '-' || c == '+') && next.is_some_and(|d| d.is_ascii_digit() || d == '.'))
            || (c == '.' && next.is_some_and(|d| d.is_ascii_digit()))
        {
            let start = i;
            i += 1;
            while i < chars.len() {
                let d = chars[i];
                let exp_sign = (d == '-' || d == '+') && matches!(chars[i - 1], 'e' | 'E');
                if d.is_ascii_digit() || d == '.' || d == 'e' || d == 'E' || exp_sign {
                    i += 1;
                } else {
                    break;
                }
            }
            let s: String = chars[start..i].iter().collect();
            let x: f64 = s
                .parse()
                .map_err(|_| syntax(line, format!("`{s}` is not a number")))?;
            out.push((Tok::Num(x), line));
        } else if c == '"' {
            let start_line = line;
            i += 1;
            let start = i;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\n' {
                    line += 1;
                }
                i += 1;
            }
            if i >= chars.len() {
                return Err(syntax(start_line, "unterminated string"));
            }
            out.push((Tok::Str(chars[start..i].iter().collect()), start_line));
            i += 1;
        } else if "=().[]{},;".contains(c) {
            out.push((Tok::Punct(c), line));
            i += 1;
        } else {
            return Err(syntax(line, format!("unexpected character `{c}`")));
        }
    }
    Ok((out, line))
}

struct Parser {
    toks: Vec<(Tok, usize)>,
    pos: usize,
    last_line: usize,
}

impl Parser {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.pos).map(|t| &t.0)
    }

    /// Line of the next token, or of the last token at the end of input.
    fn line(&self) -> usize {
        self.toks
            .get(self.pos)
            .or_else(|| self.toks.last())
            .map_or(self.last_line, |t| t.1)
    }

    fn found(&self) -> String {
        self.peek()
            .map_or_else(|| "end of input".to_string(), Tok::describe)
    }

    fn fail<T>(&self, expected: &str) -> Result<T, TestbedError> {
        Err(syntax(
            self.line(),
            format!("expected {expected}, found {}", self.found()),
        ))
    }

    fn punct(&mut self, c: char, expected: &str) -> Result<(), TestbedError> {
        if self.peek() == Some(&Tok::Punct(c)) {
            self.pos += 1;
            Ok(())
        } else {
            self.fail(expected)
        }
    }

    fn eat(&mut self, c: char) -> bool {
        let hit = self.peek() == Some(&Tok::Punct(c));
        if hit {
            self.pos += 1;
        }
        hit
    }

    fn ident(&mut self, expected: &str) -> Result<(String, usize), TestbedError> {
        match self.toks.get(self.pos) {
            Some((Tok::Ident(s), line)) => {
                let out = (s.clone(), *line);
                self.pos += 1;
                Ok(out)
            }
            _ => self.fail(expected),
        }
    }

    fn number(&mut self, expected: &str) -> Result<f64, TestbedError> {
        match self.peek() {
            Some(Tok::Num(x)) if x.is_finite() => {
                let x = *x;
                self.pos += 1;
                Ok(x)
            }
            Some(Tok::Num(x)) => Err(syntax(self.line(), format!("{x} is not a finite number"))),
            _ => self.fail(expected),
        }
    }

    /// `[x, y, z]` for the field `key`.
    fn triple(&mut self, key: &str) -> Result<[f64; 3], TestbedError> {
        self.punct('[', &format!("`[` to open the coordinates of `{key}`"))?;
        let mut out = [0.0; 3];
        for (i, slot) in out.iter_mut().enumerate() {
            if i > 0 {
                self.punct(
                    ',',
                    &format!("`,` after {i} coordinate(s) of `{key}` (it needs 3)"),
                )?;
            }
            *slot = self.number(&format!("coordinate {} of `{key}`", i + 1))?;
        }
        self.punct(']', "`]` after 3 coordinates")?;
        Ok(out)
    }

    /// A number or a (nested) array of numbers, flattened.
    fn numbers(&mut self, key: &str, out: &mut Vec<f64>) -> Result<(), TestbedError> {
        match self.peek() {
            Some(Tok::Num(_)) => {
                out.push(self.number("a number")?);
                Ok(())
            }
            Some(Tok::Punct('[')) => {
                self.pos += 1;
                if self.eat(']') {
                    return Ok(());
                }
                loop {
                    self.numbers(key, out)?;
                    if self.eat(']') {
                        return Ok(());
                    }
                    self.punct(',', &format!("`,` or `]` in the array of `{key}`"))?;
                }
            }
            Some(Tok::Str(_)) => Err(syntax(
                self.line(),
                format!("field `{key}` holds a string; only numeric fields are kept"),
            )),
            _ => self.fail(&format!("a number or `[` for the value of `{key}`")),
        }
    }
}

struct FaceDef {
    names: Vec<(String, usize)>,
}

fn parse_point(p: &mut Parser, name: &str, line: usize) -> Result<Vertex, TestbedError> {
    p.punct('(', "`(`")?;
    let (head, _) = p.ident("`Point`")?;
    if head != "Point" {
        return Err(syntax(
            line,
            format!("expected `Point` after `(`, found `{head}`"),
        ));
    }
    p.punct('.', "`.` after `Point`")?;
    let mut pos = None;
    let mut norm = None;
    let mut shape = None;
    let mut extra = ExtraFields::new();
    while !p.eat(')') {
        let field_line = p.line();
        p.punct('(', "`(` to open a field or `)` to close the point")?;
        let (key, _) = p.ident("a field name")?;
        p.punct('.', &format!("`.` after field name `{key}`"))?;
        match key.as_str() {
            "pos" => pos = Some(p.triple("pos")?),
            "norm" => norm = Some(p.triple("norm")?),
            "shape" => {
                let mut v = Vec::new();
                p.numbers("shape", &mut v)?;
                if v.len() != 9 {
                    return Err(syntax(
                        field_line,
                        format!(
                            "`shape` of `{name}` has {} numbers, expected 9 (a 3×3 tensor, row by row)",
                            v.len()
                        ),
                    ));
                }
                let s = Matrix3::from_row_slice(&v);
                let scale = s.amax().max(f64::MIN_POSITIVE);
                if (s - s.transpose()).amax() > SHAPE_SYMMETRY_TOLERANCE * scale {
                    return Err(syntax(
                        field_line,
                        format!("`shape` of `{name}` is not symmetric"),
                    ));
                }
                shape = Some((s + s.transpose()) * 0.5);
            }
            _ => {
                let mut v = Vec::new();
                p.numbers(&key, &mut v)?;
                extra.insert(key.clone(), v);
            }
        }
        p.punct(')', &format!("`)` to close field `{key}`"))?;
    }
    let pos = pos.ok_or_else(|| syntax(line, format!("point `{name}` has no `pos` field")))?;
    let norm = norm.ok_or_else(|| syntax(line, format!("point `{name}` has no `norm` field")))?;
    let n = Vector3::from(norm);
    if n.norm() == 0.0 {
        return Err(syntax(line, format!("point `{name}` has a zero normal")));
    }
    let mut vertex = match shape {
        Some(s) => Vertex::new(curves::VertexData::new(Point3::from(pos), n.normalize(), s)),
        None => Vertex::without_curvature(Point3::from(pos), n.normalize()),
    };
    vertex.name = Some(name.to_string());
    vertex.extra = extra;
    Ok(vertex)
}

fn name_list(
    p: &mut Parser,
    close: char,
    what: &str,
) -> Result<Vec<(String, usize)>, TestbedError> {
    let mut out = Vec::new();
    if p.eat(close) {
        return Ok(out);
    }
    loop {
        out.push(p.ident(&format!("a {what} name"))?);
        if p.eat(close) {
            return Ok(out);
        }
        p.punct(',', &format!("`,` or `{close}` in the list of {what}s"))?;
    }
}

/// Reads a mesh in the testbed's format from text (see the module docs).
pub fn read_testbed(text: &str) -> Result<Mesh, TestbedError> {
    let (toks, last_line) = lex(text)?;
    let mut p = Parser {
        toks,
        pos: 0,
        last_line,
    };
    let mut points: Vec<(String, Vertex)> = Vec::new();
    let mut faces: HashMap<String, FaceDef> = HashMap::new();
    let mut defined: HashMap<String, usize> = HashMap::new();
    let mut mesh_stmt: Option<(usize, Vec<(String, usize)>)> = None;
    while p.peek().is_some() {
        let (name, line) = p.ident("a name at the start of a statement")?;
        p.punct('=', &format!("`=` after `{name}`"))?;
        if name != "mesh" {
            if let Some(first) = defined.get(&name) {
                return Err(syntax(
                    line,
                    format!("`{name}` is already defined (line {first})"),
                ));
            }
            defined.insert(name.clone(), line);
        }
        match p.peek() {
            Some(Tok::Punct('(')) => {
                let vertex = parse_point(&mut p, &name, line)?;
                points.push((name, vertex));
            }
            Some(Tok::Punct('[')) => {
                p.pos += 1;
                let names = name_list(&mut p, ']', "vertex")?;
                if names.len() != 3 {
                    return Err(syntax(
                        line,
                        format!(
                            "face `{name}` has {} vertices; only triangles are supported",
                            names.len()
                        ),
                    ));
                }
                faces.insert(name, FaceDef { names });
            }
            Some(Tok::Punct('{')) => {
                if name != "mesh" {
                    return Err(syntax(
                        line,
                        format!("a face list in braces must be `mesh = {{…}};`, found `{name}`"),
                    ));
                }
                if let Some((first, _)) = mesh_stmt {
                    return Err(syntax(
                        line,
                        format!("second `mesh` statement (the first is at line {first})"),
                    ));
                }
                p.pos += 1;
                mesh_stmt = Some((line, name_list(&mut p, '}', "face")?));
            }
            _ => {
                return p.fail(&format!(
                    "`(Point . …)`, `[` (a face) or `{{` (the mesh) after `{name} =`"
                ))
            }
        }
        if !p.eat(';') {
            let prev = p
                .pos
                .checked_sub(1)
                .and_then(|i| p.toks.get(i))
                .map_or(line, |t| t.1);
            return Err(syntax(
                prev,
                format!(
                    "expected `;` at the end of the statement, found {}",
                    p.found()
                ),
            ));
        }
    }
    let (mesh_line, mesh_faces) = mesh_stmt.ok_or_else(|| {
        syntax(
            last_line,
            "no `mesh = {…};` statement: the mesh has no faces",
        )
    })?;

    let index: HashMap<&str, usize> = points
        .iter()
        .enumerate()
        .map(|(i, (n, _))| (n.as_str(), i))
        .collect();
    let mut tris = Vec::with_capacity(mesh_faces.len());
    let mut face_names = Vec::with_capacity(mesh_faces.len());
    for (fname, fline) in &mesh_faces {
        let def = faces.get(fname).ok_or_else(|| {
            let what = if index.contains_key(fname.as_str()) {
                "a point, not a face"
            } else {
                "not defined"
            };
            syntax(
                *fline,
                format!("mesh refers to unknown face `{fname}` ({what})"),
            )
        })?;
        let mut tri = [0; 3];
        for (slot, (vname, vline)) in tri.iter_mut().zip(&def.names) {
            *slot = *index.get(vname.as_str()).ok_or_else(|| {
                syntax(
                    *vline,
                    format!("face `{fname}` refers to unknown vertex `{vname}`"),
                )
            })?;
        }
        tris.push(tri);
        face_names.push(fname.clone());
    }
    let vertices: Vec<Vertex> = points.into_iter().map(|(_, v)| v).collect();
    let lines: Vec<usize> = mesh_faces.iter().map(|(_, l)| *l).collect();
    Mesh::new(vertices, tris)
        .map(|m| m.with_face_names(face_names.clone()))
        .map_err(|source| {
            let face = match &source {
                MeshError::MissingVertex { face, .. }
                | MeshError::RepeatedVertex { face, .. }
                | MeshError::ZeroArea { face, .. } => Some(*face),
                MeshError::InconsistentOrientation { faces, .. } => Some(faces[1]),
                MeshError::NonManifoldEdge { faces, .. } => faces.last().copied(),
                _ => None,
            };
            TestbedError::Mesh {
                line: face
                    .and_then(|f| lines.get(f).copied())
                    .unwrap_or(mesh_line),
                face_name: face.and_then(|f| face_names.get(f).cloned()),
                source,
            }
        })
}

/// Reads a mesh file in the testbed's format; errors name the file.
pub fn read_testbed_file(path: impl AsRef<Path>) -> Result<Mesh, TestbedError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| TestbedError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_testbed(&text).map_err(|e| TestbedError::InFile {
        path: path.to_path_buf(),
        source: Box::new(e),
    })
}

fn valid_name(s: &str) -> bool {
    let mut chars = s.chars();
    chars.next().is_some_and(|c| c.is_alphabetic() || c == '_')
        && chars.all(|c| c.is_alphanumeric() || c == '_')
        && s != "mesh"
}

fn list(xs: &[f64]) -> String {
    let parts: Vec<String> = xs.iter().map(|x| format!("{x}")).collect();
    format!("[{}]", parts.join(","))
}

/// Writes a mesh in the testbed's format: every vertex as a point (with `shape` when its
/// curvature is known, and its extra fields), every face, and the `mesh` statement. The names
/// of the mesh are used when they are valid and unique; otherwise vertices are named `v0, v1,
/// …` and faces `f0, f1, …`. Numbers are written in Rust's shortest round-trip form, so
/// reading the output gives the same mesh.
pub fn write_testbed(mesh: &Mesh) -> String {
    let mut vnames: Vec<String> = mesh
        .vertices()
        .iter()
        .map(|v| v.name.clone().unwrap_or_default())
        .collect();
    let mut fnames: Vec<String> = (0..mesh.num_faces())
        .map(|f| mesh.face_name(f).unwrap_or_default().to_string())
        .collect();
    let mut seen = std::collections::HashSet::new();
    let all_ok = vnames
        .iter()
        .chain(&fnames)
        .all(|n| valid_name(n) && seen.insert(n.clone()));
    if !all_ok {
        vnames = (0..vnames.len()).map(|i| format!("v{i}")).collect();
        fnames = (0..fnames.len()).map(|i| format!("f{i}")).collect();
    }
    let mut out = String::from("% Mesh written by the surface crate (testbed format).\n");
    for (v, name) in mesh.vertices().iter().zip(&vnames) {
        let d = &v.data;
        let _ = write!(
            out,
            "{name} = (Point . (pos . {}) (norm . {})",
            list(d.p.coords.as_slice()),
            list(d.n.as_slice())
        );
        if v.curvature_known {
            let rows: Vec<f64> = (0..3)
                .flat_map(|i| (0..3).map(move |j| (i, j)))
                .map(|(i, j)| d.shape[(i, j)])
                .collect();
            let _ = write!(out, " (shape . {})", list(&rows));
        }
        for (k, vals) in &v.extra {
            let _ = write!(out, " ({k} . {})", list(vals));
        }
        out.push_str(");\n");
    }
    for (face, name) in mesh.faces().iter().zip(&fnames) {
        let _ = writeln!(
            out,
            "{name} = [{},{},{}];",
            vnames[face[0]], vnames[face[1]], vnames[face[2]]
        );
    }
    let _ = writeln!(out, "mesh = {{{}}};", fnames.join(","));
    out
}

/// Writes [`write_testbed`]'s text to `path` through a temporary file renamed into place, so an
/// existing file is never left half-written.
pub fn write_testbed_file(mesh: &Mesh, path: impl AsRef<Path>) -> Result<(), TestbedError> {
    crate::obj::write_atomically(path.as_ref(), write_testbed(mesh).as_bytes()).map_err(|source| {
        TestbedError::Io {
            path: path.as_ref().to_path_buf(),
            source,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line_of(text: &str) -> (usize, String) {
        match read_testbed(text) {
            Err(TestbedError::Syntax { line, message }) => (line, message),
            Err(TestbedError::Mesh { line, source, .. }) => (line, source.to_string()),
            other => panic!("expected a syntax error, got {other:?}"),
        }
    }

    const TWO: &str = "% two triangles\n\
        a = (Point . (pos . [0,0,0]) (norm . [0,0,1]));\n\
        b = (Point . (pos . [1,0,0]) (norm . [0,0,1]));\n\
        c = (Point . (pos . [0,1,0]) (norm . [0,0,1]));\n\
        d = (Point . (pos . [1,1,0]) (norm . [0,0,1]));\n\
        T1 = [a,b,c];\n\
        T2 = [b,d,c];\n\
        mesh = {T1,T2};\n";

    #[test]
    fn reads_a_small_mesh() {
        let m = read_testbed(TWO).unwrap();
        assert_eq!((m.num_vertices(), m.num_faces(), m.num_edges()), (4, 2, 5));
        assert_eq!(m.face_name(1), Some("T2"));
        assert_eq!(m.vertex(3).unwrap().name.as_deref(), Some("d"));
        assert!(!m.vertex(0).unwrap().curvature_known);
        assert_eq!(m.vertex(0).unwrap().data.shape, Matrix3::zeros());
    }

    #[test]
    fn malformed_inputs_name_their_line() {
        let bad = TWO.replace("[1,0,0]) (norm", "[1,0,0,0]) (norm");
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 3);
        assert!(msg.contains("expected `]` after 3 coordinates"), "{msg}");

        let bad = TWO.replace("[0,1,0]) (norm", "[0,1]) (norm");
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 4);
        assert!(msg.contains("`,` after 2 coordinate(s) of `pos`"), "{msg}");

        let bad = TWO.replace("T2 = [b,d,c]", "T2 = [b,q,c]");
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 7);
        assert!(msg.contains("unknown vertex `q`"), "{msg}");

        let bad = TWO.replace("T2 = [b,d,c]", "T2 = [b,d,c,a]");
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 7);
        assert!(msg.contains("has 4 vertices"), "{msg}");

        let bad = TWO.replace("mesh = {T1,T2};\n", "");
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 8);
        assert!(msg.contains("no `mesh"), "{msg}");

        let bad = TWO.replace("mesh = {T1,T2}", "mesh = {T1,T3}");
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 8);
        assert!(msg.contains("unknown face `T3`"), "{msg}");

        let bad = TWO.replace("(norm . [0,0,1]));\nc", "(norm . [0,0,1]))\nc");
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 3);
        assert!(msg.contains("expected `;`"), "{msg}");

        let bad = TWO.replace(
            "c = (Point . (pos . [0,1,0]) (norm . [0,0,1]));",
            "c = (Point . (pos . [0,1,0]));",
        );
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 4);
        assert!(msg.contains("no `norm`"), "{msg}");

        let bad = TWO.replace("d = (Point", "c = (Point");
        let (line, msg) = line_of(&bad);
        assert_eq!(line, 5);
        assert!(msg.contains("already defined (line 4)"), "{msg}");

        // [c,d,b] runs b→c, as T1 = [a,b,c] does: the orientations disagree.
        let bad = TWO.replace("T2 = [b,d,c]", "T2 = [c,d,b]");
        match read_testbed(&bad) {
            Err(TestbedError::Mesh {
                line, face_name, ..
            }) => {
                assert_eq!(line, 8);
                assert_eq!(face_name.as_deref(), Some("T2"));
            }
            other => panic!("expected a mesh error, got {other:?}"),
        }
    }

    #[test]
    fn extra_fields_and_shape_round_trip() {
        let text = "p = (Point . (pos . [0,0,1]) (norm . [0,0,2]) (shape . [-1,0,0, 0,-1,0, 0,0,0]) (weight . 0.25) (k . [[1,2],[3]]));\n\
            q = (Point . (pos . [1,0,0]) (norm . [1,0,0]));\n\
            r = (Point . (pos . [0,1,0]) (norm . [0,1,0]));\n\
            F = [q,r,p];\nmesh = {F};";
        let m = read_testbed(text).unwrap();
        let p = m.vertex(0).unwrap();
        assert!(p.curvature_known);
        assert_eq!(p.data.n, Vector3::z());
        assert_eq!(p.data.shape[(0, 0)], -1.0);
        assert_eq!(p.extra.get("weight"), Some(&vec![0.25]));
        assert_eq!(p.extra.get("k"), Some(&vec![1.0, 2.0, 3.0]));
        let again = read_testbed(&write_testbed(&m)).unwrap();
        assert_eq!(again, m);
    }
}
