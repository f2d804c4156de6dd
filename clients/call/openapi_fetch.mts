// Calls the running server through openapi-fetch with openapi-typescript's types
// (.ci/clients). `createClient<paths, "application/json">` types each body as its JSON schema
// (without the media type, a body that may also be CSV or SVG is `X | string`); the
// assignments below do not compile if it is not.
//
//   node main.mjs URL EXAMPLES_DIR   (compiled by tsc --strict)

import createClient from "openapi-fetch";
import type { components, paths } from "./whirl.js";

declare const process: { argv: string[]; exit(code: number): never };
const { readFileSync } = (await import("node:fs" as string)) as {
  readFileSync(path: string, encoding: string): string;
};

type Schemas = components["schemas"];
const [url, examples] = process.argv.slice(2);
const example = <T,>(name: string): T =>
  JSON.parse(readFileSync(`${examples}/${name}`, "utf8")) as T;
const round = (xs: number[]) => xs.map((x) => Math.round(x * 1e6) / 1e6);
const whirl = createClient<paths, "application/json">({ baseUrl: url });

const sweep = example<Schemas["SweepRequest"]>("jeffcott-nvd.campbell.json");
const c = await whirl.POST("/v1/campbell", { body: sweep });
if (!c.data) throw new Error(`campbell: ${JSON.stringify(c.error)}`);
const campbell: Schemas["CampbellResponse"] = c.data;
const speeds = round(campbell.critical_speeds);
console.log(`openapi-fetch: campbell critical speeds ${JSON.stringify(speeds)}`);

const unbalance = example<Schemas["UnbalanceResponseRequest"]>("example1-nvd.unbalance-response.json");
const u = await whirl.POST("/v1/unbalance-response", { body: unbalance });
if (!u.data) throw new Error(`unbalance: ${JSON.stringify(u.error)}`);
const response: Schemas["UnbalanceResponseResponse"] = u.data;
const peaks = response.nodes.flatMap((n) => n.peaks ?? []);
if (peaks.length === 0) throw new Error("no peak");
const peak = peaks.reduce((a, b) => (b.amplitude > a.amplitude ? b : a));
console.log(`openapi-fetch: unbalance peak ${peak.amplitude.toPrecision(4)} m at ${peak.speed.toFixed(1)} rad/s`);

const submitted = await whirl.POST("/v1/jobs", { body: { analysis: "campbell", input: sweep } });
if (!submitted.data) throw new Error(`submit: ${JSON.stringify(submitted.error)}`);
const id = submitted.data.id;
let status: Schemas["JobStatus"] = submitted.data.status;
while (status === "queued" || status === "running") {
  await new Promise((r) => setTimeout(r, 50));
  const polled = await whirl.GET("/v1/jobs/{id}", { params: { path: { id } } });
  if (!polled.data) throw new Error(`poll: ${JSON.stringify(polled.error)}`);
  status = polled.data.status;
}
if (status !== "succeeded") throw new Error(`job ${id}: ${status}`);
const r = await whirl.GET("/v1/jobs/{id}/result", { params: { path: { id } } });
if (!r.data) throw new Error(`result: ${JSON.stringify(r.error)}`);
const result: Schemas["JobResult"] = r.data;
if (result.analysis !== "campbell") throw new Error(`a ${result.analysis} result`);
const typed: Schemas["CampbellResult"] = result;
if (JSON.stringify(round(typed.critical_speeds)) !== JSON.stringify(speeds)) {
  throw new Error(`job result ${typed.critical_speeds} differs from ${speeds}`);
}
console.log(`openapi-fetch: job ${id} -> ${result.analysis} result, same critical speeds`);
