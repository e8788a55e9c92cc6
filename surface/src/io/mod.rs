//! Patch files: JSON Lines and the compact binary `.bzp`.

pub mod patch_io;
