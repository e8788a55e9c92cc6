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
    type Args = PictureArgs;

    fn run(args: PictureArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let view = args.view(false)?;
        draw::picture(Self::NAME, &stream, &view)
    }
}
