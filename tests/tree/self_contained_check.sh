#!/usr/bin/env bash
# The source tree stands on its own: no file (code, docs, scenarios, shipped reports) cites
# a document or a path outside the repository. Sources are cited by title (docs/model.md
# "Sources"); code comments point at docs/ sections.
set -euo pipefail
cd "${1:?usage: self_contained_check.sh SOURCE_DIR}"
# Design notes and data tables that were never part of the repository, and machine paths.
# (Spelled in pieces so that this file does not match itself.)
design='DESIGN''\.md' notes='shar''ed/' data='seed-tables\.csv|seed-sweeps\.csv|physical-''parameters\.md'
paths='/wo''rk/|/che''ck/|/ho''me/[a-z]'
pattern="$design|${notes}reference|\.\./${notes%/}|$data|$paths"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  list() { git ls-files -z; }
else
  list() { find . -type f -not -path './.git/*' -not -path './build*' -print0; }
fi
hits=$(list | xargs -0 grep -nIE "$pattern" -- 2>/dev/null || true)
if [ -n "$hits" ]; then
  echo "self_contained_check: these lines point outside the repository (cite by title instead):" >&2
  echo "$hits" >&2
  exit 1
fi
echo "self_contained_check: ok: $(list | tr -cd '\0' | wc -c) files cite nothing outside the repository"
