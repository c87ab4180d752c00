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
# shot of this layout (the image spans x 8–942, y 83–783).
ox=8 oy=83 z=1.8242
px() { python3 -c "print(int($ox + $1 * $z), int($oy + $2 * $z))"; }
click_image() { read -r x y < <(px "$1" "$2"); xdotool mousemove "$x" "$y" click 1; sleep 0.4; }
# Tool-bar buttons (window coordinates x y, as laid out at 1280 px wide: three rows).
button() { xdotool mousemove "$1" "$2" click 1; sleep "${3:-0.5}"; }
play="28 58" next_event="213 58" reset="286 58"
seed="352 12" select="561 12" delete="928 12" beside="405 35"
# 1. The sample opens with a wrap rectangle: "Next event" twice shows the first splits,
#    with the motion regions that caused them flashed in magenta.
button $next_event
button $next_event 1
shot split
# 2. Play to convergence: final contours and the plots.
button $play 8
shot final
# 3. Reset, select the wrap rectangle and delete it, then place seeds in three cells.
button $reset
button $select
click_image 6 150
button $delete
button $seed
for c in "318 98" "230 190" "145 125" "455 310"; do click_image $c; done
sleep 0.5
shot seeds

# 4. Side by side: the implicit engine beside the adaptive one on those seeds, to the end.
button $beside
button 405 127
button $play 8
shot side_by_side
