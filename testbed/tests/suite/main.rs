//! The integration tests of `testbed`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod bzp;
mod examples;
mod fit_options;
mod kcolor_map;
mod library;
mod numerics;
mod pipeline;
mod principal;
mod registry;
mod render_modes;
mod shell_docs;
mod stream_bounds;
mod support;
