"""The README documents segment()'s keywords once, as a table made from the command
line's flags: it must be exactly what python/tools/keywords_table.py prints now."""

import sys
from pathlib import Path

from conftest import ROOT

sys.path.insert(0, str(ROOT / "python" / "tools"))
from keywords_table import table  # noqa: E402

import topocontour as tc  # noqa: E402


def test_readme_table_is_the_cli_flags():
    readme = (ROOT / "README.md").read_text()
    start, end = "<!-- segment-keywords -->\n", "<!-- /segment-keywords -->"
    assert start in readme and end in readme
    documented = readme.split(start, 1)[1].split(end, 1)[0]
    assert documented == table(), "README table drifted: run python/tools/keywords_table.py"


def test_every_flag_is_a_keyword():
    import inspect

    named = set(inspect.signature(tc.segment).parameters) - {"image", "name", "params"}
    keywords = {key for key, *_ in tc.segment_flags()}
    assert named <= keywords
    assert {"seeds", "rects", "strokes", "max_frames", "min_area"} <= keywords
