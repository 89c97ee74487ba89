#!/usr/bin/env bash
# Install (idempotently) the Debian packages named: the shared libraries that the gmsh wheel and
# off-screen VTK need (make setup), the benchmarks' peer solver CalculiX (make bench-peer).
# Does nothing when they are already present; uses sudo only when not root.
set -euo pipefail
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "installing Debian packages: ${missing[*]}"
$SUDO apt-get update -q || true
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
