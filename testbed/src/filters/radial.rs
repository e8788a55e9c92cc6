//! `radial`, the seed's Radial: a sequential colour of the distance to the true surface (a
//! data set's analytic surface), and the distance itself as `dist`, at every vertex of every
//! `Triangle` and `TriangleMesh` (`crate::binders`); other records pass through.

use crate::binders::{colour, robust_max, Colouring, DEFAULT_BLOCK, MAX_BLOCK};
use crate::error::{FieldError, FilterError};
use crate::filters::Filter;
use crate::options;
use crate::pipe::StreamOptions;
use crate::record::Vertex;

/// `testbed radial`.
pub struct Radial;

/// Options of `radial`.
#[derive(clap::Args, Debug)]
pub struct RadialArgs {
    /// The true surface: ring, sphere, capsule (octa lies on the unit sphere).
    #[arg(long)]
    pub surface: String,
    /// Colour range `A:B` of |distance| (default 0 to its 95% quantile over the first
    /// --block triangles).
    #[arg(long, allow_hyphen_values = true)]
    pub range: Option<String>,
    /// Without --range: triangles held to fix the range before streaming (0: the whole
    /// stream, up to 4194304 triangles; at most 4194304).
    #[arg(long, default_value_t = DEFAULT_BLOCK as u64,
          value_parser = clap::value_parser!(u64).range(0..=MAX_BLOCK as u64))]
    pub block: u64,
}

impl Filter for Radial {
    const NAME: &'static str = "radial";
    const SUMMARY: &'static str =
        "Sequential colours of the distance to the true surface (and `dist` at each vertex)";
    const DESCRIPTION: &'static str = "\
        The distance is signed (`dist`), the colour follows its magnitude. Without --range the \
        first --block triangles are held, the range is taken from them and printed on standard \
        error, and the rest of the stream is coloured as it comes with the same range. Sets \
        `color` and `dist` in each vertex of a Triangle and as columns of a TriangleMesh, in \
        place when present, appended otherwise; records of other types keep their place \
        (written at once while no triangle is held). What is held stays within 64 MiB of \
        memory; the rest waits in a temporary file, removed when the filter ends. A stream \
        without a Triangle or TriangleMesh is an error (exit 1; `tess` goes before radial).";
    const SEED: &'static str = "Radial";
    type Args = RadialArgs;

    fn run(args: RadialArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let name = if args.surface == "octa" {
            "sphere"
        } else {
            args.surface.as_str()
        };
        if !["ring", "sphere", "capsule"].contains(&name) {
            return Err(FilterError::Usage(format!(
                "radial --surface {}: ring, sphere or capsule",
                args.surface
            )));
        }
        // The data set's analytic surface (the coarsest sampling: only the surface is used).
        let data = surface::dataset_by_name(name, Some(if name == "sphere" { 0 } else { 4 }))
            .or_else(|_| surface::dataset_by_name(name, None))?;
        let colouring = SurfaceDistance {
            surface: data.surface,
        };
        let range = options::range(args.range.as_deref())?;
        // Within MAX_BLOCK by the option's parser.
        let block = usize::try_from(args.block).unwrap_or(MAX_BLOCK);
        stream.filter(Self::NAME, &mut |p| colour(p, &colouring, "", range, block))
    }
}

/// Radial's colouring: a sequential colour of the distance to a true surface.
pub struct SurfaceDistance {
    /// The true surface.
    pub surface: std::sync::Arc<dyn surface::AnalyticSurface>,
}

impl Colouring for SurfaceDistance {
    fn name(&self) -> &'static str {
        Radial::NAME
    }
    fn value(&self, v: &Vertex, _: &str) -> Result<Option<f64>, FieldError> {
        Ok(Some(self.surface.signed_distance(&v.pos)))
    }
    fn color(&self, value: f64, (lo, hi): (f64, f64)) -> [f32; 3] {
        render::colors::sequential(value.abs(), lo, hi)
    }
    fn extra_field(&self) -> Option<&'static str> {
        Some("dist")
    }
    fn default_range(&self, values: &mut [f64]) -> (f64, f64) {
        (0.0, robust_max(values))
    }
}
