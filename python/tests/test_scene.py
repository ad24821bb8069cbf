"""Scenes: built-ins load, dicts round-trip, overrides use --set's keys, bad input names its field."""
import json

import pytest

import rtsph


def test_every_builtin_scene_loads():
    names = rtsph.builtin_scenes()
    assert "dam_break_2d" in names and "dam_break_3d" in names
    for name, description in names.items():
        s = rtsph.scene(name)
        assert s.name == name and s.dimension in (2, 3) and description


def test_dict_round_trips_through_to_dict():
    s = rtsph.scene("nozzle_obstacle_2d")
    d = s.to_dict()
    json.dumps(d)  # JSON-compatible
    again = rtsph.scene(d)
    assert again == s
    assert again.to_dict() == d


def test_minimal_dict_scene_gets_defaults():
    s = rtsph.scene({
        "dimension": 2,
        "domain": {"min": [0, 0], "max": [1, 1]},
        "fluid": {"spacing": 0.05},
        "fluid_blocks": [{"min": [0, 0], "max": [0.5, 0.5]}],
    })
    d = s.to_dict()
    assert d["fluid"]["spacing"] == 0.05
    assert d["fluid"]["rest_density"] == 1000.0  # the parameter table's default


def test_overrides_use_dotted_keys():
    s = rtsph.scene("dam_break_2d", {"fluid.spacing": 0.04, "solver.method": "pbf"})
    assert s.to_dict()["fluid"]["spacing"] == 0.04
    assert s.method == "pbf"
    t = rtsph.scene("dam_break_2d", **{"gravity": [0.0, -1.62]})
    assert t.to_dict()["gravity"][:2] == [0.0, -1.62]
    # Scenes are values: overriding returns a copy.
    base = rtsph.scene("dam_break_2d")
    changed = base.with_overrides({"fluid.viscosity": 1e-3})
    assert base.to_dict()["fluid"]["viscosity"] != changed.to_dict()["fluid"]["viscosity"]


@pytest.mark.parametrize("source, field", [
    ({"dimension": 2, "domain": {"min": [0, 0], "max": [1, 1]}, "fluid": {"spacing": -0.01},
      "fluid_blocks": [{"min": [0, 0], "max": [0.5, 0.5]}]}, "fluid.spacing"),
    ({"dimension": 4}, "dimension"),
    ({"dimension": 2, "domain": {"min": [0, 0], "max": [1, 1]}, "fluid": {"spacing": 0.05},
      "fluid_blocks": [{"min": [0, 0], "max": [0.5, 0.5]}], "solver": {"method": "sph2014"}}, "solver.method"),
])
def test_bad_dict_raises_scene_error_naming_the_field(source, field):
    with pytest.raises(rtsph.SceneError) as e:
        rtsph.scene(source)
    assert field in str(e.value)
    assert "\n" not in str(e.value)
    assert isinstance(e.value, ValueError)


def test_bad_override_and_missing_file():
    with pytest.raises(rtsph.SceneError, match="fluid.spacing"):
        rtsph.scene("dam_break_2d", {"fluid.spacing": "wet"})
    with pytest.raises(rtsph.SceneError, match="no_such_key"):
        rtsph.scene("dam_break_2d", {"no_such_key": 1})
    with pytest.raises(rtsph.SceneError, match="no_such_scene"):
        rtsph.scene("no_such_scene")


def test_scene_file_path(tmp_path):
    p = tmp_path / "tank.json"
    p.write_text(rtsph.scene("hydrostatic_2d").to_json())
    assert rtsph.scene(p) == rtsph.scene("hydrostatic_2d")
    p.write_text("{ not json")
    with pytest.raises(rtsph.SceneError, match="tank.json"):
        rtsph.scene(str(p))
