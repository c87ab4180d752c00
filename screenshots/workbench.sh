#!/usr/bin/env bash
# Runs inside Xvfb (see make.sh): the workbench shots — a brush stroke merging two cells,
# the object table linked to the canvas, a folder run's progress, and the help window.
# Image pixel → screen for the 512×384 sample in a 1280×820 window with the three-row
# tool bar (the image spans x 8–942, y 83–783).
set -euo pipefail
out=$1
folder=$(mktemp -d)
./target/release/topocontour &
app=$!
trap 'kill $app 2>/dev/null || true; rm -rf "$folder"' EXIT
sleep 4
win=$(xdotool search --sync --name topocontour | head -1)
xdotool windowmove "$win" 0 0
xdotool windowsize "$win" 1280 820
sleep 1
xdotool windowfocus --sync "$win"
shot() { import -window root "$out/$1.png"; }
ox=8 oy=83 z=1.8242
px() { python3 -c "print(int($ox + $1 * $z), int($oy + $2 * $z))"; }
button() { xdotool mousemove "$1" "$2" click 1; sleep "${3:-0.5}"; }
brush="666 12" play="28 58" session="216 12"
# The sample's wrap rectangle shrinks onto every cell.
button $play 8
# Brush: from inside the orange cell towards the teal one on its left; the disc pushes
# the orange boundary ahead of it until the two touch and merge.
button $brush
read -r x0 y0 < <(px 199 59)
read -r x1 y1 < <(px 86 67)
xdotool mousemove "$x0" "$y0" mousedown 1
for k in $(seq 1 40); do
  xdotool mousemove "$((x0 + (x1 - x0) * k / 40))" "$((y0 + (y1 - y0) * k / 40))"
  sleep 0.1
done
xdotool mouseup 1
sleep 1
xdotool mousemove 600 795
sleep 0.5
shot brush_merge
# The object table: the first row (the largest cell) selected, haloed on the canvas.
button 990 193 1
shot object_table
# Apply to folder: no desktop portal here, so the path field takes the folder.
for i in $(seq 1 12); do
  for c in $(ls tests/cases); do
    cp "tests/cases/$c/image.png" "$folder/$c-$i.png" 2>/dev/null || true
  done
done
button $session 0.8
xdotool mousemove 250 95 click 1
sleep 2
xdotool type --delay 5 "$folder"
xdotool key Return
sleep 1.2
shot folder_progress
sleep 8
xdotool key F1
sleep 1
shot help
