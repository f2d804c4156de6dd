#!/usr/bin/env python3
"""ROSS 2.3.0's `run_level1` and ross-report 0.0.1's API 684 unbalance rules, as references
for tests/it/audit_ross_report.rs. Writes api_rules.json beside this file.

Rerun from the repository root (ROSS as in generate.py; ross-report needs `black` too):

    pip install "ross-rotordynamics==2.3.0" "plotly<7" ross-report==0.0.1 black
    OMP_NUM_THREADS=1 python3 tests/data/ross/api_rules.py

* Level I: `rotor.run_level1(n=node, stiffness_range=(0, q_max), num=5)` with `rated_w` set to
  the speed: the log decrement of the first non-backward mode of `run_modal` with a bearing
  `kxy = Q, kyx = -Q` added at `node`, Q = linspace(0, q_max, 5) (given as values: with the
  default range ROSS takes linspace(k - 3, k + 3) of the exponent k and uses the exponents
  themselves as N/m). Each chosen mode's damped frequency is stored to check it is the first
  forward lateral mode.
* ross-report: `Report(rotor, config)._unbalance_forces(mode)` (kg m) with the maximum
  continuous speed in rpm, and `_static_forces()` (kgf, its g = 9.8065). Its rules: rotor type
  from the disks' positions relative to the bearings; between bearings `2 max(6350e-6 W / N,
  254e-6 W)` with W the sum of the bearing loads; overhung `2 x 6350e-6 W3 / N` with W3 the
  disks and shaft elements outboard; and `N < 25.000` decides whether N or 25,000 rpm is used.
"""

import json
import sys
import warnings
from pathlib import Path

import numpy as np

warnings.filterwarnings("ignore")
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import generate as g  # noqa: E402
import ross as rs  # noqa: E402
from report.analysis import Report  # noqa: E402
from report.config import Config  # noqa: E402


def shaft_rotor(supports, disks, elements=10):
    return {
        "type": "beam",
        "materials": {"steel": dict(g.STEEL)},
        "shaft": [{"length": 1.5, "outer_diameter": 0.05, "inner_diameter": 0.0,
                   "material": "steel", "elements": elements}],
        "disks": disks,
        "supports": supports,
    }


DISK = {"mass": 32.6, "polar_inertia": 0.32, "transverse_inertia": 0.17}
LIGHT = {"mass": 12.0, "polar_inertia": 0.08, "transverse_inertia": 0.05}

CASES = {
    "between_bearings": shaft_rotor(
        [g.support(1, kxx=2e7, kyy=3e7, cxx=2e3, cyy=2e3), g.support(9, kxx=2e7, kyy=3e7, cxx=2e3, cyy=2e3)],
        [{"node": 5, **DISK}]),
    "single_overhung_r": shaft_rotor(
        [g.support(0, kxx=5e7, kyy=5e7, cxx=1e3, cyy=1e3), g.support(7, kxx=5e7, kyy=5e7, cxx=1e3, cyy=1e3)],
        [{"node": 4, **LIGHT}, {"node": 10, **DISK}]),
    "double_overhung": shaft_rotor(
        [g.support(2, kxx=5e7, kyy=5e7, cxx=1e3, cyy=1e3), g.support(8, kxx=5e7, kyy=5e7, cxx=1e3, cyy=1e3)],
        [{"node": 0, **LIGHT}, {"node": 10, **DISK}]),
}
RPM = 9000.0


def report(rotor):
    config = Config()
    config.update_config(rotor_properties={
        "rotor_speeds": {"min_speed": 0.7 * RPM, "max_speed": RPM, "oper_speed": 0.9 * RPM,
                         "trip_speed": 1.05 * RPM, "unit": "rpm"},
        "rotor_id": {"type": "compressor"}})
    return Report(g.ross_rotor(rotor), config)


def level1(rotor, node, speed, q_max):
    r = g.ross_rotor(rotor)
    r.rated_w = speed
    res = r.run_level1(n=node, stiffness_range=(0.0, q_max), num=5)
    # The mode each point took, for the check.
    chosen = []
    for q in res.stiffness_range:
        brg = [b for b in r.bearing_elements] + [
            rs.BearingElement(n=node, kxx=0, cxx=0, kxy=q, kyx=-q)]
        m = rs.Rotor(r.shaft_elements, r.disk_elements, brg).run_modal(speed=speed)
        fwd = m.whirl_direction() != "Backward"
        chosen.append({"wd": float(m.wd[fwd][0]), "log_dec": float(m.log_dec[fwd][0]),
                       "whirl": str(m.whirl_direction()[fwd][0])})
    return {"node": node, "speed": speed, "cross_coupling": [float(q) for q in res.stiffness_range],
            "log_decrement": [float(v) for v in res.log_dec], "modes": chosen}


def main():
    out = {"ross_version": rs.__version__, "rpm": RPM, "cases": {}}
    for name, rotor in CASES.items():
        rep = report(rotor)
        assert rep.rotor_type == name, (name, rep.rotor_type)
        out["cases"][name] = {
            "rotor": rotor,
            "rotor_type": rep.rotor_type,
            "static_forces_kgf": [float(f) for f in rep._static_forces()],
            "unbalance_forces": {str(m): [float(f) for f in np.atleast_1d(rep._unbalance_forces(m))]
                                 for m in (0, 2)},
        }
    out["level1"] = [
        {"case": "between_bearings", **level1(CASES["between_bearings"], 5, 600.0, 4e6)},
        {"case": "single_overhung_r", **level1(CASES["single_overhung_r"], 10, 500.0, 2e6)},
    ]
    path = HERE / "api_rules.json"
    path.write_text(json.dumps(out, indent=1) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
