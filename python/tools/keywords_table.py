"""Prints the README's table of segment()'s keywords, made from the command line's own
flag definitions (tests/test_docs.py checks that the README holds exactly this).

    python python/tools/keywords_table.py
"""

import topocontour as tc


def table() -> str:
    rows = [
        "| keyword | flag | value | meaning |",
        "|---|---|---|---|",
    ]
    lists = {"seeds": "[(x, y, r), …]", "rects": "[(x0, y0, x1, y1), …]"}
    for key, long, value, choices, help in tc.segment_flags():
        if key in lists:
            py = lists[key]
        elif not value:
            py = "True / False"
        elif choices:
            py = " / ".join(f'"{c}"' for c in choices.split(", "))
        else:
            py = value
        flag = f"`--{long}`" if not value else f"`--{long} {value}`"
        rows.append(f"| `{key}` | {flag} | {py} | {help} |")
    return "\n".join(rows) + "\n"


if __name__ == "__main__":
    print(table(), end="")
