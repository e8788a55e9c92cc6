//! `render`, the seed's Sgp | Render: a shaded picture of the stream's triangles, PNG
//! (`crate::draw`), or a picture of their reflection lines, isophotes or highlight lines
//! (`--mode`; `render::interrogation`).

use nalgebra::Vector3;
use render::interrogation::{Shading, DEFAULT_STRIPES, DEFAULT_WIDTH, MAX_STRIPES};

use crate::draw::{self, PictureArgs};
use crate::error::FilterError;
use crate::filters::Filter;
use crate::pipe::StreamOptions;

/// `testbed render`.
pub struct Render;

/// Default `--width` of `--mode isophotes`: thin lines on the band borders (the other modes'
/// default is half a period, [`DEFAULT_WIDTH`]).
pub const ISOPHOTE_WIDTH: f64 = 0.15;

/// `render`'s options: the picture's, and the shading mode's.
#[derive(clap::Args, Debug, Clone, Default, PartialEq, Eq)]
pub struct RenderArgs {
    /// The picture (`--view`, `--size`).
    #[command(flatten)]
    pub picture: PictureArgs,
    /// Shading: `shaded` (lit, the default), `reflection` (reflection lines: a mirror in a
    /// cylinder of light stripes around --direction), `isophotes` (bands of constant n·L,
    /// L = --direction), `highlight` (highlight lines of parallel linear lights along
    /// --direction in a plane facing the viewer).
    #[arg(long)]
    pub mode: Option<String>,
    /// Stripes: reflection lines round the full circle, isophote bands over n·L ∈ [−1, 1],
    /// highlight lines across the object's bounding diameter; 1 to 100000 (default 16).
    #[arg(long)]
    pub stripes: Option<String>,
    /// Direction `X,Y,Z` (world coordinates, any length but not zero): the light cylinder's
    /// axis, the isophotes' light, the highlight lights' direction. Default: the camera's up
    /// direction (reflection, highlight), towards the eye (isophotes).
    #[arg(long, allow_hyphen_values = true)]
    pub direction: Option<String>,
    /// Dark fraction of a stripe period, 0 to 1 (default 0.5; isophotes 0.15).
    #[arg(long)]
    pub width: Option<String>,
}

impl RenderArgs {
    /// The shading they ask for: `--mode` one of the four names; `--stripes`, `--direction`
    /// and `--width` only with an interrogation mode, in their ranges. Every fault is a usage
    /// error naming the option.
    pub fn shading(&self) -> Result<Shading, FilterError> {
        let usage = |m: String| FilterError::Usage(m);
        let mode = self.mode.as_deref().unwrap_or("shaded");
        let names = "shaded, reflection, isophotes, highlight";
        if mode == "shaded" {
            for (given, option) in [
                (&self.stripes, "--stripes"),
                (&self.direction, "--direction"),
                (&self.width, "--width"),
            ] {
                if given.is_some() {
                    return Err(usage(format!(
                        "{option} needs --mode reflection, isophotes or highlight (the shaded picture has no stripes)"
                    )));
                }
            }
            return Ok(Shading::Lit);
        }
        if !["reflection", "isophotes", "highlight"].contains(&mode) {
            return Err(usage(format!("--mode {mode}: expected one of {names}")));
        }
        let stripes = match &self.stripes {
            None => DEFAULT_STRIPES,
            Some(s) => match s.trim().parse::<u32>() {
                Ok(n) if (1..=MAX_STRIPES).contains(&n) => n,
                _ => {
                    return Err(usage(format!(
                        "--stripes {s}: a whole number from 1 to {MAX_STRIPES}"
                    )))
                }
            },
        };
        let width = match &self.width {
            None if mode == "isophotes" => ISOPHOTE_WIDTH,
            None => DEFAULT_WIDTH,
            Some(s) => match s.trim().parse::<f64>() {
                Ok(w) if (0.0..=1.0).contains(&w) => w,
                _ => {
                    return Err(usage(format!(
                        "--width {s}: a fraction from 0 to 1 (the dark part of a stripe period)"
                    )))
                }
            },
        };
        let direction = self.direction.as_deref().map(direction).transpose()?;
        Ok(match mode {
            "reflection" => Shading::Reflection {
                stripes,
                direction,
                width,
            },
            "isophotes" => Shading::Isophotes {
                bands: stripes,
                light: direction,
                width,
            },
            _ => Shading::Highlight {
                lines: stripes,
                direction,
                width,
            },
        })
    }
}

/// Parses `--direction X,Y,Z`: three finite numbers, not all zero.
fn direction(s: &str) -> Result<Vector3<f64>, FilterError> {
    let parts: Vec<Option<f64>> = s.split(',').map(|p| p.trim().parse().ok()).collect();
    match parts[..] {
        [Some(x), Some(y), Some(z)] if [x, y, z].iter().all(|v| v.is_finite()) => {
            if x == 0.0 && y == 0.0 && z == 0.0 {
                return Err(FilterError::Usage(format!(
                    "--direction {s}: the zero vector has no direction"
                )));
            }
            Ok(Vector3::new(x, y, z))
        }
        _ => Err(FilterError::Usage(format!(
            "--direction {s}: expected three finite numbers X,Y,Z separated by `,`"
        ))),
    }
}

impl Filter for Render {
    const NAME: &'static str = "render";
    const SUMMARY: &'static str = "A shaded picture of the triangles, PNG; or their reflection lines, isophotes or highlight lines (--mode)";
    const DESCRIPTION: &'static str = "\
        The triangles are drawn as they come, unwelded (a Triangle's own three vertices, a \
        TriangleMesh's shared as in the record), with their normals (the geometric normal where \
        a vertex has none) and colours (the uniform material where a vertex has none); the \
        camera looks at their bounding box's centre from --view, as near as keeps every vertex \
        inside the middle 90% of the width and the height. Other \
        records are ignored. A picture with nothing drawn on it (no triangles in the stream: \
        `tess` forgotten) is an error, and a --size whose drawing would not fit in memory is \
        refused before the stream is read. The triangles are kept for drawing in at most 64 MiB \
        of memory, the rest in a temporary file (TMPDIR, removed when the filter ends), and \
        drawn chunk by chunk: the memory does not grow with the stream.\n\n\
        --mode reflection|isophotes|highlight draws dark and light stripes instead of the \
        lighting, computed at every pixel from the interpolated normal: reflection lines \
        (Klass 1980), isophotes (Poeschl 1984), highlight lines (Beier and Chen 1994). A \
        stripe that breaks shows a crease (the normals jump: not G1), one that kinks a jump of \
        curvature (G1, not G2). Triangles without normals get their flat normals, so their \
        stripes break at every edge: tessellate with normals (`tess`).";
    const SEED: &'static str = "Sgp | Render";
    type Args = RenderArgs;

    fn run(args: RenderArgs, stream: StreamOptions) -> Result<(), FilterError> {
        let view = args.picture.view(false)?;
        let shading = args.shading()?;
        draw::picture_with(Self::NAME, &stream, &view, shading)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(
        mode: Option<&str>,
        stripes: Option<&str>,
        direction: Option<&str>,
        width: Option<&str>,
    ) -> RenderArgs {
        RenderArgs {
            picture: PictureArgs::default(),
            mode: mode.map(String::from),
            stripes: stripes.map(String::from),
            direction: direction.map(String::from),
            width: width.map(String::from),
        }
    }

    fn usage(a: &RenderArgs) -> String {
        match a.shading() {
            Err(FilterError::Usage(m)) => m,
            other => panic!("expected a usage error, got {other:?}"),
        }
    }

    #[test]
    fn modes_parse_with_their_defaults_and_values() {
        assert_eq!(
            args(None, None, None, None).shading().unwrap(),
            Shading::Lit
        );
        assert_eq!(
            args(Some("shaded"), None, None, None).shading().unwrap(),
            Shading::Lit
        );
        assert_eq!(
            args(Some("reflection"), None, None, None)
                .shading()
                .unwrap(),
            Shading::Reflection {
                stripes: 16,
                direction: None,
                width: 0.5
            }
        );
        assert_eq!(
            args(Some("isophotes"), Some("8"), Some("0, 0,-2"), None)
                .shading()
                .unwrap(),
            Shading::Isophotes {
                bands: 8,
                light: Some(Vector3::new(0.0, 0.0, -2.0)),
                width: 0.15
            }
        );
        assert_eq!(
            args(
                Some("highlight"),
                Some("100000"),
                Some("1,2,3"),
                Some("0.25")
            )
            .shading()
            .unwrap(),
            Shading::Highlight {
                lines: 100_000,
                direction: Some(Vector3::new(1.0, 2.0, 3.0)),
                width: 0.25
            }
        );
        for w in ["0", "1", "0.0", " 1.0 "] {
            assert!(
                args(Some("reflection"), None, None, Some(w))
                    .shading()
                    .is_ok(),
                "{w}"
            );
        }
    }

    #[test]
    fn bad_values_are_usage_errors_naming_the_option() {
        let cases = [
            (args(Some("zebra"), None, None, None), "--mode zebra"),
            (args(None, Some("4"), None, None), "--stripes needs --mode"),
            (
                args(Some("shaded"), None, None, Some("0.5")),
                "--width needs --mode",
            ),
            (
                args(Some("reflection"), Some("0"), None, None),
                "--stripes 0",
            ),
            (
                args(Some("reflection"), Some("-3"), None, None),
                "--stripes -3",
            ),
            (
                args(Some("reflection"), Some("2.5"), None, None),
                "--stripes 2.5",
            ),
            (
                args(Some("reflection"), Some("100001"), None, None),
                "--stripes 100001",
            ),
            (
                args(Some("isophotes"), None, None, Some("1.5")),
                "--width 1.5",
            ),
            (
                args(Some("isophotes"), None, None, Some("-0.1")),
                "--width -0.1",
            ),
            (
                args(Some("isophotes"), None, None, Some("nan")),
                "--width nan",
            ),
            (
                args(Some("highlight"), None, Some("0,0,0"), None),
                "zero vector",
            ),
            (
                args(Some("highlight"), None, Some("1,2"), None),
                "--direction 1,2",
            ),
            (
                args(Some("highlight"), None, Some("1,inf,0"), None),
                "--direction 1,inf,0",
            ),
            (
                args(Some("highlight"), None, Some("1,2,3,4"), None),
                "--direction 1,2,3,4",
            ),
        ];
        for (a, expect) in &cases {
            let m = usage(a);
            assert!(m.contains(expect), "{m:?} should contain {expect:?}");
        }
    }
}
