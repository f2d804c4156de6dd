#!/usr/bin/env python3
"""Whirl beside ROSS 2.3.0 and scipy, on the same rotor and speeds, in one run.

Not part of CI. Setup and run (from the repository root):

    python3 -m venv .venv && .venv/bin/pip install -r benches/requirements.txt
    cargo build --release --benches
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 .venv/bin/python benches/compare_ross.py

The rotor is the compressor example (examples/compressor-nvd.campbell.json: 100 Timoshenko
elements, 8 disks, 2 bearings) without its Guyan reduction, so that Whirl (202 complex dof) and
ROSS (606 real dof, 6 per node) model the same physics; bearing damping only (Whirl's `viscous`
model), as ROSS has no material loss. It compares:

1. Campbell, 100 speeds from 0 to 1500 rad/s: wall time (Whirl through HTTP, JSON included;
   ROSS `run_campbell`), and the first 8 lateral damped frequencies at every speed.
2. One dense complex eigendecomposition (values and vectors) of Whirl's own state matrix,
   Whirl (faer) against scipy (LAPACK zgeev), both on one thread.
3. 1 s of unbalance response at constant speed, 10,001 samples (Whirl `/v1/time-response`,
   ROSS `run_time_response`): wall time and the largest difference at 3 nodes.

Whirl runs on every core (its sweeps are parallel); ROSS and scipy on one thread, as pinned
above (ROSS gains little from threads at this size; scipy's single-thread time is the
reference the issue asks for).
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
import scipy.linalg

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "compressor-nvd.campbell.json"
SPEEDS = np.linspace(0.0, 1500.0, 100)
BOUND = 6000.0  # rad/s: Campbell branches below this
LATERAL = 8


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Whirl:
    """The release binary on a loopback port."""

    def __init__(self):
        self.port = free_port()
        binary = ROOT / "target" / "release" / "whirl"
        env = dict(os.environ, HOST="127.0.0.1", PORT=str(self.port), WHIRL_LOG_FORMAT="json")
        env.pop("OMP_NUM_THREADS", None)
        self.proc = subprocess.Popen([str(binary), "serve"], env=env, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)
        for _ in range(100):
            try:
                urllib.request.urlopen(f"http://127.0.0.1:{self.port}/healthz", timeout=1)
                return
            except OSError:
                time.sleep(0.1)
        raise RuntimeError("whirl did not start")

    def post(self, path, body):
        req = urllib.request.Request(f"http://127.0.0.1:{self.port}{path}",
                                     data=json.dumps(body).encode(),
                                     headers={"content-type": "application/json"})
        with urllib.request.urlopen(req, timeout=600) as r:
            return json.load(r)

    def timed(self, path, body, runs=3):
        best, out = float("inf"), None
        for _ in range(runs):
            t = time.perf_counter()
            out = self.post(path, body)
            best = min(best, time.perf_counter() - t)
        return best, out

    def close(self):
        self.proc.terminate()
        self.proc.wait()


def ross_rotor(rotor):
    import ross as rs

    mat = next(iter(rotor["materials"].values()))
    steel = rs.Material(name="whirl_steel", rho=mat["density"], E=mat["young_modulus"],
                        Poisson=mat["poisson_ratio"])
    shaft = []
    for seg in rotor["shaft"]:
        count = seg.get("elements", 1)
        for _ in range(count):
            shaft.append(rs.ShaftElement(L=seg["length"] / count, idl=seg.get("inner_diameter", 0.0),
                                         odl=seg["outer_diameter"], material=steel,
                                         shear_effects=True, rotary_inertia=True, gyroscopic=True))
    disks = [rs.DiskElement(n=d["node"], m=d["mass"], Id=d["transverse_inertia"], Ip=d["polar_inertia"])
             for d in rotor["disks"]]
    bearings = [rs.BearingElement(n=s["node"], kxx=s["stiffness"], cxx=s["damping"])
                for s in rotor["supports"]]
    return rs.Rotor(shaft, disks, bearings)


def whirl_frequencies(campbell):
    """Per speed, the LATERAL lowest |frequency| over all branches."""
    out = []
    for i in range(len(campbell["speeds"])):
        f = sorted(abs(b["frequency"][i]) for b in campbell["branches"] if b["frequency"][i] is not None)
        out.append(f[:LATERAL])
    return np.array(out)


def ross_frequencies(campbell):
    out = []
    for w in SPEEDS:
        modal = campbell.modal_results[w]
        f = sorted(wd for wd, s in zip(modal.wd, modal.shapes) if s.mode_type == "Lateral")
        out.append(f[:LATERAL])
    return np.array(out)


def eigen_matrix(whirl, rotor, speed, path):
    """Whirl's state matrix A0 + speed A1 (equivalent model: every matrix a sweep solves)."""
    d = whirl.post("/v1/damping", {"rotor": rotor, "damping": {"model": "equivalent"}, "form": "state"})
    a0, a1 = d["state"]["constant"], d["state"]["per_speed"]
    re = np.array(a0["re"]) + speed * np.array(a1["re"])
    im = np.array(a0["im"]) + speed * np.array(a1["im"])
    path.write_text(json.dumps({"re": re.tolist(), "im": im.tolist()}))
    return re + 1j * im


def whirl_eigen_ms(path):
    out = subprocess.run(["cargo", "bench", "-q", "--bench", "speed", "--", "--matrix", str(path)],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout
    line = next(l for l in out.splitlines() if l.startswith("eigen:"))
    return float(line.split()[1])


def best_of(runs, f):
    best = float("inf")
    for _ in range(runs):
        t = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t)
    return best


def main():
    example = json.loads(EXAMPLE.read_text())
    guyan = example["rotor"]
    rotor = {k: v for k, v in guyan.items() if k != "reduction"}
    whirl = Whirl()
    report = []
    try:
        print(f"machine: {os.cpu_count()} cores; ROSS and scipy on 1 thread, Whirl on all cores\n")

        # 1. Campbell
        body = {"rotor": rotor, "damping": {"model": "viscous"},
                "speeds": {"start": 0.0, "stop": 1500.0, "count": len(SPEEDS)}, "max_frequency": BOUND}
        t_whirl, camp = whirl.timed("/v1/campbell", body)
        red = camp.get("reduction")
        print(f"Whirl  Campbell, 100 speeds: {t_whirl:.3f} s"
              + (f" ({red['states']} states from {red['full_states']}, checked error "
                 f"{red['max_relative_error']:.1e})" if red else " (full model)"))
        t_full, camp_full = whirl.timed("/v1/campbell", dict(body, modal_reduction=False), runs=1)
        print(f"Whirl  Campbell, 100 speeds, full model (no modal reduction): {t_full:.3f} s")
        t_guyan, _ = whirl.timed("/v1/campbell", dict(body, rotor=guyan))
        print(f"Whirl  Campbell, 100 speeds, the example's Guyan model: {t_guyan:.3f} s")
        import ross as rs  # noqa: F401  (imported late: it takes seconds)

        model = ross_rotor(rotor)
        model.run_modal(0.0, num_modes=2 * (LATERAL + 2))  # warm-up (first call compiles caches)
        t = time.perf_counter()
        ross_camp = model.run_campbell(SPEEDS, frequencies=LATERAL)
        t_ross = time.perf_counter() - t
        print(f"ROSS   Campbell, 100 speeds: {t_ross:.3f} s")
        fw, fr = whirl_frequencies(camp), ross_frequencies(ross_camp)
        fwf = whirl_frequencies(camp_full)
        dev = np.max(np.abs(fw - fr) / fr)
        dev_full = np.max(np.abs(fwf - fr) / fr)
        report.append(("Campbell (a), 100 speeds", t_ross / t_whirl, 50.0))
        print(f"  first {LATERAL} lateral frequencies, every speed: largest relative difference "
              f"{dev:.2e} (full-model Whirl: {dev_full:.2e})")
        report.append(("  frequency agreement (max rel. diff, must be <= 1e-3)", dev, None))

        # 2. One eigendecomposition of Whirl's state matrix.
        tmp = ROOT / "target" / "compare"
        tmp.mkdir(parents=True, exist_ok=True)
        for name, r in [("Guyan", guyan), ("full", rotor)]:
            path = tmp / f"state-{name}.json"
            a = eigen_matrix(whirl, r, 1000.0, path)
            t_scipy = best_of(7, lambda: scipy.linalg.eig(a))
            t_faer = whirl_eigen_ms(path) / 1e3
            print(f"eigen {a.shape[0]} x {a.shape[0]} ({name} model at 1000 rad/s): Whirl {t_faer * 1e3:.1f} ms, "
                  f"scipy zgeev {t_scipy * 1e3:.1f} ms, ratio {t_faer / t_scipy:.2f}")
            report.append((f"eigen {a.shape[0]} states, Whirl/scipy (must be <= 1.3)", t_faer / t_scipy, None))

        # 3. Time response at constant speed.
        speed, amount, node = 1000.0, 1e-3, 45
        nodes = [10, 45, 90]
        body = {"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                "unbalances": [{"node": node, "amount": amount, "phase": 0.0, "from": 0.0}],
                "duration": 1.0, "output_interval": 1e-4, "nodes": nodes}
        t_whirl, tr = whirl.timed("/v1/time-response", body)
        print(f"Whirl  time response, 1 s, {len(tr['time'])} samples: {t_whirl:.3f} s ({tr['method']}, "
              f"{tr['states']} states)")
        t_axis = np.array(tr["time"])
        force = np.zeros((len(t_axis), model.ndof))
        f0 = amount * speed ** 2
        force[:, 6 * node] = f0 * np.cos(speed * t_axis)
        force[:, 6 * node + 1] = f0 * np.sin(speed * t_axis)
        t = time.perf_counter()
        ross_tr = model.run_time_response(speed, force, t_axis)
        t_ross = time.perf_counter() - t
        print(f"ROSS   time response: {t_ross:.3f} s")
        worst = 0.0
        for entry in tr["nodes"]:
            n = entry["node"]
            for k, key in enumerate(["x", "y"]):
                mine = np.array(entry[key])
                theirs = ross_tr.yout[:, 6 * n + k]
                worst = max(worst, np.max(np.abs(mine - theirs)) / np.max(np.abs(theirs)))
        # lsim holds the force linear between samples: for a sinusoid sampled at x = Omega dt
        # that scales the response by sinc(x/2)^2 = 1 - x^2/12 + ...
        x = speed * (t_axis[1] - t_axis[0])
        hold = 1.0 - (np.sin(x / 2) / (x / 2)) ** 2
        print(f"  largest difference at nodes {nodes}, relative to the peak: {worst:.2e}; "
              f"ROSS's first-order hold of the force accounts for {hold:.2e}")
        report.append(("time response (c), constant speed", t_ross / t_whirl, 50.0))
        report.append(("  response agreement (max diff / peak)", worst, None))
    finally:
        whirl.close()

    print("\nsummary")
    for name, value, target in report:
        if target is None:
            print(f"  {name}: {value:.3g}")
        else:
            print(f"  {name}: Whirl {value:.0f}x faster than ROSS (target {target:.0f}x)")


if __name__ == "__main__":
    sys.exit(main())
