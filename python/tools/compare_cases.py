"""segment() against the command line on case folders (each CASE/image.png with its
case.json), the runs tools/golden.sh makes (the case's shapes in adaptive, preserve and
implicit mode, and automatic seeds in preserve mode): JSON compared byte for byte, from
the path and from the array that load() reads:

  python python/tools/compare_cases.py BINARY CASES_DIR...
"""

import json
import subprocess
import sys
import tempfile
from pathlib import Path

import topocontour as tc


def runs(case: dict):
    i = case["init"]
    kind = dict(object=i.get("object", "dark"))
    flags = ["--object", kind["object"]]
    if "modality" in i:
        kind["modality"] = i["modality"]
        flags += ["--modality", i["modality"]]
    given, gflags = dict(kind), list(flags)
    if i.get("seeds"):
        given["seeds"] = [tuple(s) for s in i["seeds"]]
        for x, y, r in i["seeds"]:
            gflags += ["--seed", f"{x},{y},{r}"]
    if "border_margin" in i:
        given["wrap"] = i["border_margin"]
        gflags += ["--wrap", str(i["border_margin"])]
    for mode in ("adaptive", "preserve", "implicit"):
        yield mode, dict(given, mode=mode), gflags + ["--mode", mode]
    yield "auto", dict(kind, auto_seeds=True, mode="preserve"), ["--auto-seeds", "--mode", "preserve"] + flags


def main():
    binary, dirs = sys.argv[1], sys.argv[2:]
    same = total = 0
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "cli.json"
        for d in dirs:
            for case in sorted(Path(d).glob("*/case.json")):
                png = case.parent / "image.png"
                for run, keywords, flags in runs(json.loads(case.read_text())):
                    p = subprocess.run([binary, "segment", str(png), *flags, "--json", str(out)],
                                       capture_output=True, text=True)
                    total += 1
                    if p.returncode != 0:
                        try:
                            tc.segment(png, **keywords)
                            ok, why = False, "the CLI refused, Python did not"
                        except ValueError as e:
                            ok = str(e) == p.stderr.strip().removeprefix("topocontour: ")
                            why = f"refused: {e}"
                    else:
                        want = out.read_text()
                        a = tc.segment(png, **keywords).to_json() == want
                        b = tc.segment(tc.load(png), name="image.png", **keywords).to_json() == want
                        ok, why = a and b, f"path {'=' if a else '!='}, array {'=' if b else '!='}"
                    same += ok
                    print(f"{'same' if ok else 'DIFFERENT'}  {case.parent.name}.{run}  {why}")
    print(f"{same} of {total} runs JSON-identical to the CLI")
    sys.exit(0 if same == total else 1)


if __name__ == "__main__":
    main()
