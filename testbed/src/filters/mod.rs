//! The pipeline's filters, one module a filter, and their registry ([`FILTERS`]): the seed's
//! Fitter0/Nielson ([`fit`](mod@fit)), Tess, G1, Mat0, KColor, Radial, and its ends Render,
//! XRender and a mesh file. `testbed` builds its command line from the registry, in its
//! order, and `testbed/README.md`'s table of filters is rendered from it
//! ([`markdown_table`], checked by the tests).
//!
//! **A filter** is a unit struct implementing [`Filter`]: its name, a one-line summary (the
//! `testbed --help` line and the README's), optionally a longer description (`testbed NAME
//! --help`), its own options as one `clap::Args` struct, and how it runs given them and the
//! options every filter takes ([`StreamOptions`]: `--input`, `--output`, `--format`,
//! `--keep-going`). Adding a filter is a module here (and its `pub mod` line) and one line in
//! the registry, [`FILTERS`].
//!
//! **Pass-through.** Every filter writes the records it does not use unchanged and in order,
//! and keeps the fields it does not use in the records it changes, in order:
//!
//! * `tess` turns each `BezierTriangle` into `s²` `Triangle`s; each triangle gets the three
//!   vertex fields first, then **every field of its patch except `type`, `degree` and
//!   `points`** (the fields tess consumes, [`TESS_CONSUMES`]), in the patch's order: `face`,
//!   `subpatch`, `scheme` and anything added upstream (a `provenance`) reach the triangles;
//! * `tess --mesh` writes one `TriangleMesh` per patch instead (`crate::triangle_mesh`): its
//!   vertex columns and `triangles` first, then the same carried fields;
//! * `mat0`, `kcolor`, `radial` set `color` (and `radial` also `dist`) in each vertex object
//!   of a `Triangle`, and the `color` (and `dist`) column of a `TriangleMesh`, in place when
//!   present, appended otherwise (`crate::binders`);
//! * `g1` writes every record unchanged.
//!
//! Records of other types pass through all of them. Malformed records are errors naming the
//! record number, its line and the field; with `keep_going` they are skipped (not written),
//! counted and reported on standard error.
//!
//! The shared machinery lives beside this module: the streams and the [`Pipe`]
//! (`crate::pipe`), samples and the `Triangle` records built from them (`crate::sample`), the
//! patch tessellator (`crate::tessellator`), the colour binders (`crate::binders`), the
//! pictures (`crate::draw`). The names this module exported before it was split are
//! re-exported here.

use clap::{ArgMatches, Args, Command, FromArgMatches};

use crate::error::FilterError;

pub use crate::binders::{colour, robust_max, Colouring, DEFAULT_BLOCK, ROBUST_QUANTILE};
pub use crate::pipe::{Pipe, StreamOptions, REPORTED_SKIPS};
pub use crate::sample::{
    carried_fields, sample_value, triangle_value, CurvatureFields, Sample, TESS_CONSUMES,
};
pub use crate::tessellator::{tessellate_patch, IndexedPatch, PatchTessellator};
pub use kcolor::KColor;
pub use mat0::Mat0;
pub use radial::SurfaceDistance;
pub use tess::{check_tess_memory, tess, TessRecords, MAX_SEGMENTS};

/// A filter of the pipeline: one subcommand of `testbed`.
///
/// Its options are declared once, as the fields of [`Filter::Args`]; the stream options are
/// added to every filter after them. The command line is built from the registry
/// ([`Registered::command`]), so the name, summary and options are all the filter says.
pub trait Filter {
    /// The subcommand's name (`tess`, `to-mesh`).
    const NAME: &'static str;
    /// One line, no final period: what the filter reads and writes. Listed by `testbed
    /// --help` and in the README's table of filters.
    const SUMMARY: &'static str;
    /// More about it, after the summary in `testbed NAME --help` (empty: the summary alone).
    const DESCRIPTION: &'static str = "";
    /// The module(s) of the seed testbed (Lounsbery et al. 1990) the filter stands for, for
    /// the README's table (empty: none).
    const SEED: &'static str = "";
    /// The filter's own options (not the stream options, which every filter takes).
    type Args: Args + 'static;
    /// Runs the filter with its options over the streams `stream` names.
    fn run(args: Self::Args, stream: StreamOptions) -> Result<(), FilterError>;
}

/// A filter parsed from its command line, ready to run.
pub type Job = Box<dyn FnOnce() -> Result<(), FilterError>>;

/// A [`Filter`] as the registry holds it, its options' type erased (implemented for every
/// filter).
pub trait Registered: Sync {
    /// [`Filter::NAME`].
    fn name(&self) -> &'static str;
    /// [`Filter::SUMMARY`].
    fn summary(&self) -> &'static str;
    /// [`Filter::DESCRIPTION`] (empty when there is none).
    fn description(&self) -> &'static str;
    /// [`Filter::SEED`] (empty when there is none).
    fn seed(&self) -> &'static str;
    /// The subcommand: the filter's options, then the stream options; the summary as its
    /// `about`, with the description as its long help.
    fn command(&self) -> Command;
    /// The filter's options and the stream options from the subcommand's matches (a clap
    /// error if they do not fit the command, which [`Registered::command`] rules out).
    fn parse(&self, matches: &ArgMatches) -> Result<Job, clap::Error>;
}

impl<F: Filter + Sync + 'static> Registered for F {
    fn name(&self) -> &'static str {
        F::NAME
    }

    fn summary(&self) -> &'static str {
        F::SUMMARY
    }

    fn description(&self) -> &'static str {
        F::DESCRIPTION
    }

    fn seed(&self) -> &'static str {
        F::SEED
    }

    fn command(&self) -> Command {
        let command = StreamOptions::augment_args(F::Args::augment_args(Command::new(F::NAME)));
        // Set last: a derived `Args` sets its own doc comment as the command's about.
        let command = command.about(F::SUMMARY);
        if F::DESCRIPTION.is_empty() {
            command.long_about(None)
        } else {
            command.long_about(format!("{}.\n\n{}", F::SUMMARY, F::DESCRIPTION))
        }
    }

    fn parse(&self, matches: &ArgMatches) -> Result<Job, clap::Error> {
        let args = F::Args::from_arg_matches(matches)?;
        let stream = StreamOptions::from_arg_matches(matches)?;
        Ok(Box::new(move || F::run(args, stream)))
    }
}

pub mod fit;
pub mod g1;
pub mod kcolor;
pub mod mat0;
pub mod radial;
pub mod render;
pub mod tess;
pub mod to_mesh;
pub mod wire;

/// The registry: every filter, one line each, in the order `testbed --help` and the README
/// list them.
pub static FILTERS: &[&dyn Registered] = &[
    &fit::Fit,
    &tess::Tess,
    &g1::G1,
    &mat0::Mat0,
    &kcolor::KColor,
    &radial::Radial,
    &render::Render,
    &wire::Wire,
    &to_mesh::ToMesh,
];

/// The registered filter named `name`.
pub fn find(name: &str) -> Option<&'static dyn Registered> {
    FILTERS.iter().copied().find(|f| f.name() == name)
}

/// The README's table of filters: one row a filter, in registry order: its name, its summary
/// and the seed's module(s) it stands for (`—` for none), as Markdown (`|` escaped).
pub fn markdown_table() -> String {
    let cell = |s: &str| s.replace('|', "\\|");
    let mut table = String::from("| filter | what it does | seed module |\n|---|---|---|\n");
    for f in FILTERS {
        let seed = if f.seed().is_empty() { "—" } else { f.seed() };
        table.push_str(&format!(
            "| `{}` | {} | {} |\n",
            f.name(),
            cell(f.summary()),
            cell(seed)
        ));
    }
    table
}
