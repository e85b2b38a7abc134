//! Writes the shipped faces file `data/wing_m6_co_faces.x` of the C–O wing example
//! (`examples/wing_m6_co.toml`): the six faces F1 … F6 of the block above the upper surface of
//! the ONERA M6 wing that wraps around the rounded tip, from the shape in
//! `examples/common/wing_co_shape.rs`. Plot3D, unformatted double, six surface blocks in the
//! face orientation of `faces = { file }` (no `orient` needed). Also prints the quality of the
//! algebraic block the faces are cut from (the solver starts from the faces alone).
//!
//! `cargo run --release --example make_wing_co [OUT [NI NJ NK]]` (default
//! `data/wing_m6_co_faces.x`, 65 49 33)

#[path = "common/wing_co_shape.rs"]
mod shape;

use ellipgrid::io::plot3d::{write_plot3d, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::quality::quality3d::quality3d;
use ellipgrid::Error;

fn main() -> ellipgrid::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args
        .first()
        .cloned()
        .unwrap_or_else(|| "data/wing_m6_co_faces.x".into());
    let n = args
        .iter()
        .skip(1)
        .map(|a| a.parse::<usize>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| Error::input("make_wing_co", format!("NI NJ NK: {e}")))?;
    let [ni, nj, nk] = match n.as_slice() {
        [] => [65, 49, 33],
        [a, b, c] if [a, b, c].iter().all(|&&v| v >= 5) => [*a, *b, *c],
        _ => {
            return Err(Error::input(
                "make_wing_co",
                "expected OUT [NI NJ NK], each count at least 5",
            ))
        }
    };
    let blocks: Vec<Block> = shape::faces(ni, nj, nk)
        .into_iter()
        .map(Block::Surface)
        .collect();
    write_plot3d(
        std::path::Path::new(&out),
        &blocks,
        &Plot3dFormat::default(),
        None,
    )?;
    println!("wrote {out} (faces of a {ni} × {nj} × {nk} block)");
    println!(
        "algebraic block:\n{}",
        quality3d(&shape::algebraic_block(ni, nj, nk))
    );
    Ok(())
}
