#!/usr/bin/env python3
"""Reads what ellipgrid writes with independent readers (VTK's own) and compares the points.

Usage: python3 .ci/independent_readers.py ELLIPGRID_BINARY WORKDIR

Base grids: the shipped examples (planar, one block, gridded by `ellipgrid run`), and two
synthetic multi-block grids written here as formatted Plot3D (two planar blocks; two curved
volume blocks). Every base is converted by `ellipgrid convert` into every Plot3D flavour (Fortran
unformatted / C stream / formatted; single / double; little / big endian; multi / single block;
2D / 3D; with / without IBLANK) and read with vtkMultiBlockPLOT3DReader (AutoDetectFormat on for
binary files, the options set by hand for ASCII ones, as VTK requires); into .vts (read with
vtkXMLStructuredGridReader), .vtm (vtkXMLMultiBlockDataReader) and .obj (vtkOBJReader). The points
must equal the base's: to 1e-15 of the grid size for double precision, 1e-6 for single. Prints
every check and exits 1 on any mismatch.
"""
import itertools
import math
import os
import subprocess
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

EXE, WORK = sys.argv[1], sys.argv[2]
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.makedirs(WORK, exist_ok=True)
checks, failures = 0, []


def run(*args):
    r = subprocess.run([EXE, *args], cwd=WORK, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"ellipgrid {' '.join(args)} failed ({r.returncode}):\n{r.stdout}{r.stderr}")


def check(name, ok, detail=""):
    global checks
    checks += 1
    print(f"{'ok  ' if ok else 'FAIL'} {name} {detail}")
    if not ok:
        failures.append(f"{name} {detail}")


def write_formatted(path, blocks, two_d):
    """A multi-block formatted Plot3D file; blocks are arrays of shape (nk, nj, ni, 3)."""
    with open(os.path.join(WORK, path), "w") as f:
        f.write(f"{len(blocks)}\n")
        for b in blocks:
            nk, nj, ni, _ = b.shape
            f.write(f"{ni} {nj}\n" if two_d else f"{ni} {nj} {nk}\n")
        for b in blocks:
            for c in range(2 if two_d else 3):
                f.write(" ".join(repr(float(v)) for v in b[..., c].ravel()) + "\n")


def read_formatted(path, two_d):
    """Parses an ASCII multi-block Plot3D file (no IBLANK) into (nk, nj, ni, 3) arrays."""
    tok = open(os.path.join(WORK, path)).read().split()
    nb = int(tok[0])
    rest = tok[1:]
    nd = 2 if two_d else 3
    dims = [tuple(int(v) for v in rest[nd * k:nd * k + nd]) + ((1,) if two_d else ())
            for k in range(nb)]
    vals = np.array([float(v) for v in rest[nd * nb:]])
    out, o = [], 0
    for ni, nj, nk in dims:
        n = ni * nj * nk
        b = np.zeros((nk, nj, ni, 3))
        for c in range(nd):
            b[..., c] = vals[o:o + n].reshape(nk, nj, ni)
            o += n
        out.append(b)
    return out


def compare(name, got, ref, tol):
    """got: list of (points (n, 3), dims) per block; ref: list of (nk, nj, ni, 3) arrays."""
    if len(got) != len(ref):
        return check(name, False, f"{len(got)} blocks, expected {len(ref)}")
    size = max(np.ptp(r.reshape(-1, 3), axis=0).max() for r in ref)
    err = 0.0
    for (pts, dims), r in zip(got, ref):
        nk, nj, ni, _ = r.shape
        if tuple(dims) != (ni, nj, nk):
            return check(name, False, f"dims {tuple(dims)}, expected {(ni, nj, nk)}")
        err = max(err, np.abs(pts - r.reshape(-1, 3)).max() / size)
    check(name, err <= tol, f"max error {err:.2e} of the grid size (tol {tol:.0e})")


def grid_points(g):
    d = [0, 0, 0]
    g.GetDimensions(d)
    return vtk_to_numpy(g.GetPoints().GetData()).astype(float), tuple(d)


def read_plot3d_vtk(path, enc, multi, two_d, iblank, double, big):
    """VTK's reader: autodetection for binary files, except C-stream 2D multi-block files, whose
    first ints (nblocks ni nj …) read equally well as a single 3D block (1 × ni × nj) of another
    precision/IBLANK combination: no reader can tell them apart, so their layout is given."""
    r = vtk.vtkMultiBlockPLOT3DReader()
    r.SetXYZFileName(os.path.join(WORK, path))
    if enc != "formatted" and not (enc == "stream" and two_d and multi):
        r.AutoDetectFormatOn()
    else:
        r.AutoDetectFormatOff()
        r.ForceReadOn()  # VTK still checks its own guess and refuses to differ without this
        r.SetBinaryFile(enc != "formatted")
        r.HasByteCountOff()
        # Formatted: VTK parses the text into float unless told double.
        r.SetDoublePrecision(double or enc == "formatted")
        if big:
            r.SetByteOrderToBigEndian()
        else:
            r.SetByteOrderToLittleEndian()
        r.SetMultiGrid(multi)
        r.SetTwoDimensionalGeometry(two_d)
        r.SetIBlanking(iblank)
    r.Update()
    mb = r.GetOutput()
    return [grid_points(mb.GetBlock(k)) for k in range(mb.GetNumberOfBlocks())]


def plot3d_flavours(base, ref, planar):
    nb = len(ref)
    for enc, prec, endian, multi, two_d, ib in itertools.product(
            ["unformatted", "stream", "formatted"], ["double", "single"], ["little", "big"],
            [True, False], [True, False], [False, True]):
        if (enc == "formatted" and endian == "big") or (not multi and nb > 1) or (two_d and not planar):
            continue
        out = f"{base}_{enc}_{prec}_{endian}_{'m' if multi else 's'}{'2' if two_d else '3'}{'_ib' if ib else ''}.x"
        args = ["convert", "-q", f"{base}_ref.xyz", out, "--encoding", enc, "--precision", prec,
                f"--{endian}-endian", "--multi-block" if multi else "--single-block",
                "--two-d" if two_d else "--three-d", "--iblank" if ib else "--no-iblank"]
        run(*args)
        got = read_plot3d_vtk(out, enc, multi, two_d, ib, prec == "double", endian == "big")
        compare(f"vtkMultiBlockPLOT3DReader {out}", got, ref, 1e-15 if prec == "double" else 1e-6)


def vtk_xml(base, ref):
    if len(ref) == 1:
        run("convert", "-q", f"{base}_ref.xyz", f"{base}.vts")
        r = vtk.vtkXMLStructuredGridReader()
        r.SetFileName(os.path.join(WORK, f"{base}.vts"))
        r.Update()
        compare(f"vtkXMLStructuredGridReader {base}.vts", [grid_points(r.GetOutput())], ref, 1e-15)
    run("convert", "-q", f"{base}_ref.xyz", f"{base}.vtm")
    r = vtk.vtkXMLMultiBlockDataReader()
    r.SetFileName(os.path.join(WORK, f"{base}.vtm"))
    r.Update()
    mb = r.GetOutput()
    got = [grid_points(mb.GetBlock(k)) for k in range(mb.GetNumberOfBlocks())]
    compare(f"vtkXMLMultiBlockDataReader {base}.vtm", got, ref, 1e-15)
    if ref[0].shape[0] == 1:
        names = [mb.GetBlock(0).GetCellData().GetArrayName(k)
                 for k in range(mb.GetBlock(0).GetCellData().GetNumberOfArrays())]
        check(f"{base}.vtm cell data", "skewness" in names, f"arrays {names}")


def obj(base, ref):
    run("convert", "-q", f"{base}_ref.xyz", f"{base}.obj")
    r = vtk.vtkOBJReader()
    r.SetFileName(os.path.join(WORK, f"{base}.obj"))
    r.Update()
    poly = r.GetOutput()
    quads = 0
    for b in ref:
        nk, nj, ni, _ = b.shape
        if nk == 1:
            quads += (ni - 1) * (nj - 1)
        else:
            quads += 2 * ((ni - 1) * (nj - 1) + (nj - 1) * (nk - 1) + (ni - 1) * (nk - 1))
    n = poly.GetNumberOfPolys()
    check(f"vtkOBJReader {base}.obj", n == quads, f"{n} faces, expected {quads} quads")
    # Every written vertex is a node of the grid.
    pts = vtk_to_numpy(poly.GetPoints().GetData()).astype(float)
    nodes = np.concatenate([b.reshape(-1, 3) for b in ref])
    lo, hi = nodes.min(axis=0), nodes.max(axis=0)
    inside = np.all((pts >= lo - 1e-12) & (pts <= hi + 1e-12))
    check(f"vtkOBJReader {base}.obj bounds", bool(inside), "vertices within the grid's box")


def main():
    bases = []
    for ex in ["curved", "boundary_layer", "folding_start"]:
        run("run", "-q", os.path.join(ROOT, "examples", f"{ex}.toml"), "-o", f"{ex}.x")
        run("convert", "-q", f"{ex}.x", f"{ex}_ref.xyz", "--encoding", "formatted",
            "--precision", "double")
        bases.append((ex, True))
    # Two planar blocks (2D multi-block) and two curved volume blocks (3D multi-block).
    def planar(ni, nj, x0):
        i, j = np.meshgrid(np.linspace(0, 1, ni), np.linspace(0, 1, nj))
        b = np.zeros((1, nj, ni, 3))
        b[0, ..., 0] = x0 + i + 0.1 * np.sin(3 * j)
        b[0, ..., 1] = j + 0.05 * i * i
        return b

    def volume(ni, nj, nk, z0):
        k, j, i = np.meshgrid(np.linspace(0, 1, nk), np.linspace(0, 1, nj), np.linspace(0, 1, ni),
                              indexing="ij")
        r = 1 + i
        b = np.zeros((nk, nj, ni, 3))
        b[..., 0] = r * np.cos(1.2 * j)
        b[..., 1] = r * np.sin(1.2 * j)
        b[..., 2] = z0 + k + 0.1 * i * j
        return b

    write_formatted("planar2_ref.xyz", [planar(9, 7, 0.0), planar(5, 11, 1.5)], True)
    write_formatted("volume2_ref.xyz", [volume(6, 5, 4, 0.0), volume(3, 7, 5, 2.0)], False)
    bases += [("planar2", True), ("volume2", False)]
    for base, is_planar in bases:
        ref = read_formatted(f"{base}_ref.xyz", is_planar)
        run("check", f"{base}_ref.xyz")  # our reader takes the text too
        plot3d_flavours(base, ref, is_planar)
        vtk_xml(base, ref)
        obj(base, ref)
    print(f"{checks - len(failures)} passed, {len(failures)} failed")
    if failures:
        print("failures:\n  " + "\n  ".join(failures))
        sys.exit(1)


if __name__ == "__main__":
    main()
