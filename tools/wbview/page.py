"""One self-contained HTML file from the viewer's data: the template, its script and style
(tools/wbview/page/), the metadata as JSON and each binary block as base64 text in a
script element of its own type (the browser does not parse it as code).

The script is plain JavaScript on Canvas 2D, no library (docs/view.md, "Why plain
Canvas"), in six files joined here into one function in this order (geom.js is shared with
the live pages, tools/wbview/live)."""
import html
import json
import os
import re

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "page")
SCRIPTS = ["geom.js", "core.js", "view2d.js", "view3d.js", "charts.js", "ui.js"]


def _read(name):
    with open(os.path.join(HERE, name), encoding="utf-8") as f:
        return f.read()


def _script_safe(text):
    """Text that cannot end the <script> element it sits in."""
    return text.replace("</", "<\\/").replace("<!--", "<\\!--")


def render(meta):
    """The page's HTML text. Binary blocks (base64 strings in meta under the keys
    "data" and "pos") move out of the JSON into <script type="application/octet-stream">
    elements, referred to as "#blob:K"."""
    blobs = []

    def take(s):
        blobs.append(s)
        return f"#blob:{len(blobs) - 1}"
    for run in meta["runs"]:
        run["data"] = take(run["data"])
    if meta.get("exact"):
        meta["exact"]["pos"] = take(meta["exact"]["pos"])
    meta_json = _script_safe(json.dumps(meta, separators=(",", ":"), allow_nan=False))
    blob_html = "\n".join(f'<script type="application/octet-stream" id="wb-blob-{k}">{b}</script>'
                          for k, b in enumerate(blobs))
    title = (meta.get("name") or os.path.basename(meta["runs"][0]["path"])) + " — tools/view"
    js = ('"use strict";\n(function () {\n' + "\n".join(_read(name) for name in SCRIPTS)
          + "})();\n")
    if re.search(r"</script|<script|<!--", js, re.I):
        raise AssertionError("tools/wbview/page/*.js hold '</script', '<script' or '<!--', "
                             "which would end their <script> element early")
    parts = {"TITLE": html.escape(title), "CSS": _read("view.css"), "JS": js,
             "META": meta_json, "BLOBS": blob_html}
    # One pass over the template: a value that holds "{{...}}" (a scene's description) is
    # never expanded again.
    return re.sub(r"\{\{([A-Z]+)\}\}", lambda m: parts[m.group(1)], _read("view.html"))
