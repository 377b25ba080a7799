"""One self-contained live page of a lab: the template, its script (tools/wbview's
geom.js, then tools/wbview/live/page/*.js) and style, the lab's default scenes with what the
page draws of them, the solution's recorded runs where there are some, and the lab's
WebAssembly modules (their JavaScript, the WebAssembly inside as base64), each in a
script element of its own. Opens from disk: no server, no network."""
import html
import json
import math
import os
import re

from wbplot.claims import strip_markers
from wbview.data import InputError, particle_scene, rigid_scene

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "page")
SHARED = os.path.join(os.path.dirname(os.path.dirname(HERE)), "page", "geom.js")
SCRIPTS = ["core.js", "view2d.js", "view3d.js", "ui.js"]
# The scene a lab's page opens on (another is a menu away); a lab not named here opens
# on its first scene.
FIRST_SCENE = {"forces": "flock", "euler": "oscillator", "midpoint": "orbit-eccentric",
               "implicit": "stiff-rope", "collisions": "pile", "rigid": "dzhanibekov"}


def _read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def _json_in_script(value):
    """JSON text that cannot end or comment its <script> element: every '<' (only ever
    inside a JSON string) is written as \\u003c."""
    return json.dumps(value, separators=(",", ":"), allow_nan=False).replace("<", "\\u003c")


def particle_count(doc):
    """The particles a scene declares: its particles, emitters and generators."""
    n = len(doc.get("particles", []) or [])
    n += sum(int(e.get("count", 0)) for e in doc.get("emitters", []) or [] if isinstance(e, dict))
    rope, cloth = doc.get("rope"), doc.get("cloth")
    if isinstance(rope, dict):
        n += int(rope.get("beads", 0))
    if isinstance(cloth, dict):
        n += int(cloth.get("rows", 0)) * int(cloth.get("cols", 0))
    return n


def oscillator_omega(doc):
    """w = sqrt(k/m) of a scene whose exact motion is the oscillator, else None: the page
    shows explicit Euler's energy factor 1 + h^2 w^2 beside the measured one."""
    if doc.get("exact") != "oscillator":
        return None
    try:
        return math.sqrt(doc["forces"][0]["k"] / doc["particles"][0]["m"])
    except (KeyError, IndexError, TypeError, ZeroDivisionError, ValueError):
        return None


def scene_block(path, kind, recorded):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    try:
        doc = json.loads(text)
    except ValueError as e:
        raise InputError(f"{path}: not valid JSON ({e})") from None
    name = os.path.basename(path)[:-5]
    if kind == "rigid":
        shown = rigid_scene(doc, len(doc.get("bodies", [])), path)
    else:
        shown = particle_scene(doc, particle_count(doc), path)
        shown.pop("radii")  # the page reads them from the scene as the knobs change it
    desc = doc.get("description")
    if recorded is not None:
        recorded["integrator"] = doc.get("integrator")
    return {"name": name, "file": os.path.relpath(path, os.getcwd()), "text": text,
            "description": strip_markers(desc) if isinstance(desc, str) else None,
            "dt": doc.get("dt"), "integrator": doc.get("integrator"), "model": shown,
            "omega": oscillator_omega(doc), "reference": recorded}


def module_script(side, js):
    if re.search(r"</script", js, re.I):
        raise AssertionError(f"the {side} module holds '</script', which would end its element")
    return ('<script>(function () {\n' + js + '\n(window.WB_LIVE_MODULES = '
            'window.WB_LIVE_MODULES || {})[' + json.dumps(side) + '] = wbLiveModule;\n})();'
            '</script>')


def render(lab, kind, scenes, modules, main, built):
    """The page's HTML. scenes: scene_block()s; modules: {side: the module's JavaScript};
    main: the side the first run uses; built: {"from": ..., "command": ...}."""
    first = FIRST_SCENE.get(lab)
    names = [s["name"] for s in scenes]
    meta = {"version": 1, "lab": lab, "kind": kind, "scenes": scenes, "main": main,
            "modules": sorted(modules, key=lambda s: s != main), "built": built,
            "default_scene": first if first in names else names[0]}
    js = ("\"use strict\";\n(function () {\n" + _read(SHARED) + "\n"
          + "\n".join(_read(os.path.join(HERE, n)) for n in SCRIPTS) + "})();\n")
    if re.search(r"</script|<script|<!--", js, re.I):
        raise AssertionError("tools/wbview/live/page/*.js hold '</script', '<script' or '<!--'")
    parts = {"TITLE": html.escape(f"{lab} — live"), "CSS": _read(os.path.join(HERE, "live.css")),
             "JS": js, "META": _json_in_script(meta),
             "MODULES": "\n".join(module_script(s, modules[s]) for s in meta["modules"])}
    return re.sub(r"\{\{([A-Z]+)\}\}", lambda m: parts[m.group(1)],
                  _read(os.path.join(HERE, "live.html")))
