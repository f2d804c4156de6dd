#!/usr/bin/env python3
"""Issue 30's benchmark: one rotor meshed 100 to 1600 elements, bounded Campbell, Whirl beside ROSS 2.3.0.

Not part of CI. Setup and run (from the repository root; ROSS at 400 elements takes minutes on
one core):

    python3 -m venv .venv && .venv/bin/pip install -r benches/requirements.txt
    cargo build --release
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python benches/mesh_ross.py
    # quick: two meshes, ROSS at both, about 2 minutes
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python benches/mesh_ross.py --meshes 100,200 --ross-max 200

Options: --meshes 100,200,... (element counts, default 100,200,400,800,1600; each a multiple of
10 so that the disks and the steps of the shaft land on nodes), --ross-max N (ROSS at the meshes
of at most N elements, default 400), --no-ross (Whirl only; ROSS is not even imported).

The rotor (`rotor(elements)`): one physical rotor, only its mesh changes (the shaft segments'
`elements`). A 1.6 m steel shaft (E = 2.11e11, rho = 7810, nu = 0.3), outer diameter 0.09 m over
0-0.32 m and 1.28-1.6 m, 0.11 m between; disks of 30, 45 and 30 kg at 0.48, 0.80 and 1.12 m
(multiples of 1.6 / 100 m: nodes 30, 50, 70 of 100 elements, 60, 100, 140 of 200, ...); two
bearings at the ends, anisotropic and cross-coupled (kxx 1e8 / 1.2e8, kyy 7e7 / 8e7, kxy 2e7,
kyx -2e7 N/m, cxx 4e4 / 5e4, cyy 3e4 / 4e4 N s/m, constant in speed). Bearing damping only
(Whirl's `viscous` model), as ROSS has no material loss.

Sweep, the same for every mesh (set on the 100-element mesh, w_k its undamped natural frequencies
at rest from /v1/modal, as benches/campbell_ross.py chooses them): 40 speeds over 0 - 1.5 w1,
`max_frequency` 1.3 w3.

Whirl: /v1/campbell over HTTP, JSON included, with its default checked modal reduction; best of 3
at meshes of at most 400 elements, one run above. Past 600 coordinates (here from 150 elements,
4 complex coordinates per node on these bearings) the reduction holds the rotor sparse
(`analysis::large`: Lanczos modes, sparse factors, Arnoldi check; the answer's
`reduction.full_model` says `sparse`), which the default limits admit up to the memory budget; a
mesh the service refuses is reported with the answer's status and message, and the run carries on
with the next mesh. ROSS: `run_campbell(speeds,
frequencies=N)` at equal work, the same 40 speeds and N = the number of branches Whirl reports
below the bound at that mesh (ROSS itself asks ARPACK for 2 (N + 2) eigenvalues per speed), one
run after a warm-up (`run_modal` at rest), on one thread; the Whirl rotor JSON becomes the ROSS
rotor by tests/data/ross/generate.py `ross_rotor` (through benches/runup_ross.py), which carries
the 8 bearing coefficients. ROSS runs only where Whirl answered (N comes from Whirl's answer).

Compared per mesh: wall time; growth of Whirl's time against the smallest mesh answered (100
elements in the default run; issue 30's target <= 28x at 1600); Whirl's `reduction` (modes kept,
states solved, full model's states, checked error); the 4 lowest |frequency| over Whirl's
branches at speed 0 (the mesh convergence; a block after the table gives each one's change
against the finest mesh answered); ROSS's time and ROSS / Whirl (target >= 300x at 400
elements); the largest relative deviation of each Whirl pole's |frequency| from the nearest mode
ROSS computed at that speed, whatever ROSS labels it (`nearest_deviation`: at 400 elements ROSS
2.3.0 labels its two torsional modes lateral), and the same over the Whirl poles with
|decay_rate| <= `max_frequency` only ("dev chk"): Whirl's reduction check (`max_relative_error`)
covers only those, while its branches also carry heavily damped bearing modes (|frequency| below
the bound, |decay_rate| above it) that the reduced model places less exactly.
"""

import argparse
import os
import sys
import time
import urllib.error
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")  # ROSS on one thread (compare_ross's Whirl drops it)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benches"))
sys.path.insert(0, str(ROOT / "tests" / "data" / "ross"))
from compare_ross import Whirl  # noqa: E402

LENGTH = 1.6  # m
BASE = 100  # elements of the mesh that sets the sweep
SEGMENTS = [(0.32, 0.09), (0.96, 0.11), (0.32, 0.09)]  # (length m, outer diameter m)
DISKS = [(0.48, 30.0, 0.20), (0.80, 45.0, 0.25), (1.12, 30.0, 0.20)]  # (position m, mass kg, radius m)
BEARINGS = [(0.0, dict(kxx=1e8, kyy=7e7, kxy=2e7, kyx=-2e7, cxx=4e4, cyy=3e4)),
            (LENGTH, dict(kxx=1.2e8, kyy=8e7, kxy=2e7, kyx=-2e7, cxx=5e4, cyy=4e4))]
STEEL = {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3, "loss_factor": 0.0}
SPEEDS = 40
STOP_OVER_W1 = 1.5
BOUND_OVER_W3 = 1.3
LOWEST = 4  # frequencies at speed 0 shown per mesh
BEST_OF_UP_TO = 1600  # elements: best of 3 up to this mesh, one run above
TIME_LIMIT = 600  # s: the server's synchronous time limit for this run (its default is 60)


def node_at(x, elements):
    """The node at x on an even mesh of `elements`; refuses a mesh that does not put one there."""
    n = x / LENGTH * elements
    if abs(n - round(n)) > 1e-9:
        raise SystemExit(f"{elements} elements put no node at {x} m: use multiples of 10")
    return int(round(n))


def rotor(elements):
    """The Whirl beam rotor, its shaft split into `elements` equal elements."""
    shaft = []
    for length, od in SEGMENTS:
        shaft.append({"length": length, "outer_diameter": od, "inner_diameter": 0.0, "material": "steel",
                      "elements": node_at(length, elements)})
    assert sum(s["elements"] for s in shaft) == elements
    disks = []
    for x, m, r in DISKS:
        ip = m * r * r / 2
        disks.append({"node": node_at(x, elements), "mass": m, "polar_inertia": ip,
                      "transverse_inertia": ip / 2})
    supports = [dict({"node": node_at(x, elements)}, **k) for x, k in BEARINGS]
    return {"type": "beam", "materials": {"steel": dict(STEEL)}, "shaft": shaft, "disks": disks,
            "supports": supports}


def problem(err):
    """'status title: detail (path: message; ...)' of an HTTP error's problem+json."""
    import json

    try:
        p = json.loads(err.read())
    except Exception:  # noqa: BLE001
        return f"{err.code} {err.reason}"
    text = f"{err.code} {p.get('title') or err.reason}"
    if p.get("detail"):
        text += f": {p['detail']}"
    errs = [f"{e.get('path', '')}: {e.get('message', '')}" for e in p.get("errors") or []]
    errs = "; ".join(e for e in errs if e not in text)  # the detail often lists them already
    return text + (f" ({errs})" if errs else "")


def at_rest(camp, count):
    f = sorted(abs(b["frequency"][0]) for b in camp["branches"] if b["frequency"][0] is not None)
    return f[:count]


def nearest_deviation(camp, result, speeds, bound):
    """Each Whirl pole's |frequency| against the nearest of every mode ROSS computed at that speed,
    whatever its mode_type (at 400 elements ROSS 2.3.0 labels its torsional modes at 2373.8 and
    3289.5 rad/s 'Lateral', which shifts a comparison of sorted lists by two modes): the largest
    relative deviation over all Whirl poles, over those in the region Whirl's reduction check
    covers (|decay_rate| <= max_frequency), and the worst pair (relative, speed, Whirl's, ROSS's,
    Whirl's decay rate)."""
    dev, dev_checked, worst = 0.0, 0.0, (0.0, None, None, None, None)
    for i, speed in enumerate(speeds):
        ross = [q for q in result.modal_results[speed].wd if q > 1e-6]
        for b in camp["branches"]:
            f, d = b["frequency"][i], b["decay_rate"][i]
            if f is None:
                continue
            q = min(ross, key=lambda q: abs(q - abs(f)))
            e = abs(abs(f) - q) / q
            dev = max(dev, e)
            if abs(d) <= bound:
                dev_checked = max(dev_checked, e)
            if e > worst[0]:
                worst = (e, speed, abs(f), q, d)
    return dev, dev_checked, worst


def run_ross(rot, camp, speeds, bound):
    """ROSS run_campbell at equal work: seconds, N, deviation (all, checked region, worst pair),
    frequencies compared at every speed, fewest lateral frequencies ROSS gave at a speed."""
    from campbell_ross import lowest, ross_lowest  # imports ROSS (seconds)
    from runup_ross import quiet, ross_rotor

    n = len(camp["branches"])
    with quiet():
        model = ross_rotor(rot)
        model.run_modal(0.0, num_modes=2 * n)  # warm-up (not 2 (n + 2): run_modal is lru-cached)
        t = time.perf_counter()
        result = model.run_campbell(speeds, frequencies=n)
        seconds = time.perf_counter() - t
    fw, fr = lowest(camp, n), ross_lowest(result, speeds, n)
    compared = min(min(len(a), len(b)) for a, b in zip(fw, fr))
    dev, dev_checked, worst = nearest_deviation(camp, result, speeds, bound)
    return seconds, n, dev, dev_checked, worst, compared, min(len(b) for b in fr)


def run_mesh(whirl, elements, body, args):
    rot = rotor(elements)
    body = dict(body, rotor=rot)
    runs = 3 if elements <= BEST_OF_UP_TO else 1
    row = {"elements": elements, "runs": runs}
    print(f"\n== {elements} elements ({elements + 1} nodes; disks at nodes "
          f"{[d['node'] for d in rot['disks']]}, bearings at {[s['node'] for s in rot['supports']]})", flush=True)
    try:
        t_whirl, camp = whirl.timed("/v1/campbell", body, runs)
    except urllib.error.HTTPError as e:
        row["refused"] = problem(e)
        print(f"   Whirl refused it: {row['refused']}", flush=True)
        if not args.no_ross and elements <= args.ross_max:
            print("   ROSS not run: no Whirl answer to set its work (the number of branches)")
        return row
    row.update(whirl=t_whirl, camp=camp, info=camp.get("reduction"), rest=at_rest(camp, LOWEST),
               branches=len(camp["branches"]))
    info = row["info"]
    print(f"   Whirl {t_whirl:.3f} s (best of {runs}), {row['branches']} branches below the bound; reduction: "
          + (f"{info['modes']} modes, {info['states']} of {info['full_states']} states, checked "
             f"{info['max_relative_error']:.1e}, full model held {info.get('full_model', 'dense')}"
             if info else "none (full model)"), flush=True)
    print(f"   lowest {LOWEST} |frequencies| at rest: " + ", ".join(f"{f:.3f}" for f in row["rest"]) + " rad/s")
    if args.no_ross or elements > args.ross_max:
        return row
    speeds = np.linspace(0.0, body["speeds"]["stop"], SPEEDS)
    assert np.allclose(camp["speeds"], speeds, rtol=1e-12, atol=1e-9), "Whirl's speeds are not the linspace"
    bound = body["max_frequency"]
    t_ross, n, dev, dev_checked, worst, compared, ross_lateral = run_ross(rot, camp, speeds, bound)
    row.update(ross=t_ross, dev=dev, dev_checked=dev_checked, compared=compared)
    print(f"   ROSS run_campbell(frequencies={n}) {t_ross:.2f} s: {t_ross / t_whirl:.1f}x Whirl; every Whirl "
          f"pole's frequency within {dev:.1e} of the nearest ROSS mode at every speed (ROSS's modes labelled "
          f"lateral per speed: at least {ross_lateral} of its {n + 2})", flush=True)
    print(f"   within {dev_checked:.1e} over the poles with |decay_rate| <= max_frequency (Whirl's checked "
          f"region); worst pair: {worst[0]:.1e} at {worst[1]:.1f} rad/s, Whirl {worst[2]:.3f}, ROSS "
          f"{worst[3]:.3f} rad/s, decay rate {worst[4]:.1f} 1/s")
    if compared < n:
        print(f"   note: equal-work mismatch, ROSS gave {ross_lateral} lateral frequencies at some speed for "
              f"Whirl's {n} branches; {compared} compared")
    return row


def fmt(x, spec, width):
    return f"{'-':>{width}}" if x is None else format(x, f"{width}{spec}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshes", default="100,200,400,800,1600",
                    help="element counts, comma-separated (multiples of 10)")
    ap.add_argument("--ross-max", type=int, default=400, help="ROSS at meshes of at most this many elements")
    ap.add_argument("--no-ross", action="store_true", help="Whirl only")
    args = ap.parse_args()
    meshes = sorted({int(m) for m in args.meshes.split(",") if m.strip()})
    for m in meshes + [BASE]:
        rotor(m)  # every mesh puts the disks and steps on nodes (exits otherwise)

    binary = ROOT / "target" / "release" / "whirl"
    if not binary.exists():
        raise SystemExit(f"{binary} missing: cargo build --release")
    os.environ.setdefault("WHIRL_REQUEST_TIME_LIMIT", str(TIME_LIMIT))
    print(f"machine: {os.cpu_count()} cores; ROSS on 1 thread (OMP/OPENBLAS_NUM_THREADS="
          f"{os.environ['OMP_NUM_THREADS']}/{os.environ['OPENBLAS_NUM_THREADS']}), Whirl on all cores; "
          f"whirl binary of {time.ctime(binary.stat().st_mtime)}")
    start = time.perf_counter()
    whirl = Whirl()
    rows = []
    try:
        w = whirl.post("/v1/modal", {"rotor": rotor(BASE), "damping": {"model": "viscous"},
                                     "speed": 0.0})["natural_frequencies"]
        stop, bound = STOP_OVER_W1 * w[0], BOUND_OVER_W3 * w[2]
        print(f"rotor: {LENGTH} m shaft, {len(DISKS)} disks, 2 anisotropic cross-coupled bearings; at {BASE} "
              f"elements w1..w4 = {', '.join(f'{x:.2f}' for x in w[:4])} rad/s (undamped, at rest)")
        print(f"sweep: {SPEEDS} speeds over 0-{stop:.2f} rad/s ({STOP_OVER_W1} w1), max_frequency {bound:.2f} "
              f"({BOUND_OVER_W3} w3); meshes {meshes}; ROSS "
              + ("off" if args.no_ross else f"at <= {args.ross_max} elements"))
        body = {"damping": {"model": "viscous"},
                "speeds": {"start": 0.0, "stop": float(stop), "count": SPEEDS}, "max_frequency": float(bound)}
        for m in meshes:
            rows.append(run_mesh(whirl, m, body, args))
    finally:
        whirl.close()

    answered = [r for r in rows if "whirl" in r]
    base = answered[0] if answered else None
    print(f"\nsummary (wall s; growth = Whirl's time / at {base['elements'] if base else '-'} elements; "
          f"red. = Whirl's reduction: modes, states / full states, checked error; f1-f4 the lowest "
          f"|frequencies| at rest, rad/s; dev = largest relative deviation of a Whirl pole's frequency from "
          f"the nearest mode ROSS computed, over every speed; dev chk the same over the poles with "
          f"|decay_rate| <= max_frequency, the region Whirl's reduction check covers)")
    print(f"{'elements':>8}{'Whirl s':>9}{'runs':>5}{'growth':>8}{'modes':>6}{'states':>11}{'red.err':>9}"
          + "".join(f"{'f' + str(i + 1):>10}" for i in range(LOWEST))
          + f"{'ROSS s':>9}{'ratio':>9}{'dev':>9}{'dev chk':>9}")
    notes = []
    for r in rows:
        if "refused" in r:
            notes.append(f"{r['elements']} elements: {r['refused']}")
            print(f"{r['elements']:>8}{'refused ' + r['refused'].split()[0]:>14}  (see below)")
            continue
        info = r["info"]
        states = f"{info['states']}/{info['full_states']}" if info else "full"
        rest = r["rest"] + [None] * (LOWEST - len(r["rest"]))
        ratio = r["ross"] / r["whirl"] if "ross" in r else None
        print(f"{r['elements']:>8}{r['whirl']:9.3f}{r['runs']:>5}{r['whirl'] / base['whirl']:7.2f}x"
              f"{info['modes'] if info else '-':>6}{states:>11}{fmt(info and info['max_relative_error'], '.1e', 9)}"
              + "".join(fmt(f, ".3f", 10) for f in rest)
              + f"{fmt(r.get('ross'), '.2f', 9)}{fmt(ratio, '.1f', 8)}{'x' if ratio else ' '}"
              f"{fmt(r.get('dev'), '.1e', 9)}{fmt(r.get('dev_checked'), '.1e', 9)}")
    for n in notes:
        print(f"  {n}")
    if len(answered) > 1:
        fine = answered[-1]
        print(f"\nconvergence: the lowest {LOWEST} |frequencies| at rest relative to {fine['elements']} elements")
        for r in answered[:-1]:
            print(f"{r['elements']:>8}" + "".join(f"{(a - b) / b:+10.1e}" for a, b in zip(r["rest"], fine["rest"])))
    print(f"\ntotal script time: {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    sys.exit(main())
