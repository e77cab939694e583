"""Bad input raises an exception with the command line's one-line text; the interpreter lives on."""

import json
import math
import os
import subprocess

import pytest

import shade_sim


def cli_error(cli, *args):
    """The CLI's error line without its "error: " prefix; asserts exit code 2."""
    r = subprocess.run([cli, *args], capture_output=True, text=True)
    assert r.returncode == 2, r.stderr
    line = r.stderr.strip()
    assert line.startswith("error: ") and "\n" not in line
    return line[len("error: "):]


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def broken_scenes(tmp_path, example):
    good = json.load(open(example("bedroom_rect")))
    nan = json.loads(json.dumps(good))
    nan["humans"][0]["frames"][3][2][0] = "NaN-marker"
    crossed = json.loads(json.dumps(good))
    crossed["floor_plan"]["polygon"] = [[0, 0], [4, 3], [4, 0], [0, 3]]
    return {
        "missing": str(tmp_path / "missing.json"),
        "malformed": write(tmp_path, "malformed.json", '{"format": "shade-scene/1", "room_type": '),
        "nan": write(tmp_path, "nan.json", json.dumps(nan).replace('"NaN-marker"', "NaN")),
        "self_intersecting": write(tmp_path, "crossed.json", json.dumps(crossed)),
        "trailing": write(tmp_path, "trailing.json", json.dumps(good) + "\0xyz"),
    }


def test_every_bad_scene_raises_scene_error_with_the_clis_line(tmp_path, example, cli):
    for name, path in broken_scenes(tmp_path, example).items():
        expected = cli_error(cli, "check", path)
        for call in (shade_sim.load_scene, shade_sim.check, shade_sim.to_mjcf, shade_sim.generate):
            with pytest.raises(shade_sim.SceneError) as e:
                call(path)
            assert str(e.value) == expected, (name, call.__name__)
            assert isinstance(e.value, ValueError)


def test_a_bad_dict_names_the_dict_and_the_field(example):
    raw = json.load(open(example("living_l")))
    raw["humans"][0]["fps"] = -30.0
    with pytest.raises(shade_sim.SceneError, match=r"^<dict>: humans\[0\]\.fps"):
        shade_sim.load_scene(raw)
    raw = json.load(open(example("living_l")))
    raw["floor_plan"]["polygon"][1][0] = math.nan
    with pytest.raises(shade_sim.SceneError, match=r"^<dict>: "):
        shade_sim.load_scene(raw)
    with pytest.raises(shade_sim.SceneError, match=r"missing field `room_type`"):
        shade_sim.load_scene({"format": "shade-scene/1"})


def test_bad_arguments_raise_value_error(example):
    path = example("living_l")
    with pytest.raises(ValueError, match="guidance"):
        shade_sim.generate(path, guidance="gravity")
    with pytest.raises(ValueError, match="samples"):
        shade_sim.generate(path, samples=0)
    with pytest.raises(ValueError, match="expected a Scene, a path or a dict, not int"):
        shade_sim.load_scene(42)
    with pytest.raises(ValueError, match="repair"):
        shade_sim.generate(path, repair=3.5)
    with pytest.raises(IndexError):
        shade_sim.load_scene(path).frames(99)
    with pytest.raises(ValueError, match="clearance"):
        shade_sim.free_spot(path, -1.0)


def test_a_corrupt_model_raises_model_error_naming_the_file(tmp_path, example, cli):
    model = tmp_path / "model"
    model.mkdir()
    (model / "config.json").write_text("{ not json")
    (model / "model.safetensors").write_bytes(b"\0" * 64)
    expected = cli_error(cli, "generate", "--input", example("bedroom_l"), "--out", str(tmp_path / "o"), "--model", str(model))
    with pytest.raises(shade_sim.ModelError) as e:
        shade_sim.generate(example("bedroom_l"), model=model)
    assert str(e.value) == expected
    assert str(e.value).startswith(os.path.join(str(model), "config.json") + ": ")
    assert not (tmp_path / "o").exists()
