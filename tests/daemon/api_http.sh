#!/bin/bash
# tlsphd's HTTP layer against hostile clients, through raw sockets
# (tests/support/raw_http.py): the token is checked on the headers, before any
# of the body is read; malformed requests are refused with problem+json and
# the connection closed.
. "$(dirname "$0")/common.sh"
RAW="$PY $top_srcdir/tests/support/raw_http.py"
port_of() { echo "${1##*:}"; }

# --------------------------------------------------------- auth before body
TOKEN=http-test-token-$(head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n')
printf '%s\n' "$TOKEN" >"$TMP/tokens"
chmod 600 "$TMP/tokens"
start_daemon A "$TMP/data-auth" --token-file "$TMP/tokens" || exit 1
if $RAW auth-before-body "$(port_of "$A_URL")" "$A_PID"; then ok "auth before body"; else fail "auth before body"; fi
req GET "$A_URL/healthz"
check "daemon up after the uploads" [ "$STATUS" = 200 ]

# --------------------------------------------------------- malformed requests
start_daemon M "$TMP/data-malformed" || exit 1
if $RAW malformed "$(port_of "$M_URL")"; then ok "malformed requests"; else fail "malformed requests"; fi
req GET "$M_URL/healthz"
check "daemon up after the malformed requests" [ "$STATUS" = 200 ]

finish
