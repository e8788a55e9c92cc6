//! `render`, the seed's Sgp | Render: a shaded picture of the stream's triangles, PNG
//! (`crate::draw`).

use crate::draw::{self, PictureArgs};
use crate::error::FilterError;
use crate::filters::Filter;
use crate::pipe::StreamOptions;

/// `testbed render`.
pub struct Render;

impl Filter for Render {
    const NAME: &'static str = "render";
    const SUMMARY: &'static str = "A shaded picture of the triangles, PNG";
    const DESCRIPTION: &'static str = "\
        The triangles are drawn as they come, unwelded (a Triangle's own three vertices, a \
        TriangleMesh's shared as in the record), with their normals (the geometric normal where \
        a vertex has none) and colours (the uniform material where a vertex has none); the \
        camera frames their bounding box from --view. Other records are ignored. A picture with \
        nothing drawn on it (no triangles in the stream: `tess` forgotten) is an error, and a \
        --size whose drawing would not fit in memory is refused before the stream is read.";
    const SEED: &'static str = "Sgp | Render";
    type Args = PictureArgs;

    fn run(args: PictureArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let view = args.view(false)?;
        draw::picture(Self::NAME, &stream, &view)
    }
}
