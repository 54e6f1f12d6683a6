"""Studio permalinks in Python: the page's format (#p= + base64url(raw deflate)), read back by
`matloom studio --link`; bad links get one line and create nothing."""

from __future__ import annotations

import base64
import subprocess
import sys
import zlib
from pathlib import Path

import pytest

from matloom.studio.permalink import MAX_CHARS, PermalinkError, decode, encode

DEMO = Path(__file__).resolve().parents[2] / "matloom" / "examples" / "black_ceramic_tiles.mat"


def test_round_trip_of_a_program_with_comments_and_unicode() -> None:
    text = "# glaze: ✓ naïve\n" + DEMO.read_text(encoding="utf-8")
    fragment = encode(text)
    assert fragment.startswith("p=") and "=" not in fragment[2:]
    for link in (fragment, "#" + fragment, f"http://127.0.0.1:8800/?token=x#{fragment}"):
        assert decode(link) == text


def test_it_reads_the_raw_deflate_a_browser_writes() -> None:
    # CompressionStream("deflate-raw") output: a raw deflate stream (no zlib header)
    raw = zlib.compress(b"Material(Layer(1))", 6)[2:-4]
    code = base64.urlsafe_b64encode(raw).decode().rstrip("=")
    assert decode(f"#p={code}") == "Material(Layer(1))"


@pytest.mark.parametrize(
    "link, words",
    [
        ("http://example.com/page", "not a MatLoom permalink"),
        ("#p=!!!", "not a MatLoom permalink"),
        ("#p=________", "damaged"),
        ("#p=AAAA", "cut short"),
        ("#" + encode("Material(Layer(1))")[:-6], "damaged|cut short"),
    ],
)
def test_bad_links_get_one_line(link: str, words: str) -> None:
    with pytest.raises(PermalinkError, match=words):
        decode(link)


def test_a_deflate_bomb_is_refused_without_expanding_it() -> None:
    deflate = zlib.compressobj(9, zlib.DEFLATED, -15)
    raw = deflate.compress(b" " * (MAX_CHARS * 4 + 10)) + deflate.flush()
    code = base64.urlsafe_b64encode(raw).decode().rstrip("=")
    with pytest.raises(PermalinkError, match="more than"):
        decode("#p=" + code)


def test_cli_refuses_a_bad_link_in_one_line_and_creates_nothing(tmp_path: Path) -> None:
    pytest.importorskip("starlette", reason="the studio needs the [studio] extra")
    result = subprocess.run(
        [sys.executable, "-m", "matloom", "studio", "--no-browser", "--link", "#p=________"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode != 0
    assert "damaged" in result.stderr and "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []
