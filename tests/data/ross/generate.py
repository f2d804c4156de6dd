#!/usr/bin/env python3
"""Reference data from ROSS 2.3.0 for Whirl's general (anisotropic, speed-dependent) supports.

Rerun (from the repository root, ~1-2 min on one core):

    python3 -m venv .venv && .venv/bin/pip install "ross-rotordynamics==2.3.0" "plotly<7" scipy numpy
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python tests/data/ross/generate.py

It rewrites every JSON file in tests/data/ross/ (no randomness; floats are written at full
precision, nothing is rounded; LAPACK/OpenBLAS results can differ between runs in the last bits,
observed up to 1e-14 of the largest eigenvalue, so compare with a tolerance). heldout.py, in the
same folder, writes heldout/*.json.

Conventions (all checked by this script, see each file's "checks")
-----------------------------------------------------------------
* Units SI, speeds and frequencies in rad/s. Each file's "rotor" is a Whirl beam rotor; every
  reference is computed on the ROSS rotor rebuilt from that JSON by `ross_rotor()` below
  (Timoshenko ShaftElement with shear, rotary inertia and gyroscopics on, Cowper shear factor,
  Material(rho, E, Poisson); DiskElement(n, m, Id, Ip); BearingElement with the 12 coefficients).
* ROSS equation of motion: M q'' + (C(W) + W G) q' + K(W) q = F, W = spin speed, per node
  q = [x, y, z, alpha, beta, theta]; a bearing's K = [[kxx, kxy], [kyx, kyy]] is ADDED to the
  global K on (x, y) (same for C and M), i.e. force on the shaft f = -K[x,y] - C[x',y'] - M[x'',y''].
  Lateral = x, y, alpha, beta (ross.utils.remove_dofs drops z and theta; they are decoupled).
* Poles: all eigenvalues s of A = [[0, I], [-M^-1 K, -M^-1 (C + W G)]] built from the 4-dof/node
  matrices (scipy.linalg.eig), q = q0 e^{st}, s = sigma + i omega, stored [re, im] sorted by
  (im, re). Compare as sets (match nearest): near-equal imaginary parts may swap order.
  checks.state_matrix: this A equals the lateral block of ROSS's own rotor.A(W);
  checks.run_modal: every pole is in rotor.run_modal(W, sparse=False).evalues.
* Unbalance: ROSS rotor.run_unbalance_response(node, amount, phase, frequency=speeds). The force is
  F_x = amount W^2 e^{i phase}, F_y = -i amount W^2 e^{i phase} (rotor_assembly.py 2068-2070),
  i.e. f_x(t) = amount W^2 cos(W t + phase), f_y(t) = amount W^2 sin(W t + phase): the spin and
  forward whirl go from +x towards +y. Responses are complex amplitudes X with
  x(t) = Re(X e^{i W t}) (so x_amp = |X|, x_phase = arg X), stored [re, im];
  H = (K - W^2 M + i W (C + W G))^-1 with every coefficient evaluated at W.
  checks.unbalance: the same from a 4-dof solve here.
* Speed-dependent supports: ROSS's BearingElement interpolates a table with
  scipy.interpolate.UnivariateSpline(frequency, values) (cubic SMOOTHING spline, s = len(table),
  extrapolating; bearing_seal_element.py 260-266), not linearly and without holding the end values.
  Whirl interpolates linearly and holds the end values. So every reference for a tabulated
  support is computed on a ROSS rotor whose supports are CONSTANT BearingElements carrying
  numpy.interp(W, speeds, values) (= Whirl's rule), rebuilt for each speed ("frozen");
  "ross_native" blocks show what ROSS's own spline gives, for information only.

Cases
-----
A aniso.json           10 x 0.15 m, 50 mm steel shaft, disk at node 5, two different
                       anisotropic bearings with cross-coupled k and c (nodes 0, 10). Poles at
                       [0, 300, 800, 1500, 3000]; unbalance 1e-4 kg m at node 5, phase 0, 30
                       speeds, X and Y at nodes 0, 5, 10.
B aniso_mass.json      A with mass coefficients (mxx, mxy, myx, myy) on the node-10 bearing; poles
                       at [0, 800, 2000].
C speed_dependent.json A's rotor with both bearings tabulated (all 8 k and c) at
                       [200, 600, 1000, 1500, 2500]; poles and unbalance (as A) at the table
                       speeds, the midpoints, 100 (below) and 3000 (above), frozen as above.
D seal.json            A plus a skew cross-coupled seal at node 7 (kxx = kyy, kxy = -kyx,
                       cxx = cyy, cxy = -cyx); poles at [0, 1000, 2500]. Also the same with
                       isotropic bearings ("isotropic"), a fully isotropic system.
E rotor_example.json   rs.rotor_example() mapped exactly (6 elements, 2 disks, 2 bearings
                       kxx = 1e6, kyy = 0.8e6, no damping); poles at [0, 250, 500, 1000] and
                       unbalance 1e-3 kg m at node 3, phase 0.7 rad.
  compressor_example.json
                       rs.compressor_example() does NOT map exactly (concentric "sleeve" shaft
                       elements, see README); "rotor" is a mapped variant (steel core exactly,
                       each sleeve lumped as two disks), all 14 tabulated supports kept; poles
                       and unbalance on that variant, and the first forward mode's log
                       decrement at 10,000 rpm, real vs averaged supports, for the original
                       and for the variant.
F ucs.json             rotor.run_ucs() on rotor A and on rotor_example: ROSS's arrays and
                       intersections, plus an independent check.
G static.json          rotor.run_static() on rotor_example and on rotor A: deformation, shear
                       force, bending moment, bearing reactions, plus an independent check.
"""

import json
import math
import os
import sys
import warnings
from collections import defaultdict
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import scipy.linalg as sla

warnings.filterwarnings("ignore")
import ross as rs  # noqa: E402
from ross.bearing_seal_element import SealElement  # noqa: E402
from ross.utils import intersection, remove_dofs  # noqa: E402

HERE = Path(__file__).resolve().parent
COEFFS = ["kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "mxx", "mxy", "myx", "myy"]
ROSS_VERSION = rs.__version__

STEEL = {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3, "loss_factor": 0.0}


# --------------------------------------------------------------------------- Whirl JSON helpers

def support(node, speeds=None, **coeffs):
    """A Whirl general support; missing coefficients are 0."""
    out = {"node": node}
    for k in COEFFS:
        v = coeffs.pop(k, 0.0)
        out[k] = [float(x) for x in v] if isinstance(v, (list, tuple, np.ndarray)) else float(v)
    assert not coeffs, coeffs
    out["speeds"] = None if speeds is None else [float(x) for x in speeds]
    return out


def cplx(z):
    return [float(np.real(z)), float(np.imag(z))]


def coefficient_at(sup, name, speed):
    """Whirl's rule: linear in spin speed between table speeds, end values held outside."""
    v = sup.get(name, 0.0)
    if isinstance(v, list):
        return float(np.interp(speed, sup["speeds"], v))
    return float(v)


# --------------------------------------------------------------------------- Whirl -> ROSS

def ross_support(sup, speed=None):
    """BearingElement for a Whirl support.

    Constant support: constant element. Tabulated support: with `speed`, a constant element
    carrying Whirl's interpolated values at that speed ("frozen"); without, ROSS's own tabulated
    element (frequency=speeds, UnivariateSpline interpolation) ("native").
    """
    n = sup["node"]
    if sup.get("speeds") is None or speed is not None:
        at = 0.0 if speed is None else speed
        c = {k: coefficient_at(sup, k, at) for k in COEFFS}
        return rs.BearingElement(n=n, **c)
    table = [float(x) for x in sup["speeds"]]
    c = {}
    for k in COEFFS:
        v = sup.get(k, 0.0)
        c[k] = [float(x) for x in v] if isinstance(v, list) else [float(v)] * len(table)
    return rs.BearingElement(n=n, frequency=table, **c)


def ross_rotor(rotor, speed=None):
    """The ROSS rotor of a Whirl beam rotor (see ross_support for `speed`)."""
    mats = {name: rs.Material(name=f"whirl_{name}", rho=m["density"], E=m["young_modulus"],
                              Poisson=m["poisson_ratio"])
            for name, m in rotor["materials"].items()}
    shaft = []
    for seg in rotor["shaft"]:
        count = seg.get("elements", 1)
        for _ in range(count):
            shaft.append(rs.ShaftElement(L=seg["length"] / count, idl=seg.get("inner_diameter", 0.0),
                                         odl=seg["outer_diameter"], material=mats[seg["material"]],
                                         shear_effects=True, rotary_inertia=True, gyroscopic=True))
    disks = [rs.DiskElement(n=d["node"], m=d["mass"], Id=d["transverse_inertia"], Ip=d["polar_inertia"])
             for d in rotor.get("disks", [])]
    bearings = [ross_support(s, speed) for s in rotor["supports"]]
    return rs.Rotor(shaft, disks, bearings)


def has_tables(rotor):
    return any(s.get("speeds") is not None for s in rotor["supports"])


def rotor_at(rotor, speed):
    """ROSS rotor for references at `speed` (frozen supports if any is tabulated)."""
    return ross_rotor(rotor, speed if has_tables(rotor) else None)


# --------------------------------------------------------------------------- ROSS -> numbers

def lateral_matrices(r, speed):
    return (remove_dofs(r.M(speed)), remove_dofs(r.K(speed)), remove_dofs(r.C(speed)),
            remove_dofs(r.G()))


def state_matrix(M, K, C, G, speed):
    n = len(M)
    return np.block([[np.zeros((n, n)), np.eye(n)],
                     [-sla.solve(M, K), -sla.solve(M, C + speed * G)]])


def lateral_index(r):
    lat = [i for i in range(r.ndof) if i % 6 not in (2, 5)]
    return lat + [r.ndof + i for i in lat]


def poles(r, speed, check=True):
    """All lateral eigenvalues, sorted by (imag, real); plus the two checks."""
    A = state_matrix(*lateral_matrices(r, speed), speed)
    ev = sla.eigvals(A)
    ev = np.array(sorted(ev, key=lambda z: (z.imag, z.real)))
    out = {"speed": float(speed), "eigenvalues": [cplx(z) for z in ev]}
    if check:
        keep = lateral_index(r)
        A6 = r.A(speed)[np.ix_(keep, keep)]
        ev6 = r.run_modal(speed, sparse=False).evalues
        miss = max(np.min(np.abs(ev6 - z)) / max(abs(z), 1.0) for z in ev)
        out["_check"] = {"state_matrix": float(np.max(np.abs(A6 - A)) / np.max(np.abs(A))),
                         "run_modal": float(miss)}
    return out


def pole_table(rotor, speeds):
    """Poles at each speed (frozen supports if tabulated) and the worst checks."""
    table, worst = [], {"state_matrix": 0.0, "run_modal": 0.0}
    for w in speeds:
        p = poles(rotor_at(rotor, w), w)
        for k, v in p.pop("_check").items():
            worst[k] = max(worst[k], v)
        table.append(p)
    return table, worst


def own_unbalance(r, speed, node, amount, phase, nodes):
    M, K, C, G = lateral_matrices(r, speed)
    F = np.zeros(len(M), complex)
    F[4 * node] = amount * speed**2 * np.exp(1j * phase)
    F[4 * node + 1] = -1j * amount * speed**2 * np.exp(1j * phase)
    X = sla.solve(K - speed**2 * M + 1j * speed * (C + speed * G), F)
    return {n: (X[4 * n], X[4 * n + 1]) for n in nodes}


def unbalance(rotor, node, amount, phase, speeds, nodes):
    """ROSS run_unbalance_response; one call over all speeds (constant supports) or one per speed
    on the frozen rotor (tabulated supports)."""
    res = {n: {"x": [], "y": []} for n in nodes}
    worst = 0.0
    groups = [(rotor_at(rotor, w), [w]) for w in speeds] if has_tables(rotor) else \
        [(ross_rotor(rotor), list(speeds))]
    for r, ws in groups:
        resp = r.run_unbalance_response(node=node, unbalance_magnitude=amount, unbalance_phase=phase,
                                        frequency=np.array(ws, dtype=float))
        fr = resp.forced_resp
        for i, w in enumerate(ws):
            own = own_unbalance(r, w, node, amount, phase, nodes)
            for n in nodes:
                x, y = fr[6 * n, i], fr[6 * n + 1, i]
                res[n]["x"].append(cplx(x))
                res[n]["y"].append(cplx(y))
                scale = max(abs(x), abs(y), 1e-300)
                worst = max(worst, abs(x - own[n][0]) / scale, abs(y - own[n][1]) / scale)
    call = (f"rotor.run_unbalance_response(node={node}, unbalance_magnitude={amount!r}, "
            f"unbalance_phase={phase!r}, frequency=speeds)")
    if has_tables(rotor):
        call += " on the frozen rotor of each speed, frequency=[speed]"
    out = {"call": call, "unbalances": [{"node": node, "amount": amount, "phase": phase}],
           "speeds": [float(w) for w in speeds],
           "nodes": [{"node": n, "x": res[n]["x"], "y": res[n]["y"]} for n in nodes]}
    return out, worst


def forward_modes(r, speed, count=3):
    """ROSS's own view: run_modal(speed) (ARPACK, 12 modes) with its whirl classification."""
    m = r.run_modal(speed)
    wdir = list(m.whirl_direction())
    out = []
    for i, d in enumerate(wdir):
        if d == "Forward":
            out.append({"index": i, "eigenvalue": cplx(m.evalues[i]), "wd": float(m.wd[i]),
                        "log_dec": float(m.log_dec[i])})
    return out[:count], [str(d) for d in wdir]


def write(name, data):
    path = HERE / name
    path.write_text(json.dumps(data, indent=1) + "\n")
    size = path.stat().st_size
    print(f"wrote {path.relative_to(HERE.parent.parent.parent)} ({size / 1024:.0f} kB)")
    assert size < 300 * 1024, name


COMMON = {
    "ross_version": ROSS_VERSION,
    "conventions": (
        "SI, rad/s. Poles: eigenvalues s = sigma + i omega of q = q0 e^{st} of the lateral "
        "(x, y, alpha, beta per node) first-order system A = [[0, I], [-M^-1 K, -M^-1 (C + W G)]], "
        "[re, im], sorted by (im, re): compare as sets. Unbalance: complex amplitudes X, Y with "
        "x(t) = Re(X e^{i W t}), [re, im]; unbalance force f_x = a W^2 cos(W t + phase), "
        "f_y = a W^2 sin(W t + phase). Supports: f = -K[x,y] - C[x',y'] - M[x'',y''], "
        "K = [[kxx, kxy], [kyx, kyy]]; tabulated coefficients: linear in W, held outside the table "
        "(references computed that way, see generate.py)."),
    "poles_call": (
        "scipy.linalg.eigvals(A), A = [[0, I], [-solve(M, K), -solve(M, C + W G)]] with "
        "M, K, C, G = ross.utils.remove_dofs of rotor.M(W), rotor.K(W), rotor.C(W), rotor.G(); "
        "rotor = generate.ross_rotor(file's rotor) (tabulated supports: ross_rotor(rotor, W), "
        "frozen); checked against rotor.A(W) and rotor.run_modal(W, sparse=False).evalues"),
}


# --------------------------------------------------------------------------- the rotors

def rotor_a(supports=None):
    return {
        "type": "beam",
        "materials": {"steel": dict(STEEL)},
        "shaft": [{"length": 1.5, "outer_diameter": 0.05, "inner_diameter": 0.0, "material": "steel",
                   "elements": 10}],
        "disks": [{"node": 5, "mass": 32.6, "polar_inertia": 0.32, "transverse_inertia": 0.17}],
        "supports": supports if supports is not None else A_BEARINGS,
    }


A_BEARINGS = [
    support(0, kxx=1.0e6, kxy=5.0e5, kyx=-8.0e5, kyy=2.0e6, cxx=3.0e3, cxy=4.0e2, cyx=6.0e2, cyy=4.5e3),
    support(10, kxx=1.2e6, kxy=6.0e5, kyx=-9.0e5, kyy=2.4e6, cxx=3.5e3, cxy=5.0e2, cyx=7.0e2, cyy=5.0e3),
]

A_SPEEDS = [0.0, 300.0, 800.0, 1500.0, 3000.0]
A_UNBALANCE_SPEEDS = [0.0, 50.0, 100.0, 110.0, 116.0, 120.0, 122.0, 124.0, 125.0, 126.0, 127.0,
                      128.0, 129.0, 130.0, 131.0, 133.0, 136.0, 140.0, 150.0, 175.0, 200.0, 300.0,
                      450.0, 600.0, 700.0, 800.0, 1000.0, 1500.0, 2000.0, 3000.0]


def case_a():
    rotor = rotor_a()
    table, checks = pole_table(rotor, A_SPEEDS)
    unb, worst = unbalance(rotor, 5, 1e-4, 0.0, A_UNBALANCE_SPEEDS, [0, 5, 10])
    checks["unbalance"] = worst
    write("aniso.json", {
        "case": "A", **COMMON,
        "description": "10-element steel shaft, disk at node 5, two different anisotropic "
                       "bearings with cross-coupled stiffness and damping at nodes 0 and 10.",
        "rotor": rotor, "speeds": A_SPEEDS, "poles": table, "unbalance_response": unb, "checks": checks})


def case_b():
    sup = [dict(A_BEARINGS[0]), dict(A_BEARINGS[1])]
    sup[1].update({"mxx": 2.0, "mxy": 0.5, "myx": -0.3, "myy": 3.0})
    rotor = rotor_a(sup)
    speeds = [0.0, 800.0, 2000.0]
    table, checks = pole_table(rotor, speeds)
    write("aniso_mass.json", {
        "case": "B", **COMMON,
        "description": "Case A with mass coefficients on the node-10 bearing (mxx=2, mxy=0.5, "
                       "myx=-0.3, myy=3 kg): the bearing M is added to the global M.",
        "rotor": rotor, "speeds": speeds, "poles": table, "checks": checks})


C_TABLE = [200.0, 600.0, 1000.0, 1500.0, 2500.0]
C_BEARINGS = [
    support(0, speeds=C_TABLE,
            kxx=[1.0e6, 1.3e6, 1.7e6, 2.2e6, 3.0e6], kxy=[3.0e5, 6.0e5, 9.0e5, 1.3e6, 2.0e6],
            kyx=[-5.0e5, -8.0e5, -1.1e6, -1.5e6, -2.2e6], kyy=[2.0e6, 2.3e6, 2.8e6, 3.4e6, 4.5e6],
            cxx=[4.0e3, 3.5e3, 3.1e3, 2.8e3, 2.4e3], cxy=[3.0e2, 4.0e2, 4.5e2, 5.0e2, 6.0e2],
            cyx=[5.0e2, 6.0e2, 7.0e2, 7.5e2, 8.0e2], cyy=[6.0e3, 5.2e3, 4.6e3, 4.1e3, 3.5e3]),
    support(10, speeds=C_TABLE,
            kxx=[1.5e6, 1.6e6, 2.0e6, 2.9e6, 3.1e6], kxy=[2.0e5, 7.0e5, 8.0e5, 1.6e6, 1.7e6],
            kyx=[-4.0e5, -9.0e5, -1.0e6, -1.2e6, -2.6e6], kyy=[2.5e6, 2.6e6, 3.3e6, 3.6e6, 5.0e6],
            cxx=[5.0e3, 3.0e3, 2.9e3, 2.5e3, 2.45e3], cxy=[1.0e2, 5.0e2, 4.0e2, 6.0e2, 6.5e2],
            cyx=[7.0e2, 5.5e2, 8.0e2, 7.0e2, 9.0e2], cyy=[7.0e3, 5.0e3, 4.8e3, 3.9e3, 3.0e3]),
]


def case_c():
    rotor = rotor_a(C_BEARINGS)
    mids = [(a + b) / 2 for a, b in zip(C_TABLE, C_TABLE[1:])]
    speeds = sorted([100.0] + C_TABLE + mids + [3000.0])
    kinds = {w: ("table" if w in C_TABLE else "below" if w < C_TABLE[0] else
                 "above" if w > C_TABLE[-1] else "midpoint") for w in speeds}
    table, checks = pole_table(rotor, speeds)
    unb, worst = unbalance(rotor, 5, 1e-4, 0.0, speeds, [0, 5, 10])
    checks["unbalance"] = worst
    # what ROSS's own tabulated element does (information only)
    native = ross_rotor(rotor)
    coeff_native = []
    for s, b in zip(rotor["supports"], native.bearing_elements):
        rows = {}
        for k in COEFFS[:8]:
            f = getattr(b, f"{k}_interpolated")
            rows[k] = {"ross_spline": [float(f(w)) for w in speeds],
                       "whirl_linear": [coefficient_at(s, k, w) for w in speeds]}
        coeff_native.append({"node": s["node"], "coefficients": rows})
    pole_diff = []
    for w, ref in zip(speeds, table):
        A = state_matrix(*lateral_matrices(native, w), w)
        ev = sla.eigvals(A)
        refz = np.array([complex(*z) for z in ref["eigenvalues"]])
        pole_diff.append(float(max(np.min(np.abs(ev - z)) / abs(z) for z in refz if abs(z) > 1)))
    write("speed_dependent.json", {
        "case": "C", **COMMON,
        "description": "Case A's rotor with both bearings tabulated over 5 speeds (all 8 k and c "
                       "coefficients). References use Whirl's rule (linear, held at the ends): each "
                       "speed's ROSS rotor carries constant BearingElements with numpy.interp(W, "
                       "speeds, values). ROSS itself would use a cubic smoothing spline that "
                       "extrapolates: see ross_native.",
        "rotor": rotor, "table_speeds": C_TABLE, "speeds": speeds,
        "speed_kind": [kinds[w] for w in speeds],
        "poles": table, "unbalance_response": unb, "checks": checks,
        "ross_native": {
            "interpolation": "scipy.interpolate.UnivariateSpline(frequency, coefficient) with default "
                             "k=3, s=len(frequency), ext=0 (extrapolate): ross/bearing_seal_element.py "
                             "lines 260-266 (interp1d linear/quadratic only for 2-3 table points, "
                             "lines 268-275; a constant -> interp1d over [0, 1] held constant, 281-287)",
            "speeds": speeds, "supports": coeff_native,
            "pole_max_rel_diff_vs_reference": pole_diff}})


D_SEAL = support(7, kxx=4.0e5, kxy=2.5e5, kyx=-2.5e5, kyy=4.0e5, cxx=1.5e3, cxy=3.0e2, cyx=-3.0e2,
                 cyy=1.5e3)


def case_d():
    rotor = rotor_a(A_BEARINGS + [D_SEAL])
    speeds = [0.0, 1000.0, 2500.0]
    table, checks = pole_table(rotor, speeds)
    iso = rotor_a([support(0, kxx=1.5e6, kyy=1.5e6, cxx=4.0e3, cyy=4.0e3),
                   support(10, kxx=1.8e6, kyy=1.8e6, cxx=4.5e3, cyy=4.5e3), D_SEAL])
    table_iso, checks_iso = pole_table(iso, speeds)
    write("seal.json", {
        "case": "D", **COMMON,
        "description": "Case A plus a seal (a general support) at node 7 with skew cross-coupling "
                       "only: kxx = kyy, kxy = -kyx, cxx = cyy, cxy = -cyx. 'isotropic' is the same "
                       "seal with isotropic bearings (no cross terms): a fully isotropic system "
                       "(its poles are the union of Whirl's complex-coordinate poles and their "
                       "conjugates).",
        "rotor": rotor, "speeds": speeds, "poles": table, "checks": checks,
        "isotropic": {"rotor": iso, "speeds": speeds, "poles": table_iso, "checks": checks_iso}})


# --------------------------------------------------------------------------- ROSS -> Whirl

def whirl_from_ross(r, supports, disks=None):
    """Whirl rotor JSON from a ROSS rotor whose shaft is one chain of uniform elements."""
    mats, shaft = {}, []
    for el in sorted(r.shaft_elements, key=lambda e: e.n):
        assert el.idl == el.idr and el.odl == el.odr, "tapered element"
        m = el.material
        key = None
        for name, v in mats.items():
            if (v["young_modulus"], v["density"], v["poisson_ratio"]) == (m.E, m.rho, m.Poisson):
                key = name
        if key is None:
            key = "steel" if not mats else f"steel{len(mats)}"
            mats[key] = {"young_modulus": m.E, "density": m.rho, "poisson_ratio": m.Poisson,
                         "loss_factor": 0.0}
        seg = {"L": el.L, "outer_diameter": el.odl, "inner_diameter": el.idl, "material": key}
        if shaft and all(shaft[-1][k] == seg[k] for k in seg):
            shaft[-1]["elements"] += 1
        else:
            shaft.append(dict(seg, elements=1))
    for seg in shaft:
        seg["length"] = seg.pop("L") * seg["elements"]
    shaft = [{k: s[k] for k in ("length", "outer_diameter", "inner_diameter", "material", "elements")}
             for s in shaft]
    if disks is None:
        disks = [{"node": d.n, "mass": d.m, "polar_inertia": d.Ip, "transverse_inertia": d.Id}
                 for d in r.disk_elements]
    return {"type": "beam", "materials": mats, "shaft": shaft, "disks": disks, "supports": supports}


def support_from_ross(b):
    if b.frequency is None:
        return support(b.n, **{k: float(getattr(b, k)[0]) for k in COEFFS})
    vals = {}
    for k in COEFFS:
        v = [float(x) for x in getattr(b, k)]
        vals[k] = v[0] if len(set(v)) == 1 else v
    return support(b.n, speeds=[float(x) for x in b.frequency], **vals)


def matrix_mismatch(r1, r2, speed=0.0):
    out = 0.0
    for f in ("M", "K", "C"):
        a, b = getattr(r1, f)(speed), getattr(r2, f)(speed)
        out = max(out, float(np.max(np.abs(a - b)) / np.max(np.abs(a))))
    a, b = r1.G(), r2.G()
    return max(out, float(np.max(np.abs(a - b)) / np.max(np.abs(a))))


def case_rotor_example():
    orig = rs.rotor_example()
    rotor = whirl_from_ross(orig, [support_from_ross(b) for b in orig.bearing_elements])
    mapped = ross_rotor(rotor)
    speeds = [0.0, 250.0, 500.0, 1000.0]
    table, checks = pole_table(rotor, speeds)
    checks["matrices_vs_rs.rotor_example()"] = matrix_mismatch(orig, mapped)
    uspeeds = [50.0, 150.0, 200.0, 400.0, 500.0, 750.0]
    unb, worst = unbalance(rotor, 3, 1e-3, 0.7, uspeeds, [0, 2, 3, 4, 6])
    checks["unbalance"] = worst
    write("rotor_example.json", {
        "case": "E", **COMMON,
        "description": "rs.rotor_example() (ross/rotor_assembly.py 5396): 6 x 0.25 m, 50 mm solid "
                       "shaft of ROSS's Steel (E = 211e9, G = 81.2e9 -> Poisson = E/(2G) - 1), "
                       "two DiskElement.from_geometry disks (nodes 2, 4), bearings kxx = 1e6, "
                       "kyy = 0.8e6, no damping (nodes 0, 6). Maps exactly (see checks). Undamped: "
                       "unbalance speeds avoid the resonances.",
        "rotor": rotor, "speeds": speeds, "poles": table, "unbalance_response": unb,
        "checks": checks})


RATED = 1047.1975511965977  # 10,000 rpm, a table speed of every support of the compressor


def averaged(supports, kinds, which):
    """Supports averaged to isotropic, cross terms dropped: (kxx+kyy)/2 etc."""
    out = []
    for s, kind in zip(supports, kinds):
        if which == "bearings" and kind != "bearing":
            out.append(s)
            continue
        arr = lambda k: np.asarray(s[k], float)  # noqa: E731
        c = {}
        for d in ("k", "c", "m"):
            v = (arr(d + "xx") + arr(d + "yy")) / 2
            c[d + "xx"] = c[d + "yy"] = v.tolist() if v.ndim else float(v)
        out.append(support(s["node"], speeds=s["speeds"], **c))
    return out


def log_decs(make, speed):
    """First forward mode (ROSS's classification) of rotors made by make(variant)."""
    out = {}
    for variant in ("real", "bearings_averaged", "all_supports_averaged"):
        fwd, _ = forward_modes(make(variant), speed, count=1)
        out[variant] = fwd[0]
    return out


def case_compressor():
    orig = rs.compressor_example()
    by_node = defaultdict(list)
    for el in orig.shaft_elements:
        by_node[el.n].append(el)
    core = []
    extra_disks = defaultdict(lambda: [0.0, 0.0, 0.0])
    sleeves = []
    for n in sorted(by_node):
        els = by_node[n]
        core.append(els[0])
        assert els[0].material.E > 1e11
        for s in els[1:]:
            assert s.material.E < 1e5 and abs(s.idl - els[0].odl) < 1e-12
            sleeves.append({"node": n, "L": s.L, "idl": s.idl, "odl": s.odl, "m": s.m,
                            "E": s.material.E, "G_s": s.material.G_s})
            mh = s.m / 2
            ip = mh * (s.odl**2 + s.idl**2) / 8
            for nn in (n, n + 1):
                extra_disks[nn][0] += mh
                extra_disks[nn][1] += ip
                extra_disks[nn][2] += ip / 2
    for d in orig.disk_elements:
        extra_disks[d.n][0] += d.m
        extra_disks[d.n][1] += d.Ip
        extra_disks[d.n][2] += d.Id
    disks = [{"node": n, "mass": v[0], "polar_inertia": v[1], "transverse_inertia": v[2]}
             for n, v in sorted(extra_disks.items())]
    sups = [support_from_ross(b) for b in orig.bearing_elements]
    kinds = ["seal" if isinstance(b, SealElement) else "bearing" for b in orig.bearing_elements]

    class Core:  # a stand-in with only the core elements
        shaft_elements = core
        disk_elements = []
    rotor = whirl_from_ross(Core, sups, disks)

    speeds = [418.87902047863906, 628.3185307179587, 700.0, 837.7580409572781, RATED, 1500.0]
    table, checks = pole_table(rotor, speeds)
    unb, worst = unbalance(rotor, 29, 1e-4, 0.0, speeds, [7, 29, 48])
    checks["unbalance"] = worst

    # how far the variant is from the shipped rotor (native ROSS both, at the rated speed)
    native_variant = ross_rotor(rotor)
    p_orig = sla.eigvals(state_matrix(*lateral_matrices(orig, RATED), RATED))
    p_var = sla.eigvals(state_matrix(*lateral_matrices(native_variant, RATED), RATED))
    low = sorted([z for z in p_orig if z.imag > 1], key=lambda z: z.imag)[:10]
    first10 = [{"original": cplx(z), "variant": cplx(min(p_var, key=lambda v: abs(v - z)))}
               for z in low]

    def make_orig(variant):
        bs = list(orig.bearing_elements)
        if variant == "real":
            return orig
        new = []
        for b in bs:
            if variant == "bearings_averaged" and isinstance(b, SealElement):
                new.append(b)
                continue
            f = list(b.frequency)
            g = lambda k: np.asarray(getattr(b, k), float)  # noqa: E731
            new.append(rs.BearingElement(n=b.n, frequency=f, kxx=list((g("kxx") + g("kyy")) / 2),
                                         cxx=list((g("cxx") + g("cyy")) / 2)))
        return rs.Rotor(orig.shaft_elements, orig.disk_elements, new)

    def make_variant(variant):
        s = rotor["supports"] if variant == "real" else averaged(
            rotor["supports"], kinds, "bearings" if variant == "bearings_averaged" else "all")
        return ross_rotor(dict(rotor, supports=s), RATED)

    write("compressor_example.json", {
        "case": "E", **COMMON,
        "description": "rs.compressor_example() (ross/tests/data/compressor_example.toml: 91 shaft "
                       "elements on 55 stations, 7 disks, 2 tabulated bearings at nodes 7 and 48, 12 "
                       "tabulated seals). It does not map exactly: 36 stations carry a second, "
                       "concentric shaft element (a 'sleeve' of material shaft_mat_2, E = G = "
                       "6894.75 Pa (1 psi), rho = 7833.412, i.e. mass without stiffness), and a "
                       "Whirl shaft has one element per station. 'rotor' is a VARIANT: the steel "
                       "core exactly, each sleeve lumped as two rigid disks at its end nodes (m/2 "
                       "each, Ip = (m/2)(od^2 + id^2)/8, Id = Ip/2; disks on one node summed with "
                       "the original disks), all 14 supports with their tables. All poles and "
                       "responses here are exact ROSS references for that variant (frozen "
                       "supports, Whirl's interpolation rule).",
        "rotor": rotor, "support_kinds": kinds, "sleeves": sleeves,
        "speeds": speeds, "poles": table, "unbalance_response": unb, "checks": checks,
        "variant_vs_original": {
            "note": "lowest 10 poles with omega > 1 at the rated speed, both with ROSS's native "
                    "spline supports",
            "speed": RATED, "poles": first10},
        "log_decrement": {
            "speed": RATED, "speed_rpm": 10000.0,
            "definition": "first mode classified 'Forward' by ROSS (ModalResults.whirl_direction(): "
                          "every node's orbit forward) in rotor.run_modal(speed) (ARPACK, 12 "
                          "modes); log_dec = 2 pi zeta / sqrt(1 - zeta^2), zeta = -Re s / |s| "
                          "(= -2 pi Re s / Im s)",
            "variants": {"real": "supports as given",
                         "bearings_averaged": "the 2 bearings averaged to isotropic ((kxx+kyy)/2, "
                                              "(cxx+cyy)/2, cross terms dropped), seals as given",
                         "all_supports_averaged": "bearings and the 12 seals averaged the same way "
                                                  "(drops the seals' skew cross-coupling)"},
            "original_ross_native": log_decs(make_orig, RATED),
            "variant_frozen": log_decs(make_variant, RATED)}})


# --------------------------------------------------------------------------- UCS and static

def own_natural_frequencies(r_json, k):
    """Undamped, nonrotating natural frequencies with every non-seal support -> kxx = kyy = k."""
    rotor = dict(r_json, supports=[support(s["node"], kxx=k, kyy=k) for s in r_json["supports"]])
    r = ross_rotor(rotor)
    M, K, _, _ = lateral_matrices(r, 0.0)
    return np.sqrt(np.abs(sla.eigh(K, M, eigvals_only=True)))


def ucs(r_json, label):
    r = ross_rotor(r_json)
    res = r.run_ucs()
    b0 = [b for b in r.bearing_elements if not isinstance(b, SealElement)][0]
    coeffs = ["kxx"] if np.array_equal(b0.kxx, b0.kyy) else ["kxx", "kyy"]
    labelled = []
    for mode, wn in enumerate(res.wn):
        for c in coeffs:
            x2 = getattr(b0, f"{c}_interpolated")(res.bearing_frequency_range)
            xs, ys = intersection(res.stiffness_log, wn, x2, res.bearing_frequency_range)
            for x, y in zip(xs, ys):
                labelled.append({"mode": mode, "coefficient": c, "stiffness": float(x),
                                 "frequency": float(y)})
    assert [p["stiffness"] for p in labelled] == res.intersection_points["x"]
    own = np.array([own_natural_frequencies(r_json, k)[:8] for k in res.stiffness_log]).T
    check = float(np.max(np.abs(own[0::2] - res.wn) / res.wn))
    check_pairs = float(np.max(np.abs(own[1::2] - own[0::2]) / own[0::2]))
    return {
        "rotor_name": label, "rotor": r_json,
        "call": "rotor.run_ucs()  (defaults: stiffness_range=None -> (6, 11) as rated_w is None, "
                "num=20, num_modes=16, synchronous=False)",
        "stiffness_range": [float(x) for x in res.stiffness_range],
        "stiffness": [float(x) for x in res.stiffness_log],
        "frequencies": [[float(x) for x in row] for row in res.wn],
        "bearing_frequency_range": [float(x) for x in res.bearing_frequency_range],
        "intersection_bearing_node": b0.n,
        "intersections": labelled,
        "critical_points_modal_wn": [[float(x) for x in m.wn[:8]] for m in res.critical_points_modal],
        "lowest_8_natural_frequencies": [[float(x) for x in row] for row in own],
        "checks": {"frequencies_vs_own_eigh_even_rows": check,
                   "degenerate_pairs_own_eigh": check_pairs}}


def case_ucs():
    ex = rs.rotor_example()
    ex_json = whirl_from_ross(ex, [support_from_ross(b) for b in ex.bearing_elements])
    write("ucs.json", {
        "case": "F", "ross_version": ROSS_VERSION,
        "what_ross_does": (
            "ross/rotor_assembly.py 3175-3361. stiffness = numpy.logspace(*stiffness_range, num) "
            "(default (6, 11), 20 points; with rated_w set: int(log10(kxx of the first bearing at "
            "rated_w)) +- 3). For each k: a new Rotor of the same shaft elements (alpha = beta = 0) "
            "and disk elements, no point masses, seals (SealElement) dropped, every other bearing "
            "replaced by BearingElement(n, kxx=k, cxx=0) (so kyy = k, no cross terms, no damping, "
            "no mass), converted to 4 dof/node; run_modal(speed=0, num_modes=16) (ARPACK "
            "shift-invert around 1, 32 eigenvalues, |s| > 0.1, sorted by imag) -> wn = |s| of "
            "the 8 lowest positive-imag eigenvalues; frequencies[:, i] = wn[::2], 4 values: at "
            "speed 0 with isotropic springs every mode is a degenerate x/y pair, so this is one "
            "per pair (the 4 lowest distinct natural frequencies). Intersections: only the FIRST "
            "non-seal bearing; for 'kxx' (and 'kyy' too when its kxx and kyy arrays differ) the "
            "curve (k = coefficient(f), f) for f in bearing_frequency_range (the bearing's own "
            "frequency table; for a constant bearing linspace(min(wn) - 0.1 min(wn), max(wn) + "
            "0.1 min(wn), 10), a vertical line) is intersected with each mode's polyline "
            "(stiffness[i], frequencies[m, i]) by ross.utils.intersection: straight segments in "
            "LINEAR k and frequency (not log k). Order: mode, then coefficient."),
        "cases": [ucs(rotor_a(), "A"), ucs(ex_json, "rotor_example")]})


def own_static(r):
    """Rigid pinned supports (x, y of every non-seal bearing node fixed), consistent gravity load."""
    aux = rs.Rotor(r.shaft_elements, r.disk_elements,
                   [rs.BearingElement(n=b.n, kxx=0.0, cxx=0.0) for b in r.bearing_elements
                    if not isinstance(b, SealElement)])
    M = remove_dofs(aux.M(0))
    K = remove_dofs(aux.K(0))
    W = M @ np.tile([0.0, -9.8065, 0.0, 0.0], len(M) // 4)
    fixed = sorted({4 * b.n + j for b in aux.bearing_elements for j in (0, 1)})
    free = [i for i in range(len(M)) if i not in fixed]
    u = np.zeros(len(M))
    u[free] = sla.solve(K[np.ix_(free, free)], W[free])
    R = K @ u - W
    return u[1::4], {b.n: R[4 * b.n + 1] for b in aux.bearing_elements}


def static(r_json, label):
    r = ross_rotor(r_json)
    res = r.run_static()
    own_y, own_r = own_static(r)
    bf = {int(k.split("_")[1]): float(v) for k, v in res.bearing_forces.items()}
    return {
        "rotor_name": label, "rotor": r_json, "call": "rotor.run_static()",
        "nodes_pos": [float(x) for x in r.nodes_pos],
        "deformation_y": [float(x) for x in res.deformation],
        "bearing_reactions": [{"node": n, "force_y": v} for n, v in sorted(bf.items())],
        "disk_forces": [{"node": int(k.split("_")[1]), "value": float(v)}
                        for k, v in res.disk_forces.items()],
        "shaft_weight": float(res.w_shaft),
        "shear_force": {"x": [float(x) for x in res.Vx_axis], "value": [float(x) for x in res.Vx]},
        "bending_moment": {"x": [float(x) for x in res.Vx_axis], "value": [float(x) for x in res.Bm]},
        "own_pinned_solution": {"deformation_y": [float(x) for x in own_y],
                                "bearing_reactions": [{"node": n, "force_y": float(v)}
                                                      for n, v in sorted(own_r.items())]},
        "checks": {
            "deformation_max_abs_diff_vs_own": float(np.max(np.abs(res.deformation - own_y))),
            "deformation_max_abs": float(np.max(np.abs(own_y))),
            "reaction_max_abs_diff_vs_own": float(max(abs(bf[n] - own_r[n]) for n in own_r)),
            "reactions_plus_weights": float(sum(bf.values()) - res.w_shaft
                                            - sum(res.disk_forces.values()))}}


def case_static():
    ex = rs.rotor_example()
    ex_json = whirl_from_ross(ex, [support_from_ross(b) for b in ex.bearing_elements])
    write("static.json", {
        "case": "G", "ross_version": ROSS_VERSION,
        "what_ross_does": (
            "ross/rotor_assembly.py 4126-4323. Seals are skipped; every other bearing becomes "
            "BearingElement(n, kxx=1e20, cxx=0) (isotropic 1e20 N/m on x and y, nothing on the "
            "rotations: rigid PINNED supports by penalty; the real bearing coefficients are "
            "ignored); the auxiliary rotor has the shaft and disk elements only (no point masses). "
            "Gravity g = 9.8065 m/s^2 along -y: W = M(0) @ [0, -9.8065, 0, 0]*nodes on the 4-dof "
            "consistent mass matrix (so W has moment terms), u = K^-1 W with the 1e20 springs; "
            "deformation_y = u[1::4] (m, negative = down, ~1e-19 at the bearings). "
            "bearing_reactions (N, positive = upward force on the shaft) = (K_shaft u - W)[y dof "
            "of the node], K_shaft = the K without bearings. disk_forces = m * 9.8065 (positive "
            "number). shaft_weight = 9.8065 * sum of element masses. Shear force and bending "
            "moment: two stations per element j, at x = (x_left, x_right) (shear_force.x, "
            "flattened). With F_i = (K_shaft u)_y,i - (lumped shaft weight at node i by each "
            "element's beam_cg) = reaction + disk weight (-m g) at node i, and w_j = -9.8065 m_j "
            "(m_j the element mass; the LAST element's w is set to 0): V_0 = [F_0, F_0 + w_0], "
            "V_j = [V_{j-1,R} + F_j, V_{j,L} + w_j], last element V = [V_{j-1,R} + F_j, -F_n]; "
            "shear_force = -V. Bending moment by the trapezoid rule on the shear: "
            "Bm_0 = [0, 0.5 (V_0L + V_0R) L_0] (signs as stored: -V), Bm_j = [Bm_{j-1,R}, "
            "Bm_{j,L} + 0.5 (V_jL + V_jR) L_j], but the last element is set to "
            "[-0.5 (V_L + V_R) L, 0] (forced to 0 at the right end, not continued)."),
        "cases": [static(ex_json, "rotor_example"), static(rotor_a(), "A")]})


def main():
    steps = [case_a, case_b, case_c, case_d, case_rotor_example, case_compressor, case_ucs,
             case_static]
    only = sys.argv[1:]
    for f in steps:
        if not only or f.__name__ in only:
            f()


if __name__ == "__main__":
    main()
