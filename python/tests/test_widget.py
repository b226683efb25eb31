"""The notebook widget's Python side, without a browser: options as the element takes them, the
messages step(n) and reset() put on the wire, the state the front end writes back, and the
server that hands the browser the package's copy of www/."""

from __future__ import annotations

import json
import urllib.error
import urllib.request
from pathlib import Path

import pytest
import traitlets

import flockpath
from flockpath import FlockPath, _assets

REPO = Path(__file__).resolve().parents[2]


class Wire:
    """Records what the widget sends over its comm (as the front end would receive it)."""

    def __init__(self, widget: FlockPath) -> None:
        self.sent: list[dict] = []
        widget.comm.send = lambda data=None, buffers=None, **_: self.sent.append(data)

    def custom(self) -> list[dict]:
        return [m["content"] for m in self.sent if m.get("method") == "custom"]


def front_end_update(widget: FlockPath, state: dict) -> None:
    """Delivers an update message as the browser's `model.save_changes()` sends it."""
    widget._handle_msg({"content": {"data": {"method": "update", "state": state, "buffer_paths": []}}, "buffers": []})


def test_defaults_sync_the_documented_state() -> None:
    w = FlockPath()
    state = w.get_state()
    assert state["scene"] == "pillars"
    assert state["controls"] == "all"
    assert (state["lock"], state["hide"], state["theme"], state["playing"]) == ("", "", "standard", False)
    for written_back in ("steps", "metrics", "digest", "activity_report", "error"):
        assert written_back in state
    assert (w.steps, w.digest, w.activity_report) == (0, "", None)


def test_options_become_the_elements_attributes() -> None:
    w = FlockPath("corridor", controls=["play", "step"], lock=True, hide="metrics")
    assert (w.scene, w.controls, w.lock, w.hide) == ("corridor", "play,step", "all", "metrics")
    assert FlockPath(controls=False).controls == "none"
    assert FlockPath(controls=" play,reset ").controls == "play,reset"
    with pytest.raises(TypeError, match="controls"):
        FlockPath(controls=3)
    with pytest.raises(TypeError, match="scene"):
        FlockPath(scene=42)


def test_a_scene_dict_travels_as_json_and_load_replaces_it() -> None:
    scene = {"name": "mine", "width": 400, "height": 300, "groups": []}
    w = FlockPath(scene)
    assert json.loads(w.scene) == scene
    w.load("2.abc")
    assert w.scene == "2.abc"


def test_theme_is_checked() -> None:
    w = FlockPath(theme="projector")
    assert w.theme == "projector"
    with pytest.raises(traitlets.TraitError, match="standard, projector"):
        w.theme = "dark"


def test_step_and_reset_send_messages_to_the_front_end() -> None:
    w = FlockPath()
    wire = Wire(w)
    w.step(300)
    w.step()
    w.reset()
    assert wire.custom() == [{"type": "step", "n": 300}, {"type": "step", "n": 1}, {"type": "reset"}]


@pytest.mark.parametrize("bad", [-1, 1.5, True, "3", flockpath.MAX_STEPS + 1])
def test_step_refuses_what_is_not_a_step_count(bad: object) -> None:
    w = FlockPath()
    wire = Wire(w)
    with pytest.raises(ValueError, match="whole number of steps"):
        w.step(bad)  # type: ignore[arg-type]
    assert wire.custom() == []


def test_the_front_ends_answer_is_read_from_python() -> None:
    w = FlockPath()
    seen = []
    w.observe(lambda change: seen.append(change["name"]), names=["steps", "digest"])
    report = {"met": True, "step": 416}
    front_end_update(
        w,
        {"steps": 300, "digest": "224dd2468fa5099e", "metrics": {"arrived_share": 0.5}, "activity_report": report},
    )
    assert (w.steps, w.digest, w.metrics["arrived_share"], w.activity_report) == (300, "224dd2468fa5099e", 0.5, report)
    assert sorted(seen) == ["digest", "steps"]
    front_end_update(w, {"error": "The scene could not be loaded", "playing": True})
    assert (w.error, w.playing) == ("The scene could not be loaded", True)


def test_setting_state_in_python_is_sent_to_the_front_end() -> None:
    w = FlockPath()
    wire = Wire(w)
    w.playing = True
    w.theme = "projector"
    updates = [m["state"] for m in wire.sent if m.get("method") == "update"]
    assert {"playing": True} in updates and {"theme": "projector"} in updates


def test_the_loader_imports_the_served_module() -> None:
    w = FlockPath()
    assert w.assets_url.startswith("http://127.0.0.1:") and w.assets_url.endswith("/")
    assert "new URL('js/widget.js', base)" in w._esm
    assert FlockPath(assets_url="https://example.org/flockpath").assets_url == "https://example.org/flockpath/"


def test_the_server_hands_out_the_module_and_the_wasm_with_cors() -> None:
    base = FlockPath().assets_url
    for path, mime in [("js/widget.js", "text/javascript"), ("js/core/boot.js", "text/javascript"), ("pkg/flockpath_bg.wasm", "application/wasm")]:
        with urllib.request.urlopen(base + path) as response:
            assert response.headers["Content-Type"] == mime, path
            assert response.headers["Access-Control-Allow-Origin"] == "*", path
            assert len(response.read()) > 0
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(base + "js/no-such-module.js")
    assert refused.value.code == 404
    # One server per kernel, however many widgets.
    assert FlockPath().assets_url == base


def test_the_package_holds_the_current_build() -> None:
    # A stale copy would run other code than www/ (rebuild: scripts/build-python.sh, pip install).
    static = _assets.STATIC_DIR
    for name in ("js/widget.js", "js/flock-path.js", "js/core/boot.js"):
        assert (static / name).read_bytes() == (REPO / "www" / name).read_bytes(), name


def test_without_the_build_it_says_how_to_make_it(tmp_path: Path) -> None:
    with pytest.raises(_assets.AssetsMissing, match="scripts/build-python.sh"):
        _assets.assets_url(tmp_path)
    assert _assets.missing_files(tmp_path) == list(_assets.REQUIRED)
