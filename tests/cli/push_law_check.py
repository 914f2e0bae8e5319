#!/usr/bin/env python3
"""A knife's push, followed contact by contact, against Coulomb sliding along the arm.

A body pressed on a knife turning at w slides out along it (in the knife's frame: the
centrifugal force drives it out, the Coriolis force 2 m w r' presses it on the face, and
Coulomb friction mu times that holds it back): r'' = w^2 r - 2 mu w r'. From r0 and r'0 at
the push's first contact, r(t) = A e^(l1 t) + B e^(l2 t) with l = w (-mu +- sqrt(1 + mu^2)).
j232 does not integrate this law: it resolves the push as hundreds of separate impacts, each
with Coulomb friction in its impulse. This check replays one such push (`j232 trace --json`),
takes the radius of the body's centre from the spindle's axis at each contact of its longest
run of blade contacts, fits mu of the law above to it, and asks that the fitted mu be the
blade's to within 0.05, with the law fitting to within 0.5 mm and mu = 0 and mu doubled
missing by at least 20 times as much (so the check tells the law apart). The law treats the
body as a point on a face through the axis; a cobble's centre sits its radius ahead of the
face, so the centrifugal force also pulls it off the face (about -0.03 in the fitted mu),
and the bevel's tilted normal acts the other way: hence 0.05, not closer.

With `held` or `impacts` after WORKDIR the scenario is run with `[contacts] blade_push` set
so. Held, the push is a slide along the face integrated step by step (RK4 in the world's
frame, the face put back at each step's end), broken where the body rides over the bevel's
edge and is caught again, and the check fits the body's centre at each logged step and
strike of it: an independent check of that integration against the closed form.

usage: push_law_check.py J232 SCENARIO OBJECT SPINDLE_X SPINDLE_Y RPM MU WORKDIR [held|impacts]
"""
import json
import math
import os
import re
import subprocess
import sys


def main():
    exe, scenario, obj = sys.argv[1], sys.argv[2], sys.argv[3]
    cx, cy, rpm, mu_blade = (float(a) for a in sys.argv[4:8])
    work = sys.argv[8]
    push_as = sys.argv[9] if len(sys.argv) > 9 else None
    held = push_as == "held"
    os.makedirs(work, exist_ok=True)
    if push_as:
        text = open(scenario).read()
        line = f'blade_push = "{push_as}"'
        if re.search(r'^blade_push = "[a-z]+"', text, re.M):
            text = re.sub(r'^blade_push = "[a-z]+"', line, text, count=1, flags=re.M)
        elif "\n[contacts]\n" in text:
            text = text.replace("\n[contacts]\n", "\n[contacts]\n" + line + "\n", 1)
        else:
            text += "\n[contacts]\n" + line + "\n"
        scenario = os.path.join(work, push_as + ".toml")
        # (Meshes and other files the scenario names are relative to it: none in the scenarios checked.)
        open(scenario, "w").write(text)
    trail = os.path.join(work, "push.json")
    subprocess.run([exe, "trace", scenario, "--object", obj, "--json", trail], check=True, stdout=subprocess.DEVNULL)
    events = json.load(open(trail))["events"]
    kinds = ("strike", "push") if held else ("strike",)
    strikes = [e for e in events if e["event"] in kinds]
    runs, run = [], strikes[:1]
    for a, b in zip(strikes, strikes[1:]):
        # (Held, the body slides up the bevel and over its edge, and the knife catches it again
        # within a few tenths of a ms: its strikes and held steps, on one knife, are the push.)
        gap = 5e-4 if held else 2e-4
        if b["time_s"] - a["time_s"] < gap and b.get("spindle") == a.get("spindle"):
            run.append(b)
        else:
            runs.append(run)
            run = [b]
    runs.append(run)
    push = max(runs, key=len)
    least = 20 if held else 100
    if len(push) < least:
        print(f"FAILED: the longest run of blade contacts has {len(push)}; expected a push of at least {least}")
        return 1
    if held:  # the hold must have engaged: most of the run held steps, each pressed on the face
        steps = [e for e in push if e["event"] == "push"]
        if len(steps) < 20 or 2 * len(steps) < len(push) or not all(e["pressed_m_s2"] > 0 for e in steps):
            print(f"FAILED: {len(steps)} held steps of {len(push)} in the push; expected at least 20 and most of it, each pressed")
            return 1
    w = rpm * 2 * math.pi / 60
    t0 = push[0]["time_s"]
    ts, rs, rds = [], [], []
    for e in push:
        x, y = e["centre_m"][0] - cx, e["centre_m"][1] - cy
        vx, vy = e["velocity_m_s"][0], e["velocity_m_s"][1]
        r = math.hypot(x, y)
        ts.append(e["time_s"] - t0)
        rs.append(r)
        rds.append((x * vx + y * vy) / r)

    def law(mu, t):
        s = math.sqrt(1 + mu * mu)
        l1, l2 = w * (-mu + s), w * (-mu - s)
        a = (rds[0] - l2 * rs[0]) / (l1 - l2)
        return a * math.exp(l1 * t) + (rs[0] - a) * math.exp(l2 * t)

    def rms(mu):
        return math.sqrt(sum((law(mu, t) - r) ** 2 for t, r in zip(ts, rs)) / len(ts))

    coarse = min((rms(k / 100), k) for k in range(0, 201))[1]  # then to 0.001 about the best
    fit_rms, fit_mu = min((rms(k / 1000), k / 1000) for k in range(max(0, 10 * coarse - 10), 10 * coarse + 11))
    print(f"push: {len(push)} contacts over {1e3 * ts[-1]:.2f} ms, {rs[0]:.4f} -> {rs[-1]:.4f} m from the axis")
    print(f"Coulomb sliding law fitted: mu {fit_mu:.3f} (the blade's {mu_blade}), rms {1e3 * fit_rms:.3f} mm; "
          f"mu 0: {1e3 * rms(0):.2f} mm, mu {2 * mu_blade}: {1e3 * rms(2 * mu_blade):.2f} mm")
    # The law must fit, and fit far better than without friction or with twice the blade's:
    # a short push near the tip (1.9 ms, 57 mm) tells them apart by 0.17 mm against a fit of
    # 1 um, a long one (4.4 ms, 0.13 m) by 7 mm against 18 um.
    ok = abs(fit_mu - mu_blade) <= 0.05 and fit_rms < 5e-4 and min(rms(0), rms(2 * mu_blade)) > 20 * fit_rms
    print("passed" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
