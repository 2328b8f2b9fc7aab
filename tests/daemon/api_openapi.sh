#!/bin/bash
# The API definition (issue 13, item 17), read by tools that are not ours:
#   - schemas/openapi.json (served at /openapi.json) is one self-contained
#     document, made from schemas/openapi.src.json by schemas/bundle_openapi.py
#     (checked: the committed file is what the source makes);
#   - it is a valid OpenAPI 3.1 document by the OpenAPI Initiative's own JSON
#     Schema: @seriousme/openapi-schema-validator, pinned to 2.11.0 (npm;
#     deploy/install-deps.sh installs it in /opt/tlsph-test-tools, or
#     TLSPH_TEST_TOOLS).  It is the validator that refused the old document
#     ("Can't resolve study.schema.json#/$defs/summary, only internal refs are
#     supported").  Skipped, saying so, only when it is not installed;
#   - real answers of every documented operation (GET, its HEAD twin, POST,
#     DELETE; success and error states) are documented: status, content type,
#     JSON body valid against the documented schema (python3-jsonschema,
#     Debian 4.10.3-1, Draft 2020-12), headers; bearer auth is optional
#     (security [{}, {bearer: []}]) and 401 documented where a token is
#     needed (tests/daemon/openapi_responses.py);
#   - /conformance claims no oas30 (the document is OpenAPI 3.1).
. "$(dirname "$0")/common.sh"

check "schemas/openapi.json is what openapi.src.json makes (bundle_openapi.py --check)" \
    "$PY" "$top_srcdir/schemas/bundle_openapi.py" --check "$top_srcdir/schemas/openapi.src.json" "$top_srcdir/schemas/openapi.json"
check "the bundle has no reference outside itself" "$PY" -c "
import json, sys
refs = []
def walk(n):
    if isinstance(n, dict):
        for k, v in n.items():
            if k == '\$ref' and not v.startswith('#/'): refs.append(v)
            walk(v)
    elif isinstance(n, list):
        for v in n: walk(v)
walk(json.load(open(sys.argv[1])))
refs and print(refs[:5]); sys.exit(1 if refs else 0)" "$top_srcdir/schemas/openapi.json"

DATA=$TMP/data
start_daemon D "$DATA" --max-jobs 1 --kill-grace 1 || exit 1
curl -s -o "$TMP/served.json" "$D_URL/openapi.json"
check "GET /openapi.json serves the bundle" cmp -s "$TMP/served.json" "$top_srcdir/schemas/openapi.json"
req GET "$D_URL/conformance"
check "/conformance claims no oas30 (a 3.1 document)" [ "$(jget "$BODY" "any(c.endswith('/oas30') for c in d['conformsTo'])")" = False ]

TOOLS=${TLSPH_TEST_TOOLS:-/opt/tlsph-test-tools}
VALIDATOR=$TOOLS/node_modules/.bin/validate-api
PKG=$TOOLS/node_modules/@seriousme/openapi-schema-validator/package.json
if [ -x "$VALIDATOR" ] && command -v node >/dev/null 2>&1; then
    check "the validator is the pinned 2.11.0" [ "$(jget "$PKG" "d['version']")" = 2.11.0 ]
    node "$VALIDATOR" "$TMP/served.json" >"$TMP/validate.out" 2>&1
    check "openapi-schema-validator: the served document is valid OpenAPI 3.1" \
        grep -q '"valid": true' "$TMP/validate.out"
    cat "$TMP/validate.out" | head -5 | sed 's/^/# /'
else
    echo "# SKIP the OpenAPI 3.1 document check: @seriousme/openapi-schema-validator 2.11.0 is not installed in $TOOLS (bash deploy/install-deps.sh installs it)"
fi

"$PY" -c "
import json, sys
def load(p): return json.load(open(p))
print(json.dumps({'tiny': load(sys.argv[1])['inputs']['scene'], 'long': load(sys.argv[2])['inputs']['scene'],
                  'unstable': load(sys.argv[3])}))" \
    <(strip_scene 2e-4 2 tiny | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))") \
    <(strip_scene 2e-2 100 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))") \
    "$top_srcdir/tests/scenes/good/unstable.json" >"$TMP/scenes.json"

TOKEN=$(head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n')
printf '%s\n' "$TOKEN" >"$TMP/tokens"
chmod 600 "$TMP/tokens"
start_daemon A "$TMP/data-auth" --token-file "$TMP/tokens" || exit 1
"$PY" "$here/openapi_responses.py" "$D_URL" "$TMP/scenes.json" "$A_URL" "$TOKEN" >"$TMP/responses.out" 2>&1
rc=$?
cat "$TMP/responses.out"
check "every real answer is what the document says (openapi_responses.py)" [ "$rc" = 0 ]
finish
