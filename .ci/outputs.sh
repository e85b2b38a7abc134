#!/usr/bin/env bash
# Checks ellipgrid's outputs with independent tools (run by .ci/run after the tests):
#  - VTK's readers on every Plot3D flavour, .vts, .vtm and .obj (.ci/independent_readers.py);
#  - the Khronos glTF validator on the .glb of every example, of a volume grid with quality
#    colours, and on a .gltf (.ci/gltf_validate.js; zero errors required);
#  - NASA's plot3d package on the connectivity file of every multi-block example: the faces
#    it matches from the coordinates alone are the .conn file's interfaces, its exterior
#    faces the .conn file's patches (.ci/check_conn.py), and on that of a STEP file's face
#    blocks (`step grid --all -o .conn`).
# Needs: python3 with vtk and plot3d (pip install vtk plot3d), node with gltf-validator under
# target/ci-node.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --features cgns
exe="$PWD/target/release/ellipgrid"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

python3 .ci/independent_readers.py "$exe" "$work"

glbs=()
conns=()
meshes=()
for ex in examples/*.toml; do
  name="$(basename "$ex" .toml)"
  extra=()
  if grep -q '^\[\[edge\]\]' "$ex"; then
    extra=(-o "$work/$name.conn")
  fi
  "$exe" run -q "$ex" -o "$work/${name}_run.x" -o "$work/$name.glb" -o "$work/$name.png" \
    -o "$work/$name.svg" "${extra[@]}"
  "$exe" convert -q "$work/${name}_run.x" "$work/${name}_skewness.glb" --color skewness
  glbs+=("$work/$name.glb" "$work/${name}_skewness.glb")
  if [ ${#extra[@]} -gt 0 ]; then
    meshes+=("$work/${name}_run.x:$work/$name.conn")
  else
    meshes+=("$work/${name}_run.x")
  fi
  if [ ${#extra[@]} -gt 0 ]; then
    "$exe" convert -q "$work/${name}_run.x" "$work/${name}_3d.x" --three-d
    conns+=("$work/${name}_3d.x" "$work/$name.conn")
  fi
done
# The ONERA M6 four-block C–O grid (examples/m6, outside the loop above: ~40 s at full size):
# its solver mesh through checkMesh (ALLOWED in check_meshes.py: the aspect ratio only).
"$exe" run -q examples/m6/wing_m6_4block.toml -o "$work/wing_m6_4block_run.x" \
  -o "$work/wing_m6_4block.conn"
meshes+=("$work/wing_m6_4block_run.x:$work/wing_m6_4block.conn")
# The connectivity of CAD face blocks (`step grid … -o .conn`): the plate's hole rings, its
# cylinder faces' seams and the faces' common edges.
"$exe" step grid data/step/plate_with_holes.step --all --ni 9 --nj 9 -q \
  -o "$work/plate_faces.x" -o "$work/plate_faces.conn"
conns+=("$work/plate_faces.x" "$work/plate_faces.conn")
status=0
python3 .ci/check_conn.py "${conns[@]}" > "$work/conn.log" 2>&1 || status=$?
grep -a 'conn: \|only in' "$work/conn.log" || cat "$work/conn.log"
[ "$status" -eq 0 ]
# Multi-block volume and planar grids written by independent_readers.py.
"$exe" convert -q "$work/volume2_ref.xyz" "$work/volume2.glb" --color jacobian
"$exe" convert -q "$work/planar2_ref.xyz" "$work/planar2.gltf" --color aspect
"$exe" plot -q "$work/volume2_ref.xyz" -o "$work/volume2.png" --color skewness
NODE_PATH="$PWD/target/ci-node/node_modules" node .ci/gltf_validate.js \
  "${glbs[@]}" "$work/volume2.glb" "$work/planar2.gltf"
# Solver meshes of every example, checked by the solvers' tools.
mkdir -p "$work/meshes"
python3 .ci/check_meshes.py "$exe" "$work/meshes" "${meshes[@]}" 2>"$work/meshes.log" ||
  { cat "$work/meshes.log"; exit 1; }
