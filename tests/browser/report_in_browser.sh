#!/usr/bin/env bash
# report_in_browser.sh J232 SCENARIO WORKDIR ARTEFACT_STEM [CHARTS [RUN OPTIONS...]]: runs
# `j232 run` on the scenario (with the extra options) and checks its report.html in headless
# Chromium against its result.json (check_page.py), expecting CHARTS charts (6 unless told),
# leaving a screenshot and PDF at ARTEFACT_STEM.png/.pdf.
set -euo pipefail
exe=$1 scenario=$2 work=$3 stem=$4 charts=${5:-6}
shift $(( $# < 5 ? $# : 5 ))
rm -rf "$work"
code=0
"$exe" run "$scenario" --replicates 200 "$@" --out "$work" >/dev/null || code=$?
case $code in 0|1) ;; *) echo "report_in_browser: j232 run exit code $code" >&2; exit 1 ;; esac
exec python3 "$(dirname "$0")/check_page.py" "$work/report.html" "$work/result.json" "$stem" --svgs "$charts"
