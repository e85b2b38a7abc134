#!/usr/bin/env python3
"""ellipgrid against Gmsh on the same domains, side by side in one run (#16 item 3).

Usage: python3 bench/gmsh_side_by_side.py [--exe target/release/ellipgrid]
           [--sizes 257 513 1025] [--cases curved dented] [--sweeps 1000] [--repeat 1]

For every case and size N (N x N nodes) it
  1. grids the case file with `ellipgrid run` (the [[block]]'s ni and nj set to N; wall time of
     the whole process: reading the case, the boundary, the solve, writing the Plot3D file;
     the block's solve time from the --report JSON in brackets);
  2. meshes the SAME domain with Gmsh (the `gmsh` Python package): the boundary nodes of
     ellipgrid's grid become the points of a built-in-kernel plane surface, one straight
     transfinite curve of 2 nodes per boundary segment, the surface transfinite with the four
     block corners and recombined into quadrilaterals, so that Gmsh's boundary nodes are
     ellipgrid's bit for bit. Gmsh's transfinite surface mesher (src/mesh/
     meshGFaceTransfinite.cpp) interpolates transfinitely and then, when `Mesh.Smoothing` is
     above 1, runs Mesh.Smoothing - 1 Gauss-Seidel sweeps of its elliptic (Winslow) smoother
     on the interior nodes (no control functions); the default Mesh.Smoothing = 1 runs none.
     Two runs: the default (the transfinite grid) and `--sweeps` sweeps (Mesh.Smoothing =
     sweeps + 1). Timed: gmsh.model.mesh.generate(2) alone (model building excluded);
  3. reads Gmsh's quadrilaterals back into the structured (i, j) array (the mesher creates
     them i-major, checked against the boundary), writes it as Plot3D and counts its folded
     cells with `ellipgrid check`, exactly as for ellipgrid's own grid;
and prints one line per case and size: the times, the fold counts and the ratios of Gmsh's
time to ellipgrid's. Gmsh's smoother is serial; ellipgrid uses RAYON_NUM_THREADS threads (all
cores by default; the line says how many).

The domains: `curved` is examples/curved.toml (a smooth curved quadrilateral), `dented` is
examples/dented_square.toml (a unit square with a deep, narrow mushroom-shaped dent whose
transfinite grid folds).
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

import gmsh
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASES = {
    "curved": os.path.join(ROOT, "examples", "curved.toml"),
    "dented": os.path.join(ROOT, "examples", "dented_square.toml"),
}


def sized_case(src, n, dst):
    """The case file with its one block's ni and nj set to n."""
    text = open(src).read()
    text, ki = re.subn(r"(?m)^ni\s*=\s*\d+", f"ni = {n}", text)
    text, kj = re.subn(r"(?m)^nj\s*=\s*\d+", f"nj = {n}", text)
    if ki != 1 or kj != 1:
        sys.exit(f"{src}: expected one block with ni and nj")
    # relative input paths stay relative to the original case file
    text = re.sub(r'file\s*=\s*"(?!/)', 'file = "' + os.path.dirname(src) + "/", text)
    with open(dst, "w") as f:
        f.write(text)


def read_plot3d_2d(path):
    """A single-block 2D Plot3D file as ellipgrid writes it by default (unformatted Fortran
    records, doubles, with the block-count record): x, y as (nj, ni) arrays."""
    raw = open(path, "rb").read()
    pos = 0
    recs = []
    while pos < len(raw):
        n = int.from_bytes(raw[pos:pos + 4], "little")
        recs.append(raw[pos + 4:pos + 4 + n])
        pos += 8 + n
    if len(recs) != 3 or np.frombuffer(recs[0], "<i4")[0] != 1:
        sys.exit(f"{path}: not a one-block 2D Plot3D file")
    ni, nj = np.frombuffer(recs[1], "<i4")[:2]
    xy = np.frombuffer(recs[2], "<f8").reshape(2, nj, ni)
    return xy[0], xy[1]


def write_plot3d_2d(path, x, y):
    """The same flavour back (what `ellipgrid check` reads)."""
    def rec(b):
        return len(b).to_bytes(4, "little") + b + len(b).to_bytes(4, "little")
    nj, ni = x.shape
    with open(path, "wb") as f:
        f.write(rec(np.array([1], "<i4").tobytes()))
        f.write(rec(np.array([ni, nj], "<i4").tobytes()))
        f.write(rec(np.concatenate([x.ravel(), y.ravel()]).astype("<f8").tobytes()))


def folded(exe, grid, work):
    """Folded cells of a grid file, counted by `ellipgrid check` (its report JSON)."""
    rep = os.path.join(work, "check.json")
    subprocess.run([exe, "check", grid, "--report", rep], capture_output=True)
    return json.load(open(rep))["blocks"][0]["quality"]["folded_cells"]


def gmsh_grid(x, y, sweeps):
    """Gmsh's transfinite grid of the domain bounded by the boundary nodes of (x, y), with
    `sweeps` elliptic smoothing sweeps (0: Gmsh's default). Returns (seconds of generate(2),
    x, y as (nj, ni) arrays)."""
    nj, ni = x.shape
    # the boundary counter-clockwise from (0, 0): j = 0, i = N, j = M backwards, i = 0 backwards
    loop = ([(i, 0) for i in range(ni - 1)] + [(ni - 1, j) for j in range(nj - 1)]
            + [(i, nj - 1) for i in range(ni - 1, 0, -1)] + [(0, j) for j in range(nj - 1, 0, -1)])
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("side_by_side")
    geo = gmsh.model.geo
    pts = [geo.addPoint(x[j, i], y[j, i], 0.0) for i, j in loop]
    lines = [geo.addLine(pts[k], pts[(k + 1) % len(pts)]) for k in range(len(pts))]
    cl = geo.addCurveLoop(lines)
    s = geo.addPlaneSurface([cl])
    geo.synchronize()
    for c in lines:
        gmsh.model.mesh.setTransfiniteCurve(c, 2)
    corners = [pts[0], pts[ni - 1], pts[ni - 1 + nj - 1], pts[2 * (ni - 1) + nj - 1]]
    gmsh.model.mesh.setTransfiniteSurface(s, "Left", corners)
    gmsh.model.mesh.setRecombine(2, s)
    gmsh.option.setNumber("Mesh.Smoothing", sweeps + 1 if sweeps else 1)
    t0 = time.perf_counter()
    gmsh.model.mesh.generate(2)
    seconds = time.perf_counter() - t0
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = np.empty((int(tags.max()) + 1, 3))
    xyz[tags] = coords.reshape(-1, 3)
    _, quads = gmsh.model.mesh.getElementsByType(3)
    gmsh.finalize()
    # Quadrilaterals come i-major: quad (i, j) = (tab[i][j], tab[i+1][j], tab[i+1][j+1],
    # tab[i][j+1]) for i < L, j < H, L along the first corners' side.
    q = quads.reshape(ni - 1, nj - 1, 4)
    node = np.zeros((ni, nj), dtype=np.int64)
    node[:-1, :-1] = q[:, :, 0]
    node[1:, :-1] = q[:, :, 1]
    node[1:, 1:] = q[:, :, 2]
    node[:-1, 1:] = q[:, :, 3]
    if not (np.array_equal(node[1:, :-1], q[:, :, 1]) and np.array_equal(node[:-1, 1:], q[:, :, 3])
            and np.array_equal(node[:-1, :-1], q[:, :, 0])):
        sys.exit("Gmsh's quadrilaterals are not in the transfinite (i, j) order")
    gx = xyz[node, 0].T.copy()
    gy = xyz[node, 1].T.copy()
    edge = np.concatenate([np.abs(gx - x)[[0, -1], :].ravel(), np.abs(gx - x)[:, [0, -1]].ravel(),
                           np.abs(gy - y)[[0, -1], :].ravel(), np.abs(gy - y)[:, [0, -1]].ravel()])
    if edge.max() > 1e-12 * (np.ptp(x) + np.ptp(y)):
        sys.exit(f"Gmsh's boundary nodes are not ellipgrid's ({edge.max():.2e} apart)")
    return seconds, gx, gy


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", default=os.path.join(ROOT, "target", "release", "ellipgrid"))
    ap.add_argument("--sizes", type=int, nargs="+", default=[257, 513, 1025])
    ap.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    ap.add_argument("--sweeps", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=1, help="runs of each; the fastest is printed")
    a = ap.parse_args()
    threads = os.environ.get("RAYON_NUM_THREADS", str(os.cpu_count()))
    print(f"ellipgrid ({threads} threads) vs gmsh {gmsh.__version__} (serial); wall seconds, "
          f"fastest of {a.repeat}; folds = folded cells by `ellipgrid check`")
    print(f"{'case':8} {'nodes':>6} | {'ellipgrid s':>17} {'folds':>5} | {'gmsh TFI s':>10} "
          f"{'folds':>6} | {f'gmsh {a.sweeps} sweeps s':>20} {'folds':>6} | {'ratio':>6}")
    with tempfile.TemporaryDirectory() as work:
        for case in a.cases:
            for n in a.sizes:
                toml = os.path.join(work, f"{case}.toml")
                sized_case(CASES[case], n, toml)
                grid = os.path.join(work, f"{case}.x")
                rep = os.path.join(work, "run.json")
                best = None
                for _ in range(a.repeat):
                    t0 = time.perf_counter()
                    r = subprocess.run([a.exe, "run", "-q", toml, "-o", grid, "--report", rep,
                                        "--allow-folded"], capture_output=True, text=True)
                    wall = time.perf_counter() - t0
                    if r.returncode not in (0, 3):  # 3: it folds (counted below)
                        sys.exit(f"ellipgrid run {case} {n}: exit {r.returncode}: {r.stderr}")
                    solve = json.load(open(rep))["blocks"][0]["seconds"]
                    if best is None or wall < best[0]:
                        best = (wall, solve)
                ours = folded(a.exe, grid, work)
                x, y = read_plot3d_2d(grid)
                res = {}
                for sweeps in (0, a.sweeps):
                    times = []
                    for _ in range(a.repeat):
                        sec, gx, gy = gmsh_grid(x, y, sweeps)
                        times.append(sec)
                    g = os.path.join(work, "gmsh.x")
                    write_plot3d_2d(g, gx, gy)
                    res[sweeps] = (min(times), folded(a.exe, g, work))
                (t0s, f0), (t1s, f1) = res[0], res[a.sweeps]
                print(f"{case:8} {n:>4}^2 | {best[0]:7.3f} ({best[1]:6.3f}) {ours:>5} | "
                      f"{t0s:10.3f} {f0:>6} | {t1s:20.3f} {f1:>6} | {t1s / best[0]:5.1f}x",
                      flush=True)


if __name__ == "__main__":
    main()
