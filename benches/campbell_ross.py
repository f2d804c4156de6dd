#!/usr/bin/env python3
"""Bounded Campbell sweeps, Whirl beside ROSS 2.3.0, on rotors nobody tuned for, in one run.

Not part of CI. Setup and run (from the repository root, a few minutes):

    python3 -m venv .venv && .venv/bin/pip install -r benches/requirements.txt
    cargo build --release
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python benches/campbell_ross.py

Cases: the issue's rotor (the compressor example unreduced, supports c = 5e4 N s/m; 40 speeds
over 0-2000 rad/s, `max_frequency` 2500) and the held-out rotors of benches/runup_ross.py (40
speeds over 0 to 2 w1, `max_frequency` 1.3 w3, w_k the undamped natural frequencies at rest).
Bearing damping only (Whirl's `viscous` model), as ROSS has no material loss.

Whirl: /v1/campbell over HTTP, JSON included, best of 3, with its checked modal reduction, and
once on the full model (`modal_reduction: false`). ROSS: `run_campbell(speeds, frequencies=6)`
(ARPACK per speed), one run after a warm-up. Compared: wall time, and the 6 lowest lateral
damped frequencies at every speed (Whirl's lowest |frequency| over its branches).
"""

import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benches"))
sys.path.insert(0, str(ROOT / "tests" / "data" / "ross"))
from compare_ross import Whirl, ross_rotor as ross_rotor_simple  # noqa: E402
from runup_ross import HELDOUT, heldout_rotor, issue_case, quiet, ross_rotor  # noqa: E402

SPEEDS = 40
FREQUENCIES = 6


def lowest(camp, count):
    out = []
    for i in range(len(camp["speeds"])):
        f = sorted(abs(b["frequency"][i]) for b in camp["branches"] if b["frequency"][i] is not None)
        out.append(f[:count])
    return out


def ross_lowest(result, speeds, count):
    out = []
    for w in speeds:
        modal = result.modal_results[w]
        f = sorted(wd for wd, s in zip(modal.wd, modal.shapes) if s.mode_type == "Lateral")
        out.append(f[:count])
    return out


def deviation(a, b):
    worst = 0.0
    for x, y in zip(a, b):
        n = min(len(x), len(y))
        for p, q in zip(x[:n], y[:n]):
            if q > 1e-6:
                worst = max(worst, abs(p - q) / q)
    return worst


def run_case(whirl, name, rotor, stop, bound):
    speeds = np.linspace(0.0, stop, SPEEDS)
    body = {"rotor": rotor, "damping": {"model": "viscous"},
            "speeds": {"start": 0.0, "stop": float(stop), "count": SPEEDS}, "max_frequency": float(bound)}
    t_red, red = whirl.timed("/v1/campbell", body, 3)
    t_full, full = whirl.timed("/v1/campbell", dict(body, modal_reduction=False), 1)
    # Equal work: the branches ROSS returns, bounded by count (`modes`) instead of a frequency.
    by_count = {k: v for k, v in body.items() if k != "max_frequency"}
    t_modes, modes = whirl.timed("/v1/campbell", dict(by_count, modes=FREQUENCIES), 3)
    model = (ross_rotor_simple if "stiffness" in rotor["supports"][0] else ross_rotor)(rotor)
    with quiet():
        model.run_modal(0.0, num_modes=2 * FREQUENCIES)
        t = time.perf_counter()
        result = model.run_campbell(speeds, frequencies=FREQUENCIES)
        t_ross = time.perf_counter() - t
    info = red.get("reduction")
    fr = ross_lowest(result, speeds, FREQUENCIES)
    dev_red = deviation(lowest(red, FREQUENCIES), fr)
    dev_full = deviation(lowest(full, FREQUENCIES), fr)
    dev_self = deviation(lowest(red, FREQUENCIES), lowest(full, FREQUENCIES))
    dev_modes = deviation(lowest(modes, FREQUENCIES), lowest(full, FREQUENCIES))
    info_m = modes.get("reduction")
    print(f"\n== {name}: {model.ndof // 6} nodes, 0-{stop:.0f} rad/s, {SPEEDS} speeds, max_frequency {bound:.0f}")
    print("   Whirl reduction: " + (f"{info['states']} of {info['full_states']} states, checked "
                                     f"{info['max_relative_error']:.1e}" if info else "none (full model)"))
    print(f"   Whirl {t_red:.3f} s, Whirl full model {t_full:.3f} s, ROSS run_campbell {t_ross:.2f} s: "
          f"{t_ross / t_red:.1f}x (full model {t_ross / t_full:.1f}x)")
    print(f"   lowest {FREQUENCIES} frequencies: reduced vs full Whirl {dev_self:.1e}, "
          f"vs ROSS {dev_red:.1e} (full Whirl vs ROSS {dev_full:.1e})")
    print(f"   modes {FREQUENCIES}: Whirl {t_modes:.3f} s, {t_ross / t_modes:.1f}x ROSS, "
          + (f"{info_m['states']} of {info_m['full_states']} states, " if info_m else "full model, ")
          + f"{len(modes['branches'])} branches, vs full Whirl {dev_modes:.1e}")
    return name, t_red, t_full, t_ross, info, t_modes


def main():
    whirl = Whirl()
    rows = []
    try:
        body = issue_case()
        rows.append(run_case(whirl, "issue rotor (compressor, c = 5e4)", body["rotor"], 2000.0, 2500.0))
        for name, opts in HELDOUT:
            rotor = heldout_rotor(**opts)
            w = whirl.post("/v1/modal", {"rotor": rotor, "damping": {"model": "viscous"},
                                         "speed": 0.0})["natural_frequencies"]
            rows.append(run_case(whirl, name, rotor, 2.0 * w[0], 1.3 * w[2]))
    finally:
        whirl.close()
    print(f"\n{'case':<36}{'Whirl':>8}{'W full':>8}{'ROSS':>8}{'ratio':>8}{'states':>12}"
          f"{'modes 6':>9}{'ratio':>8}")
    for name, tr, tf, tross, info, tm in rows:
        states = f"{info['states']}/{info['full_states']}" if info else "full"
        print(f"{name:<36}{tr:8.3f}{tf:8.2f}{tross:8.2f}{tross / tr:7.1f}x{states:>12}"
              f"{tm:9.3f}{tross / tm:7.1f}x")


if __name__ == "__main__":
    sys.exit(main())
