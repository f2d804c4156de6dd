#!/usr/bin/env python3
"""Held-out rotors for a later speed benchmark: seeded, uniform-random, tuned for nothing.

    OMP_NUM_THREADS=1 .venv/bin/python tests/data/ross/heldout.py

writes heldout/rotor_1.json ... rotor_6.json (a Whirl beam rotor each, nothing else). Nothing is
timed here.

heldout_rotor(seed, ...) returns one Whirl rotor:
* 50-200 Timoshenko elements in 3-8 uniform segments (random split), total length 0.8-3 m,
  outer diameters around length/U(10, 25) (x U(0.7, 1.4) per segment), a third of the
  segments hollow (inner = outer x U(0.2, 0.6)); steel E = 2.11e11, rho = 7810, nu = 0.3.
* disks (optional): 1-5 at distinct interior nodes, m in U(2, 60) kg, Ip = m r^2 / 2 with
  r in U(0.08, 0.3) m, Id = Ip / 2 (+ 0..20 % random).
* 2 bearings (or 3, one at an interior node), the first within the first 5 % of the nodes and the
  last within the last 5 %: k log-uniform in [1e6, 1e9] ("soft" [1e6, 10^7.5], "stiff"
  [10^7.5, 1e9]), c log-uniform in [1e2, 1e5] ("light" [1e2, 10^3.5], "heavy" [10^3.5, 1e5]);
  anisotropic (optional): kyy = kxx U(0.5, 2), cyy = cxx U(0.5, 2), kxy, kyx = kxx U(-0.5, 0.5),
  cxy, cyx = cxx U(-0.2, 0.2); no mass coefficients, constant in speed.
Every unspecified option is drawn from the seed too.

ross_rotor(rotor) (from generate.py, same folder) is the same rotor in ROSS 2.3.0.
"""

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from generate import STEEL, ross_rotor, support  # noqa: E402,F401  (ross_rotor re-exported)


def _log_uniform(rng, lo, hi):
    return float(10 ** rng.uniform(np.log10(lo), np.log10(hi)))


def heldout_rotor(seed, disks=None, stiff=None, heavy=None, anisotropic=None, bearings=None):
    rng = np.random.default_rng(seed)
    pick = lambda v: bool(rng.random() < 0.5) if v is None else v  # noqa: E731
    disks, stiff, heavy, anisotropic = pick(disks), pick(stiff), pick(heavy), pick(anisotropic)
    if bearings is None:
        bearings = 3 if rng.random() < 0.25 else 2

    n_el = int(rng.integers(50, 201))
    n_seg = int(rng.integers(3, 9))
    cuts = np.sort(rng.choice(np.arange(1, n_el), n_seg - 1, replace=False))
    counts = np.diff(np.concatenate([[0], cuts, [n_el]])).astype(int)
    length = float(rng.uniform(0.8, 3.0))
    weights = rng.uniform(0.5, 1.5, n_seg) * counts
    seg_len = length * weights / weights.sum()
    base_d = length / rng.uniform(10, 25)
    shaft = []
    for count, sl in zip(counts, seg_len):
        od = float(base_d * rng.uniform(0.7, 1.4))
        idd = float(od * rng.uniform(0.2, 0.6)) if rng.random() < 1 / 3 else 0.0
        shaft.append({"length": float(sl), "outer_diameter": od, "inner_diameter": idd,
                      "material": "steel", "elements": int(count)})

    out_disks = []
    if disks:
        nodes = rng.choice(np.arange(1, n_el), int(rng.integers(1, 6)), replace=False)
        for n in sorted(int(x) for x in nodes):
            m = float(rng.uniform(2, 60))
            ip = m * float(rng.uniform(0.08, 0.3)) ** 2 / 2
            out_disks.append({"node": n, "mass": m, "polar_inertia": ip,
                              "transverse_inertia": ip / 2 * float(rng.uniform(1.0, 1.2))})

    edge = max(1, int(0.05 * n_el))
    nodes = [int(rng.integers(0, edge + 1)), int(rng.integers(n_el - edge, n_el + 1))]
    if bearings == 3:
        nodes.insert(1, int(rng.integers(n_el // 4, 3 * n_el // 4)))
    k_range = (10**7.5, 1e9) if stiff else (1e6, 10**7.5)
    c_range = (10**3.5, 1e5) if heavy else (1e2, 10**3.5)
    supports = []
    for n in nodes:
        k, c = _log_uniform(rng, *k_range), _log_uniform(rng, *c_range)
        co = {"kxx": k, "kyy": k, "cxx": c, "cyy": c}
        if anisotropic:
            co.update(kyy=k * float(rng.uniform(0.5, 2)), cyy=c * float(rng.uniform(0.5, 2)),
                      kxy=k * float(rng.uniform(-0.5, 0.5)), kyx=k * float(rng.uniform(-0.5, 0.5)),
                      cxy=c * float(rng.uniform(-0.2, 0.2)), cyx=c * float(rng.uniform(-0.2, 0.2)))
        supports.append(support(n, **co))

    return {"type": "beam", "materials": {"steel": dict(STEEL)}, "shaft": shaft,
            "disks": out_disks, "supports": supports}


# the six written rotors: every combination of interest at least once
WRITTEN = [
    dict(seed=101, disks=True, stiff=True, heavy=False, anisotropic=False, bearings=2),
    dict(seed=202, disks=False, stiff=False, heavy=True, anisotropic=True, bearings=2),
    dict(seed=303, disks=True, stiff=False, heavy=False, anisotropic=True, bearings=2),
    dict(seed=404, disks=False, stiff=True, heavy=True, anisotropic=False, bearings=2),
    dict(seed=505, disks=True, stiff=None, heavy=None, anisotropic=True, bearings=3),
    dict(seed=606, disks=True, stiff=None, heavy=None, anisotropic=False, bearings=None),
]


def main():
    out = HERE / "heldout"
    out.mkdir(exist_ok=True)
    for i, kw in enumerate(WRITTEN, 1):
        rotor = heldout_rotor(**kw)
        ross_rotor(rotor)  # builds in ROSS (sanity)
        path = out / f"rotor_{i}.json"
        path.write_text(json.dumps(rotor, indent=1) + "\n")
        n_el = sum(s["elements"] for s in rotor["shaft"])
        print(f"{path.name}: {n_el} elements, {len(rotor['disks'])} disks, "
              f"{len(rotor['supports'])} supports, options {kw}")


if __name__ == "__main__":
    main()
