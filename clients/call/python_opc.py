"""Calls the running server through openapi-python-client's generated client (.ci/clients).

    PYTHONPATH=<generated> python python_opc.py URL EXAMPLES_DIR

A Campbell diagram and an unbalance response synchronously, then a job submitted, polled and
its result read back: the result must come typed as the Campbell answer (the `JobResult`
union picks it by `analysis`) and equal the synchronous one.
"""

import json
import pathlib
import sys
import time

from whirl_client import Client
from whirl_client.api.analyses import campbell, unbalance_response
from whirl_client.api.jobs import get_job, job_result, submit_job
from whirl_client import models

url, examples = sys.argv[1], pathlib.Path(sys.argv[2])
client = Client(base_url=url, timeout=120)


def example(name):
    return json.loads((examples / name).read_text())


sweep = models.SweepRequest.from_dict(example("jeffcott-nvd.campbell.json"))
c = campbell.sync(client=client, body=sweep)
assert type(c).__name__ == "CampbellResponse", type(c)
speeds = [round(w, 6) for w in c.critical_speeds]
print(f"python (openapi-python-client): campbell critical speeds {speeds}")

unbalance = models.UnbalanceResponseRequest.from_dict(example("example1-nvd.unbalance-response.json"))
u = unbalance_response.sync(client=client, body=unbalance)
assert type(u).__name__ == "UnbalanceResponseResponse", type(u)
peaks = [p for n in u.nodes if isinstance(n.peaks, list) for p in n.peaks]
assert peaks, "no peak"
peak = max(peaks, key=lambda p: p.amplitude)
print(f"python (openapi-python-client): unbalance peak {peak.amplitude:.4g} m at {peak.speed:.1f} rad/s")

job = models.CampbellJob.from_dict({"analysis": "campbell", "input": example("jeffcott-nvd.campbell.json")})
info = submit_job.sync(client=client, body=job)
assert type(info).__name__ == "JobInfo", info
status = info.status
while status in ("queued", "running"):
    time.sleep(0.05)
    status = get_job.sync(client=client, id=info.id).status
assert status == "succeeded", status
r = job_result.sync(client=client, id=info.id)
assert type(r).__name__ == "CampbellResult", type(r)
assert [round(w, 6) for w in r.critical_speeds] == speeds
print(f"python (openapi-python-client): job {info.id} -> {type(r).__name__}, same critical speeds")
