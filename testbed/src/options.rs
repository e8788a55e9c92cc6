//! Option values several filters parse alike: `A:B` colour ranges (`kcolor`, `radial`), and
//! the pairs of the pictures' `--view AZ,EL` and `--size WxH` (`render`, `wire`). A malformed
//! value is a usage error naming the option.

use crate::error::FilterError;

/// Parses two values of `T` separated by `sep` (spaces around each allowed); `what` names the
/// option in the error.
pub fn pair<T: std::str::FromStr>(s: &str, sep: char, what: &str) -> Result<(T, T), FilterError> {
    let bad = || {
        FilterError::Usage(format!(
            "{what} `{s}`: expected two numbers separated by `{sep}`"
        ))
    };
    let (a, b) = s.split_once(sep).ok_or_else(bad)?;
    Ok((
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    ))
}

/// Parses `--range A:B`: two finite numbers, `A < B` (`None` when not given).
pub fn range(s: Option<&str>) -> Result<Option<(f64, f64)>, FilterError> {
    let Some(s) = s else { return Ok(None) };
    let (a, b): (f64, f64) = pair(s, ':', "--range")?;
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(FilterError::Usage(format!(
            "--range {s}: need finite A < B"
        )));
    }
    Ok(Some((a, b)))
}
