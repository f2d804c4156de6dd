// Calls the running server through openapi-generator's typescript-fetch client (.ci/clients):
// a Campbell diagram and an unbalance response, then a job submitted, polled and its result
// read back as the Campbell answer (`JobResult` is a union on `analysis`).
//
//   node main.js URL EXAMPLES_DIR   (compiled by tsc --strict, CommonJS, next to the client)

import {
  AnalysesApi,
  Configuration,
  JobsApi,
  JobRequestFromJSON,
  SweepRequestFromJSON,
  UnbalanceResponseRequestFromJSON,
} from "../openapi-generator-typescript-fetch/index";

declare const process: { argv: string[]; exit(code: number): never };
declare function require(name: string): any;
const fs = require("fs");

const [url, examples] = process.argv.slice(2);
const example = (name: string): unknown =>
  JSON.parse(fs.readFileSync(`${examples}/${name}`, "utf8"));
const round = (xs: number[]) => xs.map((x) => Math.round(x * 1e6) / 1e6);

async function main(): Promise<void> {
  const config = new Configuration({ basePath: url });
  const analyses = new AnalysesApi(config);
  const jobs = new JobsApi(config);

  const c = await analyses.campbell({
    sweepRequest: SweepRequestFromJSON(example("jeffcott-nvd.campbell.json")),
  });
  const speeds = round(c.criticalSpeeds);
  console.log(`typescript-fetch: campbell critical speeds ${JSON.stringify(speeds)}`);

  const u = await analyses.unbalanceResponse({
    unbalanceResponseRequest: UnbalanceResponseRequestFromJSON(
      example("example1-nvd.unbalance-response.json"),
    ),
  });
  const peaks = u.nodes.flatMap((n) => n.peaks ?? []);
  if (peaks.length === 0) throw new Error("no peak");
  const peak = peaks.reduce((a, b) => (b.amplitude > a.amplitude ? b : a));
  console.log(
    `typescript-fetch: unbalance peak ${peak.amplitude.toPrecision(4)} m at ${peak.speed.toFixed(1)} rad/s`,
  );

  const info = await jobs.submitJob({
    jobRequest: JobRequestFromJSON({
      analysis: "campbell",
      input: example("jeffcott-nvd.campbell.json"),
    }),
  });
  let status: string = info.status;
  while (status === "queued" || status === "running") {
    await new Promise((r) => setTimeout(r, 50));
    status = (await jobs.getJob({ id: info.id })).status;
  }
  if (status !== "succeeded") throw new Error(`job ${info.id}: ${status}`);
  const r = await jobs.jobResult({ id: info.id });
  if (r.analysis !== "campbell") throw new Error(`a ${r.analysis} result`);
  if (JSON.stringify(round(r.criticalSpeeds)) !== JSON.stringify(speeds)) {
    throw new Error(`job result ${r.criticalSpeeds} differs from ${speeds}`);
  }
  console.log(`typescript-fetch: job ${info.id} -> ${r.analysis} result, same critical speeds`);
}

main().catch((e) => {
  console.error("typescript-fetch:", e);
  process.exit(1);
});
