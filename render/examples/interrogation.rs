//! The interrogation modes on a torus of 10⁵ triangles (R = 1, r = 0.4; a 640 × 480 picture):
//! the time of each mode (best of five) and, given a prefix, its picture as `PREFIX-MODE.png`.
//! `cargo run --release -p render --example interrogation [PREFIX]`.

use std::f64::consts::TAU;
use std::time::Instant;

use nalgebra::{Point3, Vector3};
use render::{render, write_png, Camera, RenderMesh, RenderOptions, Shading};

/// A torus (R = 1, r = 0.4) of `nu × nv` quads split in two.
fn torus(nu: usize, nv: usize) -> RenderMesh {
    let mut m = RenderMesh::default();
    for i in 0..nu {
        for j in 0..nv {
            let (u, v) = (TAU * i as f64 / nu as f64, TAU * j as f64 / nv as f64);
            let n = Vector3::new(v.cos() * u.cos(), v.cos() * u.sin(), v.sin());
            m.positions
                .push(Point3::new(u.cos(), u.sin(), 0.0) + n * 0.4);
            m.normals.push(n);
            m.colors.push([0.8, 0.8, 0.8]);
            let at = |a: usize, b: usize| (a % nu) * nv + b % nv;
            m.faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            m.faces.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    m
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let prefix = std::env::args().nth(1);
    let mesh = torus(250, 200);
    // The camera `Camera::framing` gave this box from (35°, 35°) before it fitted the box's
    // corners (0.8 of the bounding sphere's distance), so the times compare with the
    // renderer's before the interrogation modes: the same pixels covered.
    let (centre, radius) = (Point3::origin(), Vector3::new(1.4, 1.4, 0.4).norm());
    let (az, el) = (35f64.to_radians(), 35f64.to_radians());
    let dir = Vector3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
    let cam = Camera {
        eye: centre + dir * (radius / 15f64.to_radians().sin() * 0.8),
        target: centre,
        up: Vector3::z(),
        fov_y_degrees: 30.0,
    };
    let modes = [
        ("lit", Shading::Lit),
        ("reflection", Shading::REFLECTION),
        ("isophotes", Shading::ISOPHOTES),
        ("highlight", Shading::HIGHLIGHT),
    ];
    for (name, shading) in modes {
        let o = RenderOptions {
            width: 640,
            height: 480,
            shading,
            ..RenderOptions::default()
        };
        let mut best = f64::INFINITY;
        let mut image = None;
        for _ in 0..5 {
            let t = Instant::now();
            let img = render(&mesh, &cam, &o)?;
            best = best.min(t.elapsed().as_secs_f64());
            image = Some(img);
        }
        println!(
            "{name}: {} triangles, best {:.1} ms",
            mesh.faces.len(),
            best * 1e3
        );
        if let (Some(prefix), Some(img)) = (&prefix, image) {
            let mut file = std::fs::File::create(format!("{prefix}-{name}.png"))?;
            write_png(&img, &mut file)?;
        }
    }
    Ok(())
}
