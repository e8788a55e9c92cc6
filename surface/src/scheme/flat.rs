//! `flat`: the testbed's Fitter0 (Lounsbery et al. 1990, §3.1): each data triangle is its own
//! patch, a degree-1 Bézier triangle on the three vertices. C0; the normal jumps across every
//! edge by the dihedral angle, which the G1 measurement reports.

use nalgebra::Point3;

use super::{Continuity, FaceInput, Layout, Scheme, WHOLE};
use crate::fit::FaceFallbackReason;

/// The flat scheme.
#[derive(Clone, Copy, Debug, Default)]
pub struct Flat;

impl Scheme for Flat {
    fn name(&self) -> &'static str {
        "flat"
    }

    fn layout(&self) -> Layout {
        Layout::bezier(1, &WHOLE)
    }

    fn continuity(&self) -> Continuity {
        Continuity::C0
    }

    fn uses_curves(&self) -> bool {
        false
    }

    /// Net order of degree 1: `b100, b010, b001` = `V_0, V_1, V_2`.
    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        for (slot, v) in out.iter_mut().zip(input.vertices) {
            *slot = v.p;
        }
        Ok(())
    }
}
