#!/usr/bin/env bash
# The installed package works for a program outside the tree: `cmake --install` into a
# temporary prefix, a consumer built against it with find_package(j232) runs an assessment,
# and its counts equal those of `j232 run` on the same scenario and seed. With --embed, the
# same consumer in a project that adds the source tree by add_subdirectory instead.
set -euo pipefail
embed=0
if [ "${1:-}" = --embed ]; then embed=1; shift; fi
build=${1:?usage: package_check.sh [--embed] BUILD_DIR SOURCE_DIR J232}
source=${2:?}
j232=${3:?}
work=$(mktemp -d "${TMPDIR:-/tmp}/j232-package.XXXXXX")
trap 'rm -rf "$work"' EXIT
if [ $embed -eq 1 ]; then
  # On baseline x86-64 unoptimised (-O0) and as a unity build (sources compiled eight to a
  # batch, so Eigen, CGAL and toml++ are parsed once per batch): about 3 min alone instead of
  # 4.5 (CI's time is short), and the counts must still equal the optimised program's (no
  # fast-math; no fused multiply-add there for -O2 to contract into, unless CXXFLAGS asks for
  # it). Elsewhere (aarch64 has FMA in its baseline) and with -march/-mfma, optimised and file
  # by file as the program is: a batch would let the compiler inline across files and place
  # its fused multiply-adds elsewhere than in the program, moving last bits.
  flags=()
  if [ "$(uname -m)" = x86_64 ] && ! [[ "${CXXFLAGS:-}" =~ -march|-mfma ]]; then
    flags=("-DCMAKE_CXX_FLAGS_RELEASE=-O0 -DNDEBUG" -DCMAKE_UNITY_BUILD=ON)
  fi
  cmake -S "$source/tests/package/embed" -B "$work/consumer" -DJ232_SOURCE_DIR="$source" -DCMAKE_BUILD_TYPE=Release \
        "${flags[@]}" >/dev/null
else
  cmake --install "$build" --prefix "$work/prefix" >/dev/null
  for header in include/j232/assess/runner.hpp include/j232/scenario/scenario_reader.hpp include/j232/version.hpp \
                lib/cmake/j232/j232Config.cmake bin/j232; do
    [ -e "$work/prefix/$header" ] || { echo "package_check: $header not installed" >&2; exit 1; }
  done
  if [ -e "$work/prefix/include/j232/cli" ]; then echo "package_check: the program's own headers were installed" >&2; exit 1; fi
  cmake -S "$source/tests/package/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$work/consumer" -j 2 >/dev/null
scenario=$source/scenarios/highway-pivoted-raised-skirt.toml
"$work/consumer/consumer" "$scenario" 20 7 > "$work/consumer.json"
"$j232" run "$scenario" --replicates 20 --seed 7 --out "$work/run" >/dev/null || [ $? -eq 1 ]  # 1: the mower fails
how=$([ $embed -eq 1 ] && echo "add_subdirectory" || echo "find_package")
python3 - "$work/consumer.json" "$work/run/result.json" "$how" <<'PY'
import json, sys
mine, run = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
keys = ["replicates", "replicates_passed", "nails_fed", "nails_struck", "marks"]
diff = [k for k in keys if mine[k] != run[k]]
if mine["pass_probability"] != run["pass_probability"]["estimate"]:
    diff.append("pass_probability")
if diff or mine["nails_struck"] == 0 or mine["version"] != run["provenance"]["version"]:
    sys.exit(f"package_check: the installed library disagrees with j232 run on {diff}: {mine}")
print(f"package_check: ok: the consumer ({sys.argv[3]}) = j232 run ({mine['nails_struck']} nails struck, {mine['marks']} marks)")
PY
