#!/usr/bin/env python3
"""robust_check.py J232 SOURCE_DIR WORK_DIR [--no-memory-check]: one case for each finding of the robustness
audit (bad input as a careless or hostile user writes it, hangs, memory, output folders,
injection). Every case must end within its time limit with the exit code and message
given; prints "N passed, M failed". --no-memory-check skips the peak-memory case (a
sanitizer build holds freed memory in quarantine, so its peak says nothing)."""
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import time

exe, source, work = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
base_text = open(os.path.join(source, "scenarios", "highway-pivoted.toml")).read()
passed, failed = 0, []


def scenario(name, text):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def with_keys(table, lines, text=base_text):
    """The base scenario with `lines` added to [table] (created if missing)."""
    header = f"[{table}]\n"
    if header in text:
        return text.replace(header, header + lines + "\n", 1)
    return text + f"\n{header}{lines}\n"


def run(args, timeout=60):
    start = time.monotonic()
    try:
        p = subprocess.run([exe] + args, cwd=work, capture_output=True, text=True, timeout=timeout)
        return p.returncode, p.stdout + p.stderr, time.monotonic() - start
    except subprocess.TimeoutExpired:
        return None, "(timed out)", timeout


def case(name, args, code, regex, timeout=60):
    global passed
    got, out, _ = run(args, timeout)
    problems = []
    codes = code if isinstance(code, tuple) else (code,)  # a verdict either way: (0, 1)
    if got not in codes:
        problems.append(f"exit {got}, expected {' or '.join(map(str, codes))}")
    if not re.search(regex, out, re.S):
        problems.append(f"output does not match /{regex}/")
    if re.search(r"(^|[^a-z])(nan|-?inf)([^a-z]|$)", out, re.I):
        problems.append("output holds nan or inf")
    check(name, problems, out)


def check(name, problems, out=""):
    global passed
    if problems:
        failed.append(name)
        print(f"FAIL {name}: {'; '.join(problems)}\n    " + out.strip().replace("\n", "\n    "))
    else:
        passed += 1
        print(f"ok   {name}")


def run_case(name, text, code, regex, extra=(), timeout=60):
    stem = re.sub(r"[^A-Za-z0-9]+", "-", name)
    case(name, ["run", scenario(stem + ".toml", text), "--replicates", "4", "--out", os.path.join(work, "out-" + stem)] +
         list(extra), code, regex, timeout)


# 1. Silent, meaningless PASS.
run_case("feed radius in metres", base_text + '\n[[feed.stations]]\nradius = "22 m"\n', 2,
         r'feed\.stations\[1\]\.radius = "22 m": expected a length .*from 0 m to 0\.6096 m')
run_case("time limit 3 ms", with_keys("run", 'time_limit = "3 ms"'), 2, r'run\.time_limit = "3 ms": expected a time .*from 0\.1 s')
run_case("nail 1e300 m", with_keys("nail", 'length = "1e300 m"'), 2, r'nail\.length = "1e300 m": expected a length')
run_case("no nail struck is invalid", base_text.replace('speed = "1000 rpm"', 'speed = "0.01 rpm"'), 4,
         r"NO VERDICT.*struck none of the")
run_case("nails cut off is invalid", with_keys("run", "max_bounces = 1"), 4, r"NO VERDICT.*cut off still moving")
# 2. Hangs.
run_case("air 1e200 kg/m^3", with_keys("air", 'density = "1e200 kg/m^3"'), 2, r"air\.density .*from 0 kg/m\^3 to 5 kg/m\^3", timeout=20)
run_case("cd_normal 1e200", with_keys("air", "cd_normal = 1e200"), 2, r"air\.cd_normal", timeout=20)
run_case("cd_axial 1e200", with_keys("air", "cd_axial = 1e200"), 2, r"air\.cd_axial", timeout=20)
run_case("chord tolerance 1e-300 m", with_keys("run", 'chord_tolerance = "1e-300 m"'), 2, r"run\.chord_tolerance", timeout=20)
os.symlink("/dev/zero", os.path.join(work, "zero.obj"))
meshes_text = open(os.path.join(source, "scenarios", "highway-meshes.toml")).read()
meshes_dir = os.path.join(source, "scenarios", "meshes")
run_case("mesh is a device", meshes_text.replace("meshes/deck.obj", os.path.join(work, "zero.obj")), 2,
         r"zero\.obj: not a regular file", timeout=20)
# 3. Memory.
run_case("mesh in inches without scale", re.sub(r"scale = 0\.0254.*", "", meshes_text).replace("meshes/", meshes_dir + "/"), 2,
         r"meshes\[\d\]\.path: .*is `scale` right", timeout=30)
run_case("blade 1000 km high", with_keys("blade", 'height = "1000 km"').replace('height = "3 in"\n', ""), 2, r"blade\.height")
links = "".join('[[blade.arms.links]]\nlength = "0.1 in"\nmass = "0.01 lb"\n' for _ in range(20000))
run_case("20000 links", base_text.replace("[restitution]", links + "\n[restitution]", 1), 2, r"expected at most 16", timeout=30)
many_meshes = "".join(f'[[meshes]]\npath = "{meshes_dir}/deck.obj"\nlabel = "housing"\nscale = 0.0254\n' for _ in range(20000))
run_case("20000 meshes", base_text + many_meshes, 2, r"expected at most 32", timeout=30)
case("replicates beyond 64 bits", ["run", scenario("b.toml", base_text), "--replicates", "99999999999999999999"], 2, r"--replicates")


def peak_rss_mb(replicates):
    """Peak resident memory of a child run, in MB (a fresh process group keeps children's peaks apart)."""
    path = scenario(f"memory-{replicates}.toml", with_keys("feed", "nails = 5"))
    p = subprocess.Popen([exe, "run", path, "--replicates", str(replicates), "--out", os.path.join(work, f"mem-{replicates}")],
                         cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    return usage.ru_maxrss / 1024, os.waitstatus_to_exitcode(status)


if "--no-memory-check" not in sys.argv[4:]:
    small, code_small = peak_rss_mb(4000)
    large, code_large = peak_rss_mb(100000)
    check(f"memory does not grow with replicates ({small:.0f} MB at 4,000, {large:.0f} MB at 100,000)",
          [] if code_small in (0, 1) and code_large in (0, 1) and large < 1.25 * small + 5 else ["peak memory grew"])

# 4. The output set, and a second run into the same folder.
out = os.path.join(work, "set")
long_run = scenario("long.toml", base_text)
code, text, _ = run(["run", long_run, "--replicates", "20", "--out", out])
before = json.load(open(os.path.join(out, "result.json")))
p = subprocess.Popen([exe, "run", long_run, "--replicates", "2000000", "--seed", "5", "--out", out], cwd=work,
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
time.sleep(1.0)
case("second run into a locked folder", ["run", long_run, "--replicates", "2", "--out", out], 2, r"another j232 run is writing")
p.send_signal(signal.SIGKILL)
p.wait()
after = json.load(open(os.path.join(out, "result.json")))
problems = [] if after == before else ["result.json changed by a killed run"]
for f in after["provenance"]["files"]:
    data = open(os.path.join(out, f["name"]), "rb").read()
    h = 1469598103934665603
    for b in data:
        h = ((h ^ b) * 1099511628211) % (1 << 64)
    if len(data) != f["bytes"] or f"{h:016x}" != f["fnv1a64"]:
        problems.append(f"{f['name']} is not the one result.json names")
check("a killed run leaves the previous set whole", problems)
case("the next run clears the killed run's leftovers", ["run", long_run, "--replicates", "2", "--out", out], (0, 1), r"Wrote")
check("no staging folder left", [n for n in os.listdir(out) if n.startswith(".j232-staging")])

# 5. The environment, checked before simulating.
open(os.path.join(work, "afile"), "w").close()
case("--out is a file", ["run", long_run, "--replicates", "1000000", "--out", "afile"], 2, r"afile: exists and is not a folder", timeout=10)
os.makedirs(os.path.join(work, "taken", "result.json"))
case("result.json is a folder", ["run", long_run, "--replicates", "1000000", "--out", "taken"], 2,
     r"taken/result\.json: exists and is not a regular file", timeout=10)
case("--out cannot be created", ["run", long_run, "--replicates", "2", "--out", "afile/inside"], 2, r"afile/inside: cannot create")

# 6. Overflow.
run_case("unit exponent overflow", base_text.replace('speed = "1000 rpm"', 'speed = "1000 rpm^2147483647"'), 2, r"bad exponent")
with open(os.path.join(work, "far.obj"), "w") as f:
    f.write("v 0 0 0\nv 1e31 0 0\nv 0 1e31 1\nf 1 2 3\n")
run_case("mesh 1e31 m away", meshes_text.replace("meshes/deck.obj", os.path.join(work, "far.obj")), 2, r"far\.obj: vertex 2 lies")

# 7. Seeds.
case("seed 2^64-1", ["run", long_run, "--replicates", "2", "--seed", "18446744073709551615", "--out", "seed"], (0, 1), r"VERDICT: (PASSES|FAILS)")
check("seed kept whole", [] if '"seed": 18446744073709551615' in open(os.path.join(work, "seed", "result.json")).read()
      else ["seed changed"])
case("seed beyond 64 bits", ["run", long_run, "--seed", "99999999999999999999999"], 2, r"--seed: expected a whole number")

# 8. Injection and paths.
os.makedirs(os.path.join(work, "names"))
hostile = base_text.replace('title = "', 'title = "=HYPERLINK(\\"x\\") \\u001b[31mred ', 1)
for name in ("javascript:alert(3).toml", "...toml"):
    open(os.path.join(work, "names", name), "w").write(hostile)
code, text, _ = run(["batch", "names/javascript:alert(3).toml", "names/...toml", "--replicates", "2", "--out", "batch/out"])
html = open(os.path.join(work, "batch", "out", "summary.html")).read()
csv = open(os.path.join(work, "batch", "out", "summary.csv")).read()
problems = []
if code not in (0, 1):  # a verdict either way
    problems.append(f"batch exit {code}")
if 'href="./javascript_alert_3_/report.html"' not in html or "javascript:" in html.replace("javascript:alert(3).toml", ""):
    problems.append("summary.html link not relative and encoded")
if sorted(os.listdir(os.path.join(work, "batch"))) != ["out"]:
    problems.append("batch wrote beside its --out")
if not os.path.isdir(os.path.join(work, "batch", "out", "__")):
    problems.append("'...toml' did not get a safe folder")
if "\x1b" in text or "\x1b" in csv:
    problems.append("control characters reached the terminal")
if ",'=HYPERLINK" not in csv and ",\"'=HYPERLINK" not in csv:
    problems.append("formula not neutralised in summary.csv")
check("batch names, links, terminal and CSV are safe", problems, text)

# 9. Messages.
run_case("skirt 1e308 m", with_keys("housing", 'skirt_bottom = "1e308 m"').replace('skirt_bottom = "1.5 in"\n', ""), 2,
         r'housing\.skirt_bottom = "1e308 m": expected a length')
with open(os.path.join(work, "holes.obj"), "w") as f:
    f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 99\n")
run_case("mesh names a missing vertex", meshes_text.replace("meshes/deck.obj", os.path.join(work, "holes.obj")), 2,
         r"holes\.obj: .*(vertex that does not exist|cannot read)")
case("scenario is a folder", ["run", work], 2, r"is a folder; expected a scenario file")
run_case("target half width 0", with_keys("run", "target_half_width = 0"), 2, r"run\.target_half_width = 0: expected .*from 0\.001")
case("unknown --set key blamed on the option",
     ["impact", os.path.join(source, "scenarios", "impact", "highway-straight.toml"), "--set", "blade.frobnicate=1"], 2,
     r"command line: option for blade\.frobnicate: unknown key")

# What J232 counts: a scenario that departs from it says so.
run_case("counted height departs from J232", with_keys("criteria", 'counted_height = "0 m"\nhits_outside = "25 %"'), (0, 1),
         r"DEPARTS FROM SAE J232: criteria limits 20 %, 0\.5 %, 25 %, 5 %.*DEPARTS FROM SAE J232: marks counted from 0 mm")

print(f"{passed} passed, {len(failed)} failed")
sys.exit(1 if failed else 0)
