# Shared by the client tests that run against tests/client/fake_results.py
# (a stand-in for tlsphd's result endpoints with data of known shape).
# Sources tests/daemon/common.sh (check, finish, $TMP, $PY); sets CLIENT (the
# client under test: $TLSPH_CLIENT, else the built one), FAKE_URL and FID (a
# job id the fake server answers for), and the helpers cl, rc_is.
. "$(cd "$(dirname "$0")/.." && pwd)/daemon/common.sh"

CLIENT=${TLSPH_CLIENT:-$top_builddir/tlsph}
[ -x "$CLIENT" ] || { echo "FAIL: $CLIENT not built"; exit 1; }
cl() { ${CLIENT_WRAPPER:-} "$CLIENT" "$@" >"$TMP/out" 2>"$TMP/err"; RC=$?; }
rc_is() { [ "$RC" = "$1" ] || { echo "# exit code $RC, wanted $1; stderr:"; sed 's/^/#   /' "$TMP/err"; return 1; }; }
export XDG_CONFIG_HOME=$TMP/xdg HOME=$TMP/home
unset TLSPH_URL TLSPH_TOKEN

"$PY" "$top_srcdir/tests/client/fake_results.py" "$top_srcdir/schemas" "$TMP/fake.port" 2>"$TMP/fake.log" &
DAEMON_PIDS="$DAEMON_PIDS $!" # stopped with the daemons at exit
FAKE_PID=$!
# a hang detector, not a deadline: the server writes its port once it listens
for _ in $(seq 3000); do
    [ -s "$TMP/fake.port" ] && break
    kill -0 "$FAKE_PID" 2>/dev/null || { echo "FAIL: fake server died"; cat "$TMP/fake.log"; exit 1; }
    sleep 0.1
done
[ -s "$TMP/fake.port" ] || { echo "FAIL: fake server did not start"; exit 1; }
FAKE_URL=http://127.0.0.1:$(cat "$TMP/fake.port")
export TLSPH_URL=$FAKE_URL
FID=0123456789abcdef0123456789abcdef
