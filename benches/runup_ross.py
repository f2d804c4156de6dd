#!/usr/bin/env python3
"""Whirl's run-up time response beside ROSS 2.3.0's, on the same rotors, in one run.

Not part of CI. Setup and run (from the repository root, ~5 min on one core for ROSS):

    python3 -m venv .venv && .venv/bin/pip install -r benches/requirements.txt
    cargo build --release
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python benches/runup_ross.py

Each case runs a rotor up at a constant angular acceleration from rest, 0 -> W_end, through its
first critical speed, with one unbalance, and records the response at the unbalance node every
1e-4 s (bearing damping only: Whirl's `viscous` model, as ROSS has no material loss):

1. the issue's case (/tmp/runup.json if present, else the same request rebuilt here): the
   compressor example without its Guyan reduction (101 nodes, supports c = 5e4 N s/m),
   0 -> 750 rad/s in 0.3 s, 5e-4 kg m at node 46;
2. held-out rotors (tests/data/ross/heldout.py) soft + light, stiff + heavy and with anisotropic
   bearings, 0 -> 1.7 x their first undamped natural frequency (Whirl /v1/modal at rest) at the
   same ~2500 rad/s^2, unbalance at the disk node nearest midspan. Seeds picked for <= 80
   elements (ROSS's direct Newmark refactors a dense ndof^2 matrix every step).

Methods: Whirl /v1/time-response through HTTP, JSON included, best of 9, with its checked modal
reduction (default) and once with "modal_reduction": false (given up after 60 s); ROSS
`run_time_response` with the speed array (Newmark, the only integrator it has for a varying
speed; dt = 1e-4, the output grid) direct (one run) and pseudo-modal (24 modes, best of 3),
after a numba warm-up. Both sides' best of several runs: on a shared 2-core machine a single
run of a few milliseconds varies by 2x and more. Compared: the peak radial amplitude
sqrt(x^2 + y^2) at the unbalance node (the same samples for every method) and its time.

Conventions: ROSS has 6 dof per node (x, y, z, alpha, beta, theta), so node n is x = 6 n,
y = 6 n + 1. The unbalance force is ROSS's own `unbalance_force_over_time`,
f_x = a (W^2 cos phi + W' sin phi), f_y = a (W^2 sin phi - W' cos phi), phi = int W: checked
below to equal Whirl's a (W^2 - i W') e^{i phi} (src/analysis/time/mod.rs). ROSS also adds the
angular-acceleration stiffness W' Ksdt (disk/shaft Ip terms), which Whirl does not model.
"""

import contextlib
import json
import os
import sys
import time
import urllib.error
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benches"))
sys.path.insert(0, str(ROOT / "tests" / "data" / "ross"))
from compare_ross import Whirl, ross_rotor as ross_rotor_simple  # noqa: E402



@contextlib.contextmanager
def quiet():
    """stdout to /dev/null, file descriptor included (ROSS prints; its CoolProp import chatters)."""
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            sys.stdout.flush()
            os.dup2(saved, 1)
            os.close(saved)


with quiet():
    from heldout import heldout_rotor, ross_rotor  # noqa: E402

DT = 1e-4
ACCEL = 2500.0  # rad/s^2, case 1's
LIMIT = 60.0  # s: Whirl's synchronous time limit (503 after it)
PSEUDO = {"method": "pseudomodal", "num_modes": 24}
HELDOUT = [("held-out soft + light", dict(seed=3, stiff=False, heavy=False, anisotropic=False)),
           ("held-out stiff + heavy", dict(seed=8, stiff=True, heavy=True, anisotropic=False)),
           ("held-out anisotropic", dict(seed=3, anisotropic=True))]


def issue_case():
    path = Path("/tmp/runup.json")
    if path.exists():
        return json.loads(path.read_text())
    example = json.loads((ROOT / "examples" / "compressor-nvd.campbell.json").read_text())
    rotor = {k: v for k, v in example["rotor"].items() if k != "reduction"}
    rotor["supports"] = [dict(s, damping=5e4) for s in rotor["supports"]]
    return {"rotor": rotor, "damping": {"model": "viscous"}, "speed_profile": [[0, 0], [0.3, 750]],
            "unbalances": [{"node": 46, "amount": 5e-4}], "duration": 0.3, "output_interval": DT,
            "nodes": [46]}


def heldout_case(whirl, options):
    rotor = heldout_rotor(**options)
    n_el = sum(s["elements"] for s in rotor["shaft"])
    node = min((d["node"] for d in rotor["disks"]), key=lambda n: abs(n - n_el / 2), default=n_el // 2)
    w1 = whirl.post("/v1/modal", {"rotor": rotor, "damping": {"model": "viscous"},
                                  "speed": 0.0})["natural_frequencies"][0]
    w_end = 1.7 * w1
    duration = round(w_end / ACCEL, 3)
    return {"rotor": rotor, "damping": {"model": "viscous"}, "speed_profile": [[0, 0], [duration, w_end]],
            "unbalances": [{"node": node, "amount": 5e-4}], "duration": duration, "output_interval": DT,
            "nodes": [node]}


def whirl_run(whirl, body, runs):
    """(best seconds, answer), or (None, None) if the server stopped it at its time limit (503)."""
    try:
        return whirl.timed("/v1/time-response", body, runs)
    except urllib.error.HTTPError as e:
        if e.code != 503:
            raise
        return None, None


def peak(t, x, y):
    r = np.hypot(x, y)
    i = int(np.argmax(r))
    return r[i], t[i]


def ross_force(model, body, t):
    (u,) = body["unbalances"]
    (t1, w1) = body["speed_profile"][-1]
    speed = w1 * t / t1
    f = model.unbalance_force_over_time([u["node"]], [u["amount"]], [0.0], speed, t).T
    # Whirl's convention, a (W^2 - i W') e^{i phi}, on the same samples:
    acc, phi = w1 / t1, 0.5 * w1 / t1 * t ** 2
    mine = u["amount"] * (speed ** 2 - 1j * acc) * np.exp(1j * phi)
    n = model.number_dof * u["node"]
    assert np.allclose(f[:, n] + 1j * f[:, n + 1], mine, rtol=1e-9, atol=1e-9 * np.abs(mine).max())
    return speed, f


def ross_run(model, speed, f, t, node, **kw):
    start = time.perf_counter()
    with quiet():
        y = model.run_time_response(speed, f, t, **kw).yout
    return (time.perf_counter() - start, *peak(t, y[:, 6 * node], y[:, 6 * node + 1]))


def whirl_row(label, seconds, out):
    if out is None:
        return label, None, None, None
    n = out["nodes"][0]
    return (label, seconds, *peak(np.array(out["time"]), np.array(n["x"]), np.array(n["y"])))


def fmt(x, spec, width):
    if x is None:
        return f"{'-':>{width}}"
    sign = "+" if spec.startswith("+") else ""
    return format(x, f"{sign}{width}{spec.lstrip('+')}")


def run_case(whirl, name, body):
    rotor, (u,) = body["rotor"], body["unbalances"]
    w_end, dur = body["speed_profile"][-1][1], body["duration"]
    model = (ross_rotor_simple if "stiffness" in rotor["supports"][0] else ross_rotor)(rotor)
    print(f"\n== {name}: {model.ndof // 6} nodes ({model.ndof} ROSS dof), {len(rotor['disks'])} disks, "
          f"{len(rotor['supports'])} supports; 0 -> {w_end:.0f} rad/s in {dur} s ({w_end / dur:.0f} rad/s^2), "
          f"{u['amount']:.0e} kg m at node {u['node']}")

    body = dict(body, modal_reduction=True)
    t_red, red = whirl_run(whirl, body, 9)
    t_full, full = whirl_run(whirl, dict(body, modal_reduction=False), 1)
    info = (red or {}).get("reduction")
    print("   Whirl reduction: " + (f"{info['states']} states of {info['full_states']} (modes {info['modes']}, "
                                     f"vectors {info['vectors']}), checked max relative error "
                                     f"{info['max_relative_error']:.1e} at {info['checked_speed']:.0f} rad/s"
                                     if info else "none"))
    t = np.arange(round(dur / DT) + 1) * DT
    speed, f = ross_force(model, body, t)
    rows = [whirl_row("Whirl (modal reduction)", t_red, red), whirl_row("Whirl full model", t_full, full),
            ("ROSS direct Newmark", *ross_run(model, speed, f, t, u["node"])),
            ("ROSS pseudo-modal 24", *min((ross_run(model, speed, f, t, u["node"], model_reduction=dict(PSEUDO))
                                           for _ in range(3)), key=lambda r: r[0]))]

    _, _, ref_peak, ref_t = rows[2]
    print(f"   {'method':<24}{'wall s':>9}{'peak r m':>13}{'at s':>9}{'vs ROSS direct':>16}{'dt ms':>8}")
    for label, sec, pk, tp in rows:
        if sec is None:
            print(f"   {label:<24}{'> ' + str(int(LIMIT)) + ' s':>9}")
            continue
        print(f"   {label:<24}{sec:9.3f}{pk:13.5e}{tp:9.4f}{(pk / ref_peak - 1) * 100:+15.3f}%"
              f"{(tp - ref_t) * 1e3:+8.1f}")
    fastest = min(rows[2][1], rows[3][1])
    ratio = None if t_red is None else fastest / t_red
    print(f"   ROSS fastest / Whirl: {fmt(ratio, '.1f', 0)}x")
    ok = red is not None
    return (name, t_red, t_full, rows[2][1], rows[3][1], ratio,
            (rows[0][2] / ref_peak - 1) * 100 if ok else None, (rows[0][3] - ref_t) * 1e3 if ok else None)


def main():
    start = time.perf_counter()
    binary = ROOT / "target" / "release" / "whirl"
    print(f"machine: {os.cpu_count()} cores; ROSS on 1 thread, Whirl on all cores; dt = output interval "
          f"= {DT} s; whirl binary of {time.ctime(binary.stat().st_mtime)}")
    os.environ.setdefault("WHIRL_REQUEST_TIME_LIMIT", str(int(LIMIT)))
    whirl = Whirl()
    summary = []
    try:
        # numba compiles ROSS's Newmark step on first use: keep that out of the timings.
        warm = ross_rotor(heldout_rotor(1))
        t = np.arange(3) * DT
        ross_run(warm, 100.0 * t, np.ones((3, warm.ndof)), t, 0)
        cases = [("issue case (compressor)", issue_case())]
        cases += [(name, heldout_case(whirl, opts)) for name, opts in HELDOUT]
        for name, body in cases:
            summary.append(run_case(whirl, name, body))
    finally:
        whirl.close()

    print("\nsummary (wall s; peak = radial amplitude at the unbalance node; Whirl with modal reduction "
          "against ROSS direct)")
    print(f"{'case':<26}{'Whirl':>8}{'W full':>8}{'ROSS dir':>10}{'ROSS pm':>9}{'ROSS/Whirl':>12}"
          f"{'peak diff %':>13}{'t diff ms':>11}")
    for name, tw, tf, td, tp, ratio, dp, dtp in summary:
        print(f"{name:<26}{fmt(tw, '.3f', 8)}{fmt(tf, '.2f', 8)}{td:10.2f}{tp:9.2f}{fmt(ratio, '.1f', 11)}x"
              f"{fmt(dp, '+.3f', 13)}{fmt(dtp, '+.1f', 11)}")
    print(f"\ntotal script time: {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    sys.exit(main())
