//! Headless plotting and rendering: curve and curvature plots, line charts and histograms,
//! shaded meshes by a CPU rasterizer, colour maps, picture composites.
//!
//! Everything here draws without a display or system fonts: text uses the DejaVu Sans font
//! bundled with the workspace (`assets/fonts`), registered with plotters from bytes
//! ([`font`]), and every output file is written atomically (`meshio::outfile::write_atomic`) so a
//! failed or interrupted run never leaves a half-written figure in place of a good one.
//!
//! * [`curveplot`] — figures in the style of Mann (1994), *Using local optimization in surface
//!   fitting*, Figure 2: one column per boundary-curve construction method, each showing the
//!   cubic with its control polygon above its signed curvature against normalized arc length,
//!   together with the straight line joining the target end curvatures. Written as PNG and SVG.
//! * [`chart`] — line charts (optionally log y, in grids) and grouped bar charts;
//! * [`camera`] — the perspective camera and its framing of the points drawn;
//! * [`canvas`] — the same pictures drawn from triangles as they come, in bounded memory;
//! * [`shade`] — a z-buffer rasterizer with near-plane clipping, perspective-correct
//!   interpolation, Blinn–Phong shading and an optional wireframe;
//! * [`interrogation`] — reflection lines, isophotes and highlight lines, per pixel from the
//!   interpolated normal ([`shade::Shading`]);
//! * [`srgb`] — linear → 8-bit sRGB by table, equal to the formula;
//! * [`colors`] — diverging and sequential colour maps (Moreland, viridis);
//! * [`mosaic`] — composites of rendered tiles with a title and a legend;
//! * [`font`] — the bundled font and its one-time registration.

pub mod camera;
pub mod canvas;
pub mod chart;
pub mod colors;
pub mod curveplot;
pub mod error;
pub mod font;
pub mod interrogation;
pub mod mosaic;
pub mod shade;
pub mod srgb;

pub use canvas::{Canvas, SceneBounds};
pub use chart::{
    write_histogram, write_line_chart, write_line_charts, Histogram, LineChart, Series,
};
pub use curveplot::{
    curvature_y_range, equal_aspect_ranges, figure_size, write_curve_figure, CurveFigure,
    CurvePanel, YRange,
};
pub use error::RenderError;
pub use mosaic::{write_composite, Legend, LegendKind, Tile};
pub use shade::{
    blank_wire_frame, draw_wire_frame, interrogation_field, render, render_many, wire_frame,
    write_png, Camera, Field, FrameBox, Image, RenderMesh, RenderOptions, Shading,
};
