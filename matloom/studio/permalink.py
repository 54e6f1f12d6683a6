"""Studio permalinks: a program deflated into the URL fragment, ``#p=`` + base64url(raw
deflate(UTF-8 text)), as the page writes them (studio-web/src/history.ts). Python reads and
writes the same format, so ``matloom studio --link URL`` reopens a link made on any machine."""

from __future__ import annotations

import base64
import re
import zlib

#: Largest program a link may expand to: the language's program-size limit (docs/limits.md).
MAX_CHARS = 2_000_000


class PermalinkError(ValueError):
    """A link that is not a MatLoom permalink (one line)."""


def encode(text: str) -> str:
    """The fragment (``p=...``, without ``#``) that reopens ``text``."""
    deflate = zlib.compressobj(9, zlib.DEFLATED, -15)
    raw = deflate.compress(text.encode("utf-8")) + deflate.flush()
    return "p=" + base64.urlsafe_b64encode(raw).decode("ascii").rstrip("=")


def decode(link: str) -> str:
    """The program text of ``link``: a whole studio URL, its ``#p=...`` fragment, or the code."""
    m = re.search(r"(?:^|[#&])p=([A-Za-z0-9_-]*)$", link.strip()) or re.fullmatch(
        r"([A-Za-z0-9_-]+)", link.strip()
    )
    if m is None:
        raise PermalinkError("not a MatLoom permalink: expected a URL ending in #p=...")
    code = m.group(1)
    try:
        raw = base64.urlsafe_b64decode(code + "=" * (-len(code) % 4))
        inflate = zlib.decompressobj(-15)
        data = inflate.decompress(raw, MAX_CHARS * 4 + 1)
        if len(data) > MAX_CHARS * 4 or inflate.unconsumed_tail:
            raise PermalinkError(f"the permalink expands to more than {MAX_CHARS:,} characters")
        if not inflate.eof:
            raise PermalinkError("the permalink is cut short (copy the whole link)")
        text = data.decode("utf-8")
    except PermalinkError:
        raise
    except (ValueError, zlib.error, UnicodeDecodeError):
        raise PermalinkError("the permalink is damaged (copy the whole link)") from None
    if len(text) > MAX_CHARS:
        raise PermalinkError(f"the permalink expands to more than {MAX_CHARS:,} characters")
    return text
