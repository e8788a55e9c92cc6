//! Writes the benchmark meshes as OBJ files into the directory given, for the C++ timings:
//! `cargo run --release -p subdiv --example export_bench_meshes -- /tmp/subdiv-bench`.

use std::io::Write;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args()
        .nth(1)
        .ok_or("usage: export_bench_meshes DIR")?;
    std::fs::create_dir_all(&dir)?;
    for (name, mesh) in subdiv::bench_meshes::bench_meshes() {
        let path = std::path::Path::new(&dir).join(format!("{name}.obj"));
        let mut out = std::io::BufWriter::new(std::fs::File::create(&path)?);
        for p in mesh.positions() {
            writeln!(out, "v {:?} {:?} {:?}", p.x, p.y, p.z)?;
        }
        for f in mesh.faces() {
            write!(out, "f")?;
            for v in f {
                write!(out, " {}", v + 1)?;
            }
            writeln!(out)?;
        }
        println!("{}: {} faces", path.display(), mesh.num_faces());
    }
    Ok(())
}
