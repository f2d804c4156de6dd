"""Reads every request example into the openapi-python-client models of its request schema
and writes it back: the union variants are chosen right and nothing is lost (.ci/clients).

    python clients/roundtrip.py OPENAPI_JSON EXAMPLES_DIR GENERATED_CLIENT_DIR
"""

import importlib
import json
import pathlib
import sys

doc_path, examples_dir, client_dir = sys.argv[1:4]
doc = json.loads(pathlib.Path(doc_path).read_text())
sys.path.insert(0, client_dir)
package = next(p.parent.name for p in pathlib.Path(client_dir).glob("*/client.py"))
models = importlib.import_module(f"{package}.models")
REF = "#/components/schemas/"


def request_schema(path):
    media = doc["paths"][path]["post"]["requestBody"]["content"]["application/json"]
    return media["schema"]["$ref"].removeprefix(REF)


bodies = []
for f in sorted(pathlib.Path(examples_dir).glob("*.json")):
    endpoint = f.name.removesuffix(".json").rsplit(".", 1)[-1]
    bodies.append((f.name, request_schema(f"/v1/{endpoint}"), json.loads(f.read_text())))
for path, item in doc["paths"].items():
    media = item.get("post", {}).get("requestBody", {}).get("content", {}).get("application/json", {})
    if "example" in media:
        bodies.append((f"POST {path}", request_schema(path), media["example"]))

failed = 0
for what, schema, body in bodies:
    union = doc["components"]["schemas"][schema].get("discriminator")
    if union and not hasattr(models, schema):
        # A top-level union is a type alias in the client: its variant's model reads it.
        schema = union["mapping"][body[union["propertyName"]]].removeprefix(REF)
    model = getattr(models, schema, None)
    if model is None:
        print(f"roundtrip: {what}: no model {schema}")
        failed += 1
        continue
    try:
        back = model.from_dict(body).to_dict()
    except Exception as e:  # a refused valid body is the failure this looks for
        print(f"roundtrip: {what}: {schema}.from_dict failed: {e!r}")
        failed += 1
        continue
    if back != body:
        print(f"roundtrip: {what}: {schema} changed the body: {json.dumps(back)[:400]}")
        failed += 1
print(f"roundtrip: {len(bodies) - failed} of {len(bodies)} examples read and written back unchanged")
sys.exit(1 if failed else 0)
