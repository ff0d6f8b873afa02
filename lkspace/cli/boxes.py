"""A table drawn as ``rich`` draws its default one (heavy head, light body), without importing rich.

For the start-up path of commands as cheap as ``trace``: rich costs tens of milliseconds to
import.  Cells are shown whole (no wrapping), left aligned.
"""

from __future__ import annotations

from collections.abc import Sequence


def box_table(headers: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    """Return the table of ``headers`` and ``rows`` (strings) as lines of text, without a final newline."""
    widths = [max([len(h), *(len(r[i]) for r in rows)]) + 2 for i, h in enumerate(headers)]

    def line(left: str, fill: str, mid: str, right: str) -> str:
        return left + mid.join(fill * w for w in widths) + right

    def cells(bar: str, values: Sequence[str]) -> str:
        return bar + bar.join(f" {v:<{w - 2}} " for v, w in zip(values, widths, strict=True)) + bar

    out = [line("┏", "━", "┳", "┓"), cells("┃", headers), line("┡", "━", "╇", "┩")]
    out += [cells("│", r) for r in rows]
    out.append(line("└", "─", "┴", "┘"))
    return "\n".join(out)
