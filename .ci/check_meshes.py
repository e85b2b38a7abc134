#!/usr/bin/env python3
"""Checks ellipgrid's solver meshes with the solvers' own tools (an independent check).

Usage: check_meshes.py ELLIPGRID WORK GRID.x[:CONN] ...

For every grid (with its .conn, if any) it writes an OpenFOAM polyMesh (ASCII and binary), an
SU2 mesh and a Gmsh MSH 4.1 file with `ellipgrid convert`, then
  - runs OpenFOAM's checkMesh: every topology check must pass, and the mesh must be
    "Mesh OK." or fail only the checks ALLOWED names for that example, with the reason;
    the binary polyMesh must give checkMesh the same cells, points, patches and verdict;
  - reads the SU2 and Gmsh files with meshio, and the Gmsh file with the gmsh package: the
    same number of nodes and cells as the polyMesh (the 2D ones: half its points), every
    family a named marker / physical group with the same number of boundary faces as the
    polyMesh patch.
  - writes a CGNS file: cgnscheck must report no warning and no error, and h5py reads it
    independently: every 1to1 connection's point range, donor range and transform map each
    node onto a node of the donor zone with the same coordinates.
Surface grids (not volumes, not planar) give only the Gmsh and CGNS files.
For the airfoil C-grid (rae2822_cgrid) it also writes the runnable OpenFOAM case
(`convert grid.x DIR/rae.foam`) and runs it: checkMesh ("Mesh OK."), then simpleFoam from
the uniform free stream for FOAM_ITERATIONS iterations; it must end without error and the
initial residuals of Ux, Uy and p must fall by the factors FOAM_FALLS asks. Exit 1 on any
failure.
"""
import os
import re
import subprocess
import sys

import gmsh
import h5py
import meshio
import numpy as np

FOAM_BASHRC = "/usr/share/openfoam/etc/bashrc"
CONTROL = """FoamFile { version 2.0; format ascii; class dictionary; object %s; }
"""


def case_dir(path):
    os.makedirs(os.path.join(path, "system"), exist_ok=True)
    files = {
        "controlDict": "application simpleFoam; startFrom startTime; startTime 0; "
        "stopAt endTime; endTime 1; deltaT 1; writeControl timeStep; writeInterval 1;\n",
        "fvSchemes": "ddtSchemes { default steadyState; } gradSchemes { default Gauss linear; }\n"
        "divSchemes { default none; } laplacianSchemes { default Gauss linear corrected; }\n"
        "interpolationSchemes { default linear; } snGradSchemes { default corrected; }\n",
        "fvSolution": "",
    }
    for name, body in files.items():
        with open(os.path.join(path, "system", name), "w") as f:
            f.write(CONTROL % name + body)


# Wall spacings of 1e-5 chord carried along a flat wall or a wake give in-plane aspect ratios
# (OpenFOAM's: the ratio of the Cartesian extents) of thousands: allowed where the case design
# still has them (docs/SOLVER_MESHES.md, "What the solvers' own tools say"). rae2822_cgrid's
# wake grows its normal spacing downstream, airfoil_wall has 385 nodes along its flat floor,
# nlr7301_flap smooth wake lines and 0.5-chord cells at the outflow: they pass ("Mesh OK.").
HIGH_ASPECT = "***High aspect ratio cells found"

# Checks that may fail, with the reason.
ALLOWED = {
    # The one C-O block of the M6 tip, F6 (the wing plane beyond the tip) a boundary patch.
    # checkMesh's aspect ratio compares Cartesian projections of the faces, so a wall cell
    # counts with its true ratio (chordwise step / first height, ~2200 at mid-chord with 64
    # chordwise intervals and 1e-5 ... 2e-5 local chord) only where its faces are normal to
    # the axes: the 33 cells flagged (max 1816) are the first 3 wall layers in the last 2 k
    # intervals of the cap next to the tip edge (k = 30..31, 0.1-0.4 local chord), where the
    # cap's wall is normal to y and its x-slope vanishes; inboard the section's slope tilts
    # the same cells (checkMesh max 398 off the cap, true ratio up to 22 259; 10 666 cells above 1000).
    # Below 1000 there needs chordwise steps under 1000 x the wall spacing (0.011-0.014
    # chord over 0.1-0.4 chord; the mean step is 0.016), i.e. a chordwise distribution
    # clustered at mid-chord instead of at the leading and trailing edges (tests/wing_co.rs
    # high_aspect_ratio_cells_are_..., docs/WING_CO_BLOCK.md). No highly skewed face since
    # the cap's last step matches the step beyond the 180-degree edge at the leading edge
    # (max skewness 3.53; 166 faces on F6 up to 43.2 before).
    "wing_m6_co": [HIGH_ASPECT],
    # The ONERA M6 four-block C-O grid (examples/m6): the same wall cells, seen by checkMesh
    # where their faces are normal to the axes (max 2252 at full size, 178 cells, all in the
    # two wing volumes, mirror images, in the first 6 wall layers at 0.25-0.53 local chord):
    # 134 on the cap next to the tip edge (k = 38..47 of 48) and 44 inboard (k = 0..1,
    # 10..17) where a cell straddles the section's maximum thickness (x/c 0.35-0.43, zero
    # slope). Their true ratio (chordwise step 0.034 chord / first height) is ~2300 at
    # mid-chord along the whole span (17 760 of each wing volume's 196 608 cells above 1000;
    # the wake volumes 397 at most): below 1000 needs steps under 0.014 chord at mid-chord
    # (mean 0.016), inherent to 1e-5 chord with 64 chordwise intervals clustered at the
    # leading and trailing edges. No highly skewed face since the spanwise steps at the tip
    # match those beyond the 180-degree edges (max skewness 3.62; docs/ONERA_M6.md, "No highly
    # skewed faces").
    "wing_m6_4block": [HIGH_ASPECT],
}


def check_mesh(case, name):
    out = subprocess.run(
        ["bash", "-c", f"source {FOAM_BASHRC} >/dev/null 2>&1; checkMesh -case '{case}'"],
        capture_output=True, text=True).stdout
    problems = []
    for check in ["Boundary definition OK.", "Cell to face addressing OK.", "Point usage OK.",
                  "Upper triangular ordering OK.", "Face vertices OK.",
                  "Number of regions: 1 (OK).", "Face pyramids OK.", "Cell volumes OK."]:
        if check not in out:
            problems.append("missing '" + check + "'")
    if "Mesh OK." not in out:
        flagged = [l.strip() for l in out.splitlines() if l.strip().startswith("***")]
        allowed = ALLOWED.get(name, [])
        failed = re.search(r"Failed (\d+) mesh checks", out)
        if not failed or int(failed.group(1)) != len(flagged) or any(
                not any(l.startswith(a) for a in allowed) for l in flagged):
            problems.append("checkMesh failed:\n" + "\n".join(
                l for l in out.splitlines() if "***" in l or "Failed" in l or "FATAL" in l))
    cells = int(re.search(r"cells:\s+(\d+)", out).group(1)) if "cells:" in out else -1
    points = int(re.search(r"points:\s+(\d+)", out).group(1)) if "points:" in out else -1
    patches = dict((m.group(1), int(m.group(2))) for m in re.finditer(
        r"^\s+(\S+)\s+(\d+)\s+\d+\s+ok", out, re.M))
    verdict = "Mesh OK" if "Mesh OK." in out else "; ".join(
        l.strip().lstrip("*") for l in out.splitlines() if l.strip().startswith("***"))
    if not patches:
        problems.append("no output:\n" + out[-2000:])
    return problems, cells, points, patches, verdict


def label(node):
    v = node.attrs.get("label") if isinstance(node, h5py.Group) else None
    if v is None:
        return ""
    v = v.tobytes() if hasattr(v, "tobytes") else bytes(v)
    return v.split(b"\0")[0].decode()


def cgns_text(node):
    return node[" data"][()].tobytes().decode().rstrip("\0")


def check_cgns(exe, grid, extra, work, name):
    """cgnscheck without warnings or errors; h5py reads every zone and checks every 1to1
    connection geometrically: the node the point range, donor range and transform map a
    node to has the same coordinates."""
    path = os.path.join(work, name + ".cgns")
    subprocess.run([exe, "convert", "-q", grid, path] + extra, check=True)
    out = subprocess.run(["cgnscheck", "-w", "3", path], capture_output=True, text=True)
    problems = [l.strip() for l in (out.stdout + out.stderr).splitlines()
                if "WARNING" in l or "ERROR" in l]
    if out.returncode != 0:
        problems.append(f"cgnscheck exit {out.returncode}")
    f = h5py.File(path, "r")
    base = next(f[k] for k in f if k.strip() and label(f[k]) == "CGNSBase_t")
    zones = {k: base[k] for k in base if label(base[k]) == "Zone_t"}
    xyz = {}
    for zn, z in zones.items():
        g = z["GridCoordinates"]
        xyz[zn] = [g[c][" data"][()] for c in ("CoordinateX", "CoordinateY", "CoordinateZ") if c in g]
    scale = max(float(np.ptp(np.concatenate([c.ravel() for c in xyz[zn]]))) for zn in xyz)
    n1to1 = 0
    for zn, z in zones.items():
        if "ZoneGridConnectivity" not in z:
            continue
        for cn in z["ZoneGridConnectivity"]:
            c = z["ZoneGridConnectivity"][cn]
            if not cn.strip() or label(c) != "GridConnectivity1to1_t":
                continue
            n1to1 += 1
            donor = cgns_text(c)
            r = c["PointRange"][" data"][()]
            d = c["PointRangeDonor"][" data"][()]
            t = c["Transform"][" data"][()]
            dim = len(t)
            T = np.zeros((dim, dim), int)
            for a in range(dim):
                T[abs(t[a]) - 1, a] = np.sign(t[a])
            worst = 0.0
            ranges = [range(min(r[0][k], r[1][k]), max(r[0][k], r[1][k]) + 1) for k in range(dim)]
            for idx in np.stack(np.meshgrid(*ranges, indexing="ij"), -1).reshape(-1, dim):
                di = d[0] + T @ (idx - r[0])
                # h5py arrays are (k, j, i) / (j, i): reversed index order, 0-based
                p = [x[tuple(idx[::-1] - 1)] for x in xyz[zn]]
                q = [x[tuple(di[::-1] - 1)] for x in xyz[donor]]
                worst = max(worst, max(abs(a - b) for a, b in zip(p, q)))
            if worst > 1e-12 * scale:
                problems.append(f"1to1 {zn}/{cn} -> {donor}: nodes {worst:.3e} apart")
    return problems, len(zones), n1to1


# The example whose OpenFOAM case is run, for how many simpleFoam iterations, and how far
# the first initial residual of each field must fall by then.
FOAM_CASE_EXAMPLE = "rae2822_cgrid"
FOAM_ITERATIONS = 200
FOAM_FALLS = (("Ux", 3000.0), ("Uy", 300.0), ("p", 3000.0))


def foam(case, command):
    """Runs an OpenFOAM command in a case; its exit code and log."""
    r = subprocess.run(["bash", "-c", f"source {FOAM_BASHRC} >/dev/null 2>&1; {command} "
                        f"-case '{case}'"], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def residuals(log, field):
    """The initial residual of `field`'s first solve in each iteration (p is solved once
    per non-orthogonal corrector), in order."""
    out = []
    for step in log.split("\nTime = ")[1:]:
        m = re.search(r"Solving for " + field + r", Initial residual = ([^,]+),", step)
        if m:
            out.append(float(m.group(1)))
    return out


def run_case(exe, grid, extra, work, name):
    """Writes the runnable OpenFOAM case of a grid and runs simpleFoam for FOAM_ITERATIONS
    iterations: it must end, and the residuals must fall by FOAM_FALLS."""
    case = os.path.join(work, name + "_case")
    subprocess.run([exe, "convert", "-q", grid, os.path.join(case, name + ".foam")] + extra,
                   check=True)
    control = os.path.join(case, "system", "controlDict")
    text = re.sub(r"(?m)^endTime\s.*$", f"endTime         {FOAM_ITERATIONS};", open(control).read())
    open(control, "w").write(text)
    problems, _, _, _, verdict = check_mesh(case, name)
    if verdict != "Mesh OK":
        problems.append(f"checkMesh on the case: {verdict}")
    out = []
    code, log = foam(case, "simpleFoam")
    if code != 0 or "\nEnd" not in log or "FOAM FATAL" in log or "nan" in log.lower():
        problems.append(f"simpleFoam failed (exit {code}):\n" + log[-2000:])
    else:
        for field, fall in FOAM_FALLS:
            r = residuals(log, field)
            if len(r) < FOAM_ITERATIONS or not r[-1] * fall < r[0]:
                problems.append(f"simpleFoam: {field} residuals do not fall {fall:g}x: "
                                f"{r[:1]} ... {r[-1:]} ({len(r)} solves)")
            out.append(f"{field} {r[0]:.3g} -> {r[-1]:.3g}")
    print(f"{name}: OpenFOAM case: {FOAM_ITERATIONS} simpleFoam iterations: "
          f"{'ok' if not problems else 'FAILED'}; initial residuals {', '.join(out)}")
    for p in problems:
        print("   ", p)
    return bool(problems)


def main():
    exe, work = sys.argv[1], sys.argv[2]
    bad = 0
    for arg in sys.argv[3:]:
        grid, _, conn = arg.partition(":")
        name = re.sub(r"_run$", "", os.path.splitext(os.path.basename(grid))[0])
        extra = ["--conn", conn] if conn else []
        case = os.path.join(work, name + "_foam")
        pm = os.path.join(case, "constant", "polyMesh")
        r = subprocess.run([exe, "convert", "-q", grid, pm] + extra, capture_output=True, text=True)
        surface = r.returncode != 0 and "surface grids cannot be written" in r.stderr
        if r.returncode != 0 and not surface:
            print(f"{name}: polyMesh not written: {r.stderr.strip()}")
            bad += 1
            continue
        msh = os.path.join(work, name + ".msh")
        subprocess.run([exe, "convert", "-q", grid, msh] + extra, check=True)
        m = meshio.read(msh)
        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(msh)
        groups = {gmsh.model.getPhysicalName(d, t): (d, t) for d, t in gmsh.model.getPhysicalGroups()}
        nodes = len(gmsh.model.mesh.getNodes()[0])
        gmsh.finalize()
        cgns_problems, nzones, n1to1 = check_cgns(exe, grid, extra, work, name)
        if surface:
            print(f"{name}: surface grid: Gmsh and CGNS only ({nodes} nodes, {len(groups)} "
                  f"groups; CGNS {nzones} zones)")
            for p in cgns_problems:
                print("   ", p)
            bad += bool(cgns_problems)
            continue
        case_dir(case)
        problems, cells, points, patches, verdict = check_mesh(case, name)
        # The same mesh in OpenFOAM's binary format: checkMesh must see the same mesh.
        bcase = os.path.join(work, name + "_foam_binary")
        subprocess.run([exe, "convert", "-q", grid, os.path.join(bcase, "constant", "polyMesh"),
                        "--foam-format", "binary"] + extra, check=True)
        case_dir(bcase)
        bproblems, bcells, bpoints, bpatches, bverdict = check_mesh(bcase, name)
        problems += ["binary: " + p for p in bproblems]
        if (bcells, bpoints, bpatches, bverdict) != (cells, points, patches, verdict):
            problems.append(f"binary polyMesh differs: {bcells} cells, {bpoints} points, "
                            f"{bpatches}, {bverdict}")
        su2 = os.path.join(work, name + ".su2")
        subprocess.run([exe, "convert", "-q", grid, su2] + extra, check=True)
        s = meshio.read(su2)
        planar = "frontAndBack" in patches
        want_points = points // 2 if planar else points
        vol = "hexahedron" if not planar else "quad"
        ncells_su2 = sum(len(c.data) for c in s.cells if c.type == vol)
        ncells_msh = sum(len(c.data) for c in m.cells if c.type == vol)
        if len(s.points) != want_points or len(m.points) != want_points or nodes != want_points:
            problems.append(f"points: polyMesh {points}, su2 {len(s.points)}, msh "
                            f"{len(m.points)}, gmsh {nodes}")
        if ncells_su2 != cells or ncells_msh != cells:
            problems.append(f"cells: polyMesh {cells}, su2 {ncells_su2}, msh {ncells_msh}")
        su2_tags = open(su2).read()
        for patch, nfaces in patches.items():
            if patch == "frontAndBack":
                continue
            if patch not in groups:
                problems.append(f"patch {patch} is no Gmsh physical group")
            if f"MARKER_TAG= {patch}\nMARKER_ELEMS= {nfaces}\n" not in su2_tags:
                problems.append(f"patch {patch}: SU2 marker lacks its {nfaces} faces")
            if m.cell_sets.get(patch) is None:
                problems.append(f"patch {patch}: meshio finds no cell set")
            else:
                n = sum(len(x) for x in m.cell_sets[patch] if x is not None)
                if n != nfaces:
                    problems.append(f"patch {patch}: meshio {n} faces, polyMesh {nfaces}")
        problems += cgns_problems
        status = "ok" if not problems else "FAILED"
        print(f"{name}: {status}: {cells} cells, {points} points, {len(patches)} patches; "
              f"checkMesh: {verdict} (ASCII and binary); CGNS: {nzones} zones, {n1to1} 1to1 (cgnscheck clean, "
              f"donors coincide)")
        for p in problems:
            print("   ", p)
        bad += bool(problems)
        if name == FOAM_CASE_EXAMPLE:
            bad += run_case(exe, grid, extra, work, name)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
