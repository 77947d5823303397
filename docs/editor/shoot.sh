#!/usr/bin/env bash
# The editor's start-up frame on every preset, as a user sees it: the real `veneer`
# binary in a real X window (its own Xvfb display), one PNG of the window per preset in
# docs/editor/<preset>.png, taken once the window has stopped changing.
#
#   docs/editor/shoot.sh            # all presets (graphs/*.ron)
#   docs/editor/shoot.sh wood ...   # some
#
# Needs Xvfb, xdotool and ImageMagick's import (`.ci/run` installs them); builds the
# release binary if it is missing (VENEER=path picks another).
set -euo pipefail
cd "$(dirname "$0")/../.."

for tool in Xvfb xdotool import; do
  command -v "$tool" >/dev/null || {
    echo "shoot.sh needs $tool: apt-get install xvfb xdotool imagemagick" >&2
    exit 1
  }
done
veneer=${VENEER:-target/release/veneer}
[ -x "$veneer" ] || cargo build --release --bin veneer

if [ $# -gt 0 ]; then names=("$@"); else
  names=()
  for graph in graphs/*.ron; do names+=("$(basename "$graph" .ron)"); done
fi

work=$(mktemp -d)
mkdir -p "$work/state" "$work/runtime"
chmod 700 "$work/runtime"
xvfb=
editor=
cleanup() {
  [ -n "$editor" ] && kill "$editor" 2>/dev/null && wait "$editor" 2>/dev/null
  [ -n "$xvfb" ] && kill "$xvfb" 2>/dev/null && wait "$xvfb" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

# Xvfb picks a free display and writes its number once it listens.
Xvfb -displayfd 3 -screen 0 1600x1000x24 -nolisten tcp -noreset 3>"$work/display" 2>"$work/xvfb.log" &
xvfb=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.1; done
[ -s "$work/display" ] || { cat "$work/xvfb.log" >&2; exit 1; }
export DISPLAY=":$(tr -d '\n' <"$work/display")"
# The pointer off the window: no hover highlights in the pictures.
xdotool mousemove 1599 999

# A hash of the window's pixels.
pixels() { import -window "$1" -depth 8 rgb:- | md5sum; }

for name in "${names[@]}"; do
  graph="graphs/$name.ron"
  [ -f "$graph" ] || { echo "no preset $graph" >&2; exit 1; }
  env -u WAYLAND_DISPLAY XDG_STATE_HOME="$work/state" XDG_RUNTIME_DIR="$work/runtime" \
    "$veneer" edit "$graph" >"$work/$name.log" 2>&1 &
  editor=$!
  # The window, once the editor has drawn a frame and titled it after the file.
  # (The title is "<file> — Veneer"; the dash may reach xdotool as several bytes.)
  window=$(timeout 60 xdotool search --sync --name "^$name\.ron .* Veneer$" | head -n1) || {
    echo "$name: no window within 60 s" >&2
    cat "$work/$name.log" >&2
    exit 1
  }
  # Settled: the same pixels three times in a row, a quarter second apart (a preset
  # with distance fields solves them first), at most a minute.
  last=$(pixels "$window") same=0
  for _ in $(seq 240); do
    sleep 0.25
    now=$(pixels "$window")
    if [ "$now" = "$last" ]; then same=$((same + 1)); else same=0; fi
    last=$now
    [ "$same" -ge 2 ] && break
  done
  [ "$same" -ge 2 ] || echo "$name: the window still changes after a minute; taking it anyway" >&2
  import -window "$window" -define png:exclude-chunk=date,time,tIME "docs/editor/$name.png"
  echo "docs/editor/$name.png"
  kill "$editor"
  wait "$editor" || true
  editor=
done
