//! The integration tests of `meshio`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod common;
mod conventions;
mod every_pair;
mod fuzz;
mod glb;
mod obj;
mod obj_creases;
mod off;
mod ply;
mod ply_creases;
mod registry;
mod stl;
mod streaming;
mod testbed;
