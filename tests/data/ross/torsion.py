#!/usr/bin/env python3
"""ROSS 2.3.0 references for torsional and axial motion: machines saved by ROSS's own
`Rotor.save()` with 6 dof per node, and ROSS's poles of each motion on the rotor it loads back.

Rerun (from the repository root, a few seconds):

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python3 tests/data/ross/torsion.py

It rewrites tests/data/ross/torsion/<name>.toml (the file `Rotor.save` wrote) and
tests/data/ross/torsion/<name>.json. tests/it/train_ross.rs posts each TOML to
`/v1/convert/ross`, runs `/v1/modal` with `motion` torsional, axial and lateral on the converted
rotor and compares every pole with these.

Poles: `rotor.run_modal(W, sparse=False)` on `rs.Rotor.load(<name>.toml)`; each eigenvalue is
classed by where its eigenvector lives (`evectors[:ndof]`, 6 dofs per node: x, y, z, alpha,
beta, theta): `torsional` if more than half of |v|^2 is on theta, `axial` if on z, else
`lateral`. Only poles with Im s >= 0 are kept for torsional and axial (their conjugates are the
same motion); all lateral ones. ROSS leaves out a free train's rigid turning (its two zero
eigenvalues). Stored [re, im]; compare as sets, relative to max(|s|, 1).

Machines
--------
* `rotor_example_6dof`: ROSS's own `rotor_example_6dof()` (6 Euler-Bernoulli elements without
  rotary inertia, 2 disks, bearings with kzz = 1e5 N/m, undamped), speeds 0, 500, 1000 rad/s.
* `damped_train`: two steel shafts (5 and 4 elements, 60 and 45 mm) joined by a
  `CouplingElement` with torsional kr_z = 4e4 N m/rad, cr_z = 15 N m s/rad, axial
  kt_z = 2e7 N/m, ct_z = 400 N s/m (lateral kt = 1e7, kr = 1e4), three disks, four bearings
  (kxx = kyy = 2e7, cxx = cyy = 2e3) of which the first has kzz = 5e7 N/m, czz = 3e3 N s/m;
  speeds 0 and 800 rad/s. Its log decrements are -2 pi Re s / |Im s|.
"""

import json
from pathlib import Path

import numpy as np
import ross as rs

HERE = Path(__file__).resolve().parent / "torsion"


def damped_train():
    steel = rs.Material(name="Steel", rho=7810, E=211e9, G_s=81.2e9)
    a = [rs.ShaftElement(L=0.2, idl=0.0, odl=0.06, material=steel) for _ in range(5)]
    b = [rs.ShaftElement(L=0.2, idl=0.0, odl=0.045, material=steel) for _ in range(4)]
    coupling = rs.CouplingElement(
        n=5, m_l=3.0, m_r=2.5, Ip_l=0.02, Ip_r=0.015,
        kt_x=1e7, kt_y=1e7, kt_z=2e7, kr_x=1e4, kr_y=1e4, kr_z=4e4,
        ct_z=400.0, cr_z=15.0, L=0.1, o_d=0.12,
    )
    disks = [
        rs.DiskElement(n=2, m=20.0, Id=0.12, Ip=0.22),
        rs.DiskElement(n=8, m=12.0, Id=0.06, Ip=0.1),
        rs.DiskElement(n=10, m=8.0, Id=0.04, Ip=0.07),
    ]
    bearings = [
        rs.BearingElement(n=0, kxx=2e7, kyy=2e7, cxx=2e3, cyy=2e3, kzz=5e7, czz=3e3),
        rs.BearingElement(n=4, kxx=2e7, kyy=2e7, cxx=2e3, cyy=2e3),
        rs.BearingElement(n=7, kxx=2e7, kyy=2e7, cxx=2e3, cyy=2e3),
        rs.BearingElement(n=10, kxx=2e7, kyy=2e7, cxx=2e3, cyy=2e3),
    ]
    return rs.Rotor(a + [coupling] + b, disks, bearings)


MACHINES = {
    "rotor_example_6dof": (rs.rotor_example_6dof, [0.0, 500.0, 1000.0]),
    "damped_train": (damped_train, [0.0, 800.0]),
}


def classify(rotor, w):
    m = rotor.run_modal(w, sparse=False)
    nd = rotor.number_dof
    ev = m.evectors[: rotor.ndof, :]
    out = {"torsional": [], "axial": [], "lateral": []}
    for i, s in enumerate(m.evalues):
        v = np.abs(ev[:, i]) ** 2
        t, z = v[5::nd].sum() / v.sum(), v[2::nd].sum() / v.sum()
        kind = "torsional" if t > 0.5 else "axial" if z > 0.5 else "lateral"
        if kind != "lateral" and s.imag < 0:
            continue
        out[kind].append([float(s.real), float(s.imag)])
    for k in out:
        out[k].sort(key=lambda p: (p[1], p[0]))
    return out


def main():
    HERE.mkdir(exist_ok=True)
    for name, (make, speeds) in MACHINES.items():
        path = HERE / f"{name}.toml"
        make().save(str(path))
        rotor = rs.Rotor.load(str(path))
        poles = [{"speed": w, **classify(rotor, w)} for w in speeds]
        doc = {"toml": f"{name}.toml", "ross": rs.__version__, "poles": poles}
        (HERE / f"{name}.json").write_text(json.dumps(doc, indent=1) + "\n")
        print(name, {k: len(v) for k, v in poles[0].items() if k != "speed"})


if __name__ == "__main__":
    main()
