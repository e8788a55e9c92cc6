//! The options of the boundary-curve constructions and of the fitted surfaces, declared once as
//! argument groups and flattened into every experiment that builds curves or fits surfaces, so
//! that each flag has one name, one default and one meaning everywhere:
//!
//! | group | flags | taken by |
//! |---|---|---|
//! | [`CurveOptions`] | `--solver`, `--dbhs-pick`, `--tweak-t`, `--four-ninths` | `curve`, `ring`, `fit` (in [`FitOptions`]) |
//! | [`InteriorOption`] | `--interior` | `sweep`, `ring`, `fit` (in [`FitOptions`]) |
//! | `fitjob::cli::SchemeArgs` | `--scheme` and one option a scheme parameter (`--beta`, `--c`, `--phong-alpha`, …), generated from the scheme registry | `ring`, `fit` (in [`FitOptions`]), the pipeline's `fit` (`sweep` takes each as a list, a grid axis: `sweep::ParameterLists`) |
//! | [`FitOptions`] | `--curves` (one construction), [`CurveOptions`], [`InteriorOption`], `SchemeArgs` | `fit` |
//!
//! `ring` fits every construction of its study, so it takes no `--curves`; `sweep` takes
//! `--curves`, `--solver`, `--scheme` and every scheme parameter as lists (the axes of its grid)
//! with `--interior`; `curve` builds curves without surfaces, so it takes no `--interior` and
//! names several constructions with `--curves` (a list). The names a flag accepts come from the
//! libraries' registries:
//! constructions from [`curves::REGISTRY`], solvers from [`solver::SolverKind`], dBHS picks from
//! [`curves::DbhsPick`], interior choices from [`InteriorChoice`].

use std::sync::LazyLock;

use clap::builder::PossibleValuesParser;

use surface::fairing::InteriorChoice;

pub use fitjob::cli::CurveOptions;

/// `--interior`.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct InteriorOption {
    /// Interior parameters of the fitted surfaces: `default` (β and c as set: `--beta` and `--c`
    /// where the experiment has them, else the Shirman–Séquin β = 1/3, c = 1), or per triangle
    /// the β and c minimizing the macro-patch's `thin-plate` or `membrane` energy.
    #[arg(id = "interior", long = "interior", value_name = "INTERIOR",
          default_value_t = InteriorChoice::Default)]
    pub choice: InteriorChoice,
}

/// `--curves` (one construction) with [`CurveOptions`] and [`InteriorOption`]: how `fit` builds
/// its surface.
#[derive(clap::Args, Debug, Clone)]
pub struct FitOptions {
    /// Boundary-curve construction.
    #[arg(long, default_value = "chord", value_parser = method_names())]
    pub curves: String,
    /// The curve constructions' options.
    #[command(flatten)]
    pub curve: CurveOptions,
    /// The interior parameters.
    #[command(flatten)]
    pub interior: InteriorOption,
    /// The surface scheme and the schemes' parameters (generated from the registry).
    #[command(flatten)]
    pub scheme: fitjob::cli::SchemeArgs,
}

/// The registered construction names as the values a flag accepts (listed in its `--help`).
fn method_names() -> PossibleValuesParser {
    fitjob::cli::curve_method_names()
}

/// Every registered construction, comma-separated in registry order: the default of `curve
/// --curves`.
pub fn all_methods() -> &'static str {
    static ALL: LazyLock<String> = LazyLock::new(|| {
        curves::REGISTRY
            .iter()
            .map(|e| e.name)
            .collect::<Vec<_>>()
            .join(",")
    });
    &ALL
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::builder::TypedValueParser as _;

    #[derive(clap::Parser, Debug)]
    struct Cli {
        #[command(flatten)]
        curve: CurveOptions,
    }

    #[test]
    fn tweak_t_and_four_ninths_reach_the_method_options() {
        use clap::Parser as _;
        let o = Cli::try_parse_from(["x", "--tweak-t", "0.25", "--four-ninths"])
            .unwrap()
            .curve
            .method_options();
        assert_eq!(o.tweak_t, 0.25);
        assert_eq!(o.reach, curves::Reach::FourNinths);
        let d = Cli::try_parse_from(["x"]).unwrap().curve.method_options();
        assert_eq!(d.tweak_t, curves::tweak::DEFAULT_TWEAK_T);
        assert_eq!(d.reach, curves::Reach::Third);
        for bad in ["0", "-1", "1.5", "nan", "inf", "x"] {
            let e = Cli::try_parse_from(["x", "--tweak-t", bad]).unwrap_err();
            assert!(e.to_string().contains("tweak-t"), "{bad}: {e}");
        }
    }

    #[test]
    fn every_registered_construction_is_offered_and_builds() {
        let all: Vec<&str> = all_methods().split(',').collect();
        assert_eq!(all.len(), curves::REGISTRY.len());
        for name in &all {
            assert!(curves::method_by_name(name, &curves::MethodOptions::default()).is_ok());
        }
        let offered: Vec<String> = method_names()
            .possible_values()
            .into_iter()
            .flatten()
            .map(|v| v.get_name().to_string())
            .collect();
        assert_eq!(offered, all);
    }
}
