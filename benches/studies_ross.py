#!/usr/bin/env python3
"""A study against ROSS 2.3.0's stochastic module on the same question, in one run.

The question is ROSS's own example (`ross.stochastic.st_rotor_example`): a 1.5 m steel shaft
(50 mm) with two disks (280/50 mm, 70 mm wide) on two bearings, the first bearing's stiffness
scattered (uniform 1e6 - 2e6 N/m; the second 1.5e6 N/m, both 1500 N s/m); how do the six lowest
whirl frequencies of its Campbell diagram (0 - 500 rad/s, 11 speeds) scatter? The mesh is
refined to ELEMENTS elements so that each sample is a real analysis.

ROSS: `ST_Rotor(...).run_campbell(speeds, frequencies=6)`, one rotor per sample, in one Python
process on one thread. Whirl: one study (`/v1/studies`, design `grid` over the very same stiffness
values, so that every sample can be compared), `campbell` with `modes: 6`, outputs the six
branches' frequencies at the last speed; the time from POST to the result fetched. The lowest
lateral frequency of the first few samples is compared with ROSS's per-rotor Campbell (its
lateral modes, as benches/compare_ross.py reads them).

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python benches/studies_ross.py [SAMPLES]

(default 100 samples; WHIRL_BIN names the server binary, default target/release/whirl).
"""

import json
import os
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
ELEMENTS = 24
SPEEDS = np.linspace(0.0, 500.0, 11)
RHO, E, NU = 7810.0, 211e9, 0.3
K1, C = 1.5e6, 1500.0
CHECKED = 5  # samples whose frequencies are compared one by one


def disk(node):
    D, d, w = 0.28, 0.05, 0.07
    m = RHO * np.pi / 4 * (D**2 - d**2) * w
    ip = m / 8 * (D**2 + d**2)
    return {"node": node, "mass": m, "polar_inertia": ip, "transverse_inertia": ip / 2 + m * w**2 / 12}


def rotor(k0):
    per = ELEMENTS // 6
    return {
        "type": "beam",
        "materials": {"steel": {"young_modulus": E, "density": RHO, "poisson_ratio": NU}},
        "shaft": [{"length": 1.5, "outer_diameter": 0.05, "material": "steel", "elements": ELEMENTS}],
        "disks": [disk(2 * per), disk(4 * per)],
        "supports": [{"node": 0, "stiffness": k0, "damping": C},
                     {"node": ELEMENTS, "stiffness": K1, "damping": C}],
    }


class Server:
    def __init__(self):
        s = socket.socket()
        s.bind(("127.0.0.1", 0))
        self.port = s.getsockname()[1]
        s.close()
        binary = os.environ.get("WHIRL_BIN", str(ROOT / "target" / "release" / "whirl"))
        env = dict(os.environ, HOST="127.0.0.1", PORT=str(self.port), WHIRL_LOG_FORMAT="json",
                   WHIRL_DATA_DIR=f"/tmp/whirl-studies-ross-{self.port}")
        env.pop("OMP_NUM_THREADS", None)
        self.proc = subprocess.Popen([binary, "serve"], env=env, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)
        for _ in range(100):
            try:
                urllib.request.urlopen(self.url("/healthz"), timeout=1)
                return
            except OSError:
                time.sleep(0.1)
        raise RuntimeError("whirl did not start")

    def url(self, path):
        return f"http://127.0.0.1:{self.port}{path}"

    def call(self, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.url(path), data=data,
                                     headers={"content-type": "application/json"})
        with urllib.request.urlopen(req, timeout=600) as r:
            return json.load(r)

    def close(self):
        self.proc.terminate()
        self.proc.wait()


def whirl_study(server, ks):
    body = {
        "analysis": "campbell",
        "input": {"rotor": rotor(float(ks[0])), "damping": {"model": "viscous"},
                  "speeds": SPEEDS.tolist(), "modes": 6},
        "parameters": [{"pointer": "/rotor/supports/0/stiffness", "values": [float(k) for k in ks]}],
        "design": "grid",
        "outputs": [f"/branches/{j}/frequency/{len(SPEEDS) - 1}" for j in range(6)],
    }
    t = time.perf_counter()
    study = server.call("/v1/studies", body)
    while server.call(f"/v1/studies/{study['id']}")["status"] in ("queued", "running"):
        time.sleep(0.02)
    result = server.call(f"/v1/studies/{study['id']}/result")
    return time.perf_counter() - t, result


def ross_side(ks):
    import ross as rs
    from ross.stochastic import ST_BearingElement, ST_Rotor

    steel = rs.Material(name="whirl_steel", rho=RHO, E=E, Poisson=NU)
    shaft = [rs.ShaftElement(L=1.5 / ELEMENTS, idl=0.0, odl=0.05, material=steel, shear_effects=True,
                             rotary_inertia=True, gyroscopic=True) for _ in range(ELEMENTS)]
    disks = [rs.DiskElement(n=d["node"], m=d["mass"], Id=d["transverse_inertia"], Ip=d["polar_inertia"])
             for d in rotor(1.0)["disks"]]
    b0 = ST_BearingElement(n=0, kxx=np.asarray(ks), cxx=C, is_random=["kxx"])
    b1 = rs.BearingElement(n=ELEMENTS, kxx=K1, cxx=C)
    st = ST_Rotor(shaft, disks, [b0, b1])
    t = time.perf_counter()
    st.run_campbell(SPEEDS, frequencies=6)
    elapsed = time.perf_counter() - t
    # The lowest lateral whirl frequency at the last speed of the first samples.
    lowest = []
    for r in list(iter(st))[:CHECKED]:
        modal = r.run_modal(SPEEDS[-1], num_modes=24)
        lateral = sorted(abs(wd) for wd, s in zip(modal.wd, modal.shapes) if s.mode_type == "Lateral")
        lowest.append(lateral[0])
    return elapsed, lowest


def main():
    samples = int(sys.argv[1]) if len(sys.argv) > 1 else 100
    ks = np.random.default_rng(2026).uniform(1e6, 2e6, samples)
    server = Server()
    try:
        server.call("/v1/campbell", {"rotor": rotor(1.5e6), "damping": {"model": "viscous"},
                                     "speeds": SPEEDS.tolist(), "modes": 6})  # warm-up
        t_w, result = whirl_study(server, ks)
    finally:
        server.close()
    t_r, ross_lowest = ross_side(ks)
    outs = result["samples"]
    failed = [s for s in outs if s["status"] != "succeeded"]
    whirl_lowest = [min(abs(x) for x in s["outputs"] if x is not None) for s in outs]
    err = max(abs(a - b) / b for a, b in zip(whirl_lowest, ross_lowest))
    first = result["summary"][0]
    print(f"{samples} samples, {ELEMENTS} elements, {len(SPEEDS)} speeds, 6 frequencies")
    print(f"Whirl study: {t_w:.2f} s ({1e3 * t_w / samples:.1f} ms a sample), {len(failed)} failed")
    print(f"ROSS ST_Rotor.run_campbell: {t_r:.2f} s ({1e3 * t_r / samples:.1f} ms a sample)")
    print(f"ratio: {t_r / t_w:.1f}x")
    print(f"lowest lateral frequency at {SPEEDS[-1]:.0f} rad/s, first {CHECKED} samples: "
          f"Whirl vs ROSS within {err:.1e}")
    print(f"branch 1 (mode 1 forward) frequency at {SPEEDS[-1]:.0f} rad/s over the samples: mean {first['mean']:.4f}, "
          f"std {first['std']:.4f}, p5 {first['p5']:.4f}, p95 {first['p95']:.4f} rad/s")


if __name__ == "__main__":
    main()
