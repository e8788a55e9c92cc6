//! `kcolor`, the seed's KColor: a diverging colour of a curvature (`kg` or `km`) at every
//! vertex of every `Triangle` and `TriangleMesh` (`crate::binders`, the range from the first
//! block unless given); other records pass through.

use crate::binders::{colour, robust_max, Colouring, DEFAULT_BLOCK, MAX_BLOCK};
use crate::error::{FieldError, FilterError};
use crate::filters::Filter;
use crate::options;
use crate::pipe::StreamOptions;
use crate::record::Vertex;

/// Options of `kcolor`.
#[derive(clap::Args, Debug)]
pub struct KColorArgs {
    /// Colour range `A:B` (mapped onto blue–grey–red).
    #[arg(long, allow_hyphen_values = true)]
    pub range: Option<String>,
    /// Without --range: triangles held to fix the range before streaming (0: the whole
    /// stream, up to 4194304 triangles; at most 4194304).
    #[arg(long, default_value_t = DEFAULT_BLOCK as u64,
          value_parser = clap::value_parser!(u64).range(0..=MAX_BLOCK as u64))]
    pub block: u64,
    /// Which curvature: kg (Gaussian) or km (mean).
    #[arg(long, default_value = "kg")]
    pub field: String,
}

/// KColor: a diverging colour of a curvature (`kg` by default), white-grey at zero (`testbed
/// kcolor`, and its colouring).
pub struct KColor;

impl Colouring for KColor {
    fn name(&self) -> &'static str {
        Self::NAME
    }
    fn value(&self, v: &Vertex, field: &str) -> Result<Option<f64>, FieldError> {
        let x = match field {
            "km" => v.km,
            _ => v.kg,
        };
        x.map(Some).ok_or_else(|| {
            FieldError::new(
                format!("vertex.{field}"),
                format!("missing: run tess with --{field}"),
            )
        })
    }
    fn color(&self, value: f64, (lo, hi): (f64, f64)) -> [f32; 3] {
        // [lo, hi] onto [−1, 1] of the diverging map (for a symmetric range: value / hi).
        let t = -1.0 + 2.0 * (value - lo) / (hi - lo).max(f64::MIN_POSITIVE);
        render::colors::diverging(t, 1.0)
    }
    fn default_range(&self, values: &mut [f64]) -> (f64, f64) {
        let m = robust_max(values);
        (-m, m)
    }
}

impl Filter for KColor {
    const NAME: &'static str = "kcolor";
    const SUMMARY: &'static str = "\
        Diverging colours of the curvature (default range ±the 95% quantile of |kg| over the \
        first --block triangles)";
    const DESCRIPTION: &'static str = "\
        The curvature must be in the records (tess --kg, --km). Without --range the first \
        --block triangles are held, the range is taken from them and printed on standard error, \
        and the rest of the stream is coloured as it comes with the same range. Sets `color` in \
        each vertex of a Triangle and in the `color` column of a TriangleMesh, in place when \
        present, appended otherwise; records of other types keep their place (written at once \
        while no triangle is held). What is held stays within 64 MiB of memory; the rest waits \
        in a temporary file, removed when the filter ends. A stream without a Triangle or \
        TriangleMesh is an error (exit 1; `tess` goes before kcolor).";
    const SEED: &'static str = "KColor";
    type Args = KColorArgs;

    fn run(args: KColorArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let field = args.field;
        if field != "kg" && field != "km" {
            return Err(FilterError::Usage(format!(
                "kcolor --field {field}: kg or km"
            )));
        }
        let range = options::range(args.range.as_deref())?;
        // Within MAX_BLOCK by the option's parser.
        let block = usize::try_from(args.block).unwrap_or(MAX_BLOCK);
        stream.filter(Self::NAME, &mut |p| {
            colour(p, &KColor, &field, range, block)
        })
    }
}
