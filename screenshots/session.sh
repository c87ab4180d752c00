#!/usr/bin/env bash
# Runs inside Xvfb (see make.sh): drives the app with xdotool and grabs the screen.
set -euo pipefail
out=$1
./target/release/topocontour &
app=$!
trap 'kill $app 2>/dev/null || true' EXIT
sleep 4
win=$(xdotool search --sync --name topocontour | head -1)
xdotool windowmove "$win" 0 0
xdotool windowsize "$win" 1280 820
sleep 1
shot() { import -window root "$out/$1.png"; }
# Image pixel → screen for the 512×384 sample in a 1280×820 window, read off a first
# shot of this layout (the image spans x 8–942, y 60–760).
ox=8 oy=60 z=1.8242
px() { python3 -c "print(int($ox + $1 * $z), int($oy + $2 * $z))"; }
click_image() { read -r x y < <(px "$1" "$2"); xdotool mousemove "$x" "$y" click 1; sleep 0.4; }
# Tool-bar buttons (window coordinates, as laid out at 1280 px wide).
button() { xdotool mousemove "$1" 12 click 1; sleep "${2:-0.5}"; }
# 1. The sample opens with a wrap rectangle: "Next event" twice shows the first splits,
#    with the motion regions that caused them flashed in magenta.
button 1154
button 1154 1
shot split
# 2. Play to convergence: final contours and the plots.
button 968 8
shot final
# 3. Reset, select the wrap rectangle and delete it, then place seeds in three cells.
button 1227
button 385
click_image 6 150
button 562
button 175
for c in "318 98" "230 190" "145 125" "455 310"; do click_image $c; done
sleep 0.5
shot seeds
