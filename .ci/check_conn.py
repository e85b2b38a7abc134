#!/usr/bin/env python3
"""Checks ellipgrid's connectivity files with NASA's plot3d package (an independent tool).

Usage: check_conn.py GRID3D.x CONN [GRID3D.x CONN ...]

GRID3D.x is the grid as a 3D whole multi-block Fortran-unformatted double Plot3D file
(`ellipgrid convert --three-d`); 2D blocks (KMAX = 1) are extruded to two layers so that
their sides become faces (surface blocks too, e.g. a STEP file's face blocks: a shift along z
keeps coincident sides coincident). plot3d.connectivity finds the matching faces from the coordinates
alone; they must be exactly the 1-to-1 interfaces of the .conn file (same blocks, same index
ranges), and plot3d's exterior faces (apart from the extrusion's k planes) must cover exactly
the block sides the .conn file's boundary patches cover (plot3d merges neighbouring exterior
faces, the .conn file has one patch per edge: the cells covered are compared).
"""
import sys
import numpy as np
import plot3d


def read_conn(path):
    tok = [l.split() for l in open(path) if l.strip()]
    k = 0
    n = int(tok[k][0]); k += 1
    inter = set()
    for _ in range(n):
        a, b = tok[k], tok[k + 1]; k += 2
        inter.add(frozenset([side(a), side(b)]))
    n = int(tok[k][0]); k += 1
    patches = set()
    for _ in range(n):
        patches.add(side(tok[k][:7])); k += 1
    return inter, patches


def side(t):
    """(block 0-based, imin, jmin, imax, jmax) 0-based, min/max order, k dropped."""
    b, i0, j0, _, i1, j1, _ = (int(v) for v in t[:7])
    return (b - 1, min(i0, i1) - 1, min(j0, j1) - 1, max(i0, i1) - 1, max(j0, j1) - 1)


def cells(sides):
    """The cell edges along block sides that a set of sides covers."""
    out = set()
    for b, i0, j0, i1, j1 in sides:
        if i0 == i1:
            out.update((b, "i", i0, j) for j in range(j0, j1))
        else:
            out.update((b, "j", j0, i) for i in range(i0, i1))
    return out


def interface_cover(ifaces):
    """The block pairs the interfaces join and the cell edges they cover."""
    pairs = set()
    sides = []
    for f in ifaces:
        two = sorted(f)
        pairs.add(frozenset(s[0] for s in two))
        sides.extend(two)
    return pairs, cells(sides)


def face(d):
    lb, ub = d['lb'], d['ub']
    return (int(d['block_index']), min(lb[0], ub[0]), min(lb[1], ub[1]),
            max(lb[0], ub[0]), max(lb[1], ub[1]))


def check(grid, conn):
    blocks = plot3d.read_plot3D(grid, binary=True, read_double=True, fortran=True)
    ext = []
    for b in blocks:
        if b.KMAX == 1:
            X = np.repeat(b.X, 2, axis=2)
            Y = np.repeat(b.Y, 2, axis=2)
            Z = np.concatenate([b.Z, b.Z + 1.0], axis=2)
            b = plot3d.Block(X, Y, Z)
        ext.append(b)
    matches, outer = plot3d.connectivity.connectivity(ext)
    theirs = set(frozenset([face(m['block1']), face(m['block2'])]) for m in matches)
    ours, patches = read_conn(conn)
    ok = True
    # plot3d merges neighbouring matching faces into one; the .conn file lists one interface
    # per topology edge (an interface split at a vertex is two): compare the block pairs and
    # the cells the interfaces cover
    if theirs != ours and interface_cover(theirs) != interface_cover(ours):
        ok = False
        print(f"{conn}: interfaces differ\n  only in plot3d: {sorted(map(sorted, theirs - ours))}"
              f"\n  only in .conn:  {sorted(map(sorted, ours - theirs))}")
    # exterior faces: drop the k = const planes of the extrusion
    outer_sides = set()
    for o in outer:
        lb, ub = o['lb'], o['ub']
        if lb[2] == ub[2]:
            continue
        outer_sides.add(face(o))
    outer_sides, patches = cells(outer_sides), cells(patches)
    if outer_sides != patches:
        ok = False
        print(f"{conn}: boundary patches differ\n  only in plot3d: {sorted(outer_sides - patches)[:10]}"
              f"\n  only in .conn:  {sorted(patches - outer_sides)[:10]}")
    print(f"{conn}: {len(ours)} interfaces and the boundary patches "
          f"{'match' if ok else 'DO NOT match'} NASA plot3d's connectivity")
    return ok


if __name__ == "__main__":
    args = sys.argv[1:]
    results = [check(args[k], args[k + 1]) for k in range(0, len(args), 2)]
    sys.exit(0 if all(results) else 1)
