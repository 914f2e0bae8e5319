#!/usr/bin/env bash
# batch_compare_check.sh J232 SOURCE_DIR WORKDIR: `j232 batch --compare` compares the
# scenarios that gave a verdict exactly as `j232 compare` does (same compare.json), carries
# the comparison in summary.json, skips a refused scenario, and refuses --resume with it.
set -euo pipefail
exe=$1 src=$2 work=$3
n=${J232_CHECK_REPLICATES:-60}  # fewer under the sanitizers (tests/cli/CMakeLists.txt)
rm -rf "$work" && mkdir -p "$work"
fail() { echo "batch_compare_check: $*" >&2; exit 1; }
a=$src/scenarios/highway-pivoted-raised-skirt.toml b=$src/scenarios/highway-pivoted-raised-skirt-chains.toml
code=0
"$exe" batch "$a" "$src/tests/cli/bad/run-unknown-key.toml" "$b" --compare --replicates "$n" --out "$work/batch" >"$work/batch.txt" || code=$?
[ "$code" -eq 2 ] || fail "exit code $code, expected 2 (one scenario refused)"
grep -q "and the comparison of the designs in compare.html" "$work/batch.txt" || fail "no comparison announced"
"$exe" compare "$a" "$b" --replicates "$n" --out "$work/compare" >/dev/null
python3 - "$work/batch/compare.json" "$work/compare/compare.json" "$work/batch/summary.json" <<'PY'
import json, sys
batch, alone, summary = (json.load(open(p)) for p in sys.argv[1:4])
for d in (batch, alone):
    d.pop("program", None)
assert batch == alone, "batch --compare and j232 compare differ"
assert len(batch["designs"]) == 2, "the refused scenario was compared"
s = dict(summary["comparison"]); s.pop("program", None)
assert s == batch, "summary.json's comparison differs from compare.json"
PY
code=0
"$exe" batch "$a" "$b" --compare --resume --out "$work/resume" >"$work/resume.txt" 2>&1 || code=$?
[ "$code" -eq 2 ] && grep -q "without --resume" "$work/resume.txt" || fail "--compare --resume was not refused"
echo "batch_compare_check: passed"
