#!/usr/bin/env bash
# Fuzzes ellipgrid's input paths (issue #17) with cargo-fuzz (libFuzzer) on the stable
# toolchain: the targets of fuzz/ (case, plot3d, vtk, step, conn, smooth; see fuzz/src/lib.rs),
# one after the other, each at nice 19.
#
#   bench/fuzz.sh [-n RUNS | -t SECONDS] [TARGET…]     (default: -t 60, every target)
#
# Needs `cargo install cargo-fuzz` (crates.io). Stable Rust has no sanitizers, so the targets
# are built with `--sanitizer none` and debug assertions on (`-a`: integer overflow panics);
# libFuzzer's coverage instrumentation works on stable as it is. Limits per input: 2 GB
# resident (libFuzzer), 512 MiB in one allocation (the targets' allocator aborts above that,
# without a sanitizer libFuzzer cannot see allocations), 20 s.
#
# The corpus (fuzz/corpus/TARGET, not committed) is seeded at every start from the examples,
# data/ and small grids written by the ellipgrid binary in every Plot3D flavour and as .vts;
# what libFuzzer adds to it stays for the next run. Crashes land in fuzz/artifacts/TARGET/;
# each one found belongs in tests/fuzz_regressions.rs (its input under tests/data/fuzz/).
# A line per target (inputs run, seconds, corpus size, crashes) goes to fuzz/logs/summary.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

runs=""
secs=60
while getopts "n:t:" o; do
    case $o in
    n) runs=$OPTARG secs="" ;;
    t) secs=$OPTARG runs="" ;;
    *) echo "usage: $0 [-n RUNS | -t SECONDS] [TARGET…]" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(case plot3d vtk step conn smooth)

cargo fuzz --version >/dev/null 2>&1 || { echo "needs cargo-fuzz: cargo install cargo-fuzz" >&2; exit 2; }
flags=(--sanitizer none --debug-assertions --fuzz-dir fuzz)
nice -n 19 cargo fuzz build "${flags[@]}"
nice -n 19 cargo build --release --bin ellipgrid
bin=$root/target/release/ellipgrid

# ---- seeds ----
seeds=$(mktemp -d)
trap 'rm -rf "$seeds"' EXIT
mkdir -p "$seeds"/{case,plot3d,vtk,step,conn}
cp examples/*.toml "$seeds/case/"
cp tests/data/fuzz/*.toml "$seeds/case/" 2>/dev/null || true
for f in data/step/*.step; do
    [ "$(stat -c %s "$f")" -le 30000 ] && cp "$f" "$seeds/step/"
done
(
    cd "$seeds"
    square='[[block]]
name = "b"
ni = NI
nj = NJ
[block.E1]
curve = { type = "line", from = [0, 0], to = [0, 1] }
[block.E2]
curve = { type = "arc_through", from = [1, 0], mid = [1.1, 0.5], to = [1, 1] }
distribution = { type = "vinokur", first = 0.05 }
[block.E3]
curve = { type = "line", from = [0, 0], to = [1, 0] }
[block.E4]
curve = { type = "line", from = [0, 1], to = [1, 1] }'
    echo "${square/NI/5}" | sed 's/NJ/4/' >square.toml
    "$bin" run square.toml -o planar.x -q
    sed -e 's/ni = 49/ni = 5/' -e 's/nj = 49/nj = 5/' "$root/examples/scherk.toml" >scherk.toml
    "$bin" run scherk.toml -o surface.x -q || true
    sed -e 's/= 25$/= 4/' -e 's/first = 0.01/first = 0.2/' "$root/examples/volume_warped_cube.toml" >cube.toml
    "$bin" run cube.toml -o volume.x -q
    k=0
    for g in planar surface volume; do
        [ -f $g.x ] || continue
        "$bin" convert $g.x "vtk/$g.vts" -q
        for enc in unformatted formatted stream; do
            for prec in single double; do
                for opt in "" --big-endian --single-block --iblank "--iblank --big-endian" --two-d; do
                    k=$((k + 1))
                    # shellcheck disable=SC2086
                    "$bin" convert $g.x "plot3d/$g-$k.x" --encoding $enc --precision $prec $opt -q 2>/dev/null || true
                done
            done
        done
    done
    "$bin" step export planar.x -o step/planar_net.step -q
    cp "$root/examples/naca0012_ogrid.toml" . && sed -i 's|\.\./data|'"$root"'/data|' naca0012_ogrid.toml
    "$bin" run naca0012_ogrid.toml -o conn/naca.conn -o naca.x -q || true
)
printf '<?xml version="1.0"?>\n<VTKFile type="StructuredGrid" version="0.1"><StructuredGrid WholeExtent="0 1 0 1 0 0"><Piece Extent="0 1 0 1 0 0"><Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 1 1 0</DataArray></Points></Piece></StructuredGrid></VTKFile>\n' >"$seeds/vtk/ascii.vts"
# the fixed blocks of the conn target (fuzz/src/lib.rs: two 4 × 3 blocks meeting at x = 1)
printf '1\n 1 4 1 1 4 3 1\n 2 1 1 1 1 3 1\n6\n 1 1 1 1 4 1 1 1\n 1 1 3 1 4 3 1 1\n 1 1 1 1 1 3 1 2\n 2 1 1 1 4 1 1 1\n 2 1 3 1 4 3 1 1\n 2 4 1 1 4 3 1 2\n2\n 1 wall\n 2 farfield\n' >"$seeds/conn/planar.conn"
printf '1\n 1 4 1 1 4 3 2\n 2 1 1 1 1 3 2\n10\n 1 1 1 1 4 1 2 1\n 1 1 3 1 4 3 2 1\n 1 1 1 1 1 3 2 2\n 1 1 1 1 4 3 1 1\n 1 1 1 2 4 3 2 1\n 2 1 1 1 4 1 2 1\n 2 1 3 1 4 3 2 1\n 2 4 1 1 4 3 2 2\n 2 1 1 1 4 3 1 1\n 2 1 1 2 4 3 2 1\n2\n 1 wall\n 2 farfield\n' >"$seeds/conn/volume.conn"

seed_dir() {
    case $1 in
    smooth) echo "$seeds/plot3d" ;;
    *) echo "$seeds/$1" ;;
    esac
}

# ---- runs ----
mkdir -p fuzz/logs
for t in "${targets[@]}"; do
    corpus=fuzz/corpus/$t
    mkdir -p "$corpus" "fuzz/artifacts/$t"
    limit=(-max_total_time="$secs")
    [ -n "$runs" ] && limit=(-runs="$runs")
    dict=()
    [ -f "fuzz/dict/$t.dict" ] && dict=(-dict="fuzz/dict/$t.dict")
    [ "$t" = smooth ] && dict=()
    log=fuzz/logs/$t.log
    start=$(date +%s)
    set +e
    nice -n 19 cargo fuzz run "${flags[@]}" "$t" "$corpus" "$(seed_dir "$t")" -- \
        "${limit[@]}" "${dict[@]}" -rss_limit_mb=2048 -timeout=20 \
        -print_final_stats=1 >"$log" 2>&1
    rc=$?
    set -e
    took=$(($(date +%s) - start))
    # the final stats, or (after a crash) the last status line's count
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1 || true)
    [ -n "$execs" ] || execs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#' || true)
    crashes=$(find "fuzz/artifacts/$t" -type f | wc -l)
    # a stack overflow kills the target before libFuzzer can save the input: say so
    grep -q 'signal: 11 (SIGSEGV)' "$log" && crashes="$crashes (+1 SIGSEGV without an input: rerun under gdb)"
    line="$(date -u +%F) $t: ${execs:-?} inputs in ${took} s, corpus $(find "$corpus" -type f | wc -l) files, exit $rc, $crashes file(s) in fuzz/artifacts/$t"
    echo "$line" | tee -a fuzz/logs/summary.txt
done
