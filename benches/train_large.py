#!/usr/bin/env python3
"""Issue 30's train benchmark: the bundled 3-rotor train meshed finer, every analysis over HTTP.

Not part of CI. Setup and run (from the repository root, a few minutes):

    python3 -m venv .venv && .venv/bin/pip install -r benches/requirements.txt
    cargo build --release
    .venv/bin/python benches/train_large.py            # meshes x1, x10, x60 (18, 180, 1080 elements)
    .venv/bin/python benches/train_large.py --refine 1,60

The rotor: `examples/train-hysteretic.campbell.json` (three steel shafts joined by two flexible
couplings, four disks, six anisotropic cross-coupled bearings), every shaft segment's elements
multiplied by the refinement (its nodes renumbered; the disks, bearings and the nodes loaded or
read stay where they are). At x60 it has 1080 shaft elements, 1083 nodes, 2166 complex degrees
of freedom, 4332 coordinates (doubled on its bearings), past the dense limit (WHIRL_MAX_DOFS,
1000 degrees of freedom): the analyses that hold a rotor sparse answer, the others refuse with a
422 naming the setting, and both are reported.

Each analysis (the request below) through HTTP (JSON included) on one server with its default
settings, best of 3 runs where the first took under 2 s, else that one run: its wall time, how the full model was held (the answer's
`full_model` or `reduction.full_model`; `-` where the answer does not say), and a headline
number to follow with the mesh (in the table's `value` column):

- campbell: hysteretic, 31 speeds over 0-1500 rad/s, max_frequency 1500; the lowest |frequency|
  at rest, rad/s.
- static: the largest deflection, m.
- map: 12 stiffnesses 1e6-1e10 N/m, 4 modes; the first mode at 1e8 N/m (index 6), rad/s.
- unbalance: hysteretic, 150 speeds 10-1500 rad/s, 1e-4 kg m at the first disk, read there and at
  the third; the first peak's speed at the first disk, rad/s.
- frequency: viscous, spun at 600 rad/s, 150 frequencies 10-1500 rad/s, a unit force along x at
  the first disk, read at the third; the largest amplitude, m/N.
- level1: hysteretic, at 600 rad/s, 11 cross-couplings 0-2e4 N/m at the first disk; the log
  decrement at zero cross-coupling.
- run-up: viscous, 0 to 600 rad/s in 3 s, 1e-4 kg m at the first disk; the largest radial
  amplitude there, m.
- shock: viscous, at 600 rad/s, 10 kN along x at the first disk ramped over 11 ms and released;
  the largest radial amplitude there, m.
- modal: hysteretic, at 500 rad/s, `max_frequency` 1500 rad/s; the first natural frequency.
- stability: hysteretic, 31 speeds over 0-3000 rad/s, `max_frequency` 3000 rad/s; the threshold.
- report: hysteretic, operating range 250-350 rad/s, comparing the hysteretic and viscous
  models; the first forward critical speed of its Campbell diagram.
- damping (nonviscous): past the dense limits it still holds the rotor dense (refused).
- campbell-equ, campbell-non: the Campbell diagram above of the equivalent and nonviscous
  models (held sparse with their dampers on the modes up to 16 times the bound).
- stability-equ, stability-non: the threshold above of those models.
- modal-non: the modal analysis above of the nonviscous model.
- level1-equ, level1-non: Level I above of those models, with Level II (`machine`: a 2 MW stage
  at the first disk and 5e5 N/m more at the second); the log decrement at zero cross-coupling.
- run-up-non: the run-up above of the nonviscous model.
- report-all: the report above comparing the default four models.
"""

import argparse
import copy
import json
import os
import sys
import time
import urllib.error
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benches"))
from compare_ross import Whirl  # noqa: E402

EXAMPLE = ROOT / "examples" / "train-hysteretic.campbell.json"
TIME_LIMIT = 600  # s: the server's synchronous time limit for this run (its default is 60)


def refined(coarse, k):
    """The rotor with every shaft segment's elements times k, and each coarse node's fine node."""
    fine = copy.deepcopy(coarse)
    nodes = [0]
    for seg in fine["shaft"]:
        last = nodes[-1]
        if "coupling" in seg:
            nodes.append(last + 1)
            continue
        e = seg.get("elements", 1)
        seg["elements"] = e * k
        nodes.extend(last + i * k for i in range(1, e + 1))
    for key in ("disks", "supports"):
        for item in fine[key]:
            item["node"] = nodes[item["node"]]
    return fine, nodes


def requests(rotor, n):
    """(name, path, body, headline) of every analysis of `rotor`, `n` the fine node of a coarse one."""
    h, v = {"model": "hysteretic"}, {"model": "viscous"}
    first, third = n[3], n[15]
    peak = lambda xs, ys: max((x * x + y * y) ** 0.5 for x, y in zip(xs, ys))  # noqa: E731
    return [
        ("campbell", "/v1/campbell",
         {"rotor": rotor, "damping": h, "speeds": {"start": 0, "stop": 1500, "count": 31}, "max_frequency": 1500},
         lambda o: min(abs(b["frequency"][0]) for b in o["branches"] if b["frequency"][0] is not None)),
        ("static", "/v1/static", {"rotor": rotor}, lambda o: o["max_deflection"]),
        ("map", "/v1/critical-speed-map",
         {"rotor": rotor, "stiffness": {"start": 1e6, "stop": 1e10, "count": 12}, "modes": 4},
         lambda o: o["frequencies"][0][6]),
        ("unbalance", "/v1/unbalance-response",
         {"rotor": rotor, "damping": h, "speeds": {"start": 10, "stop": 1500, "count": 150},
          "unbalances": [{"node": first, "amount": 1e-4, "phase": 0}], "nodes": [first, third]},
         lambda o: o["nodes"][0]["peaks"][0]["speed"]),
        ("frequency", "/v1/frequency-response",
         {"rotor": rotor, "damping": v, "speed": 600, "input": {"node": first, "direction": 0},
          "output": {"node": third}, "frequencies": {"start": 10, "stop": 1500, "count": 150}},
         lambda o: max(o["amplitude"])),
        ("level1", "/v1/level1",
         {"rotor": rotor, "damping": h, "speed": 600, "node": first,
          "cross_coupling": {"start": 0, "stop": 2e4, "count": 11}},
         lambda o: o["log_decrement_0"]),
        ("run-up", "/v1/time-response",
         {"rotor": rotor, "damping": v, "speed_profile": [[0, 0], [3, 600]],
          "unbalances": [{"node": first, "amount": 1e-4, "phase": 0}], "duration": 3,
          "output_interval": 0.002, "nodes": [first]},
         lambda o: peak(o["nodes"][0]["x"], o["nodes"][0]["y"])),
        ("shock", "/v1/time-response",
         {"rotor": rotor, "damping": v, "speed": 600,
          "forces": [{"node": first, "direction": 0.0, "history": [[0, 0], [0.011, 1e4], [0.011, 0]]}],
          "duration": 0.5, "output_interval": 0.0005, "nodes": [first]},
         lambda o: peak(o["nodes"][0]["x"], o["nodes"][0]["y"])),
        ("modal", "/v1/modal", {"rotor": rotor, "damping": h, "speed": 500, "max_frequency": 1500},
         lambda o: o["natural_frequencies"][0]),
        ("stability", "/v1/stability",
         {"rotor": rotor, "damping": h, "speeds": {"start": 0, "stop": 3000, "count": 31},
          "max_frequency": 3000},
         lambda o: o["threshold"] or "stable"),
        ("report", "/v1/report",
         {"rotor": rotor, "damping": h, "operating_range": {"min": 250, "max": 350},
          "models": [h, v]},
         lambda o: o["campbell"]["critical_speeds"][0]),
        ("damping", "/v1/damping", {"rotor": rotor, "damping": {"model": "nonviscous"}}, lambda o: None),
    ] + [
        (f"campbell-{m[:3]}", "/v1/campbell",
         {"rotor": rotor, "damping": {"model": m}, "speeds": {"start": 0, "stop": 1500, "count": 31},
          "max_frequency": 1500},
         lambda o: min(abs(b["frequency"][0]) for b in o["branches"] if b["frequency"][0] is not None))
        for m in ("equivalent", "nonviscous")
    ] + [
        (f"stability-{m[:3]}", "/v1/stability",
         {"rotor": rotor, "damping": {"model": m}, "speeds": {"start": 0, "stop": 3000, "count": 31},
          "max_frequency": 3000},
         lambda o: o["threshold"] or "stable")
        for m in ("equivalent", "nonviscous")
    ] + [
        ("modal-non", "/v1/modal",
         {"rotor": rotor, "damping": {"model": "nonviscous"}, "speed": 500, "max_frequency": 1500},
         lambda o: o["natural_frequencies"][0]),
    ] + [
        (f"level1-{m[:3]}", "/v1/level1",
         {"rotor": rotor, "damping": {"model": m}, "speed": 600,
          "cross_coupling": {"start": 0, "stop": 2e4, "count": 11},
          "machine": {"stages": [{"node": first, "power": 2e6, "diameter": 0.3, "width": 0.02}],
                      "additional_cross_coupling": [{"node": n[5], "q": 5e5}]}},
         lambda o: o["log_decrement_0"])
        for m in ("equivalent", "nonviscous")
    ] + [
        ("run-up-non", "/v1/time-response",
         {"rotor": rotor, "damping": {"model": "nonviscous"}, "speed_profile": [[0, 0], [3, 600]],
          "unbalances": [{"node": first, "amount": 1e-4, "phase": 0}], "duration": 3,
          "output_interval": 0.002, "nodes": [first]},
         lambda o: peak(o["nodes"][0]["x"], o["nodes"][0]["y"])),
        ("report-all", "/v1/report",
         {"rotor": rotor, "damping": h, "operating_range": {"min": 250, "max": 350}},
         lambda o: o["campbell"]["critical_speeds"][0]),
    ]


def held(out):
    """How the answer says the full model was held."""
    if "full_model" in out:
        return out["full_model"]
    if "unbalance" in out:  # a report: its unbalance response's
        return out["unbalance"].get("full_model", "-")
    red = out.get("reduction") or {}
    return red.get("full_model", "-")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--refine", default="1,10,60", help="refinements, comma-separated")
    ap.add_argument("--only", default="", help="analyses to run (names as printed), comma-separated")
    args = ap.parse_args()
    only = {a for a in args.only.split(",") if a}
    ks = [int(k) for k in args.refine.split(",") if k.strip()]
    binary = ROOT / "target" / "release" / "whirl"
    if not binary.exists():
        raise SystemExit(f"{binary} missing: cargo build --release")
    os.environ.setdefault("WHIRL_REQUEST_TIME_LIMIT", str(TIME_LIMIT))
    coarse = json.loads(EXAMPLE.read_text())["rotor"]
    print(f"machine: {os.cpu_count()} cores; whirl binary of {time.ctime(binary.stat().st_mtime)}")
    whirl = Whirl()
    rows = []
    try:
        for k in ks:
            rotor, n = refined(coarse, k)
            elements = sum(s.get("elements", 1) for s in rotor["shaft"] if "coupling" not in s)
            for name, path, body, headline in requests(rotor, n):
                if only and name not in only:
                    continue
                try:
                    t = time.perf_counter()
                    out = whirl.post(path, body)
                    best = time.perf_counter() - t
                    if best < 2.0:  # the quick ones best of 3
                        best, out = min((best, out), whirl.timed(path, body, runs=2), key=lambda r: r[0])
                    rows.append((k, elements, name, f"{best:.3f}", held(out), headline(out)))
                except urllib.error.HTTPError as e:
                    detail = json.loads(e.read()).get("detail", "")
                    rows.append((k, elements, name, f"{e.code}", "", detail[:90]))
                print(*rows[-1], sep="  ", flush=True)
    finally:
        whirl.close()
    print(f"\n{'mesh':>5}{'elements':>9}  {'analysis':<10}{'s / status':>12}  {'held':<7}value")
    for k, elements, name, t, how, value in rows:
        shown = f"{value:.9g}" if isinstance(value, float) else (value or "")
        print(f"{'x' + str(k):>5}{elements:>9}  {name:<10}{t:>12}  {how:<7}{shown}")


if __name__ == "__main__":
    main()
