//! `kcolor`, the seed's KColor: a colour of a curvature (`kg` or `km`) at every vertex of
//! every `Triangle` and `TriangleMesh` (`crate::binders`); other records pass through. Two
//! maps (`--map`): the workbench's diverging map (default; the range from the first block
//! unless given) and the original testbed's HLS hue ramp (`render::colors::testbed_kcolor`,
//! its fixed range `[−4, 4]` unless given).

use crate::binders::{colour, robust_max, Colouring, DEFAULT_BLOCK, MAX_BLOCK};
use crate::error::{FieldError, FilterError};
use crate::filters::Filter;
use crate::options;
use crate::pipe::StreamOptions;
use crate::record::Vertex;

/// Options of `kcolor`.
#[derive(clap::Args, Debug)]
pub struct KColorArgs {
    /// Colour range `A:B` (mapped onto blue–grey–red, or with --map testbed onto blue–green–red;
    /// that map's default is the testbed's -4:4).
    #[arg(long, allow_hyphen_values = true)]
    pub range: Option<String>,
    /// Colour map: diverging (blue – light grey – red, Moreland) or testbed (the original
    /// testbed's hue ramp, HLS at lightness 0.5 and saturation 0.9, hue 240° – 120° – 0° with
    /// exponent 0.625).
    #[arg(long, value_enum, default_value_t = KColorMap::Diverging)]
    pub map: KColorMap,
    /// Without --range: triangles held to fix the range before streaming (0: the whole
    /// stream, up to 4194304 triangles; at most 4194304).
    #[arg(long, default_value_t = DEFAULT_BLOCK as u64,
          value_parser = clap::value_parser!(u64).range(0..=MAX_BLOCK as u64))]
    pub block: u64,
    /// Which curvature: kg (Gaussian) or km (mean).
    #[arg(long, default_value = "kg")]
    pub field: String,
}

/// The colour maps of `kcolor`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum KColorMap {
    /// Blue – light grey – red, centred on zero ([`render::colors::diverging`]).
    #[default]
    Diverging,
    /// The original testbed's HLS hue ramp ([`render::colors::testbed_kcolor`]).
    Testbed,
}

impl KColorMap {
    /// The colour of `value` over `(lo, hi)`.
    pub fn colour_of(self, value: f64, (lo, hi): (f64, f64)) -> [f32; 3] {
        match self {
            KColorMap::Diverging => {
                // [lo, hi] onto [−1, 1] of the diverging map (for a symmetric range: value / hi).
                let t = -1.0 + 2.0 * (value - lo) / (hi - lo).max(f64::MIN_POSITIVE);
                render::colors::diverging(t, 1.0)
            }
            KColorMap::Testbed => render::colors::testbed_kcolor(value, (lo, hi)),
        }
    }

    /// The range used without `--range`: from the data for the diverging map (`None`: the
    /// first block decides), the testbed's fixed `[−4, 4]` for its map.
    pub fn fixed_range(self) -> Option<(f64, f64)> {
        match self {
            KColorMap::Diverging => None,
            KColorMap::Testbed => Some(render::colors::TESTBED_KCOLOR_RANGE),
        }
    }
}

/// KColor: a colour of a curvature (`kg` by default), `testbed kcolor`; as a colouring, the
/// default map's ([`KColorMap::Diverging`]; each [`KColorMap`] is a colouring too).
pub struct KColor;

impl Colouring for KColorMap {
    fn name(&self) -> &'static str {
        KColor::NAME
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
    fn color(&self, value: f64, range: (f64, f64)) -> [f32; 3] {
        self.colour_of(value, range)
    }
    fn default_range(&self, values: &mut [f64]) -> (f64, f64) {
        self.fixed_range().unwrap_or_else(|| {
            let m = robust_max(values);
            (-m, m)
        })
    }
}

impl Colouring for KColor {
    fn name(&self) -> &'static str {
        Self::NAME
    }
    fn value(&self, v: &Vertex, field: &str) -> Result<Option<f64>, FieldError> {
        KColorMap::default().value(v, field)
    }
    fn color(&self, value: f64, range: (f64, f64)) -> [f32; 3] {
        KColorMap::default().colour_of(value, range)
    }
    fn default_range(&self, values: &mut [f64]) -> (f64, f64) {
        Colouring::default_range(&KColorMap::default(), values)
    }
}

impl Filter for KColor {
    const NAME: &'static str = "kcolor";
    const SUMMARY: &'static str = "\
        Colours of the curvature: diverging (default range ±the 95% quantile of |kg| over the \
        first --block triangles) or the testbed's hue ramp (--map testbed, range -4:4)";
    const DESCRIPTION: &'static str = "\
        The curvature must be in the records (tess --kg, --km). With --map testbed the range \
        is the original testbed's -4:4 unless --range is given, and nothing is held. For the \
        diverging map without --range the first \
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
        let range = options::range(args.range.as_deref())?.or(args.map.fixed_range());
        let map = args.map;
        // Within MAX_BLOCK by the option's parser.
        let block = usize::try_from(args.block).unwrap_or(MAX_BLOCK);
        stream.filter(Self::NAME, &mut |p| colour(p, &map, &field, range, block))
    }
}
