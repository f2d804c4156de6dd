#!/usr/bin/env python3
"""Whole-spectrum sweeps, Whirl beside ROSS 2.3.0's dense `run_modal`, on the rotors of
benches/campbell_ross.py, in one run.

Not part of CI. Setup and run (from the repository root, a few minutes):

    python3 -m venv .venv && .venv/bin/pip install -r benches/requirements.txt
    cargo build --release
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python benches/spectrum_ross.py

Every pole at 5 speeds (the speed ranges of campbell_ross.py): Whirl's /v1/campbell with no
frequency bound on the full model (`modal_reduction: false`: every branch, every speed, shapes
tracked), over HTTP with JSON, best of 3; ROSS's `run_modal(speed, sparse=False)` (scipy's
dense `eig` of its 2 x 6 dof-per-node state matrix, values and vectors), once per speed after a
warm-up. Compared: wall time, and the lowest 6 lateral damped frequencies at every speed.
"""

import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benches"))
sys.path.insert(0, str(ROOT / "tests" / "data" / "ross"))
from campbell_ross import deviation, lowest  # noqa: E402
from compare_ross import Whirl, ross_rotor as ross_rotor_simple  # noqa: E402
from runup_ross import HELDOUT, heldout_rotor, issue_case, quiet, ross_rotor  # noqa: E402

SPEEDS = 5
FREQUENCIES = 6


def run_case(whirl, name, rotor, stop):
    speeds = np.linspace(0.0, stop, SPEEDS)
    body = {"rotor": rotor, "damping": {"model": "viscous"}, "modal_reduction": False,
            "speeds": {"start": 0.0, "stop": float(stop), "count": SPEEDS}}
    t_whirl, camp = whirl.timed("/v1/campbell", body, 3)
    model = (ross_rotor_simple if "stiffness" in rotor["supports"][0] else ross_rotor)(rotor)
    with quiet():
        model.run_modal(0.0, sparse=False)  # warm-up
        t = time.perf_counter()
        modal = [model.run_modal(float(w), sparse=False) for w in speeds]
        t_ross = time.perf_counter() - t
    fr = [sorted(wd for wd, s in zip(m.wd, m.shapes) if s.mode_type == "Lateral")[:FREQUENCIES]
          for m in modal]
    dev = deviation(lowest(camp, FREQUENCIES), fr)
    poles = len(camp["branches"])
    print(f"== {name}: {model.ndof // 6} nodes, {SPEEDS} speeds 0-{stop:.0f} rad/s: Whirl {t_whirl:.3f} s "
          f"({poles} branches), ROSS {t_ross:.2f} s ({model.ndof * 2} states, {len(modal[0].wd)} modes kept): "
          f"{t_ross / t_whirl:.1f}x; lowest {FREQUENCIES} frequencies vs ROSS {dev:.1e}", flush=True)
    return name, t_whirl, t_ross, poles, dev


def main():
    whirl = Whirl()
    rows = []
    try:
        rows.append(run_case(whirl, "issue rotor (compressor, c = 5e4)", issue_case()["rotor"], 2000.0))
        for name, opts in HELDOUT:
            rotor = heldout_rotor(**opts)
            w = whirl.post("/v1/modal", {"rotor": rotor, "damping": {"model": "viscous"},
                                         "speed": 0.0})["natural_frequencies"]
            rows.append(run_case(whirl, name, rotor, 2.0 * w[0]))
    finally:
        whirl.close()
    print(f"\n{'case':<36}{'Whirl':>8}{'ROSS':>8}{'ratio':>8}{'branches':>10}{'vs ROSS':>10}")
    for name, tw, tr, poles, dev in rows:
        print(f"{name:<36}{tw:8.3f}{tr:8.2f}{tr / tw:7.1f}x{poles:>10}{dev:10.1e}")


if __name__ == "__main__":
    sys.exit(main())
