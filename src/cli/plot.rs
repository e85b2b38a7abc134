//! `ellipgrid plot GRID -o fig.png|fig.svg`: a picture of a grid (see `ellipgrid::plot`).

use clap::Args;
use ellipgrid::io::Block;
use ellipgrid::plot::{self, Marks, Plane, PlotOptions, Slice, View};
use ellipgrid::{Error, Result};
use std::path::PathBuf;

use crate::cli::convert::{load, metric};

/// Arguments of `ellipgrid plot`.
#[derive(Args, Debug)]
pub struct PlotArgs {
    /// The grid: a Plot3D file (any flavour), a .vts/.vtm VTK grid, or a case file (.toml, run
    /// first; a folded grid is drawn with a warning).
    grid: PathBuf,
    /// The picture: .png or .svg.
    #[arg(short, long = "output", value_name = "FIG")]
    output: PathBuf,
    /// Close-up window x0,y0,x1,y1 in projected coordinates (model x, y for the xy view).
    #[arg(long, value_name = "X0,Y0,X1,Y1", allow_hyphen_values = true)]
    window: Option<String>,
    /// Fill the cells by a quality metric, with a colour bar: skewness, jacobian (smallest
    /// scaled corner Jacobian) or aspect.
    #[arg(long, value_name = "METRIC")]
    color: Option<String>,
    /// Picture size in pixels, WxH.
    #[arg(long, value_name = "WxH", default_value = "1200x900")]
    size: String,
    /// Projection: xy, xz, yz or iso (default: xy for planar grids, iso otherwise).
    #[arg(long, value_name = "VIEW")]
    view: Option<String>,
    /// Draw one grid plane of volume blocks (0-based): i=I, j=J or k=K.
    #[arg(long, value_name = "k=K")]
    plane: Option<String>,
    /// Draw the cut of the volume blocks by a coordinate plane: x=X, y=Y or z=Z (e.g. a
    /// horizontal plane through a wing: z=0.02); seen along its normal unless --view says
    /// otherwise.
    #[arg(long, value_name = "z=Z", allow_hyphen_values = true)]
    slice: Option<String>,
    /// Fill every block with its own colour, with a legend of block names.
    #[arg(long)]
    blocks: bool,
    /// Draw only these blocks: names or 1-based numbers, comma-separated (e.g. the volumes
    /// around a wing, without the wake volumes in front of them).
    #[arg(long, value_name = "B1,B2,...")]
    select: Option<String>,
    /// Draw the topology of a multi-block case (a .toml with [[vertex]] and [[edge]] tables):
    /// every edge with its name, every vertex with its name.
    #[arg(long)]
    topology: bool,
    /// Print only errors.
    #[arg(short, long)]
    quiet: bool,
}

/// Runs `ellipgrid plot`.
pub fn plot(a: &PlotArgs) -> Result<()> {
    let bad = |opt: &str, msg: String| Error::input(opt, msg);
    let size = a
        .size
        .split_once(['x', 'X'])
        .and_then(|(w, h)| Some((w.trim().parse().ok()?, h.trim().parse().ok()?)))
        .ok_or_else(|| {
            bad(
                "--size",
                format!("'{}': expected WxH, e.g. 1200x900", a.size),
            )
        })?;
    let window = match &a.window {
        None => None,
        Some(s) => {
            let v: Vec<f64> = s
                .split(',')
                .map(|t| t.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| bad("--window", format!("'{s}': expected x0,y0,x1,y1")))?;
            match v[..] {
                [x0, y0, x1, y1] if v.iter().all(|t| t.is_finite()) && x1 > x0 && y1 > y0 => {
                    Some([x0, y0, x1, y1])
                }
                _ => {
                    let msg = format!("'{s}': expected four numbers x0,y0,x1,y1, x0 < x1, y0 < y1");
                    return Err(bad("--window", msg));
                }
            }
        }
    };
    let view = match &a.view {
        None => None,
        Some(s) => Some(
            View::parse(s)
                .ok_or_else(|| bad("--view", format!("'{s}': expected xy, xz, yz or iso")))?,
        ),
    };
    let plane = match &a.plane {
        None => None,
        Some(s) => Some(
            Plane::parse(s)
                .ok_or_else(|| bad("--plane", format!("'{s}': expected i=I, j=J or k=K")))?,
        ),
    };
    let slice = match &a.slice {
        None => None,
        Some(s) => Some(Slice::parse(s).ok_or_else(|| {
            bad(
                "--slice",
                format!("'{s}': expected x=X, y=Y or z=Z with a finite coordinate"),
            )
        })?),
    };
    if slice.is_some() && (a.plane.is_some() || a.color.is_some() || a.blocks) {
        return Err(bad(
            "--slice",
            "draws the cut as grid lines: not with --plane, --color or --blocks".into(),
        ));
    }
    let color = a.color.as_deref().map(metric).transpose()?;
    let ext = a
        .output
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    if !matches!(ext.as_deref(), Some("png" | "svg")) {
        return Err(Error::input(
            a.output.display().to_string(),
            "unknown picture extension: use .png or .svg",
        ));
    }
    let opts = PlotOptions {
        size,
        window,
        color,
        view,
        plane,
        slice,
        blocks: a.blocks,
    };
    if a.blocks && opts.color.is_some() {
        return Err(bad(
            "--blocks",
            "fills the blocks with colours: use it or --color, not both".into(),
        ));
    }
    let mut input = load(&a.grid, true, a.quiet)?;
    let marks = match (a.topology, &input.topology) {
        (false, _) => Marks::default(),
        (true, Some(t)) => Marks::topology(t, &input.blocks),
        (true, None) => {
            return Err(Error::input(
                a.grid.display().to_string(),
                "--topology needs a multi-block case file (.toml with [[vertex]] and [[edge]] \
                 tables)",
            ))
        }
    };
    if let Some(list) = &a.select {
        input.blocks = select(std::mem::take(&mut input.blocks), list)?;
    }
    plot::write_picture_marked(&a.output, &input.blocks, &opts, &marks)?;
    if !a.quiet {
        println!("wrote {}", a.output.display());
    }
    Ok(())
}

/// The blocks `list` names (names or 1-based numbers, comma-separated), in the file's order.
fn select(blocks: Vec<(String, Block)>, list: &str) -> Result<Vec<(String, Block)>> {
    let n = blocks.len();
    let mut keep = vec![false; n];
    for t in list.split(',').map(str::trim) {
        let at = blocks
            .iter()
            .position(|(name, _)| name == t)
            .or_else(|| {
                t.parse::<usize>()
                    .ok()
                    .filter(|&k| (1..=n).contains(&k))
                    .map(|k| k - 1)
            })
            .ok_or_else(|| {
                let names: Vec<&str> = blocks.iter().map(|(b, _)| b.as_str()).collect();
                Error::input(
                    "--select",
                    format!("'{t}': no such block (blocks 1..{n}: {})", names.join(", ")),
                )
            })?;
        keep[at] = true;
    }
    Ok(blocks
        .into_iter()
        .zip(keep)
        .filter_map(|(b, k)| k.then_some(b))
        .collect())
}
