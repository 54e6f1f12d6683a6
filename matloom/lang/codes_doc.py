"""Render the list of diagnostic codes (docs/diagnostics.md) from :mod:`matloom.lang.codes`."""

from __future__ import annotations

from matloom.lang.codes import Code


def render_diagnostics_reference() -> str:
    """Markdown list of every diagnostic code, straight from :class:`Code`."""
    out = [
        "# Diagnostic codes",
        "",
        "_Generated from `matloom/lang/codes.py` by "
        "`python -m matloom.lang.codes_doc > docs/diagnostics.md`; a test keeps it in sync._",
        "",
        "`matloom check` reports each problem as `file:line:col: severity CODE: message`, "
        "with a caret excerpt, what was expected and a hint. Errors (`E`) reject the program; "
        "warnings (`W`) do not. Codes are stable.",
        "",
        "| code | name | severity | meaning | usual fix |",
        "|---|---|---|---|---|",
    ]
    for c in sorted(Code, key=lambda c: c.code):
        info = c.value
        cells = (info.meaning, info.hint)
        meaning, hint = (text.replace("|", "\\|") for text in cells)
        out.append(f"| {info.code} | `{c.name}` | {info.severity.value} | {meaning} | {hint} |")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    print(render_diagnostics_reference(), end="")
