"""Page bytes as text (:func:`decode_body`): a BOM, valid UTF-8, the declared charset (the Content-Type
header, or the page's own ``<meta charset>`` when the header's UTF-8 does not fit the bytes), a detected
one, cp1252. A declared UTF-8 the bytes are not, with no other declaration, is decoded with U+FFFD marking
each error, never guessed (a product name holding one is refused: :mod:`scrapers.product_names`).
"""

from __future__ import annotations

import re

__all__ = ["DETECT_BYTES", "decode_body"]

_META_CHARSET = re.compile(rb"""<meta[^>]{0,200}?charset\s*=\s*["']?\s*([a-zA-Z0-9_.:-]+)""", re.IGNORECASE)


def decode_body(body: str | bytes, content_type: str | None = None) -> str:
    """Page bytes as text: a BOM, then UTF-8 if the bytes are valid UTF-8, then the charset of the
    Content-Type header or a ``<meta charset>`` (the ``<meta>`` one when the header says UTF-8 and the
    bytes are not), then the charset ``charset_normalizer`` detects (a saved Shift_JIS page whose header
    was lost), then cp1252 (which decodes anything)."""
    if isinstance(body, str):
        return body
    if not isinstance(body, (bytes, bytearray, memoryview)):
        return str(body)
    data = bytes(body)
    for bom, codec in ((b"\xef\xbb\xbf", "utf-8"), (b"\xff\xfe", "utf-16-le"), (b"\xfe\xff", "utf-16-be")):
        if data.startswith(bom):
            return data[len(bom) :].decode(codec, errors="replace")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        pass
    header = None
    if content_type:
        m = re.search(r"charset\s*=\s*[\"']?([\w.:-]+)", content_type, re.IGNORECASE)
        header = m.group(1) if m else None
    m = _META_CHARSET.search(data[:8192]) if header is None or _is_utf8(header) else None
    meta = m.group(1).decode("ascii", "replace") if m else None
    if header is not None and _is_utf8(header) and meta is not None and not _is_utf8(meta):
        declared = meta  # the header's UTF-8 does not fit the bytes; the page's own <meta> names another
    else:
        # a declared UTF-8 the bytes are not is decoded with U+FFFD marking each error (never a guess:
        # a name holding one is refused, scrapers.product_names)
        declared = header or meta or _detected_charset(data)
    for codec in (declared, "cp1252"):
        if codec:
            try:
                return data.decode(codec, errors="replace")
            except LookupError:
                continue
    return data.decode("latin-1")


def _is_utf8(codec: str) -> bool:
    return codec.lower().replace("_", "-") in ("utf-8", "utf8")


#: Bytes the charset detector reads (it is linear in what it reads; the start of a page says enough).
DETECT_BYTES = 200_000


def _detected_charset(data: bytes) -> str | None:
    """The charset of undeclared, non-UTF-8 bytes (``charset_normalizer``), or None."""
    try:
        from charset_normalizer import from_bytes

        best = from_bytes(data[:DETECT_BYTES]).best()
    except Exception:  # noqa: BLE001 - detection is a guess; cp1252 still decodes anything
        return None
    return best.encoding if best is not None else None
