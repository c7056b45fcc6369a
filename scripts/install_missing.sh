#!/usr/bin/env bash
# scripts/install_missing.sh — install those of the given Debian packages that are not
# installed yet (apt-get, with sudo when not root); packages already present are left
# alone, so a second call does nothing.  Used by setup.sh and fuzz.sh.
# Usage: scripts/install_missing.sh LABEL PACKAGE...   (LABEL prefixes the message)
set -euo pipefail
label=$1
shift
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((${#missing[@]})) || exit 0
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
echo "$label: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
