#!/usr/bin/env bash
# Byte comparison of every grid ellipgrid writes, between a git revision and the work tree.
#
#   scripts/same-grids.sh REV [OUT]
#
# Builds REV (in a temporary git worktree) and the work tree, runs in each: every shipped
# example case (`run`, Plot3D + .vts + .glb), `smooth` of a start grid (2D and volume),
# `convert` into the other Plot3D flavours, `step export` + `step grid`, and every benchmark
# (`--quick` sizes, `--write`: each computed grid or solution as raw f64); then compares the
# two output folders file by file (`cmp`). Exit 0 when every file is byte-identical.
# RAYON_NUM_THREADS is 1 unless set: some solver paths still reduce in a thread-dependent
# order (issue on deterministic output).
set -euo pipefail
rev="${1:?usage: scripts/same-grids.sh REV [OUT]}"
top="$(git rev-parse --show-toplevel)"
out="${2:-$(mktemp -d)}"
export RAYON_NUM_THREADS="${RAYON_NUM_THREADS:-1}"
tree="$out/tree-$rev"
rm -rf "$tree"
git -C "$top" worktree add --detach --force "$tree" "$rev" >/dev/null
trap 'git -C "$top" worktree remove --force "$tree" >/dev/null 2>&1 || true' EXIT

# Runs every case of the tree $1 (its own sources), writing into $2.
produce() {
  local src="$1" dst="$2" exe
  rm -rf "$dst"
  mkdir -p "$dst"
  # one target folder for both trees: the dependencies are built once
  (cd "$src" && CARGO_TARGET_DIR="$top/target" cargo build --release --quiet --bin ellipgrid \
    --example bench_grid --example bench_volume --example bench_multigrid --example bench_surface)
  exe="$top/target/release/ellipgrid"
  for ex in "$src"/examples/*.toml; do
    local name
    name="$(basename "$ex" .toml)"
    "$exe" run -q "$ex" -o "$dst/$name.x" -o "$dst/$name.vts" -o "$dst/$name.glb"
  done
  for name in curved orthogonal scherk volume_warped_cube; do
    "$exe" run -q "$src/examples/$name.toml" -o "$dst/${name}_again.x" \
      --write-start "$dst/${name}_start.x"
  done
  "$exe" smooth -q "$dst/curved_start.x" -o "$dst/curved_smoothed.x"
  "$exe" smooth -q "$dst/orthogonal_start.x" -o "$dst/orthogonal_e3.x" --orthogonal E3
  "$exe" smooth -q "$dst/scherk_start.x" -o "$dst/scherk_smoothed.x"
  "$exe" smooth -q "$dst/volume_warped_cube_start.x" -o "$dst/cube_smoothed.x"
  "$exe" convert -q "$dst/curved.x" "$dst/curved_s.x" --precision single --big-endian --iblank
  "$exe" convert -q "$dst/volume_shell_sector.x" "$dst/shell.p3d" --encoding formatted
  "$exe" convert -q "$src/examples/scherk.toml" "$dst/scherk_convert.x"
  "$exe" step export -q "$dst/scherk.x" -o "$dst/scherk.step"
  "$exe" step grid -q "$dst/scherk.step" --face 1 --ni 41 --nj 33 --first-i 0.01 -o "$dst/scherk_step.x"
  local b
  for b in "bench_grid --quick" "bench_volume 33" "bench_multigrid --quick" "bench_surface --quick"; do
    # shellcheck disable=SC2086
    (cd "$src" && "$top/target/release/examples/"$b --write "$dst/bench" >/dev/null)
  done
}

# the outputs of REV are kept in OUT/before and reused when OUT is given again
sha="$(git -C "$top" rev-parse "$rev")"
if [ "$(cat "$out/before/.rev" 2>/dev/null)" != "$sha" ]; then
  produce "$tree" "$out/before"
  echo "$sha" >"$out/before/.rev"
fi
produce "$top" "$out/after"
fail=0
count=0
while IFS= read -r f; do
  count=$((count + 1))
  if [ ! -f "$out/after/$f" ]; then
    echo "missing after: $f"
    fail=1
  elif [[ "$f" == *.step ]]; then
    # STEP headers carry the time of writing
    if ! cmp -s <(grep -v "^FILE_NAME" "$out/before/$f") <(grep -v "^FILE_NAME" "$out/after/$f"); then
      echo "differs: $f"
      fail=1
    fi
  elif ! cmp -s "$out/before/$f" "$out/after/$f"; then
    echo "differs: $f"
    fail=1
  fi
done < <(cd "$out/before" && find . -type f ! -name .rev | sort)
extra=$(cd "$out/after" && find . -type f | wc -l)
if [ "$extra" -ne "$count" ]; then
  echo "file counts differ: $count before, $extra after"
  fail=1
fi
if [ "$fail" -eq 0 ]; then
  echo "same-grids: all $count files byte-identical ($rev against the work tree, RAYON_NUM_THREADS=$RAYON_NUM_THREADS)"
fi
exit "$fail"
