//! The integration tests of `surface`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod c0_continuity;
mod creases;
mod fallback;
mod fan;
mod free_parameters;
mod functional;
mod interior;
mod mesh_invariants;
mod octa;
mod patch_io;
mod scheme_clough_tocher;
mod scheme_flat;
mod scheme_gregory_charrot;
mod scheme_phong;
mod scheme_pn_triangles;
mod scheme_powell_sabin;
mod scheme_side_vertex;
mod scheme_ss_curvature;
mod scheme_ss_variants;
mod schemes;
mod sharp;
mod shirman_sequin;
mod straight_corner;
mod tangent_rules;
