#!/usr/bin/env bash
# Installs the Debian 12 packages tlsph needs to build, test and run.
# Idempotent; uses sudo when not run as root.  --test-tools: also the tools
# only the test suite uses (see below).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PACKAGES=(
  build-essential autoconf automake pkg-config
  libjansson-dev libhdf5-dev hdf5-tools libmatheval-dev check
  libmicrohttpd-dev libsqlite3-dev libgnutls28-dev libcurl4-openssl-dev
  python3 python3-h5py python3-numpy python3-jsonschema python3-yaml
  curl procps valgrind
  librsvg2-bin bsdutils
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
# --test-tools (deploy/test.sh): also the independent OpenAPI 3.1 validator of
# tests/daemon/api_openapi.sh, pinned (npm; the test skips that check, saying
# so, without it).  Not needed to build or run tlsph.  TLSPH_TEST_TOOLS moves it.
if [ "${1:-}" = --test-tools ]; then
  # A private single-node Slurm for tests/daemon/api_slurm.sh (it skips, saying
  # so, without it).  Only here: on a systemd machine the packages enable Slurm's
  # and munge's services, which tlsph itself never needs.
  slurm_missing=()
  for p in slurm-wlm munge; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || slurm_missing+=("$p")
  done
  if [ ${#slurm_missing[@]} -gt 0 ]; then
    echo "install-deps: installing ${slurm_missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq "${slurm_missing[@]}" >/dev/null; } ||
      echo "install-deps: warning: slurm-wlm/munge could not be installed; api_slurm.sh will skip" >&2
  fi
  TOOLS=${TLSPH_TEST_TOOLS:-/opt/tlsph-test-tools}
  OAS_VALIDATOR="@seriousme/openapi-schema-validator@2.11.0"
  # Debian's nodejs and npm, unless a nodejs with its own npm is installed (they conflict)
  if ! command -v npm >/dev/null 2>&1; then
    export DEBIAN_FRONTEND=noninteractive
    { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq nodejs npm >/dev/null; } ||
      echo "install-deps: warning: nodejs/npm could not be installed" >&2
  fi
  if command -v npm >/dev/null 2>&1 &&
    ! grep -qs '"version": "2.11.0"' "$TOOLS/node_modules/@seriousme/openapi-schema-validator/package.json"; then
    echo "install-deps: installing $OAS_VALIDATOR in $TOOLS"
    $SUDO mkdir -p "$TOOLS"
    # bounded: a registry that cannot be reached costs minutes at most, not the CI run
    timeout 300 $SUDO npm install --no-audit --no-fund --silent --fetch-retries=1 \
      --fetch-timeout=60000 --prefix "$TOOLS" "$OAS_VALIDATOR" >/dev/null ||
      echo "install-deps: warning: $OAS_VALIDATOR could not be installed; api_openapi.sh will skip that check" >&2
  fi
fi
echo "install-deps: all dependencies present"
