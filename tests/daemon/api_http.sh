#!/bin/bash
# tlsphd's HTTP layer against hostile clients, through raw sockets
# (tests/support/raw_http.py): the token is checked on the headers, before any
# of the body is read; malformed requests are refused with problem+json and
# the connection closed; slow clients are closed at their deadlines, the
# default connection budgets keep room for a normal client while 5 addresses
# hold 64 slow connections each, and a reserve of connections is kept when
# slow clients fill the limit.
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

# --------------------------------------------------------- slow clients
# small deadlines (the defaults are 10 s and 120 s) so that the dribblers end
# soon; the connection limits are the defaults
start_daemon S "$TMP/data-slow" --header-timeout 2 --body-timeout 4 || exit 1
if $RAW slow "$(port_of "$S_URL")"; then ok "slow clients"; else fail "slow clients"; fi
req GET "$S_URL/healthz"
check "daemon up after the slow clients" [ "$STATUS" = 200 ]
check "the closes are logged" grep -q "closed .* slow connection(s)" "$S_LOG"
# a reserve of connections: when connections waiting for their headers fill
# connection_limit, the oldest are closed so that others can still connect
# (long deadlines and idle timeout here, so that only the reserve closes them)
start_daemon R "$TMP/data-reserve" --connection-limit 16 --per-ip-limit 16 --header-timeout 3600 \
    --connection-timeout 3600 || exit 1
if $RAW reserve "$(port_of "$R_URL")" 16; then ok "a reserve of connections"; else fail "a reserve of connections"; fi
# a complete request has no deadline: a long-poll outlasting header_timeout
# and body_timeout is answered (the job runs for longer than the wait)
strip_scene 2e-2 100 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/long.json"
LID=$(submit "$S_URL" "$TMP/long.json")
req GET "$S_URL/jobs/$LID?wait=6"
check "a 6 s long-poll under 2 s / 4 s deadlines is answered: $STATUS" [ "$STATUS" = 200 ]
req DELETE "$S_URL/jobs/$LID"

finish
