//! `wire`, the seed's Sgp | XRender: a wire-frame picture of the stream's triangles, every
//! edge, PNG (`crate::draw`).

use crate::draw::{self, PictureArgs};
use crate::error::FilterError;
use crate::filters::Filter;
use crate::pipe::StreamOptions;

/// `testbed wire`.
pub struct Wire;

impl Filter for Wire {
    const NAME: &'static str = "wire";
    const SUMMARY: &'static str =
        "A wire-frame picture of the triangles (every edge), PNG: the seed's XRender";
    const DESCRIPTION: &'static str = "\
        Every edge of every Triangle and of every triangle of a TriangleMesh is drawn, the \
        camera framing their bounding box from --view. Other records are ignored. A picture with \
        nothing drawn on it (no triangles in the stream: `tess` forgotten) is an error. The \
        triangles are kept for drawing in at most 64 MiB of memory, the rest in a temporary file \
        (TMPDIR, removed when the filter ends).";
    const SEED: &'static str = "Sgp | XRender";
    type Args = PictureArgs;

    fn run(args: PictureArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let view = args.view(true)?;
        draw::picture(Self::NAME, &stream, &view)
    }
}
