// Writes one TypeScript file per request example, typed by its request schema, for
// `tsc --strict` (see .ci/clients): every file examples/<name>.<endpoint>.json (the body of
// POST /v1/<endpoint>) and every example inside the document (request bodies and schemas).
//
//   node clients/examples.mjs OPENAPI_JSON EXAMPLES_DIR OUT_DIR
// OUT_DIR gets whirl.d.ts beside it from openapi-typescript; the files import it as "./whirl".
import { readFileSync, readdirSync, writeFileSync, mkdirSync } from "node:fs";
import { join } from "node:path";

const [docPath, examplesDir, outDir] = process.argv.slice(2);
const doc = JSON.parse(readFileSync(docPath, "utf8"));
const REF = "#/components/schemas/";
mkdirSync(outDir, { recursive: true });

function requestSchema(path) {
  const ref = doc.paths?.[path]?.post?.requestBody?.content?.["application/json"]?.schema?.$ref;
  if (!ref?.startsWith(REF)) throw new Error(`POST ${path}: no JSON request schema`);
  return ref.slice(REF.length);
}

const files = [];
function write(file, schema, body) {
  const ts =
    `import type { components } from "./whirl";\n` +
    `export const body: components["schemas"][${JSON.stringify(schema)}] = ` +
    `${JSON.stringify(body, null, 2)};\n`;
  writeFileSync(join(outDir, file), ts);
  files.push(file);
}

const safe = (s) => s.replace(/[^A-Za-z0-9]+/g, "_");

for (const name of readdirSync(examplesDir).sort()) {
  if (!name.endsWith(".json")) continue;
  const stem = name.slice(0, -".json".length);
  const endpoint = stem.split(".").pop();
  const body = JSON.parse(readFileSync(join(examplesDir, name), "utf8"));
  write(`file_${safe(stem)}.ts`, requestSchema(`/v1/${endpoint}`), body);
}

let embedded = 0;
for (const [path, item] of Object.entries(doc.paths)) {
  const media = item.post?.requestBody?.content?.["application/json"];
  if (media?.example !== undefined) {
    write(`doc_body_${safe(path)}.ts`, requestSchema(path), media.example);
    embedded++;
  }
}
for (const [name, schema] of Object.entries(doc.components.schemas)) {
  (schema.examples ?? []).forEach((ex, i) => {
    write(`doc_schema_${safe(name)}_${i}.ts`, name, ex);
    embedded++;
  });
}
writeFileSync(
  join(outDir, "tsconfig.json"),
  JSON.stringify(
    {
      compilerOptions: {
        strict: true,
        noEmit: true,
        target: "ES2022",
        module: "ES2022",
        moduleResolution: "bundler",
        skipLibCheck: false,
      },
      files: ["whirl.d.ts", ...files],
    },
    null,
    2,
  ),
);
console.log(`examples.mjs: ${files.length} typed examples (${embedded} from the document)`);
if (embedded === 0) {
  console.error("examples.mjs: the document has no examples");
  process.exitCode = 1;
}
