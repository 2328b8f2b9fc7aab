#!/usr/bin/env bash
# The main job: install dependencies, build, start the daemon tlsphd with its
# embedded defaults (127.0.0.1:8080, data under $XDG_STATE_HOME/tlsphd or
# ./tlsphd-data), submit an example scene with curl, wait for it, fetch
# result.h5 and result.xmf by job id and print where they are with a summary.
#
# usage: bash deploy/quickstart.sh [SCENE.json] [OUTPUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-examples/elastic-strip.json}
out=${2:-results/$(basename "$scene" .json)}
url=http://127.0.0.1:8080
bash deploy/install-deps.sh
bash deploy/build.sh

if curl -sf "$url/healthz" >/dev/null 2>&1; then
  echo "quickstart: something already listens on $url; stop it first (or use its API directly)" >&2
  exit 1
fi
mkdir -p results
build/tlsphd >results/tlsphd.log 2>&1 &
daemon=$!
trap 'kill -TERM $daemon 2>/dev/null; wait $daemon 2>/dev/null || true' EXIT
for _ in $(seq 100); do curl -sf "$url/healthz" >/dev/null 2>&1 && break; sleep 0.1; done
echo "quickstart: tlsphd running on $url (log: results/tlsphd.log)"

# submit: POST /processes/run/execution with {"inputs": {"scene": ...}}
{ printf '{"inputs":{"scene":'; cat "$scene"; printf '}}'; } >results/request.json
curl -sS -D results/submit.headers -o results/submit.json -H 'Content-Type: application/json' \
     --data-binary @results/request.json "$url/processes/run/execution"
job=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["jobID"])' results/submit.json)
echo "quickstart: submitted $scene as job $job ($(grep -i '^location' results/submit.headers | tr -d '\r'))"

# wait: long-poll GET /jobs/{id}?wait=30 until the job is final
status=accepted
while [ "$status" = accepted ] || [ "$status" = running ]; do
  curl -sS "$url/jobs/$job?wait=30" -o results/status.json
  status=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["status"])' results/status.json)
  echo "quickstart: job $job is $status"
done
[ "$status" = successful ] || { cat results/status.json; exit 1; }

# fetch the results by job id
rm -rf "$out"; mkdir -p "$out"
curl -sSf "$url/jobs/$job/results/result.h5" -o "$out/result.h5"
curl -sSf "$url/jobs/$job/results/result.xmf" -o "$out/result.xmf"
curl -sSf "$url/jobs/$job/results/series/kinetic_energy?format=csv" -o "$out/kinetic_energy.csv"

PYTHONPATH=tests/support /usr/bin/python3 - "$out/result.h5" results/status.json <<'PY'
import json, sys
from tlsph_result import Result
r = Result(sys.argv[1])
st = json.load(open(sys.argv[2]))
print("summary of", sys.argv[1])
print("  modules:", ", ".join(r.modules))
print("  frames: %d, particles: %d" % (len(r.frame_times()), len(r.field("id"))))
for k in ("kinetic_energy", "internal_energy", "external_work", "energy_balance"):
    print("  final %-16s %.6g J" % (k, r.last(k)))
for g in r.file["observables/groups"] if r.has_series("groups") else []:
    print("  group %-8s reaction force [%.4g, %.4g, %.4g] N" % (g, *r.series("groups/%s/reaction_force" % g)[1][-1]))
for k, v in st.get("cost", {}).items():
    print("  cost %-26s %s" % (k, v))
PY
echo "result: $(pwd)/$out/result.h5 and $(pwd)/$out/result.xmf (ParaView: File > Open, choose \"XDMF Reader\")"
