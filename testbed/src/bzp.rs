//! The workspace's binary patch file (`surface::patch_io`'s `.bzp`: `experiments fit --out
//! FILE.bzp`, `testbed fit --format bzp`) as a stream the filters read: after its magic and
//! header line, one patch at a time becomes the `BezierTriangle` record
//! `surface::patch_io::record_of` defines (or a `SampledPatch` for an evaluated layout,
//! which the filters pass on), without the file being held: a header promising 10¹⁸ patches
//! costs nothing until they are read, and a file that ends inside a patch is an error naming it.

use std::io::BufRead;

use surface::patch_io::{record_of, BinaryHeader, RecordKind, BINARY_MAGIC};

use crate::tape::Tape;

/// Longest header line accepted: the writer's is under 200 bytes; a header this long is not
/// one (and is not read into memory whole).
pub const MAX_HEADER_BYTES: usize = 4096;

/// Most points a patch may have: a degree-32 Bézier net (the pipeline's largest degree,
/// `record::MAX_DEGREE`) has 561; 4096 leaves room for evaluated layouts and refuses a header
/// that would make one record gigabytes.
pub const MAX_POINTS_PER_PATCH: usize = 4096;

/// Reads the patches of a `.bzp` stream whose magic has been recognised.
#[derive(Debug, Default)]
pub struct Decoder {
    header: Option<BinaryHeader>,
    /// Patches read so far.
    read: usize,
    buf: Vec<u8>,
}

impl Decoder {
    /// Reads the magic (the first byte may still be unread) and the header line.
    pub fn start<R: BufRead>(&mut self, r: &mut R) -> Result<(), String> {
        let mut magic = vec![0u8; BINARY_MAGIC.len()];
        std::io::Read::read_exact(r, &mut magic).map_err(|e| format!("reading the magic: {e}"))?;
        if magic != BINARY_MAGIC {
            return Err("not a binary patch file (no BEZPATCH1 magic)".into());
        }
        let mut line = Vec::new();
        let mut limited = std::io::Read::take(&mut *r, MAX_HEADER_BYTES as u64);
        limited
            .read_until(b'\n', &mut line)
            .map_err(|e| format!("reading the header: {e}"))?;
        if line.last() != Some(&b'\n') {
            return Err(format!(
                "the header line does not end within {MAX_HEADER_BYTES} bytes"
            ));
        }
        line.pop();
        let header = BinaryHeader::parse(&line).map_err(|e| e.to_string())?;
        if header.points_per_patch == 0 || header.points_per_patch > MAX_POINTS_PER_PATCH {
            return Err(format!(
                "{} points a patch (1 to {MAX_POINTS_PER_PATCH} are readable)",
                header.points_per_patch
            ));
        }
        if header.form.is_none() && header.degree > crate::record::MAX_DEGREE {
            return Err(format!(
                "degree {} (at most {} is readable)",
                header.degree,
                crate::record::MAX_DEGREE
            ));
        }
        if header.patches().is_none() {
            return Err("the header's patch count overflows".into());
        }
        self.header = Some(header);
        self.read = 0;
        Ok(())
    }

    /// The next patch into `tape`: `Ok(false)` after the last one the header promises.
    pub fn next_into<R: BufRead>(&mut self, r: &mut R, tape: &mut Tape) -> Result<bool, String> {
        let Some(h) = &self.header else {
            return Err("the stream has no header".into());
        };
        if self.read >= h.patches().unwrap_or(0) {
            return Ok(false);
        }
        let np = h.points_per_patch;
        self.buf.resize(np * 24, 0);
        std::io::Read::read_exact(r, &mut self.buf).map_err(|_| {
            format!(
                "the file ends inside patch {} of {} (face {})",
                self.read,
                h.patches().unwrap_or(0),
                self.read / h.patches_per_face.max(1)
            )
        })?;
        let value = |k: usize| {
            let mut a = [0u8; 8];
            a.copy_from_slice(&self.buf[8 * k..8 * k + 8]);
            f64::from_le_bytes(a)
        };
        let points: Vec<nalgebra::Point3<f64>> = (0..np)
            .map(|k| nalgebra::Point3::new(value(3 * k), value(3 * k + 1), value(3 * k + 2)))
            .collect();
        if let Some(k) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(format!("patch {}: point {k} is not finite", self.read));
        }
        let kind = match &h.form {
            None => RecordKind::Bezier { degree: h.degree },
            Some(form) => RecordKind::Sampled { form },
        };
        let record = record_of(kind, h.patches_per_face, self.read, &points);
        *tape = Tape::from_value(&serde_json::Value::Object(record));
        self.read += 1;
        Ok(true)
    }
}
