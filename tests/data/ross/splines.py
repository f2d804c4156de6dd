#!/usr/bin/env python3
"""scipy's values of the interpolation ROSS 2.3.0 applies to a tabulated bearing coefficient
(bearing_seal_element.py: UnivariateSpline(frequency, values) for 4 points or more, else
interp1d(kind=len - 1, fill_value="extrapolate")), for src/model/spline.rs's tests.

Rerun (from the repository root):

    .venv/bin/python tests/data/ross/splines.py

Each case: the table (x, y), the points `at` (inside and outside the table) and scipy's values
there; for splines also the knots and coefficients (`t`, `c`) and the residual `fp`.
"""

import json
from pathlib import Path

import numpy as np
import scipy
from scipy import interpolate

rng = np.random.default_rng(29)


def case(name, x, y):
    x, y = np.asarray(x, float), np.asarray(y, float)
    lo, hi = x[0], x[-1]
    at = np.concatenate([np.linspace(lo - 0.3 * (hi - lo), hi + 0.3 * (hi - lo), 41), x,
                         0.5 * (x[1:] + x[:-1])])
    out = {"name": name, "x": x.tolist(), "y": y.tolist(), "at": at.tolist()}
    if len(x) >= 4:
        sp = interpolate.UnivariateSpline(x, y)
        t, c, k = sp._eval_args
        out.update(kind="spline", t=list(map(float, t)), c=list(map(float, c[:len(t)])),
                   fp=float(sp.get_residual()), values=sp(at).tolist())
    else:
        f = interpolate.interp1d(x, y, kind=len(x) - 1, fill_value="extrapolate")
        out.update(kind="interp1d", values=f(at).tolist())
    return out


def main():
    cases = []
    w = np.array([200.0, 600.0, 1000.0, 1500.0, 2500.0])
    cases.append(case("5 kinked (speed_dependent.json's kxx)", w, [1.0e6, 1.6e6, 1.4e6, 2.2e6, 2.0e6]))
    cases.append(case("4 points", w[:4], [3.0, -1.0, 2.0, 5.0]))
    cases.append(case("2 points", [100.0, 300.0], [2.0e6, 2.6e6]))
    cases.append(case("3 points", [100.0, 300.0, 700.0], [2.0e6, 2.6e6, 2.1e6]))
    x = np.linspace(100.0, 1000.0, 10)
    cases.append(case("10 smooth", x, 1e7 * (1 + 0.3 * np.sin(x / 300.0))))
    x = np.linspace(50.0, 3500.0, 70)
    cases.append(case("70 plain-bearing-like", x, 5e7 * (x / 1000.0) ** 0.6 + 1e5 * rng.standard_normal(70)))
    cases.append(case("70 small cross terms", x, 2.0 + 0.5 * np.cos(x / 500.0)))
    x = np.linspace(0.0, 6000.0, 300)
    cases.append(case("300 noisy negative", x, -3e3 + 1e3 * np.sin(x / 900.0) + 50 * rng.standard_normal(300)))
    cases.append(case("12 noisy unit scale", np.arange(12.0), rng.standard_normal(12)))
    path = Path(__file__).resolve().parent / "splines.json"
    path.write_text(json.dumps({"scipy": scipy.__version__, "cases": cases}, indent=0) + "\n")
    print(f"wrote {path} ({path.stat().st_size // 1024} kB)")


if __name__ == "__main__":
    main()
