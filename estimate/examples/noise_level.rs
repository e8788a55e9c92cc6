//! The noise level `hybrid` measures on mesh files (`estimate::multiscale::noise_level`), and
//! whether it counts them as noisy scans:
//!
//! ```sh
//! cargo run --release -p estimate --example noise_level -- data/meshes/*.ply data/cad/*.ply
//! ```
//!
//! Per file: the two-radius noise estimate and the variogram's nugget in mean edge lengths,
//! the vertices that gave an estimate of those that could, and the verdict.

fn main() {
    for path in std::env::args().skip(1) {
        let raw = match meshio::read_file(&path) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("{path}: {e}");
                continue;
            }
        };
        let prepared =
            match estimate::prepare(&raw, estimate::EstimateChoice::With(&estimate::JET), false) {
                Ok(p) => p,
                Err(e) => {
                    eprintln!("{path}: {e}");
                    continue;
                }
            };
        let n = estimate::multiscale::mesh_noise(&prepared.mesh, None);
        println!(
            "{path}: sigma {:.5} h, nugget {:.5} h, {} of {} vertices, noisy: {}",
            n.sigma / n.edge,
            n.nugget / n.edge,
            n.vertices,
            n.candidates,
            n.is_noisy()
        );
    }
}
