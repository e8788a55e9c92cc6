//! The scheme options of both command lines, generated from the scheme registry: `--scheme`
//! with the registered names as its possible values, and one option a scheme parameter
//! ([`surface::scheme::ParameterSpec`]: `--beta`, `--c`, `--phong-alpha`, …) with its default,
//! its range and the schemes that read it in `--help`. A scheme added to the registry with a
//! parameter reaches `experiments` and `testbed` with no other edit.
//!
//! `--curves` and `--estimate` take their possible values from their registries the same way
//! ([`curve_method_names`], [`estimator_names`]).
//!
//! (Built with the `cli` feature, which brings in `clap`; the library itself does not need it.)

use std::marker::PhantomData;

use clap::builder::PossibleValuesParser;
use clap::{Arg, ArgMatches, Command};
use surface::scheme::{parameters_of, SchemeEntry, SchemeOptions};

/// Whether a command line offers the subdivision schemes beside the registry's (`fit`, `sweep`)
/// or only the patch schemes (`ring`, the pipeline's `fit`).
pub trait SchemeSet: Clone + Send + Sync + 'static {
    /// The subdivision schemes offered (`subdiv::SCHEMES`' names, or none).
    fn subdivision() -> Vec<&'static str>;
}

/// The patch schemes and the subdivision schemes.
#[derive(Clone, Copy, Debug, Default)]
pub struct WithSubdivision;

impl SchemeSet for WithSubdivision {
    fn subdivision() -> Vec<&'static str> {
        subdiv::SCHEMES.iter().map(|e| e.name).collect()
    }
}

/// The patch schemes only.
#[derive(Clone, Copy, Debug, Default)]
pub struct PatchesOnly;

impl SchemeSet for PatchesOnly {
    fn subdivision() -> Vec<&'static str> {
        Vec::new()
    }
}

/// `--scheme` and every scheme parameter's option (flatten it into a clap command).
#[derive(Clone, Debug)]
pub struct SchemeArgs<S: SchemeSet = WithSubdivision> {
    /// The scheme named.
    pub scheme: String,
    /// The scheme parameters' values given (the others are at their defaults).
    pub options: SchemeOptions,
    set: PhantomData<S>,
}

impl<S: SchemeSet> SchemeArgs<S> {
    /// Whether the scheme named is a subdivision scheme.
    pub fn is_subdivision(&self) -> bool {
        S::subdivision().contains(&self.scheme.as_str())
    }
}

/// Adds `--scheme` (the names of `registry`, then `subdivision`) and one option a parameter of
/// `registry`'s schemes to `cmd`.
pub fn augment(cmd: Command, registry: &[SchemeEntry], subdivision: &[&'static str]) -> Command {
    let names: Vec<&'static str> = registry
        .iter()
        .map(|e| e.name)
        .chain(subdivision.iter().copied())
        .collect();
    let subdivision_help = if subdivision.is_empty() {
        String::new()
    } else {
        format!(
            "; the subdivision schemes {} with --levels",
            subdivision.join(", ")
        )
    };
    let mut cmd = cmd.arg(
        Arg::new("scheme")
            .long("scheme")
            .value_name("SCHEME")
            .default_value(surface::DEFAULT_SCHEME)
            .value_parser(PossibleValuesParser::new(names))
            .help(format!(
                "Surface scheme (the registry: {}{subdivision_help})",
                registry
                    .iter()
                    .map(|e| e.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
    );
    for (p, owners) in parameters_of(registry) {
        cmd = cmd.arg(
            Arg::new(p.name)
                .long(p.name)
                .value_name(p.symbol)
                .value_parser(clap::value_parser!(f64))
                .help(format!(
                    "{} [{}; range {}..={}; default: {}]",
                    capitalized(p.summary),
                    owners.join(", "),
                    p.range.0,
                    p.range.1,
                    p.default
                )),
        );
    }
    cmd
}

/// The scheme named and the parameter values of `matches` (made by a command [`augment`]ed
/// with the same `registry`): the values given, the others at their declared defaults.
pub fn from_matches(matches: &ArgMatches, registry: &[SchemeEntry]) -> (String, SchemeOptions) {
    let scheme = matches
        .get_one::<String>("scheme")
        .cloned()
        .unwrap_or_else(|| surface::DEFAULT_SCHEME.to_string());
    let mut options = SchemeOptions::default();
    for (p, _) in parameters_of(registry) {
        if let Some(v) = matches.get_one::<f64>(p.name) {
            options.set(p, *v);
        }
    }
    (scheme, options)
}

/// The registered curve constructions as the values `--curves` accepts (listed in `--help`).
pub fn curve_method_names() -> PossibleValuesParser {
    PossibleValuesParser::new(curves::REGISTRY.iter().map(|e| e.name))
}

/// How creases are found (`--crease-angle DEG`, `--no-creases`); by default the file's creases
/// and, on tessellated models, edges over 40° (`mesh::features::CreaseRule::Auto`, the rules
/// in docs/conventions.md).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct CreaseArgs {
    /// Edges whose faces' planes meet at more than DEG degrees (0 < DEG ≤ 180) are creases, on
    /// every part of the mesh (scans included); the file's marked creases too. Default: 40° on
    /// tessellated models only, the file's creases everywhere.
    #[arg(long, value_name = "DEG", value_parser = parse_crease_angle, conflicts_with = "no_creases")]
    pub crease_angle: Option<f64>,
    /// No creases at all, not even those the file marks: one normal per vertex.
    #[arg(long)]
    pub no_creases: bool,
}

impl CreaseArgs {
    /// The rule these options ask for.
    pub fn rule(&self) -> mesh::features::CreaseRule {
        use mesh::features::CreaseRule;
        match (self.no_creases, self.crease_angle) {
            (true, _) => CreaseRule::None,
            (false, Some(d)) => CreaseRule::Angle(d),
            (false, None) => CreaseRule::Auto,
        }
    }
}

/// `--crease-angle`'s value: degrees in (0, 180].
fn parse_crease_angle(s: &str) -> Result<f64, String> {
    let d: f64 = s
        .parse()
        .map_err(|_| format!("`{s}` is not a number of degrees"))?;
    if d > 0.0 && d <= 180.0 {
        Ok(d)
    } else {
        Err(format!(
            "{s}° is out of range: a dihedral angle lies in (0, 180] degrees (180 finds no geometric crease)"
        ))
    }
}

/// The registered estimators and `none` as the values `--estimate` accepts.
pub fn estimator_names() -> PossibleValuesParser {
    PossibleValuesParser::new(
        estimate::ESTIMATORS
            .iter()
            .map(|e| e.name())
            .chain(std::iter::once("none")),
    )
}

fn capitalized(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

impl<S: SchemeSet> clap::FromArgMatches for SchemeArgs<S> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let (scheme, options) = from_matches(matches, surface::scheme::REGISTRY);
        Ok(SchemeArgs {
            scheme,
            options,
            set: PhantomData,
        })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl<S: SchemeSet> clap::Args for SchemeArgs<S> {
    fn augment_args(cmd: Command) -> Command {
        augment(cmd, surface::scheme::REGISTRY, &S::subdivision())
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use surface::scheme::{ParameterSpec, REGISTRY};

    /// A scheme added with a parameter of its own: `flat` under another name, with a parameter
    /// it ignores. Only its registry entry is new.
    const WIDTH: ParameterSpec = ParameterSpec {
        name: "test-width",
        symbol: "w",
        default: 0.5,
        range: (0.0, 2.0),
        range_reason: "a test",
        summary: "a test parameter",
    };

    fn registry_with_test_scheme() -> Vec<SchemeEntry> {
        let mut r: Vec<SchemeEntry> = REGISTRY
            .iter()
            .map(|e| SchemeEntry {
                name: e.name,
                summary: e.summary,
                parameters: e.parameters,
                build: e.build,
            })
            .collect();
        r.push(SchemeEntry {
            name: "test-scheme",
            summary: "a scheme added by a test",
            parameters: &[WIDTH],
            build: |_| Box::new(surface::scheme::flat::Flat),
        });
        r
    }

    #[test]
    fn a_new_scheme_with_a_parameter_is_in_the_generated_options() {
        let registry = registry_with_test_scheme();
        let mut cmd = augment(Command::new("t"), &registry, &[]);
        let help = cmd.render_help().to_string();
        assert!(help.contains("--test-width"), "{help}");
        assert!(
            help.contains("A test parameter [test-scheme; range 0..=2; default: 0.5]"),
            "{help}"
        );
        assert!(help.contains("test-scheme"), "{help}");
        let m = augment(Command::new("t"), &registry, &[])
            .try_get_matches_from(["t", "--scheme", "test-scheme", "--test-width", "1.5"])
            .expect("parses");
        let (scheme, options) = from_matches(&m, &registry);
        assert_eq!(scheme, "test-scheme");
        assert_eq!(options.value(&WIDTH), 1.5);
        let entry = registry.iter().find(|e| e.name == scheme).expect("entry");
        assert!(options.out_of_range(entry).is_none());
        assert_eq!((entry.build)(&options).name(), "flat");
        // Out of its declared range: refused by the same check every front end makes.
        let m = augment(Command::new("t"), &registry, &[])
            .try_get_matches_from(["t", "--scheme", "test-scheme", "--test-width", "3"])
            .expect("parses");
        let (_, options) = from_matches(&m, &registry);
        assert_eq!(
            options.out_of_range(entry).map(|(p, v)| (p.name, v)),
            Some(("test-width", 3.0))
        );
    }

    #[test]
    fn every_registered_parameter_is_an_option_with_its_default() {
        let m = augment(Command::new("t"), REGISTRY, &[])
            .try_get_matches_from(["t"])
            .expect("parses");
        let (scheme, options) = from_matches(&m, REGISTRY);
        assert_eq!(scheme, surface::DEFAULT_SCHEME);
        for e in REGISTRY {
            for p in e.parameters {
                assert_eq!(options.value(p), p.default, "{}", p.name);
            }
        }
        // The patch-only set offers no subdivision scheme; the other does.
        let loop_ok = augment(Command::new("t"), REGISTRY, &WithSubdivision::subdivision())
            .try_get_matches_from(["t", "--scheme", "loop"]);
        assert!(loop_ok.is_ok());
        let loop_refused = augment(Command::new("t"), REGISTRY, &PatchesOnly::subdivision())
            .try_get_matches_from(["t", "--scheme", "loop"]);
        assert!(loop_refused.is_err());
    }
}

/// `--solver`, `--dbhs-pick`, `--tweak-t`, `--four-ninths` and `--tangents`.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct CurveOptions {
    /// Solver of the optimized construction (and of `--interior` fairing); the names come from
    /// the solver registry.
    #[arg(long, default_value_t = solver::SolverKind::ExactPenalty, value_parser = solver_names())]
    pub solver: solver::SolverKind,
    /// Which dBHS solution to take: closest (to α = (1, 1)), longest-short (largest shorter
    /// tangent), or a solution index in order of increasing α0.
    #[arg(long, default_value_t = curves::DbhsPick::Closest)]
    pub dbhs_pick: curves::DbhsPick,
    /// The parameter t of `tweak`: its inner control points t of the way from each end to the
    /// end tangents' intersection, 0 < t ≤ 1 (`quadric` is t = 2/3).
    #[arg(long, default_value_t = curves::tweak::DEFAULT_TWEAK_T, value_name = "T",
          value_parser = parse_tweak_t, allow_hyphen_values = true)]
    pub tweak_t: f64,
    /// The four-ninths variants of `projection`, `projection-scaled` and `piper`: the point
    /// five ninths along the chord, (4/9) V_a + (5/9) V_b, projected instead of the third.
    #[arg(long)]
    pub four_ninths: bool,
    /// How the end tangents at a vertex are chosen: `star` (each edge's own, except in a
    /// sector where they leave a face corner that is not convex: there chosen together from
    /// the whole star, in the tangent plane, every corner convex) or `per-edge` (each edge's
    /// from its two end normals alone, as the seeds build them).
    #[arg(long, default_value_t = curves::TangentRule::Star, value_name = "RULE",
          value_parser = tangent_rules())]
    pub tangents: curves::TangentRule,
}

/// The tangent rules as the values `--tangents` accepts.
fn tangent_rules() -> impl clap::builder::TypedValueParser<Value = curves::TangentRule> {
    use clap::builder::TypedValueParser as _;
    PossibleValuesParser::new(curves::TangentRule::ALL.iter().map(|k| k.name()))
        .try_map(|name| name.parse::<curves::TangentRule>())
}

/// `--tweak-t`'s value: a number in (0, 1] (`curves::tweak::check_t`).
fn parse_tweak_t(s: &str) -> Result<f64, String> {
    let t: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number"))?;
    curves::tweak::check_t(t).map_err(|e| e.to_string())
}

/// The registered solvers as the values `--solver` accepts (`--help` lists them).
fn solver_names() -> impl clap::builder::TypedValueParser<Value = solver::SolverKind> {
    use clap::builder::TypedValueParser as _;
    PossibleValuesParser::new(solver::SolverKind::ALL.iter().map(|k| k.name()))
        .try_map(|name| name.parse::<solver::SolverKind>())
}

impl CurveOptions {
    /// The constructions' options with these choices, the rest at their defaults.
    pub fn method_options(&self) -> curves::MethodOptions {
        curves::MethodOptions {
            dbhs_pick: self.dbhs_pick,
            solver: self.solver,
            tweak_t: self.tweak_t,
            reach: if self.four_ninths {
                curves::Reach::FourNinths
            } else {
                curves::Reach::Third
            },
            tangents: self.tangents,
            ..curves::MethodOptions::default()
        }
    }
}

/// `--heightfield` and `--no-heightfield`: whether the data is fitted as a height field.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct HeightFieldArgs {
    /// Fit the data as a height field z = f(x, y): clough-tocher and powell-sabin then build
    /// their functional C1 interpolants (values and gradients ∇f = (−n_x/n_z, −n_y/n_z) at the
    /// vertices of the xy triangulation). An error when the data is not a height field (every
    /// normal with n_z > 0, no creases, the xy projection a planar triangulation without
    /// fold-overs) or the scheme has no functional form. Without it a height field is detected
    /// by the same rule and said in a note.
    #[arg(long, conflicts_with = "no_heightfield")]
    pub heightfield: bool,
    /// Never fit as a height field: the parametric schemes whatever the data.
    #[arg(long)]
    pub no_heightfield: bool,
}

impl HeightFieldArgs {
    /// The fit job's mode.
    pub fn mode(&self) -> surface::scheme::functional::HeightFieldMode {
        use surface::scheme::functional::HeightFieldMode;
        if self.heightfield {
            HeightFieldMode::On
        } else if self.no_heightfield {
            HeightFieldMode::Off
        } else {
            HeightFieldMode::Auto
        }
    }
}
