#!/usr/bin/env python3
"""ROSS 2.3.0 references for `POST /v1/convert/ross` (issue 29): six machines built in ROSS,
saved by ROSS's own `Rotor.save()`, and ROSS's results on the rotor it loads back from that file.

Rerun (from the repository root, ~1 min on one core):

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python tests/data/ross/convert.py

It rewrites tests/data/ross/convert/<name>.toml (the file `Rotor.save` wrote, byte for byte) and
tests/data/ross/convert/<name>.json (the references). tests/it/convert_ross.rs posts each TOML to
the endpoint, runs Whirl's modal analysis and unbalance response on the converted rotor and
compares them with the JSON. No randomness; LAPACK results repeat up to rounding (about 1e-14 of
the largest eigenvalue), so compare with a tolerance.

What is computed (on `rs.Rotor.load(<name>.toml)`, checked equal to the rotor that was saved)
--------------------------------------------------------------------------------------------
* Poles: all eigenvalues s of A = [[0, I], [-M^-1 K, -M^-1 (C + W G)]] of the lateral dofs,
  M, K, C, G = rotor.M(W), rotor.K(W), rotor.C(W), rotor.G() restricted to x, y, alpha, beta of
  each shaft node and x, y of each node off the shaft (ROSS numbers those on from the shaft's
  last node, 3 dofs each: x, y, z). The axial and torsional dofs are decoupled from them (checked:
  `checks.decoupled`, the largest entry of the cross blocks, is 0). Stored [re, im] sorted by
  (im, re); compare as sets. Supports at W are ROSS's own interpolation of their tables
  (interp1d for 2-3 points, UnivariateSpline with s = len for 4 or more, extrapolating): nothing
  is frozen here, unlike generate.py. `checks.run_modal`: every pole is one of
  rotor.run_modal(W, sparse=False).evalues (relative to max(|s|, 1)).
* Unbalance response: rotor.run_unbalance_response(node, amount, phase, frequency=speeds),
  X and Y of the listed nodes, [re, im], x(t) = Re(X e^{iWt}) (see generate.py's conventions:
  f_x = a W^2 cos(Wt + phase), f_y = a W^2 sin(Wt + phase)). `checks.unbalance`: the same from
  a solve of the lateral matrices here, (K - W^2 M + i W (C + W G)) X = F, relative to |X|.
* `pedestals` has a point mass on a shaft node. ROSS 2.3.0 gives every PointMass 3 dofs of its
  own in the global numbering, also one on a shaft node, whose mass it adds to the shaft node's
  x, y, z: the 3 dofs it reserved stay empty (zero rows and columns in M, K, C, G), so M is
  singular and run_modal / run_unbalance_response fail (LinAlgError). Its references are
  therefore computed as above from ROSS's own matrices with those empty dofs left out
  (`checks.empty_dofs`: the largest entry of their rows and columns, 0), the unbalance by the
  lateral solve. `checks.method`: the same two computations on the machine without that point
  mass (and its bearing) against ROSS's run_modal and run_unbalance_response.

Machines
--------
compressor_example  rs.compressor_example() as it is: 91 shaft elements on 55 nodes (36 sleeves
                    on the same nodes, E = G_s = 1 psi), 7 disks, 2 tabulated bearings (8
                    speeds), 12 tabulated seals (6 or 9 speeds).
pedestals           50 mm shaft 10 x 0.15 m, disk at node 5; anisotropic cross-coupled bearings
                    at 0 and 10 linked (n_link) to pedestal point masses 11 and 12 off the shaft,
                    each pedestal on its own anisotropic BearingElement to ground (pedestal 12
                    with mx != my); a point mass of 4 kg on shaft node 3 with a soft bearing
                    there (ROSS needs a bearing on a point mass's node).
tapered             8 conical elements (odl != odr and idl != idr: a shaft tapering from 70 to 45
                    mm with a bore from 20 to 30 mm and back), disk at node 4, two bearings.
axial_rayleigh      10 elements under 1.5e4 N of compression (axial_force = -1.5e4), one
                    element carrying 1e3 N m of torque, every element with alpha = 1.5 1/s and
                    beta = 2e-5 s; disk, two bearings. ROSS's element damping is
                    C = alpha M + beta K with K the whole element stiffness: bending, the axial
                    force's and the torque's geometric stiffness (shaft_element.py 983).
table70             shaft A with a disk, both bearings tabulated at 70 speeds (a plain-bearing-like
                    law, smooth), and a cross-coupled SealElement tabulated at 3 speeds
                    (interp1d, quadratic).
train               a train: shafts of 6, 4 and 8 elements (60, 50 and 70 mm) joined by two
                    CouplingElements (masses, inertias, kt and kr equal in x and y; the second
                    with Id left to ROSS's default, Ip / 2), four disks, six anisotropic
                    cross-coupled bearings.
"""

import json
import os
import sys
import warnings
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import scipy.linalg as sla

warnings.filterwarnings("ignore")
import ross as rs  # noqa: E402

HERE = Path(__file__).resolve().parent
OUT = HERE / "convert"

STEEL = rs.Material(name="Steel", rho=7810.0, E=211e9, G_s=81.2e9)


def cplx(z):
    return [float(np.real(z)), float(np.imag(z))]


# --------------------------------------------------------------------------- ROSS's numbering

def layout(r):
    """Shaft node count, off-shaft nodes, and the kept (lateral) / empty dof indices of r's
    6-dof matrices."""
    shaft = len(r.nodes)
    n_last = r.shaft_elements[-1].n
    off = sorted({p.n for p in r.point_mass_elements if p.n > n_last + 1})
    assert off == list(range(shaft, shaft + len(off))), off
    keep = [6 * i + k for i in range(shaft) for k in (0, 1, 3, 4)]
    keep += [6 * shaft + 3 * j + k for j in range(len(off)) for k in (0, 1)]
    axial = [6 * i + k for i in range(shaft) for k in (2, 5)]
    axial += [6 * shaft + 3 * j + 2 for j in range(len(off))]
    used = set(keep) | set(axial)
    empty = [i for i in range(r.ndof) if i not in used]
    return shaft, off, keep, axial, empty


def x_dof(r, node):
    """Index of x of `node` in r's 6-dof numbering."""
    shaft = len(r.nodes)
    return 6 * node if node < shaft else 6 * shaft + 3 * (node - shaft)


def matrices(r, speed):
    return r.M(speed), r.K(speed), r.C(speed), r.G()


def lateral(r, speed, checks):
    shaft, off, keep, axial, empty = layout(r)
    mats = matrices(r, speed)
    for m in mats:
        checks["decoupled"] = max(checks.get("decoupled", 0.0),
                                  float(np.max(np.abs(m[np.ix_(keep, axial)]), initial=0.0)),
                                  float(np.max(np.abs(m[np.ix_(axial, keep)]), initial=0.0)))
        if empty:
            checks["empty_dofs"] = max(checks.get("empty_dofs", 0.0),
                                       float(np.max(np.abs(m[empty, :]))),
                                       float(np.max(np.abs(m[:, empty]))))
    return [m[np.ix_(keep, keep)] for m in mats], keep


def state_matrix(M, K, C, G, speed):
    n = len(M)
    return np.block([[np.zeros((n, n)), np.eye(n)],
                     [-sla.solve(M, K), -sla.solve(M, C + speed * G)]])


def poles(r, speed, checks, native=True):
    (M, K, C, G), _ = lateral(r, speed, checks)
    ev = sla.eigvals(state_matrix(M, K, C, G, speed))
    ev = np.array(sorted(ev, key=lambda z: (z.imag, z.real)))
    if native:
        ev6 = r.run_modal(speed, sparse=False).evalues
        miss = max(np.min(np.abs(ev6 - z)) / max(abs(z), 1.0) for z in ev)
        checks["run_modal"] = max(checks.get("run_modal", 0.0), float(miss))
    return {"speed": float(speed), "eigenvalues": [cplx(z) for z in ev]}


def own_unbalance(r, speed, node, amount, phase, nodes, checks):
    (M, K, C, G), keep = lateral(r, speed, checks)
    where = {d: i for i, d in enumerate(keep)}
    F = np.zeros(len(M), complex)
    d = where[x_dof(r, node)]
    F[d] = amount * speed**2 * np.exp(1j * phase)
    F[d + 1] = -1j * amount * speed**2 * np.exp(1j * phase)
    X = sla.solve(K - speed**2 * M + 1j * speed * (C + speed * G), F)
    return {n: (X[where[x_dof(r, n)]], X[where[x_dof(r, n)] + 1]) for n in nodes}


def unbalance(r, node, amount, phase, speeds, nodes, checks, native=True):
    out = {n: {"x": [], "y": []} for n in nodes}
    fr = None
    if native:
        fr = r.run_unbalance_response(node=node, unbalance_magnitude=amount,
                                      unbalance_phase=phase,
                                      frequency=np.array(speeds, dtype=float)).forced_resp
    for i, w in enumerate(speeds):
        own = own_unbalance(r, w, node, amount, phase, nodes, checks)
        for n in nodes:
            if native:
                x, y = fr[x_dof(r, n), i], fr[x_dof(r, n) + 1, i]
                scale = max(abs(x), abs(y), 1e-300)
                checks["unbalance"] = max(checks.get("unbalance", 0.0),
                                          float(abs(x - own[n][0]) / scale),
                                          float(abs(y - own[n][1]) / scale))
            else:
                x, y = own[n]
            out[n]["x"].append(cplx(x))
            out[n]["y"].append(cplx(y))
    call = (f"rotor.run_unbalance_response(node={node}, unbalance_magnitude={amount!r}, "
            f"unbalance_phase={phase!r}, frequency=speeds)")
    if not native:
        call = ("(K - W^2 M + i W (C + W G)) X = F on rotor.M(W), rotor.K(W), rotor.C(W), "
                "rotor.G() without the empty dofs (ROSS's own solve fails: singular M)")
    return {"call": call, "unbalances": [{"node": node, "amount": amount, "phase": phase}],
            "speeds": [float(w) for w in speeds],
            "nodes": [{"node": n, "x": out[n]["x"], "y": out[n]["y"]} for n in nodes]}


COEFFS = ["kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "mxx", "mxy", "myx", "myy"]


def frozen(r, w):
    """r with each tabulated support constant at numpy.interp(w, frequency, values): linear
    between the table's speeds and held at its ends, Whirl's default interpolation (ROSS's own
    is a smoothing spline that misses the table points and extrapolates)."""
    bearings = []
    for b in r.bearing_elements:
        if b.frequency is None or len(np.atleast_1d(b.frequency)) < 2:
            bearings.append(b)
            continue
        c = {}
        for k in COEFFS:
            v = np.atleast_1d(np.asarray(getattr(b, k), dtype=float))
            c[k] = float(v[0]) if len(v) == 1 else float(np.interp(w, b.frequency, v))
        bearings.append(rs.BearingElement(n=b.n, n_link=b.n_link, **c))
    return rs.Rotor(r.shaft_elements, r.disk_elements, bearings,
                    point_mass_elements=r.point_mass_elements)


def linear(r, pole_speeds, node, amount, phase, speeds, nodes, checks):
    """Poles and unbalance response with Whirl's linear rule (`frozen` at each speed)."""
    table = [poles(frozen(r, w), w, checks, native=False) for w in pole_speeds]
    resp = {n: {"x": [], "y": []} for n in nodes}
    for w in speeds:
        own = own_unbalance(frozen(r, w), w, node, amount, phase, nodes, checks)
        for n in nodes:
            resp[n]["x"].append(cplx(own[n][0]))
            resp[n]["y"].append(cplx(own[n][1]))
    for w in pole_speeds[:1]:
        f = frozen(r, w)
        # The rotor rebuilt around the frozen supports is the same rotor (its M and G).
        checks["frozen_structure"] = max(
            float(np.max(np.abs(f.M(w) - r.M(w))) / np.max(np.abs(r.M(w)))),
            float(np.max(np.abs(f.G() - r.G())) / np.max(np.abs(r.G()))))
    return {"poles": table,
            "unbalance_response": {
                "call": "(K - W^2 M + i W (C + W G)) X = F, supports frozen at numpy.interp(W)",
                "unbalances": [{"node": node, "amount": amount, "phase": phase}],
                "speeds": [float(w) for w in speeds],
                "nodes": [{"node": n, "x": resp[n]["x"], "y": resp[n]["y"]} for n in nodes]}}


def same_matrices(r1, r2, speeds):
    worst = 0.0
    for w in speeds:
        for a, b in zip(matrices(r1, w), matrices(r2, w)):
            worst = max(worst, float(np.max(np.abs(a - b)) / max(np.max(np.abs(a)), 1e-300)))
    return worst


# --------------------------------------------------------------------------- the machines

def compressor_example():
    return rs.compressor_example()


def shaft_a(count=10, length=0.15, od=0.05):
    return [rs.ShaftElement(L=length, idl=0.0, odl=od, material=STEEL) for _ in range(count)]


def pedestals(shaft_mass=True):
    disks = [rs.DiskElement(n=5, m=32.6, Id=0.17, Ip=0.32)]
    bearings = [
        rs.BearingElement(n=0, n_link=11, kxx=1.0e6, kxy=5.0e5, kyx=-8.0e5, kyy=2.0e6,
                          cxx=3.0e3, cxy=4.0e2, cyx=6.0e2, cyy=4.5e3),
        rs.BearingElement(n=10, n_link=12, kxx=1.2e6, kxy=6.0e5, kyx=-9.0e5, kyy=2.4e6,
                          cxx=3.5e3, cxy=5.0e2, cyx=7.0e2, cyy=5.0e3),
        rs.BearingElement(n=11, kxx=4.0e7, kyy=2.5e7, cxx=2.0e3, cyy=1.5e3),
        rs.BearingElement(n=12, kxx=5.0e7, kyy=3.0e7, cxx=2.5e3, cyy=1.8e3),
    ]
    points = [rs.PointMass(n=11, m=15.0), rs.PointMass(n=12, mx=18.0, my=20.0, mz=19.0)]
    if shaft_mass:
        bearings.append(rs.BearingElement(n=3, kxx=2.0e5, cxx=40.0))
        points.append(rs.PointMass(n=3, m=4.0))
    return rs.Rotor(shaft_a(), disks, bearings, point_mass_elements=points)


def tapered():
    # Outer diameter 70 -> 45 mm over the shaft, the bore 20 -> 30 -> 20 mm: every element is
    # conical in both diameters.
    od = np.linspace(0.070, 0.045, 9)
    bore = [0.020, 0.0225, 0.025, 0.0275, 0.030, 0.0275, 0.025, 0.0225, 0.020]
    shaft = [rs.ShaftElement(L=0.125, idl=bore[i], odl=od[i], idr=bore[i + 1], odr=od[i + 1],
                             material=STEEL) for i in range(8)]
    disks = [rs.DiskElement(n=4, m=20.0, Id=0.12, Ip=0.22)]
    bearings = [rs.BearingElement(n=0, kxx=2.0e7, kyy=3.0e7, cxx=2.0e3, cyy=2.5e3),
                rs.BearingElement(n=8, kxx=1.5e7, kxy=2.0e6, kyx=-2.0e6, kyy=2.5e7,
                                  cxx=1.8e3, cyy=2.2e3)]
    return rs.Rotor(shaft, disks, bearings)


def axial_rayleigh():
    # Element 6 carries the torque and no beta: ROSS's beta multiplies the whole element
    # stiffness, torque's geometric term included, which Whirl's proportional damping leaves out.
    shaft = [rs.ShaftElement(L=0.12, idl=0.0, odl=0.06, material=STEEL, axial_force=-1.5e4,
                             torque=1.0e3 if i == 6 else 0.0, alpha=1.5,
                             beta=0.0 if i == 6 else 2.0e-5)
             for i in range(10)]
    disks = [rs.DiskElement(n=4, m=25.0, Id=0.18, Ip=0.35)]
    bearings = [rs.BearingElement(n=0, kxx=8.0e6, kyy=1.0e7, cxx=1.0e3, cyy=1.2e3),
                rs.BearingElement(n=10, kxx=8.0e6, kyy=1.0e7, cxx=1.0e3, cyy=1.2e3)]
    return rs.Rotor(shaft, disks, bearings)


TABLE70 = np.linspace(50.0, 3500.0, 70)


def plain_bearing(scale):
    """A short plain bearing's coefficients against speed, smooth: the direct stiffness and the
    cross-coupling grow with speed, the damping falls."""
    w = TABLE70 / 1000.0
    return dict(kxx=scale * 4.0e6 * (1.0 + 0.8 * np.sqrt(w)),
                kyy=scale * 6.0e6 * (1.0 + 0.5 * np.sqrt(w)),
                kxy=scale * 2.5e6 * w / (1.0 + 0.3 * w),
                kyx=-scale * 3.5e6 * w / (1.0 + 0.2 * w),
                cxx=scale * 9.0e3 / (1.0 + 0.6 * w),
                cyy=scale * 1.2e4 / (1.0 + 0.5 * w),
                cxy=scale * 6.0e2 * np.exp(-w),
                cyx=scale * 8.0e2 * np.exp(-w))


def table70():
    disks = [rs.DiskElement(n=5, m=32.6, Id=0.17, Ip=0.32)]
    bearings = [rs.BearingElement(n=0, frequency=TABLE70, **plain_bearing(1.0)),
                rs.BearingElement(n=10, frequency=TABLE70, **plain_bearing(1.3)),
                rs.SealElement(n=7, frequency=[300.0, 1500.0, 3000.0],
                               kxx=[3.0e5, 4.0e5, 5.5e5], kyy=[3.0e5, 4.0e5, 5.5e5],
                               kxy=[1.0e5, 2.5e5, 4.5e5], kyx=[-1.0e5, -2.5e5, -4.5e5],
                               cxx=[1.6e3, 1.5e3, 1.3e3], cyy=[1.6e3, 1.5e3, 1.3e3],
                               cxy=[250.0, 300.0, 340.0], cyx=[-250.0, -300.0, -340.0])]
    return rs.Rotor(shaft_a(), disks, bearings)


def train():
    def shaft(n, L, od):
        return [rs.ShaftElement(L=L / n, idl=0.0, odl=od, material=STEEL) for _ in range(n)]

    def bearing(n, k):
        return rs.BearingElement(n=n, kxx=k, kxy=0.1 * k, kyx=-0.15 * k, kyy=1.4 * k,
                                 cxx=1e-4 * k, cxy=5e-6 * k, cyx=8e-6 * k, cyy=1.3e-4 * k)
    elements = (shaft(6, 0.8, 0.06)
                + [rs.CouplingElement(m_l=6.0, m_r=5.0, Ip_l=0.03, Ip_r=0.025, Id_l=0.018,
                                      Id_r=0.015, kt_x=2e7, kt_y=2e7, kr_x=8e4, kr_y=8e4,
                                      L=0.12, o_d=0.14)]
                + shaft(4, 0.6, 0.05)
                + [rs.CouplingElement(m_l=4.0, m_r=4.0, Ip_l=0.02, Ip_r=0.02, kt_x=1e7,
                                      kt_y=1e7, kr_x=5e4, kr_y=5e4, L=0.1, o_d=0.12)]
                + shaft(8, 1.0, 0.07))
    disks = [rs.DiskElement(n=3, m=40.0, Id=0.25, Ip=0.4), rs.DiskElement(n=9, m=20.0, Id=0.09, Ip=0.15),
             rs.DiskElement(n=15, m=30.0, Id=0.17, Ip=0.3), rs.DiskElement(n=18, m=30.0, Id=0.17, Ip=0.3)]
    bearings = [bearing(0, 2e7), bearing(6, 2e7), bearing(7, 1.5e7), bearing(11, 1.5e7),
                bearing(12, 3e7), bearing(20, 3e7)]
    return rs.Rotor(elements, disks, bearings)


UNB_PEDESTALS = [20.0, 50.0, 80.0, 100.0, 115.0, 122.0, 127.0, 130.0, 132.0, 134.0, 137.0,
                 142.0, 150.0, 170.0, 220.0, 350.0, 600.0, 1000.0, 1500.0, 2500.0]
UNB_TABLE70 = [20.0, 50.0, 80.0, 110.0, 135.0, 145.0, 150.0, 154.0, 156.0, 158.0, 161.0,
               166.0, 175.0, 200.0, 260.0, 400.0, 700.0, 1100.0, 1800.0, 3000.0]

CASES = [
    # name, build, pole speeds, (node, amount, phase, speeds, nodes)
    ("compressor_example", compressor_example, [300.0, 628.3185307179587, 900.0, 1500.0],
     (29, 1e-4, 0.5, [200.0, 300.0, 400.0, 500.0, 600.0, 700.0, 750.0, 800.0, 850.0, 900.0,
                      950.0, 1000.0, 1050.0, 1100.0, 1150.0, 1200.0, 1300.0, 1400.0, 1600.0,
                      1800.0], [7, 20, 29, 48])),
    ("pedestals", pedestals, [0.0, 300.0, 800.0, 1500.0, 3000.0],
     (5, 1e-4, 0.3, UNB_PEDESTALS, [0, 3, 5, 10, 11, 12])),
    ("tapered", tapered, [0.0, 500.0, 1500.0, 3000.0],
     (4, 2e-4, 0.0, [50.0, 150.0, 250.0, 320.0, 350.0, 370.0, 378.0, 383.0, 386.0, 389.0,
                     393.0, 400.0, 420.0, 460.0, 550.0, 800.0, 1000.0, 1300.0, 1700.0, 2200.0],
      [0, 4, 8])),
    ("axial_rayleigh", axial_rayleigh, [0.0, 400.0, 1200.0, 2500.0],
     (4, 1e-4, 1.1, [50.0, 150.0, 220.0, 250.0, 265.0, 273.0, 278.0, 280.0, 282.0, 287.0,
                     295.0, 310.0, 340.0, 400.0, 550.0, 800.0, 1200.0, 1600.0, 2000.0,
                     2500.0], [0, 4, 6, 10])),
    ("table70", table70, [30.0, 777.7, 1500.0, 4000.0],
     (5, 1e-4, 0.0, UNB_TABLE70, [0, 5, 7, 10])),
    ("train", train, [0.0, 500.0, 1500.0, 3000.0],
     (15, 1e-4, 0.2, [100.0, 300.0, 380.0, 405.0, 415.0, 425.0, 440.0, 460.0, 500.0, 600.0,
                      700.0, 750.0, 900.0, 1200.0, 1500.0, 2000.0], [0, 3, 6, 7, 9, 12, 15, 20])),
]


def description(name):
    """The machine's paragraph of the module docstring."""
    lines = __doc__.split("\nMachines\n")[1].splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(name + " "))
    text = [lines[start][len(name):]]
    for line in lines[start + 1:]:
        if not line.startswith(" "):
            break
        text.append(line)
    return " ".join(t.strip() for t in text)


def main(only=None):
    OUT.mkdir(exist_ok=True)
    for name, build, pole_speeds, (node, amount, phase, speeds, nodes) in CASES:
        if only and name not in only:
            continue
        built = build()
        toml = OUT / f"{name}.toml"
        built.save(toml)
        r = rs.Rotor.load(toml)
        checks = {"saved_vs_loaded": same_matrices(built, r, pole_speeds[1:] + [speeds[0]])}
        native = name != "pedestals"
        table = [poles(r, w, checks, native) for w in pole_speeds]
        resp = unbalance(r, node, amount, phase, speeds, nodes, checks, native)
        if not native:
            # The method against ROSS's own analyses, on the machine without the shaft's
            # point mass (whose empty dofs make ROSS's M singular).
            method = {}
            r0 = pedestals(shaft_mass=False)
            for w in pole_speeds:
                poles(r0, w, method, True)
            unbalance(r0, node, amount, phase, speeds, [n for n in nodes if n != 3], method,
                      True)
            checks["method"] = {k: method[k] for k in ("run_modal", "unbalance")}
        if name in ("compressor_example", "table70"):
            checks_linear = {}
            linear_refs = linear(r, pole_speeds, node, amount, phase, speeds, nodes, checks_linear)
            checks["linear"] = checks_linear
        else:
            linear_refs = None
        data = {
            "case": name,
            "ross_version": rs.__version__,
            "description": description(name),
            "toml": f"{name}.toml",
            "poles_call": (
                "scipy.linalg.eigvals(A), A = [[0, I], [-solve(M, K), -solve(M, C + W G)]], "
                "M, K, C, G = rotor.M(W), rotor.K(W), rotor.C(W), rotor.G() on the lateral dofs "
                "(x, y, alpha, beta per shaft node; x, y per node off the shaft), "
                "rotor = rs.Rotor.load(toml)"),
            "poles": table,
            "unbalance_response": resp,
            "checks": checks,
        }
        if linear_refs is not None:
            data["linear"] = linear_refs
        path = OUT / f"{name}.json"
        path.write_text(json.dumps(data, indent=1) + "\n")
        print(f"{name}: {len(table[0]['eigenvalues'])} poles per speed, checks {checks}, "
              f"{path.stat().st_size // 1024} kB json, {toml.stat().st_size // 1024} kB toml")
        assert path.stat().st_size < 300 * 1024
        assert checks["saved_vs_loaded"] == 0.0, checks
        assert checks["decoupled"] == 0.0, checks
        assert checks.get("empty_dofs", 0.0) == 0.0, checks
        assert checks.get("run_modal", checks.get("method", {}).get("run_modal")) < 1e-9, checks
        assert checks.get("unbalance", checks.get("method", {}).get("unbalance")) < 1e-9, checks


if __name__ == "__main__":
    main(sys.argv[1:])
