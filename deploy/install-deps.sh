#!/usr/bin/env bash
# Installs the Debian 12 packages tlsph needs to build, test and run.
# Idempotent; uses sudo when not run as root.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PACKAGES=(
  build-essential autoconf automake pkg-config
  libjansson-dev libhdf5-dev hdf5-tools libmatheval-dev check
  libmicrohttpd-dev libsqlite3-dev libgnutls28-dev libcurl4-openssl-dev
  python3 python3-h5py python3-numpy python3-jsonschema python3-yaml
  curl procps valgrind
  nodejs
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
# The independent OpenAPI 3.1 validator of tests/daemon/api_openapi.sh, pinned
# (npm; the test skips, saying so, without it).  TLSPH_TEST_TOOLS moves it.
TOOLS=${TLSPH_TEST_TOOLS:-/opt/tlsph-test-tools}
# Debian's npm, unless a nodejs with its own npm is installed (they conflict)
if ! command -v npm >/dev/null 2>&1; then
  export DEBIAN_FRONTEND=noninteractive
  { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq npm >/dev/null; } ||
    echo "install-deps: warning: npm could not be installed" >&2
fi
OAS_VALIDATOR="@seriousme/openapi-schema-validator@2.11.0"
if command -v npm >/dev/null 2>&1 &&
  ! grep -qs '"version": "2.11.0"' "$TOOLS/node_modules/@seriousme/openapi-schema-validator/package.json"; then
  echo "install-deps: installing $OAS_VALIDATOR in $TOOLS"
  $SUDO mkdir -p "$TOOLS"
  $SUDO npm install --no-audit --no-fund --silent --prefix "$TOOLS" "$OAS_VALIDATOR" >/dev/null ||
    echo "install-deps: warning: $OAS_VALIDATOR could not be installed; api_openapi.sh will skip that check" >&2
fi
echo "install-deps: all dependencies present"
