#!/usr/bin/env python3
"""ROSS 2.3.0 references for machines as engineers model them (issue 29): point masses on and
off the shaft, bearings linked to pedestals (`n_link`).

Rerun (from the repository root, a few seconds):

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python3 tests/data/ross/machines.py

Same layout and conventions as generate.py (imported for its helpers): every file holds the
Whirl rotor under "rotor" and ROSS's lateral poles and unbalance response of the ROSS rotor
built from it by `ross_machine()`. Lateral dofs: ross.utils.remove_dofs drops z and theta of
shaft nodes (6 dof) and z of nodes off the shaft (3 dof: x, y, z), which ROSS numbers on from the
shaft's last node. A Whirl point mass's stiffness/damping to ground is an isotropic
BearingElement on its node; a Whirl support with "n_link" a BearingElement with that n_link.
"""

import sys
from pathlib import Path

import numpy as np
import scipy.linalg as sla

sys.path.insert(0, str(Path(__file__).resolve().parent))
import generate as g  # noqa: E402
import ross as rs  # noqa: E402


def ross_machine(rotor):
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
    bearings = []
    for s in rotor["supports"]:
        if "stiffness" in s:
            k, c = s["stiffness"], s.get("damping", 0.0)
            coeffs = {"kxx": k, "kyy": k, "cxx": c, "cyy": c}
        else:
            coeffs = {k: float(s.get(k, 0.0)) for k in g.COEFFS}
            coeffs.setdefault("kyy", coeffs["kxx"])
        bearings.append(rs.BearingElement(n=s["node"], n_link=s.get("n_link"), **coeffs))
    points = []
    for p in rotor.get("point_masses", []):
        points.append(rs.PointMass(n=p["node"], m=p["mass"]))
        k, c = p.get("stiffness", 0.0), p.get("damping", 0.0)
        if k or c:
            bearings.append(rs.BearingElement(n=p["node"], kxx=k, kyy=k, cxx=c, cyy=c))
    return rs.Rotor(shaft, disks, bearings, point_mass_elements=points)


def shaft_nodes(rotor):
    return sum(seg.get("elements", 1) for seg in rotor["shaft"]) + 1


def x_dof(rotor, node, per_node):
    """Index of x of `node` in matrices of `per_node` dof per shaft node (6 or 4)."""
    s = shaft_nodes(rotor)
    return per_node * node if node < s else per_node * s + (per_node // 2) * (node - s)


def poles(r, speed):
    M, K, C, G = g.lateral_matrices(r, speed)
    ev = sla.eigvals(g.state_matrix(M, K, C, G, speed))
    ev = np.array(sorted(ev, key=lambda z: (z.imag, z.real)))
    # Check: every pole is one of ROSS's own run_modal (6 dof) eigenvalues.
    ev6 = r.run_modal(speed, sparse=False).evalues
    miss = max(np.min(np.abs(ev6 - z)) / max(abs(z), 1.0) for z in ev)
    return {"speed": float(speed), "eigenvalues": [g.cplx(z) for z in ev]}, float(miss)


def unbalance(rotor, r, node, amount, phase, speeds, nodes):
    resp = r.run_unbalance_response(node=node, unbalance_magnitude=amount, unbalance_phase=phase,
                                    frequency=np.array(speeds, dtype=float))
    fr = resp.forced_resp
    worst = 0.0
    out = {n: {"x": [], "y": []} for n in nodes}
    for i, w in enumerate(speeds):
        M, K, C, G = g.lateral_matrices(r, w)
        F = np.zeros(len(M), complex)
        d = x_dof(rotor, node, 4)
        F[d] = amount * w**2 * np.exp(1j * phase)
        F[d + 1] = -1j * amount * w**2 * np.exp(1j * phase)
        X = sla.solve(K - w**2 * M + 1j * w * (C + w * G), F)
        for n in nodes:
            x, y = fr[x_dof(rotor, n, 6), i], fr[x_dof(rotor, n, 6) + 1, i]
            own = X[x_dof(rotor, n, 4)], X[x_dof(rotor, n, 4) + 1]
            scale = max(abs(x), abs(y), 1e-300)
            worst = max(worst, abs(x - own[0]) / scale, abs(y - own[1]) / scale)
            out[n]["x"].append(g.cplx(x))
            out[n]["y"].append(g.cplx(y))
    call = (f"rotor.run_unbalance_response(node={node}, unbalance_magnitude={amount!r}, "
            f"unbalance_phase={phase!r}, frequency=speeds)")
    return {"call": call, "unbalances": [{"node": node, "amount": amount, "phase": phase}],
            "speeds": [float(w) for w in speeds],
            "nodes": [{"node": n, "x": out[n]["x"], "y": out[n]["y"]} for n in nodes]}, worst


def case(name, description, rotor, speeds, unb):
    r = ross_machine(rotor)
    table, miss = [], 0.0
    for w in speeds:
        p, m = poles(r, w)
        table.append(p)
        miss = max(miss, m)
    resp, worst = unbalance(rotor, r, *unb)
    g.write(name, {"case": name, **g.COMMON, "description": description, "rotor": rotor,
                   "speeds": speeds, "poles": table, "unbalance_response": resp,
                   "checks": {"run_modal": miss, "unbalance": worst}})


STEEL = dict(g.STEEL)
UNB_SPEEDS = [0.0, 50.0, 100.0, 115.0, 120.0, 125.0, 130.0, 140.0, 200.0, 300.0, 450.0, 600.0,
              800.0, 1000.0, 1500.0, 2000.0, 3000.0]


def shaft_a():
    return {"type": "beam", "materials": {"steel": dict(STEEL)},
            "shaft": [{"length": 1.5, "outer_diameter": 0.05, "inner_diameter": 0.0,
                       "material": "steel", "elements": 10}],
            "disks": [{"node": 5, "mass": 32.6, "polar_inertia": 0.32, "transverse_inertia": 0.17}]}


def pedestals():
    """A's shaft on two anisotropic cross-coupled bearings, each linked to a pedestal (nodes 11,
    12 off the shaft) held to ground by an anisotropic support. (ROSS 2.3.0 cannot take a point
    mass on a shaft node: it adds 3 dof per point mass to the 6 per node, so one on the shaft
    leaves 3 massless dofs and a singular M; it also needs a bearing on the point mass's node.)"""
    rotor = shaft_a()
    rotor["supports"] = [
        g.support(0, kxx=1.0e6, kxy=5.0e5, kyx=-8.0e5, kyy=2.0e6, cxx=3.0e3, cxy=4.0e2, cyx=6.0e2,
                  cyy=4.5e3),
        g.support(10, kxx=1.2e6, kxy=6.0e5, kyx=-9.0e5, kyy=2.4e6, cxx=3.5e3, cxy=5.0e2, cyx=7.0e2,
                  cyy=5.0e3),
        g.support(11, kxx=4.0e7, kyy=2.5e7, cxx=2.0e3, cyy=1.5e3),
        g.support(12, kxx=5.0e7, kyy=3.0e7, cxx=2.5e3, cyy=1.8e3),
    ]
    for s in rotor["supports"]:
        del s["speeds"]
    rotor["supports"][0]["n_link"] = 11
    rotor["supports"][1]["n_link"] = 12
    rotor["point_masses"] = [{"node": 11, "mass": 15.0},
                             {"node": 12, "mass": 18.0}]
    return rotor


def pedestals_isotropic():
    """The same machine with isotropic bearings and pedestals: the pedestals' ground support is
    the point masses' own stiffness and damping."""
    rotor = shaft_a()
    rotor["supports"] = [
        {"node": 0, "n_link": 11, "stiffness": 1.5e6, "damping": 3.0e3},
        {"node": 10, "n_link": 12, "stiffness": 1.8e6, "damping": 3.5e3},
    ]
    rotor["point_masses"] = [
        {"node": 11, "mass": 15.0, "stiffness": 4.0e7, "damping": 2.0e3},
        {"node": 12, "mass": 18.0, "stiffness": 3.0e7, "damping": 1.5e3},
    ]
    return rotor


def main():
    speeds = [0.0, 300.0, 800.0, 1500.0, 3000.0]
    case("pedestals.json", pedestals.__doc__, pedestals(), speeds,
         (5, 1e-4, 0.0, UNB_SPEEDS, [0, 5, 10, 11, 12]))
    case("pedestals_isotropic.json", pedestals_isotropic.__doc__, pedestals_isotropic(), speeds,
         (5, 1e-4, 0.3, UNB_SPEEDS, [0, 5, 10, 11, 12]))


if __name__ == "__main__":
    main()
