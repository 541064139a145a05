#!/bin/sh
# Install flexmech's system dependencies from Debian/Ubuntu packages when missing.
# gnuplot-nox draws `flexmech plot` figures (headless: PNG, SVG, GIF).
# Does nothing when everything is present. Usage: install_deps.sh [extra-package ...]
# DEPS_LOG names the log of apt's output (default build/deps.log).
set -eu
pkgs="gfortran liblapack-dev libblas-dev gnuplot-nox $*"
missing=""
for p in $pkgs; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  SUDO="sudo -n"
else
  echo "flexmech: missing packages:$missing" >&2
  echo "flexmech: install them as root with:" >&2
  echo "    apt-get update && apt-get install -y$missing" >&2
  exit 1
fi
# apt's own lines go to a log; its tail is printed when the installation fails
log=${DEPS_LOG:-build/deps.log}
mkdir -p "$(dirname "$log")"
echo "flexmech: installing$missing with apt-get (log: $log)" >&2
export DEBIAN_FRONTEND=noninteractive
# shellcheck disable=SC2086
if ! { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq --no-install-recommends $missing; } > "$log" 2>&1; then
  tail -n 20 "$log" >&2
  echo "flexmech: installing$missing failed (log: $log)" >&2
  exit 1
fi
