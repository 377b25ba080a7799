"""tools/view-check's helpers (the headless-Chromium check of the viewer pages): the screenshot
reader and the camera. Guards against a screenshot misread (then a blank or wrong page passes
the check) and a body looked for where the page does not draw it."""
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from wbtools.browser import decode_png  # noqa: E402
from wbtools.view_check import screen_of  # noqa: E402


def test_png_decoder_reads_filtered_rows():
    """The screenshot reader undoes PNG filters (a wrong Paeth would shift colours)."""
    import zlib
    rows = [bytes([4, 10, 20, 30, 0, 0, 0]), bytes([2, 1, 1, 1, 5, 5, 5])]  # Paeth, Up
    raw = zlib.compress(b"".join(rows))

    def chunk(kind, data):
        crc = struct.pack(">I", zlib.crc32(kind + data))
        return struct.pack(">I", len(data)) + kind + data + crc
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", raw) + chunk(b"IEND", b""))
    img = decode_png(png)
    assert img.pixel(0, 0) == (10, 20, 30) and img.pixel(1, 0) == (10, 20, 30)
    assert img.pixel(0, 1) == (11, 21, 31) and img.pixel(1, 1) == (15, 25, 35)


def test_screen_of_matches_the_page_mapping():
    """The pixel the check samples is computed from the CSV through the page's own mapping:
    y grows downwards on screen (a sign slip would sample the mirror image)."""
    v2 = {"kind": "2d", "cx": 1.0, "cy": 2.0, "s": 10.0, "left": 5, "top": 7, "W": 100, "H": 50}
    assert screen_of(v2, [2.0, 3.0]) == (5 + 50 + 10, 7 + 25 - 10)
    v3 = {"kind": "3d", "eye": [0, 0, -10], "f": [0, 0, 1], "r": [1, 0, 0], "u": [0, 1, 0],
          "F": 100, "left": 0, "top": 0, "W": 200, "H": 100}
    assert screen_of(v3, [1, 1, 0]) == (100 + 10, 50 - 10)
    assert screen_of(v3, [0, 0, -20]) is None  # behind the camera
