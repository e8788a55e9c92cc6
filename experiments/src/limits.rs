//! The valid ranges of the numeric options and the memory estimates: the fit job's
//! (`fitjob::limits`), the same for every front end.

pub use fitjob::limits::*;
