//! `mat0`, the seed's Mat0: the uniform material colour at every vertex of every `Triangle`
//! and `TriangleMesh` (`crate::binders`); other records pass through.

use crate::binders::{colour, Colouring};
use crate::error::{FieldError, FilterError};
use crate::filters::Filter;
use crate::pipe::StreamOptions;
use crate::record::Vertex;

/// Options of `mat0`: none but the stream's.
#[derive(clap::Args, Debug)]
pub struct Mat0Args {}

/// Mat0: the uniform material colour (`testbed mat0`, and its colouring).
pub struct Mat0;

impl Colouring for Mat0 {
    fn name(&self) -> &'static str {
        Self::NAME
    }
    fn data_dependent(&self) -> bool {
        false
    }
    fn value(&self, _: &Vertex, _: &str) -> Result<Option<f64>, FieldError> {
        Ok(None)
    }
    fn color(&self, _: f64, _: (f64, f64)) -> [f32; 3] {
        render::colors::MATERIAL
    }
    fn default_range(&self, _: &mut [f64]) -> (f64, f64) {
        (0.0, 1.0)
    }
}

impl Filter for Mat0 {
    const NAME: &'static str = "mat0";
    const SUMMARY: &'static str = "The uniform material colour at every vertex";
    const DESCRIPTION: &'static str = "\
        Sets `color` in each vertex of a Triangle and in the `color` column of a TriangleMesh, \
        in place when present, appended otherwise. Records of other types pass through \
        unchanged. A stream without a Triangle or TriangleMesh is an error (exit 1; `tess` goes \
        before mat0).";
    const SEED: &'static str = "Mat0";
    type Args = Mat0Args;

    fn run(_: Mat0Args, stream: StreamOptions) -> Result<(), FilterError> {
        stream.filter(Self::NAME, &mut |p| colour(p, &Mat0, "", None, 0))
    }
}
