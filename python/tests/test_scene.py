"""Scenes in and out: paths, dicts and arrays agree with the file format."""

import json
import pathlib

import numpy as np

import shade_sim


def test_a_scene_reads_the_same_from_a_path_a_pathlike_and_a_dict(example):
    path = example("bedroom_l")
    by_str = shade_sim.load_scene(path)
    by_pathlike = shade_sim.load_scene(pathlib.Path(path))
    with open(path) as f:
        raw = json.load(f)
    by_dict = shade_sim.load_scene(raw)
    assert by_str == by_pathlike == by_dict
    assert by_str.to_dict() == raw
    assert repr(by_str) == f"Scene(bedroom, 0 objects, {len(raw['humans'])} humans)"


def test_arrays_hold_the_files_numbers(root):
    path = f"{root}/scenes/reference/living_rect.json"
    scene = shade_sim.load_scene(path)
    with open(path) as f:
        raw = json.load(f)
    boxes = scene.boxes()
    assert boxes.shape == (len(raw["objects"]), 7) and boxes.dtype == np.float64
    for row, o in zip(boxes, raw["objects"]):
        assert list(row) == o["center"] + o["size"] + [o["yaw"]]
    assert scene.categories == [o["category"] for o in raw["objects"]]
    h = raw["humans"][1]
    frames = scene.frames(1)
    assert frames.shape == (len(h["frames"]), 19, 3)
    assert np.array_equal(frames, np.array(h["frames"]))
    assert np.array_equal(scene.frames(h["id"]), frames)
    assert np.array_equal(scene.floor(), np.array(raw["floor_plan"]["polygon"]))
    assert scene.human_ids == [h["id"] for h in raw["humans"]]


def test_a_scene_without_objects_has_an_empty_box_array(example):
    assert shade_sim.load_scene(example("dining_rect")).boxes().shape == (0, 7)


def test_save_writes_the_files_bytes(root, tmp_path):
    path = f"{root}/scenes/reference/dining_l.json"
    scene = shade_sim.load_scene(path)
    out = tmp_path / "copy.json"
    scene.save(out)
    assert out.read_bytes() == pathlib.Path(path).read_bytes()
    assert scene.to_json().encode() == out.read_bytes()


def test_a_dict_may_hold_numpy_arrays_and_anything_else_is_a_scene_error(example):
    raw = json.load(open(example("living_l")))
    scene = shade_sim.load_scene(raw)
    raw["humans"][0]["frames"] = scene.frames(0)
    raw["floor_plan"]["polygon"] = scene.floor()
    raw["humans"][0]["fps"] = np.float32(raw["humans"][0]["fps"])
    assert shade_sim.load_scene(raw) == scene
    raw["humans"][0]["skeleton"] = object()
    try:
        shade_sim.load_scene(raw)
    except shade_sim.SceneError as e:
        assert str(e).startswith("<dict>: not JSON data: ")
    else:
        raise AssertionError("an object() in the dict was accepted")
