#!/usr/bin/env bash
# Draws the README's gallery of the real cases with the CLI's --overlay: for each case
# folder the default run (its case.json's initialisation, object and modality) and the
# instance run (--auto-seeds --mode preserve).
# Usage: bash screenshots/real.sh [CASES_DIR]   (from the repository root; default
# ../shared/cases_real)
set -euo pipefail
cd "$(dirname "$0")/.."
cases=${1:-../shared/cases_real}
cargo build --release -q
mkdir -p screenshots/real
for dir in "$cases"/*/; do
  name=$(basename "$dir")
  # The case's init, object and modality as flags (the scorer's rules).
  read -r -a flags < <(python3 - "$dir/case.json" <<'PY'
import json, sys
init = json.load(open(sys.argv[1]))["init"]
f = []
for s in init.get("seeds", []):
    f += ["--seed", ",".join(str(v) for v in s)]
if "border_margin" in init:
    f += ["--wrap", str(init["border_margin"])]
f += ["--object", init.get("object", "dark")]
if init.get("modality") in ("fluorescence", "phase-contrast", "brightfield"):
    f += ["--modality", init["modality"]]
print(" ".join(f))
PY
)
  object=() modality=()
  for ((i = 0; i < ${#flags[@]}; i++)); do
    case ${flags[i]} in
      --object) object=(--object "${flags[i + 1]}") ;;
      --modality) modality=(--modality "${flags[i + 1]}") ;;
    esac
  done
  target/release/topocontour segment "$dir/image.png" "${flags[@]}" \
    --overlay "screenshots/real/$name-wrap.png"
  target/release/topocontour segment "$dir/image.png" --auto-seeds --mode preserve \
    "${object[@]}" "${modality[@]}" --overlay "screenshots/real/$name-instances.png" 2>/dev/null
  echo "screenshots/real/$name-{wrap,instances}.png"
done
