#!/usr/bin/env python3
"""ROSS 2.3.0 references for shaft elements beyond uniform segments (issue 29): conical
(tapered) elements, axial force and torque, proportional (alpha M + beta K) damping, and
sleeves (several shaft elements on the same nodes).

Rerun (from the repository root, a few seconds):

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python tests/data/ross/elements.py

Same layout and conventions as machines.py (whose `poles` and `unbalance` it uses). Each rotor
is built in ROSS from the Whirl JSON by `ross_elements()`: a segment of `elements` elements is
cut into equal lengths, a conical segment's diameters linear along it; a sleeve is one extra
ShaftElement per shaft element it spans, with the same `n` and `L`; `rayleigh_damping` is
ROSS's alpha, beta (ROSS adds alpha M + beta K to C: frame "nonrotating"). ROSS's beta K
includes the torque's geometric stiffness, which Whirl's Rayleigh damping leaves out, so no
segment here has both a torque and a beta.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import generate as g  # noqa: E402
import machines as mch  # noqa: E402
import ross as rs  # noqa: E402


def materials(rotor):
    out = {}
    for name, m in rotor["materials"].items():
        nu = m["poisson_ratio"]
        E = m["young_modulus"]
        out[name] = rs.Material(name=f"whirl_{name}", rho=m["density"], E=E, G_s=E / (2 * (1 + nu)))
    return out


def pieces(seg, lengths):
    """ShaftElement keyword arguments of a segment or sleeve cut into `lengths`."""
    total = sum(lengths)
    ol, il = seg["outer_diameter"], seg.get("inner_diameter", 0.0)
    orr, irr = seg.get("outer_diameter_right", ol), seg.get("inner_diameter_right", il)
    z = 0.0
    out = []
    for L in lengths:
        t0, t1 = z / total, (z + L) / total
        at = lambda a, b, t: a if a == b else a + (b - a) * t  # noqa: E731
        ray = seg.get("rayleigh_damping", {})
        out.append(dict(L=L, odl=at(ol, orr, t0), odr=at(ol, orr, t1), idl=at(il, irr, t0),
                        idr=at(il, irr, t1), axial_force=seg.get("axial_force", 0.0),
                        torque=seg.get("torque", 0.0), alpha=ray.get("alpha", 0.0),
                        beta=ray.get("beta", 0.0)))
        z += L
    return out


def ross_elements(rotor):
    mats = materials(rotor)
    shaft, lengths = [], []
    for seg in rotor["shaft"]:
        c = seg.get("coupling")
        if c is not None:
            # ROSS's CouplingElement, isotropic; ROSS adds its C to the (nonrotating) C.
            ip = c.get("polar_inertia", [0.0, 0.0])
            tid = c.get("transverse_inertia", [ip[0] / 2, ip[1] / 2])
            kt, kr = c.get("translational_stiffness", 0.0), c.get("angular_stiffness", 0.0)
            ct, cr = c.get("translational_damping", 0.0), c.get("angular_damping", 0.0)
            shaft.append(rs.CouplingElement(
                n=len(shaft), m_l=c["mass"][0], m_r=c["mass"][1], Ip_l=ip[0], Ip_r=ip[1],
                Id_l=tid[0], Id_r=tid[1], kt_x=kt, kt_y=kt, kr_x=kr, kr_y=kr, ct_x=ct, ct_y=ct,
                cr_x=cr, cr_y=cr, L=seg["length"], o_d=seg["outer_diameter"]))
            lengths.append(seg["length"])
            continue
        n = seg.get("elements", 1)
        for kw in pieces(seg, [seg["length"] / n] * n):
            shaft.append(rs.ShaftElement(n=len(shaft), material=mats[seg["material"]], **kw))
            lengths.append(kw["L"])
    for s in rotor.get("sleeves", []):
        first, span = s["node"], s.get("elements", 1)
        for k, kw in enumerate(pieces(s, lengths[first:first + span])):
            shaft.append(rs.ShaftElement(n=first + k, material=mats[s["material"]], **kw))
    disks = [rs.DiskElement(n=d["node"], m=d["mass"], Id=d["transverse_inertia"], Ip=d["polar_inertia"])
             for d in rotor.get("disks", [])]
    bearings = []
    for s in rotor["supports"]:
        coeffs = {k: float(s.get(k, 0.0)) for k in g.COEFFS}
        bearings.append(rs.BearingElement(n=s["node"], **coeffs))
    return rs.Rotor(shaft, disks, bearings)


def case(name, description, rotor, speeds, unb):
    r = ross_elements(rotor)
    table, miss = [], 0.0
    for w in speeds:
        p, m = mch.poles(r, w)
        table.append(p)
        miss = max(miss, m)
    resp, worst = mch.unbalance(rotor, r, *unb)
    g.write(name, {"case": name, **g.COMMON, "description": description, "rotor": rotor,
                   "speeds": speeds, "poles": table, "unbalance_response": resp,
                   "checks": {"run_modal": miss, "unbalance": worst}})


STEEL = dict(g.STEEL)
BEARINGS = [
    {"node": 0, "kxx": 1.0e7, "kxy": 2.0e6, "kyx": -3.0e6, "kyy": 1.5e7, "cxx": 2.0e3, "cxy": 1.0e2,
     "cyx": 1.5e2, "cyy": 2.5e3},
    {"node": 10, "kxx": 1.2e7, "kxy": 1.5e6, "kyx": -2.5e6, "kyy": 1.8e7, "cxx": 2.2e3, "cxy": 1.2e2,
     "cyx": 1.0e2, "cyy": 2.8e3},
]
DISK = [{"node": 5, "mass": 32.6, "polar_inertia": 0.32, "transverse_inertia": 0.17}]
SPEEDS = [0.0, 300.0, 800.0, 1500.0, 3000.0]
UNB = [0.0, 100.0, 200.0, 300.0, 350.0, 400.0, 450.0, 500.0, 600.0, 800.0, 1000.0, 1500.0, 2000.0, 3000.0]


def tapered():
    """A shaft of three segments: a solid cone 40 -> 80 mm over 0.3 m (3 elements), a 80/20 mm
    tube over 0.6 m (4 elements), and a hollow cone 80/20 -> 50/10 mm over 0.3 m (3 elements);
    a disk at node 5 and two anisotropic cross-coupled bearings."""
    return {"type": "beam", "materials": {"steel": dict(STEEL)},
            "shaft": [
                {"length": 0.3, "outer_diameter": 0.04, "outer_diameter_right": 0.08,
                 "material": "steel", "elements": 3},
                {"length": 0.6, "outer_diameter": 0.08, "inner_diameter": 0.02, "material": "steel",
                 "elements": 4},
                {"length": 0.3, "outer_diameter": 0.08, "inner_diameter": 0.02,
                 "outer_diameter_right": 0.05, "inner_diameter_right": 0.01, "material": "steel",
                 "elements": 3}],
            "disks": DISK, "supports": BEARINGS}


def loaded():
    """A 60 mm shaft, 1.5 m, in three segments: 5 elements in tension 2e5 N with a torque of
    5e3 N m, 3 in compression 5e4 N with proportional damping alpha 3 1/s, beta 4e-5 s, 2 with
    alpha 1 1/s only (ROSS's C = alpha M + beta K: frame nonrotating)."""
    seg = lambda L, n: {"length": L, "outer_diameter": 0.06, "material": "steel", "elements": n}  # noqa: E731
    a, b, c = seg(0.75, 5), seg(0.45, 3), seg(0.3, 2)
    a.update(axial_force=2.0e5, torque=5.0e3)
    b.update(axial_force=-5.0e4, rayleigh_damping={"alpha": 3.0, "beta": 4.0e-5, "frame": "nonrotating"})
    c.update(rayleigh_damping={"alpha": 1.0, "beta": 0.0, "frame": "nonrotating"})
    return {"type": "beam", "materials": {"steel": dict(STEEL)}, "shaft": [a, b, c],
            "disks": DISK, "supports": BEARINGS}


def sleeved():
    """A 50 mm shaft, 1.5 m in 10 elements, with a steel sleeve 90/50 mm over nodes 3-6 (3
    elements, its matrices added) and a sleeve of 1 psi material (E = G_s = 6894.76 Pa:
    Poisson -0.5, mass without stiffness, as ROSS's compressor example's) over nodes 7-9."""
    psi = 6894.757
    return {"type": "beam",
            "materials": {"steel": dict(STEEL),
                          "soft": {"young_modulus": psi, "density": 7833.4, "poisson_ratio": -0.5,
                                   "loss_factor": 0.0}},
            "shaft": [{"length": 1.5, "outer_diameter": 0.05, "material": "steel", "elements": 10}],
            "sleeves": [
                {"node": 3, "elements": 3, "outer_diameter": 0.09, "inner_diameter": 0.05,
                 "material": "steel"},
                {"node": 7, "elements": 2, "outer_diameter": 0.12, "inner_diameter": 0.05,
                 "outer_diameter_right": 0.1, "material": "soft"}],
            "disks": DISK, "supports": BEARINGS}


def train(damped):
    """A train of three shafts on one axis joined by two flexible couplings: a 60 mm motor
    shaft of 0.8 m (6 elements, a 40 kg rotor core at node 3) on bearings at nodes 0 and 6, a
    coupling (0.12 m; kt 2e7 N/m, kr 8e4 N m/rad; halves 6 and 5 kg, Ip 0.03 and 0.025 kg m^2,
    Id 0.018 and 0.015 kg m^2), a 50 mm gearbox-like shaft of 0.6 m (4 elements, a 20 kg disk)
    on bearings at its ends, a second coupling (0.1 m; kt 1e7 N/m, kr 5e4 N m/rad; 4 and 4 kg,
    Ip 0.02 kg m^2 each, Id by ROSS's default, half Ip) and a 70 mm driven shaft of 1.0 m (8
    elements, two 30 kg impellers) on bearings at its ends: 20 elements, 21 nodes. The bearings
    are anisotropic and cross-coupled. With `damped`, the couplings have dampers too (ct 300 N
    s/m, cr 2 N m s/rad): ROSS adds them to the nonrotating C, Whirl turns them with the shaft,
    so at rest the two are the same and spun they differ by the circulatory stiffness
    of the rotating dampers."""
    def seg(L, d, n):
        return {"length": L, "outer_diameter": d, "material": "steel", "elements": n}
    c1 = {"translational_stiffness": 2.0e7, "angular_stiffness": 8.0e4, "mass": [6.0, 5.0],
          "polar_inertia": [0.03, 0.025], "transverse_inertia": [0.018, 0.015]}
    c2 = {"translational_stiffness": 1.0e7, "angular_stiffness": 5.0e4, "mass": [4.0, 4.0],
          "polar_inertia": [0.02, 0.02]}
    if damped:
        for c in (c1, c2):
            c.update(translational_damping=300.0, angular_damping=2.0)

    def bearing(node, k):
        return {"node": node, "kxx": k, "kxy": 0.1 * k, "kyx": -0.15 * k, "kyy": 1.4 * k,
                "cxx": 1.0e-4 * k, "cxy": 5.0e-6 * k, "cyx": 8.0e-6 * k, "cyy": 1.3e-4 * k}
    return {"type": "beam", "materials": {"steel": dict(STEEL)},
            "shaft": [seg(0.8, 0.06, 6),
                      {"length": 0.12, "outer_diameter": 0.14, "coupling": c1},
                      seg(0.6, 0.05, 4),
                      {"length": 0.1, "outer_diameter": 0.12, "coupling": c2},
                      seg(1.0, 0.07, 8)],
            "disks": [{"node": 3, "mass": 40.0, "polar_inertia": 0.4, "transverse_inertia": 0.25},
                      {"node": 9, "mass": 20.0, "polar_inertia": 0.15, "transverse_inertia": 0.09},
                      {"node": 15, "mass": 30.0, "polar_inertia": 0.3, "transverse_inertia": 0.17},
                      {"node": 18, "mass": 30.0, "polar_inertia": 0.3, "transverse_inertia": 0.17}],
            "supports": [bearing(0, 2.0e7), bearing(6, 2.0e7), bearing(7, 1.5e7),
                         bearing(11, 1.5e7), bearing(12, 3.0e7), bearing(20, 3.0e7)]}


def main():
    case("tapered.json", tapered.__doc__, tapered(), SPEEDS, (5, 1e-4, 0.0, UNB, [0, 2, 5, 8, 10]))
    case("loaded.json", loaded.__doc__, loaded(), SPEEDS, (5, 1e-4, 0.4, UNB, [0, 3, 5, 10]))
    case("sleeved.json", sleeved.__doc__, sleeved(), SPEEDS, (5, 1e-4, 0.0, UNB, [0, 4, 5, 8, 10]))
    case("train.json", train.__doc__, train(False), SPEEDS, (15, 1e-4, 0.0, UNB, [0, 3, 6, 7, 9, 12, 15, 20]))
    case("train_damped.json", train.__doc__, train(True), [0.0, 1500.0], (15, 1e-4, 0.0, [0.0], [3]))


if __name__ == "__main__":
    main()
