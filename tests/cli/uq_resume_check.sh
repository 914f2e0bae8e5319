#!/usr/bin/env bash
# uq_resume_check.sh J232 SOURCE_DIR WORKDIR: an uncertainty study killed part-way resumes
# from its journal (`j232 uq --resume`) to the same uq.json as an uninterrupted study; a
# journal made from other inputs is not used; a finished study leaves no journal.
set -euo pipefail
exe=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
scenario=$work/uq-small.toml
sed 's/^base_draws = 32/base_draws = 8/; s/^replicates = 100/replicates = 40/' "$src/scenarios/highway-pivoted-raised-skirt.toml" >"$scenario"
fail() { echo "uq_resume_check: $*" >&2; exit 1; }

"$exe" uq "$scenario" --threads 2 --out "$work/whole" >/dev/null
[ ! -e "$work/whole/uq-journal.csv" ] || fail "a finished study left its journal"

# Killed part-way (SIGKILL: nothing can tidy up), then resumed.
timeout -s KILL 1.5 "$exe" uq "$scenario" --threads 2 --out "$work/resumed" >/dev/null 2>&1 && fail "the study finished before it was killed; slow it down"
[ -s "$work/resumed/uq-journal.csv" ] || fail "the killed study left no journal"
lines=$(($(wc -l <"$work/resumed/uq-journal.csv") - 1))
out=$("$exe" uq "$scenario" --threads 1 --out "$work/resumed" --resume)
echo "$out" | head -1
if [ "$lines" -gt 0 ]; then echo "$out" | grep -q "Resuming: [0-9]* assessments kept" || fail "did not resume ($lines lines in the journal)"; fi
cmp "$work/whole/uq.json" "$work/resumed/uq.json" || fail "the resumed study differs from the whole one"
cmp "$work/whole/uq.csv" "$work/resumed/uq.csv" || fail "the resumed uq.csv differs"

# A journal whose inputs differ is not used.
timeout -s KILL 1.5 "$exe" uq "$scenario" --threads 2 --out "$work/other" >/dev/null 2>&1 || true
sed -i '1s/.*/# j232 uq journal 0000000000000000/' "$work/other/uq-journal.csv"
"$exe" uq "$scenario" --out "$work/other" --resume | grep -q "made from other inputs or another program: starting afresh" ||
  fail "a journal of other inputs was not refused"
cmp "$work/whole/uq.json" "$work/other/uq.json" || fail "the restarted study differs"
echo "uq_resume_check: passed ($lines assessments were journalled before the kill)"
