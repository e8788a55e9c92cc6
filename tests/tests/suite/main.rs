//! The integration tests of the workspace, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod boundary_curves_on_the_ring;
mod cad_corpus;
mod readback;
mod readme_numbers;
mod real_meshes;
mod streamed_fit;
mod support;
mod tessellate_fit;
