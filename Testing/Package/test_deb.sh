#!/usr/bin/env bash
# Run inside a clean root of the Debian the package was made for (./run package --test):
#   test_deb.sh <package.deb> <models dir>
# Installs it with apt, runs the pvpython smoke test and a GUI start that must find the
# plugin by name, removes it, and checks that no file is left behind.
set -euo pipefail
deb="$1"
models="$2"
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d /tmp/pisurfaces-deb.XXXXXX)"

files() {
  find / -xdev \( -path /proc -o -path /sys -o -path /dev -o -path /tmp -o -path /run \
    -o -path /var/lib/dpkg -o -path /var/lib/apt -o -path /var/cache -o -path /var/log \
    -o -path /root -o -path "${PISURFACES_SOURCE:-/nonexistent}" \) -prune -o -print | sort
}

files >"$work/before"
echo "== installing $(basename "$deb")"
apt-get install -y -qq --no-install-recommends "$deb" >"$work/apt.log" 2>&1 ||
  { tail -n 20 "$work/apt.log"; exit 1; }
dpkg -L pisurfaces | grep -E '\.so|\.xml|\.conf|\.py' | sed 's/^/   /'

echo "== pvpython smoke test"
(cd "$work" && pvpython --force-offscreen-rendering "$here/smoke.py" "$models")

echo "== GUI start: paraview --plugins=PiSurfaces"
export PISURF_GUI_RESULT="$work/gui.txt"
(cd "$work" && timeout 120 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  paraview --dr --plugins=PiSurfaces "--script=$here/gui.py" >"$work/gui.log" 2>&1) || true
cat "$work/gui.txt" 2>/dev/null || { tail -n 20 "$work/gui.log"; echo "GUI: no result"; exit 1; }
grep -q '^PASSED' "$work/gui.txt"

echo "== removing"
dpkg --purge pisurfaces >/dev/null
apt-get autoremove --purge -y -qq >/dev/null
files >"$work/after"
if ! diff "$work/before" "$work/after" >"$work/diff"; then
  echo "files left behind or removed by install/remove:"
  cat "$work/diff"
  exit 1
fi
echo "no file left behind ($(wc -l <"$work/before") files compared)"
rm -rf "$work"
echo "package test passed"
