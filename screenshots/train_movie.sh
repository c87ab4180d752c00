#!/usr/bin/env bash
# The Train tool and movie figures of the README, from the real app under Xvfb:
#   bash screenshots/train_movie.sh IMAGE STROKES.png MOVIE [OUT]
# IMAGE and STROKES: a phase-contrast image and its strokes (../shared/tools/scribbles.py
# writes them); MOVIE: a TIFF movie with divisions. Writes OUT/train_*.png, OUT/movie_division.png.
set -euo pipefail
cd "$(dirname "$0")/.."
image=$1 strokes=$2 movie=$3 out=${4:-screenshots}
cargo build --release --example app_shot
bin=target/release/examples/app_shot
shot() { # NAME WAIT ARGS...
  local name=$1 wait=$2; shift 2
  home=$(mktemp -d)
  HOME="$home" XDG_DATA_HOME="$home/data" XDG_CONFIG_HOME="$home/config" \
    xvfb-run -a -s "-screen 0 1280x820x24" sh -c "$bin $* & P=\$!; sleep $wait;
      import -window root '$out/$name.png'; kill \$P"
  rm -rf "$home"
}
shot train_strokes_map 8 train "$image" "$strokes" map
shot train_contours 20 train "$image" "$strokes" contours
shot movie_division 60 movie "$movie"
