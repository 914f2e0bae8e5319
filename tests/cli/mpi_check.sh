#!/usr/bin/env bash
# mpi_check.sh J232 SOURCE_DIR WORKDIR: j232 under `mpirun -n 1, 2, 3` (oversubscribed on one
# machine) gives the same results as one plain process, bit for bit: run (result.json less
# provenance, marks.csv, with trajectories), a sweep's CSV, an uncertainty study's uq.json (a
# J232 test's and a field's), a hazard run and a batch comparison; a run that fails on rank 0
# (an output folder that cannot be written) fails the whole job at once with its message and
# leaves no result.
set -euo pipefail
exe=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "mpi_check: $*" >&2; exit 1; }
mpi() { local n=$1; shift; timeout 300 mpirun --allow-run-as-root --oversubscribe -n "$n" "$@"; }
same_json() {  # same_json A B: equal but for provenance
  python3 - "$1" "$2" <<'PY' || fail "$1 and $2 differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    d.pop("provenance", None)
sys.exit(0 if a == b else 1)
PY
}
skirt=$src/scenarios/highway-pivoted-raised-skirt.toml
sed 's/^base_draws = [0-9]*/base_draws = 4/; s/^replicates = 50 /replicates = 20/' "$skirt" >"$work/uq-small.toml"

"$exe" run "$skirt" --replicates 240 --trajectories 5 --out "$work/run-plain" >/dev/null || [ $? -eq 1 ]
"$exe" sweep --base "$skirt" --x "bevel_angle=20 deg,30 deg,45 deg" --replicates 40 --out "$work/sweep-plain" >/dev/null
"$exe" uq "$work/uq-small.toml" --out "$work/uq-plain" >/dev/null
for n in 1 2 3; do
  code=0
  mpi "$n" "$exe" run "$skirt" --replicates 240 --trajectories 5 --out "$work/run-$n" >"$work/run-$n.txt" 2>&1 || code=$?
  [ "$code" -eq 1 ] || { cat "$work/run-$n.txt"; fail "run on $n ranks: exit code $code, expected 1 (the raised skirt fails)"; }
  same_json "$work/run-plain/result.json" "$work/run-$n/result.json"
  cmp "$work/run-plain/marks.csv" "$work/run-$n/marks.csv" || fail "marks.csv on $n ranks differs"
  python3 -c "import json,sys; sys.exit(0 if json.load(open('$work/run-$n/result.json'))['provenance']['ranks'] == $n else 1)" ||
    fail "provenance does not say $n ranks"
  [ "$(find "$work" -maxdepth 1 -name 'run-*' -type d | wc -l)" -ge 1 ] || fail "no output"
done
for n in 2 3; do
  mpi "$n" "$exe" sweep --base "$skirt" --x "bevel_angle=20 deg,30 deg,45 deg" --replicates 40 --out "$work/sweep-$n" >/dev/null 2>&1 ||
    fail "sweep on $n ranks failed"
  for f in "$work"/sweep-plain/*.csv; do cmp "$f" "$work/sweep-$n/$(basename "$f")" || fail "sweep CSV on $n ranks differs"; done
done
mpi 2 "$exe" uq "$work/uq-small.toml" --out "$work/uq-2" >/dev/null 2>&1 || fail "uq on 2 ranks failed"
same_json "$work/uq-plain/uq.json" "$work/uq-2/uq.json"
# The field hazard: the ranks share out the waves of chunks; rank 0 merges them and hands
# every rank the whole tally.
lawn=$src/scenarios/field/deck-72in-lawn-stones.toml
"$exe" hazard "$lawn" --objects 6000 --out "$work/hazard-plain" >/dev/null
for n in 2 3; do
  mpi "$n" "$exe" hazard "$lawn" --objects 6000 --out "$work/hazard-$n" >/dev/null 2>&1 || fail "hazard on $n ranks failed"
  same_json "$work/hazard-plain/hazard.json" "$work/hazard-$n/hazard.json"
  cmp "$work/hazard-plain/hazard.csv" "$work/hazard-$n/hazard.csv" || fail "hazard.csv on $n ranks differs"
  python3 -c "import json,sys; sys.exit(0 if json.load(open('$work/hazard-$n/hazard.json'))['provenance']['ranks'] == $n else 1)" ||
    fail "hazard provenance does not say $n ranks"
done
# A field's uncertainty study: every rank ends each draw's hazard run with the whole tally.
{ cat "$lawn"; printf '\n[uncertainty]\nbase_draws = 2\nobjects = 1500\n'; } >"$work/uq-lawn.toml"
"$exe" uq "$work/uq-lawn.toml" --out "$work/uq-lawn-plain" >/dev/null
mpi 2 "$exe" uq "$work/uq-lawn.toml" --out "$work/uq-lawn-2" >/dev/null 2>&1 || fail "a field's uq on 2 ranks failed"
same_json "$work/uq-lawn-plain/uq.json" "$work/uq-lawn-2/uq.json"
# Two fields compared object by object: the ranks share out the waves of chunks, rank 0 adds
# their sums in chunk order and every design's tallies.
sed 's/^objects_simulated = .*/objects_simulated = 6000/' "$lawn" >"$work/lawn-a.toml"
sed 's/^ground_speed = .*/ground_speed = "6 km\/h"/' "$work/lawn-a.toml" >"$work/lawn-b.toml"
"$exe" compare "$work/lawn-a.toml" "$work/lawn-b.toml" --out "$work/compare-fields-plain" >/dev/null
for n in 2 3; do
  mpi "$n" "$exe" compare "$work/lawn-a.toml" "$work/lawn-b.toml" --out "$work/compare-fields-$n" >/dev/null 2>&1 ||
    fail "compare of fields on $n ranks failed"
  same_json "$work/compare-fields-plain/compare.json" "$work/compare-fields-$n/compare.json"
  cmp "$work/compare-fields-plain/compare.csv" "$work/compare-fields-$n/compare.csv" || fail "compare.csv of fields on $n ranks differs"
done
# No stray files from the other ranks in the output folders.
listing="$(ls -A "$work/run-3" | grep -v '^scene.html$' | sort | tr '\n' ' ')"  # scene.html: when built with three.js
[ "$listing" = ".j232.lock marks.csv report.html result.json " ] || fail "unexpected files in run-3: $(ls -A "$work/run-3")"
listing="$(ls -A "$work/compare-fields-3" | sort | tr '\n' ' ')"
[ "$listing" = ".j232.lock compare.csv compare.html compare.json " ] || fail "unexpected files in compare-fields-3: $(ls -A "$work/compare-fields-3")"

# A failure on rank 0 ends the job with its message, exit code 2, no result and no hang.
touch "$work/not-a-folder"
code=0
mpi 3 "$exe" run "$skirt" --replicates 240 --out "$work/not-a-folder" >"$work/fail.txt" 2>&1 || code=$?
[ "$code" -eq 2 ] || { cat "$work/fail.txt"; fail "a failed rank 0 gave exit code $code, expected 2"; }
grep -q "not-a-folder: exists and is not a folder" "$work/fail.txt" || fail "no message from the failed rank"
echo "mpi_check: passed (1, 2 and 3 ranks give the plain results bit for bit)"
