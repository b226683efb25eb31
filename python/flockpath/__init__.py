"""flockpath in a notebook: ``FlockPath(scene="pillars")`` shows a live crowd simulation.

The widget is an anywidget (JupyterLab, Jupyter Notebook 7, VS Code, marimo): its front end is
flockpath's own ``js/widget.js``, which runs the scene in the browser with the same wasm as the
playground; Python sets the scene and the classroom options and reads back what the run did::

    from flockpath import FlockPath
    w = FlockPath(scene="pillars", controls="play,step,reset", lock="obstacles")
    w                   # shows it
    w.step(300)         # the browser steps 300 times, then writes the state below back
    w.digest, w.steps   # in a later cell: '224dd2468fa5099e', 300 (as `flockpath run` prints)
    w.metrics["arrived_share"]

A cell's ``step(n)`` returns at once: the kernel hears the browser's answer only after the cell
ends (it handles no messages while a cell runs), so read ``steps``, ``metrics`` and ``digest``
in the next cell.
"""

from __future__ import annotations

import json
from typing import Any

import anywidget
import traitlets

from ._assets import AssetsMissing, assets_url

__all__ = ["FlockPath", "AssetsMissing", "THEMES", "MAX_STEPS"]

#: The themes the canvas is drawn in (the playground's standard and projector themes).
THEMES = ("standard", "projector")
#: The most steps one ``step(n)`` asks for (the simulation's step counter is 32-bit).
MAX_STEPS = 0xFFFFFFFF

# The module the host loads from a string: it imports the real one by URL, so that module's
# relative imports (the element, js/core/, the wasm) resolve against where it is served.
_LOADER = """
export default {
  async render({ model, el }) {
    const base = model.get('assets_url');
    const { default: widget } = await import(new URL('js/widget.js', base).href);
    return widget.render({ model, el });
  },
};
"""


def _scene_text(scene: Any) -> str:
    """A scene as the widget takes it: text as given, a dict (scene JSON) as JSON text."""
    if scene is None:
        return ""
    if isinstance(scene, dict):
        return json.dumps(scene)
    if isinstance(scene, str):
        return scene
    raise TypeError(f"scene is a preset name, a link, scene JSON text or a dict, not {type(scene).__name__}")


def _option_text(value: Any, *, name: str, true: str, false: str) -> str:
    """An option as the element's attribute: True/False, a name, or a list of names."""
    if value is True:
        return true
    if value is False or value is None:
        return false
    if isinstance(value, str):
        return value.strip()
    if isinstance(value, (list, tuple, set, frozenset)) and all(isinstance(item, str) for item in value):
        return ",".join(value)
    raise TypeError(f"{name} is True, False, a comma-separated string or a list of names, not {value!r}")


class FlockPath(anywidget.AnyWidget):
    """A flockpath scene in a notebook cell, run in the browser.

    Set by you: ``scene`` (a preset name such as ``"pillars"``, a link or its fragment value, or
    scene JSON; a dict is turned into JSON), ``controls`` (``True``/``"all"``, ``False``/
    ``"none"`` or names: ``"play,step,reset,planner,fullscreen"``), ``lock`` and ``hide`` (a
    link's teacher options, e.g. ``lock="obstacles,goals"``), ``theme`` (``"standard"`` or
    ``"projector"``), ``playing``, ``height`` (a CSS length). Written by the widget: ``steps``,
    ``metrics``, ``digest`` (as ``flockpath run`` prints it), ``activity_report`` (``None``
    without an activity), ``error`` (``""``: none; a refused scene or option says why here).
    """

    _esm = _LOADER

    #: Where the browser finds js/widget.js and the wasm ('' at construction: this kernel's server).
    assets_url = traitlets.Unicode("").tag(sync=True)

    scene = traitlets.Unicode("").tag(sync=True)
    controls = traitlets.Unicode("all").tag(sync=True)
    lock = traitlets.Unicode("").tag(sync=True)
    hide = traitlets.Unicode("").tag(sync=True)
    theme = traitlets.Unicode("standard").tag(sync=True)
    playing = traitlets.Bool(False).tag(sync=True)
    height = traitlets.Unicode("").tag(sync=True)

    steps = traitlets.Int(0).tag(sync=True)
    metrics = traitlets.Dict().tag(sync=True)
    digest = traitlets.Unicode("").tag(sync=True)
    activity_report = traitlets.Dict(allow_none=True, default_value=None).tag(sync=True)
    error = traitlets.Unicode("").tag(sync=True)

    def __init__(
        self,
        scene: Any = "pillars",
        *,
        controls: Any = True,
        lock: Any = None,
        hide: Any = None,
        theme: str = "standard",
        playing: bool = False,
        height: str = "",
        assets_url: str | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(
            scene=_scene_text(scene),
            controls=_option_text(controls, name="controls", true="all", false="none"),
            lock=_option_text(lock, name="lock", true="all", false=""),
            hide=_option_text(hide, name="hide", true="all", false=""),
            theme=theme,
            playing=playing,
            height=height,
            assets_url=assets_url or _served_assets(),
            **kwargs,
        )

    @traitlets.validate("theme")
    def _check_theme(self, proposal: dict) -> str:
        if proposal["value"] not in THEMES:
            raise traitlets.TraitError(f"theme is one of {', '.join(THEMES)}, not {proposal['value']!r}")
        return proposal["value"]

    @traitlets.validate("assets_url")
    def _check_assets_url(self, proposal: dict) -> str:
        # The loader resolves js/widget.js against it: without the slash the last segment is lost.
        url = proposal["value"]
        return url if url.endswith("/") else url + "/"

    def step(self, n: int = 1) -> None:
        """Asks the widget to pause and advance ``n`` steps (1 step = 1/60 s of simulated time).

        The browser answers by updating ``steps``, ``metrics``, ``digest`` and
        ``activity_report``, which the kernel sees once the running cell has finished.
        """
        if isinstance(n, bool) or not isinstance(n, int) or not 0 <= n <= MAX_STEPS:
            raise ValueError(f"step(n) takes a whole number of steps from 0 to {MAX_STEPS}, not {n!r}")
        self.send({"type": "step", "n": n})

    def reset(self) -> None:
        """Asks the widget to go back to step 0 of the scene (same seed: the same run again)."""
        self.send({"type": "reset"})

    def load(self, scene: Any) -> None:
        """Loads another scene: a preset name, a link, scene JSON text or a dict."""
        self.scene = _scene_text(scene)


def _served_assets() -> str:
    return assets_url()
