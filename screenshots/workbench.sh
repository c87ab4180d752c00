#!/usr/bin/env bash
# Runs inside Xvfb (see make.sh): the workbench shots — a hand edit (the Edit tool drags
# a vertex of one cell towards another) and the help window. Image pixel → screen for
# the 512×384 sample in a 1280×820 window with the three-row tool bar (the image spans
# x 8–942, y 83–783).
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
xdotool windowfocus --sync "$win"
shot() { import -window root "$out/$1.png"; }
ox=8 oy=83 z=1.8242
px() { python3 -c "print(int($ox + $1 * $z), int($oy + $2 * $z))"; }
click_image() { read -r x y < <(px "$1" "$2"); xdotool mousemove "$x" "$y" click 1; sleep 0.4; }
button() { xdotool mousemove "$1" "$2" click 1; sleep "${3:-0.5}"; }
seed="352 12" select="561 12" edit="615 12" delete="870 12" play="28 58"
# Remove the sample's wrap rectangle, seed two cells, play to the end.
button $select
click_image 6 150
button $delete
button $seed
click_image 200 58
click_image 228 190
button $play 6
# Edit: drag the orange cell's lowest vertex down into the big cell below it.
button $edit
read -r x0 y0 < <(px 199.5 75)
read -r x1 y1 < <(px 226 172)
xdotool mousemove "$x0" "$y0" mousedown 1
for k in $(seq 1 20); do
  xdotool mousemove "$((x0 + (x1 - x0) * k / 20))" "$((y0 + (y1 - y0) * k / 20))"
  sleep 0.2
done
xdotool mouseup 1
sleep 1
shot hand_edit
xdotool key F1
sleep 1
shot help
