//! Writes the shipped control net `data/wing_pylon_net.x` of the wing–pylon example: a
//! 49 × 33 bicubic Hermite net whose control points cluster strongly at the pylon nose.
//!
//! `cargo run --release --example make_wing_pylon [OUT]`

#[path = "common/wing_pylon_shape.rs"]
mod shape;

use ellipgrid::io::plot3d::{write_plot3d, Encoding, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::Grid2;

fn main() -> ellipgrid::Result<()> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "data/wing_pylon_net.x".into());
    let (ni, nj) = (49, 33);
    let pts = shape::net(ni, nj, true);
    let g = Grid2::<3>::from_fn(ni, nj, |i, j| pts[i + ni * j]);
    let fmt = Plot3dFormat {
        encoding: Encoding::Formatted,
        multi_block: false,
        ..Plot3dFormat::default()
    };
    write_plot3d(std::path::Path::new(&out), &[Block::Surface(g)], &fmt, None)?;
    println!("wrote {out} ({ni} × {nj} control points)");
    Ok(())
}
