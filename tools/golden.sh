#!/usr/bin/env bash
# Golden runs: every case of the given case folders x (adaptive, preserve, implicit, and
# auto seeds in preserve mode), each writing JSON and a mask; prints one
# "sha256  case.run.ext" line per output. Two binaries behave identically on these cases
# when their listings are equal:
#   bash tools/golden.sh BINARY CASES_DIR... > a.txt   (then diff a.txt b.txt)
set -euo pipefail
bin=$(realpath "$1"); shift
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for cases in "$@"; do
  ls "$cases"/*/case.json >/dev/null 2>&1 || { echo "no cases in $cases" >&2; exit 2; }
  for d in "$cases"/*/; do
    [ -f "$d/case.json" ] || continue
    name=$(basename "$d")
    # Line 1: the case's own initialisation; line 2: the object and image type only.
    mapfile -t lines < <(python3 - "$d/case.json" <<'PY'
import json, sys
i = json.load(open(sys.argv[1]))["init"]; shapes, kind = [], ["--object", i.get("object", "dark")]
for x, y, r in i.get("seeds", []): shapes += ["--seed", f"{x},{y},{r}"]
if "border_margin" in i: shapes += ["--wrap", str(i["border_margin"])]
if "modality" in i: kind += ["--modality", i["modality"]]
print(" ".join(shapes + kind)); print(" ".join(kind))
PY
)
    read -r -a given <<<"${lines[0]}"
    read -r -a kind <<<"${lines[1]}"
    for run in adaptive preserve implicit auto; do
      if [ "$run" = auto ]; then flags=(--auto-seeds --mode preserve "${kind[@]}")
      else flags=("${given[@]}" --mode "$run"); fi
      out="$tmp/$name.$run"
      if "$bin" segment "$d/image.png" "${flags[@]}" --json "$out.json" --mask "$out.png" \
          >/dev/null 2>"$out.err"; then
        (cd "$tmp" && sha256sum "$name.$run.json" "$name.$run.png")
      else
        echo "exit $?  $name.$run: $(tail -c 200 "$out.err" | tr '\n' ' ')"
      fi
    done
  done
done
