"""Python call overhead against the CLI on the same image: the CLI process (load, run,
write JSON) against segment(path) + to_json() + write, and segment(array), interleaved:

  python python/tools/bench_overhead.py BINARY [SIZE] [REPEATS]
"""

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from test_distributed import blobs, write_png  # noqa: E402

import topocontour as tc  # noqa: E402
binary = sys.argv[1]
size = int(sys.argv[2]) if len(sys.argv) > 2 else 1024
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 7
d = Path(tempfile.mkdtemp())
img, _ = blobs(size, size * size // 3000, 4)
png = d / "img.png"
write_png(png, img)
cli, py, arr = [], [], []
for _ in range(reps):
    t = time.perf_counter()
    subprocess.run([binary, "segment", str(png), "--wrap", "4", "--object", "dark", "--json", str(d / "c.json")], check=True, capture_output=True)
    cli.append(time.perf_counter() - t)
    t = time.perf_counter()
    (d / "p.json").write_text(tc.segment(png, wrap=4, object="dark").to_json())
    py.append(time.perf_counter() - t)
    t = time.perf_counter()
    tc.segment(img, wrap=4, object="dark", name="img.png").to_json()
    arr.append(time.perf_counter() - t)
same = (d / "c.json").read_text() == (d / "p.json").read_text()
c, p, a = map(statistics.median, (cli, py, arr))
print(f"{size}^2 --wrap 4, median of {reps} interleaved: CLI process {c:.3f} s, segment(path)+to_json+write {p:.3f} s ({(p/c-1)*100:+.1f}%), segment(array)+to_json {a:.3f} s ({(a/c-1)*100:+.1f}%); JSON identical: {same}")
