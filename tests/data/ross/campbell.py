#!/usr/bin/env python3
"""ROSS 2.3.0 references for Campbell diagrams, critical speeds and seals (tests/it/campbell_ross.rs).

Rerun (from the repository root, ~10 min on one core; the venv as in generate.py):

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python tests/data/ross/campbell.py

writes tests/data/ross/campbell.json: {"ross_version", "cases": [...]}. Each case:

* "rotor": the Whirl beam rotor (seals under "seals", ROSS SealElements); "speeds" (rad/s),
  "bound" (the request's max_frequency);
* "points": ROSS's lateral Campbell points at each speed: every eigenvalue s of the 4-dof/node
  lateral state matrix (generate.poles: the matrices of rotor.A, checked there) with
  0 < Im s <= bound, i.e. each mode once as run_campbell's modal.wd lists it, [re, im];
* "criticals": {"exact": every crossing Im s_i(W) = W of the i-th lowest positive frequency
  with the 1x line within the speeds, by brentq (xtol 1e-13 relative) on the same dense lateral
  model, [speed, re, im] of the pole there; "ross": ROSS's run_critical_speed(num_modes, rtol=1e-10), its wd part
  run index by index (see ross_criticals; "ross_failed_indices": where its Newton iteration
  fails), with whirl_direction and log_dec there, only the lateral ones inside the speeds (a ROSS critical is
  lateral when the lateral model has a pole with Im s = W there to 1e-6), only for constant
  supports (with tables ROSS interpolates by its own spline, see README)};
* seal cases also "ucs" (rotor.run_ucs(): stiffness, 4 frequencies each; seals left out by
  ROSS) and "static" (rotor.run_static(): deformation_y, bearing reactions by node).

Tabulated supports are evaluated with Whirl's rule (numpy.interp, end values held) on frozen
rotors (generate.rotor_at), as in generate.py.
"""

import json
import sys
import warnings
from pathlib import Path

import numpy as np
import scipy.linalg as sla
from scipy.optimize import brentq

warnings.filterwarnings("ignore")
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import generate as g  # noqa: E402
import ross as rs  # noqa: E402

COEFFS = g.COEFFS


def whirl_rotor(rotor, speed=None):
    """generate.ross_rotor plus the rotor's seals as SealElements (frozen at `speed`)."""
    r = g.rotor_at(rotor, speed) if speed is not None else g.ross_rotor(rotor)
    seals = rotor.get("seals", [])
    if not seals:
        return r
    at = 0.0 if speed is None else speed
    extra = [rs.SealElement(n=s["node"], **{k: g.coefficient_at(s, k, at) for k in COEFFS})
             for s in seals]
    return rs.Rotor(r.shaft_elements, r.disk_elements, r.bearing_elements + extra)


def lateral_poles(rotor, w):
    r = whirl_rotor(rotor, w if g.has_tables(rotor) else None)
    A = g.state_matrix(*g.lateral_matrices(r, w), w)
    return sla.eigvals(A)


def positive(ev, bound=np.inf):
    ev = [z for z in ev if 0 < z.imag <= bound]
    return sorted(ev, key=lambda z: z.imag)


def exact_criticals(rotor, speeds, count):
    """Crossings of the i-th lowest positive frequency with the 1x line, i < count."""
    grid = np.array(speeds)
    freqs = [positive(lateral_poles(rotor, w))[:count] for w in grid]
    out = []
    for i in range(count):
        f = lambda w: positive(lateral_poles(rotor, w))[i].imag - w  # noqa: E731
        vals = [fr[i].imag - w for fr, w in zip(freqs, grid)]
        for k in range(len(grid) - 1):
            if vals[k] == 0.0 and grid[k] > 0:
                out.append(grid[k])
            elif vals[k] * vals[k + 1] < 0:
                out.append(brentq(f, grid[k], grid[k + 1], xtol=1e-13 * grid[k + 1], rtol=1e-14))
    res = []
    for w in sorted(out):
        ev = positive(lateral_poles(rotor, w))
        z = min(ev, key=lambda z: abs(z.imag - w))
        res.append([float(w), float(z.real), float(z.imag)])
    return res


def ross_criticals(rotor, speeds, bound, num_modes):
    """ROSS's run_critical_speed(rtol=1e-10), its wd part exactly as rotor_assembly.py:962-974
    does it (newton on s - run_modal(s, num_modes).wd[i] from the i-th wd at rest), one mode
    index at a time so that an index whose Newton iteration fails (ROSS raises for the whole
    call) is recorded as such; only indices starting below `bound`."""
    from scipy.optimize import newton
    r = whirl_rotor(rotor)
    modal = r.run_modal(0, num_modes)
    out, failed = [], []
    for i, wd0 in enumerate(modal.wd):
        if wd0 > bound:
            continue
        try:
            wd = newton(func=lambda s: s - r.run_modal(s, num_modes).wd[i], x0=wd0, rtol=1e-10)
        except RuntimeError:
            failed.append(i)
            continue
        if not (speeds[0] < wd <= speeds[-1]):
            continue
        ev = positive(lateral_poles(rotor, wd))
        if not ev or min(abs(z.imag - wd) for z in ev) > 1e-6 * wd:
            continue  # axial or torsional
        m = r.run_modal(wd, num_modes)
        out.append({"speed": float(wd), "whirl": str(m.whirl_direction()[i]),
                    "log_dec": float(m.log_dec[i]), "index": i})
    return sorted(out, key=lambda x: x["speed"]), failed


def case(name, rotor, speeds, bound, ross=True, seal=False):
    print(name, flush=True)
    points = [{"speed": float(w), "poles": [g.cplx(z) for z in positive(lateral_poles(rotor, w), bound)]}
              for w in speeds]
    count = max(len(positive(lateral_poles(rotor, w), 1.3 * speeds[-1])) for w in (speeds[0], speeds[-1])) + 2
    crit = {"exact": exact_criticals(rotor, speeds, count)}
    if ross and not g.has_tables(rotor):
        crit["ross"], crit["ross_failed_indices"] = ross_criticals(rotor, speeds, bound, 2 * count + 8)
    out = {"name": name, "rotor": rotor, "speeds": [float(w) for w in speeds], "bound": bound,
           "points": points, "criticals": crit}
    if seal:
        r = whirl_rotor(rotor)
        u = r.run_ucs()
        out["ucs"] = {"stiffness": [float(k) for k in u.stiffness_log],
                      "frequencies": [[float(f) for f in row] for row in u.wn]}
        s = r.run_static()
        out["static"] = {"deformation_y": [float(v) for v in s.deformation],
                         "bearing_forces": {k: float(v) for k, v in s.bearing_forces.items()}}
    return out


def main():
    cases = []
    speeds = list(np.linspace(0, 3000, 21))
    for i in range(1, 7):
        rotor = json.loads((HERE / "heldout" / f"rotor_{i}.json").read_text())
        cases.append(case(f"heldout_{i}", rotor, speeds, 3500.0))
    # The rotor: 12 elements, kxx = 2 kyy, no cross-coupling.
    aniso = {"type": "beam", "materials": {"steel": g.STEEL},
             "shaft": [{"length": 1.2, "outer_diameter": 0.05, "inner_diameter": 0.0,
                        "material": "steel", "elements": 12}],
             "disks": [{"node": 6, "mass": 20.0, "polar_inertia": 0.2, "transverse_inertia": 0.1}],
             "supports": [g.support(0, kxx=4e6, kyy=2e6, cxx=500, cyy=500),
                          g.support(12, kxx=4e6, kyy=2e6, cxx=500, cyy=500)]}
    cases.append(case("aniso_12", aniso, list(np.linspace(0, 1500, 31)), 1500.0))
    # Tabulated, cross-coupled (rotor A of generate.py with case C's tables).
    tab = g.rotor_a([
        g.support(0, speeds=[200, 600, 1000, 1500, 2500], kxx=[1e6, 1.3e6, 1.7e6, 2.2e6, 3e6],
                  kxy=[3e5, 6e5, 9e5, 1.3e6, 2e6], kyx=[-5e5, -8e5, -1.1e6, -1.5e6, -2.2e6],
                  kyy=[2e6, 2.3e6, 2.8e6, 3.4e6, 4.5e6], cxx=[800, 700, 600, 500, 400],
                  cxy=[60, 50, 40, 30, 20], cyx=[-40, -30, -20, -10, -5], cyy=[900, 800, 700, 600, 500]),
        g.support(10, speeds=[200, 600, 1000, 1500, 2500], kxx=[1.5e6, 1.8e6, 2.1e6, 2.6e6, 3.2e6],
                  kxy=[1e5, 2e5, 4e5, 6e5, 9e5], kyx=[-2e5, -3e5, -5e5, -7e5, -1e6],
                  kyy=[1.2e6, 1.5e6, 1.9e6, 2.4e6, 3e6], cxx=[500, 450, 400, 350, 300],
                  cxy=[10, 10, 10, 10, 10], cyx=[-10, -10, -10, -10, -10], cyy=[600, 550, 500, 450, 400]),
    ])
    cases.append(case("tabulated", tab, list(np.linspace(0, 3000, 31)), 3500.0))
    # Seal: rotor A's bearings and a cross-coupled seal at node 7 (case D of generate.py).
    seal = g.rotor_a()
    seal["seals"] = [g.support(7, kxx=4e5, kyy=4e5, kxy=2.5e5, kyx=-2.5e5, cxx=1.5e3, cyy=1.5e3,
                               cxy=300, cyx=-300)]
    cases.append(case("seal", seal, list(np.linspace(0, 3000, 21)), 3500.0, seal=True))
    out = {"ross_version": rs.__version__, "cases": cases}
    (HERE / "campbell.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
