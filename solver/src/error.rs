//! Errors for invalid input. A solver that does not converge is not an error: see
//! [`SolveReport`](crate::SolveReport).

/// Invalid input to a solve, detected before any iteration.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// A start coordinate is NaN or infinite.
    #[error("start point x[{index}] = {value} is not finite")]
    NonFiniteStart {
        /// The coordinate.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A lower bound is NaN or `+∞` (use `-∞` for a free unknown).
    #[error("lower bound l[{index}] = {value} is invalid (must be finite or -inf)")]
    InvalidLowerBound {
        /// The coordinate.
        index: usize,
        /// The bound.
        value: f64,
    },
    /// A start coordinate lies below its lower bound.
    #[error("start point x[{index}] = {value} is below its lower bound {lower}")]
    StartBelowBound {
        /// The coordinate.
        index: usize,
        /// Its value.
        value: f64,
        /// The bound.
        lower: f64,
    },
    /// A tolerance is negative or not finite.
    #[error("option `{name}` = {value} is invalid (must be finite and >= 0)")]
    InvalidOption {
        /// The option's field name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
}
