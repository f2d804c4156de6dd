"""Calls the running server through openapi-generator's python client (.ci/clients).

    PYTHONPATH=<generated> python python_generator.py URL EXAMPLES_DIR

The same calls as python_opc.py.
"""

import json
import pathlib
import sys
import time

import whirl_client
from whirl_client import models

url, examples = sys.argv[1], pathlib.Path(sys.argv[2])


def example(name):
    return json.loads((examples / name).read_text())


with whirl_client.ApiClient(whirl_client.Configuration(host=url)) as api:
    analyses = whirl_client.AnalysesApi(api)
    jobs = whirl_client.JobsApi(api)

    c = analyses.campbell(models.SweepRequest.from_dict(example("jeffcott-nvd.campbell.json")))
    assert isinstance(c, models.CampbellResponse), type(c)
    speeds = [round(w, 6) for w in c.critical_speeds]
    print(f"python (openapi-generator): campbell critical speeds {speeds}")

    body = models.UnbalanceResponseRequest.from_dict(example("example1-nvd.unbalance-response.json"))
    u = analyses.unbalance_response(body)
    assert isinstance(u, models.UnbalanceResponseResponse), type(u)
    peaks = [p for n in u.nodes if isinstance(n.peaks, list) for p in n.peaks]
    assert peaks, "no peak"
    peak = max(peaks, key=lambda p: p.amplitude)
    print(f"python (openapi-generator): unbalance peak {peak.amplitude:.4g} m at {peak.speed:.1f} rad/s")

    request = models.JobRequest.from_dict({"analysis": "campbell", "input": example("jeffcott-nvd.campbell.json")})
    info = jobs.submit_job(request)
    status = info.status
    while status in ("queued", "running"):
        time.sleep(0.05)
        status = jobs.get_job(info.id).status
    assert status == "succeeded", status
    r = jobs.job_result(info.id).actual_instance
    assert isinstance(r, models.CampbellResult), type(r)
    assert [round(w, 6) for w in r.critical_speeds] == speeds
    print(f"python (openapi-generator): job {info.id} -> {type(r).__name__}, same critical speeds")
