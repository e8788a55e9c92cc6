//! Everything a fit job is asked to do, in one typed struct: the input and how to complete it,
//! the scheme and its parameters, the curve method and its solver, the interior choice, the
//! tessellation, the outputs and the G1 sampling. Every front end builds one of these and calls
//! [`crate::run`]; the defaults are the command line's.

use std::path::PathBuf;

use curves::MethodOptions;
use surface::fairing::InteriorChoice;
use surface::{InteriorParameters, SchemeOptions};

use crate::input::InputOptions;

/// Samples per patch boundary at which G1 is measured (ends included): 9 resolves the quartic
/// boundaries' normal fields to rounding on the data sets, and is the measurement every report
/// of the workbench quotes.
pub const DEFAULT_G1_SAMPLES: usize = 9;

/// Segments per patch edge of the tessellation written to [`FitOptions::mesh_out`] (the
/// testbed's `Tess -s`).
pub const DEFAULT_TESS: usize = 4;

/// Subdivision steps of the subdivision schemes (`loop`, `loop-warren`, `catmull-clark`).
pub const DEFAULT_LEVELS: u32 = 3;

/// What a fit job does.
#[derive(Clone, Debug)]
pub struct FitOptions {
    /// The input mesh and how to complete it.
    pub input: InputOptions,
    /// The surface scheme (`surface::scheme::REGISTRY`, or a subdivision scheme of
    /// `subdiv::SCHEMES`).
    pub scheme: String,
    /// The schemes' parameter values (the interior β and c of `shirman-sequin`, `phong`'s α;
    /// each scheme reads its own, declared in its registry entry).
    pub scheme_options: SchemeOptions,
    /// The boundary-curve construction (`curves::REGISTRY`).
    pub curves: String,
    /// The construction's options (its solver, the dBHS pick).
    pub method_options: MethodOptions,
    /// The interior parameters: as set in [`FitOptions::scheme_options`], or chosen per
    /// triangle by an energy (then the fit is held whole, not streamed).
    pub interior: InteriorChoice,
    /// Segments per patch edge of the tessellation written to [`FitOptions::mesh_out`].
    pub tess: usize,
    /// Subdivision steps for a subdivision scheme.
    pub levels: u32,
    /// Samples per boundary of the G1 measurement.
    pub g1_samples: usize,
    /// Measure G1 and interpolation. The pipeline's `fit` leaves that to its `g1` filter, as
    /// the testbed's modules do; a streamed fit measures anyway (the measurement is part of
    /// its pass over the faces, and costs little there).
    pub measure_g1: bool,
    /// Where to write the patches: JSON Lines, or the compact binary form when the name ends
    /// in `.bzp` (`surface::patch_io`).
    pub patches_out: Option<PathBuf>,
    /// Where to write the tessellation, in the format its extension names.
    pub mesh_out: Option<PathBuf>,
    /// How the mesh file is written (the up axis of formats that fix one).
    pub mesh_options: crate::output::MeshOutputOptions,
    /// Height fields: detected and fitted with the scheme's functional (C1) form (`Auto`, the
    /// default), required (`On`, `--heightfield`), or never (`Off`, `--no-heightfield`)
    /// (`surface::scheme::functional`).
    pub heightfield: surface::scheme::functional::HeightFieldMode,
    /// Keep the mesh, the fit (every net) and the tessellation in the outcome, for a caller
    /// that works on them in memory (the pipeline's `fit`, the Python package). The fit is then
    /// held whole instead of streamed: the same report, more memory.
    pub keep: bool,
}

impl Default for FitOptions {
    /// The command line's defaults: the ring, `shirman-sequin` with β = 1/3 and c = 1 on
    /// `chord` curves, no outputs.
    fn default() -> Self {
        FitOptions {
            input: InputOptions::default(),
            scheme: surface::DEFAULT_SCHEME.into(),
            scheme_options: SchemeOptions::default(),
            curves: "chord".into(),
            method_options: MethodOptions::default(),
            interior: InteriorChoice::Default,
            tess: DEFAULT_TESS,
            levels: DEFAULT_LEVELS,
            g1_samples: DEFAULT_G1_SAMPLES,
            measure_g1: true,
            patches_out: None,
            mesh_out: None,
            mesh_options: crate::output::MeshOutputOptions::default(),
            heightfield: Default::default(),
            keep: false,
        }
    }
}

impl FitOptions {
    /// The uniform interior parameters the options set (β and c of `shirman-sequin`).
    pub fn interior_parameters(&self) -> InteriorParameters {
        surface::scheme::shirman_sequin::uniform_parameters(&self.scheme_options)
    }

    /// Whether the scheme is one of the subdivision schemes.
    pub fn is_subdivision(&self) -> bool {
        subdiv::SCHEMES.iter().any(|e| e.name == self.scheme)
    }
}
