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
echo "install-deps: all dependencies present"
