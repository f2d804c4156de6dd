"""Schemathesis hooks for .ci/fuzz (SCHEMATHESIS_HOOKS=fuzz_hooks, with .ci on PYTHONPATH).

`POST /v1/convert/ross` takes a ROSS rotor file as `application/toml`, a media type
schemathesis has no serializer for: its generated bodies (strings or bytes) go on the wire as
they are, so the fuzz reaches the endpoint with arbitrary text.
"""

import schemathesis


@schemathesis.serializer("application/toml")
def toml_body(ctx, value):
    if value is None:
        return None
    if isinstance(value, bytes):
        return value
    return str(value).encode("utf-8")
