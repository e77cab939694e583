"""Motion in from Python: files as the command line imports them, and joint arrays in memory (what a
body model gives for an AMASS or SMPL-X fit)."""

import os
import subprocess

import numpy as np
import pytest

import shade_sim


def clip(root, name):
    return os.path.join(root, "scenes", "motion", name)


def test_a_bvh_file_imports_as_the_command_line_writes_it(cli, root, tmp_path):
    walk = clip(root, "freebvh_walk.bvh")
    out = tmp_path / "walk.json"
    args = ["import-motion", walk, "--room", "bedroom", "--floor", "4x4", "--place", "1,1,0", "--trim", "0.5:2"]
    subprocess.run([cli, "-q", *args, "--out", str(out)], check=True)
    scene = shade_sim.import_motion([walk], "bedroom", (4, 4), place=[(1, 1, 0)], trim=[(0.5, 2)])
    assert scene.to_json() == shade_sim.load_scene(str(out)).to_json()
    assert scene.human_ids == ["h0"] and scene.frames(0).shape == (46, 19, 3)


def test_a_scene_human_as_an_array_comes_back_as_it_was(root):
    # A person who walks in, sits down and walks out, as (T, 19, 3) in metres with our joint
    # names; unnamed, and in centimetres (detected), the same.
    source = shade_sim.load_scene(os.path.join(root, "tests", "inputs", "sofa_visit.json"))
    frames = source.frames("guest")
    names = source.to_dict()["humans"][0]["skeleton"]["joints"]
    assert source.to_dict()["humans"][0]["id"] == "guest"
    named = shade_sim.import_motion([{"joints": frames, "names": names, "fps": 10}], "living", source, fps=10)
    back = named.frames(0)
    assert back.shape == frames.shape
    assert np.abs(back - frames).max() < 5e-4
    assert [s["action"] for s in named.to_dict()["humans"][0]["actions"]] == ["walk", "stand", "walk", "sit", "walk", "stand", "walk"]
    unnamed = shade_sim.import_motion([frames * 100.0], "living", source, fps=10, source_fps=10)
    assert np.abs(unnamed.frames(0) - back).max() < 5e-4


def test_motions_that_cannot_be_imported_raise_motion_error_with_the_command_line_text(cli, root, tmp_path):
    walk = clip(root, "freebvh_walk.bvh")
    with pytest.raises(shade_sim.MotionError, match=r"^<motion 0>: array `joints` has shape \[4, 22, 2\]"):
        shade_sim.import_motion([np.zeros((4, 22, 2))], "living", (5, 4))
    with pytest.raises(shade_sim.MotionError, match=r"^<motion 1>: unknown rig: 7 joints without names"):
        shade_sim.import_motion([walk, np.zeros((4, 7, 3))], "living", (5, 4), place=[(2, 2, 0)])
    out = tmp_path / "never.json"
    for extra, python in [
        (["--trim", "3:4"], dict(trim=[(3, 4)])),
        (["--place", "2,3.5,0"], dict(place=[(2, 3.5, 0)])),
    ]:
        args = ["import-motion", walk, "--room", "bedroom", "--floor", "4x4", "--out", str(out), *extra]
        if "--place" not in extra:
            args += ["--place", "2,1,0"]
            python["place"] = [(2, 1, 0)]
        r = subprocess.run([cli, *args], capture_output=True, text=True)
        assert r.returncode == 2 and r.stderr.startswith("error: ")
        with pytest.raises(shade_sim.MotionError) as e:
            shade_sim.import_motion([walk], "bedroom", (4, 4), **python)
        assert str(e.value) == r.stderr.strip()[len("error: "):]
        assert not out.exists()
    with pytest.raises(shade_sim.MotionError, match="missing.bvh"):
        shade_sim.import_motion([str(tmp_path / "missing.bvh")], "living", (5, 4))
    with pytest.raises(ValueError, match='room: "kitchen"'):
        shade_sim.import_motion([walk], "kitchen", (5, 4))
    with pytest.raises(ValueError, match="floor: expected"):
        shade_sim.import_motion([walk], "living", "5x4")
    # A floor given as corners that cross is named as the floor, not as the motion placed in it.
    with pytest.raises(ValueError, match=r"floor: floor_plan.polygon: floor polygon intersects itself"):
        shade_sim.import_motion([walk], "living", [(0, 0), (4, 4), (4, 0), (0, 4)])
    with pytest.raises(ValueError, match=r"floor: floor_plan.polygon: 1000 is outside"):
        shade_sim.import_motion([walk], "living", (1000, 1000), place=["auto"])
    with pytest.raises(ValueError, match=r"place: one entry per motion, e.g. \['auto'\]"):
        shade_sim.import_motion([walk], "living", (5, 4), place="auto")
    with pytest.raises(ValueError, match="motions: "):
        shade_sim.import_motion([42], "living", (5, 4))


def test_an_imported_array_is_furnished_checked_and_exported_from_python(root):
    # The README's BVH -> input -> generate -> MJCF, in Python, from a walk handed over as an
    # array; given spans replace the labels where they lie.
    walk = shade_sim.import_motion([clip(root, "freebvh_walk.bvh")], "bedroom", (4, 4), place=[(1, 1, 0)])
    frames = walk.frames(0)
    names = walk.to_dict()["humans"][0]["skeleton"]["joints"]
    spans = [{"action": "stand", "start": 0, "end": np.int64(10)}]  # numpy numbers as Python's
    again = shade_sim.import_motion(
        [{"joints": frames, "names": names, "fps": 30}], "bedroom", walk, actions=[spans]
    )
    actions = again.to_dict()["humans"][0]["actions"]
    assert actions[0] == {"action": "stand", "start": 0, "end": 10} and actions[1]["action"] == "walk"
    layout = shade_sim.generate(again, seed=0, require_clean=True)[0]
    assert shade_sim.check(layout) == []
    mjcf = shade_sim.to_mjcf(layout)
    assert "<mujoco" in mjcf and 'body name="h0_pelvis-spine" mocap="true"' in mjcf
    with pytest.raises(ValueError, match="actions: not a list of action spans"):
        shade_sim.import_motion([clip(root, "freebvh_walk.bvh")], "bedroom", (4, 4), place=[(1, 1, 0)], actions=[[{"start": 0}]])


def test_place_auto_puts_the_motion_where_it_fits_as_the_command_line_does(cli, root, tmp_path):
    cmu = clip(root, "cmu_01_01.bvh")
    out = tmp_path / "auto.json"
    args = ["import-motion", cmu, "--room", "living", "--floor", "5x4", "--place", "auto", "--out", str(out)]
    subprocess.run([cli, "-q", *args], check=True)
    scene = shade_sim.import_motion([cmu], "living", (5, 4), place=["auto"])
    assert scene.to_json() == shade_sim.load_scene(str(out)).to_json()
    with pytest.raises(shade_sim.MotionError, match="no placement keeps the clip inside"):
        shade_sim.import_motion([cmu], "living", (2, 2), place=["auto"])
    with pytest.raises(ValueError, match="place: each entry"):
        shade_sim.import_motion([cmu], "living", (5, 4), place=["centre"])
    # Two clips placed by auto are put apart, not both at the first spot that fits.
    walk = clip(root, "freebvh_walk.bvh")
    two = shade_sim.import_motion([walk, walk], "living", (5, 4), place=["auto", "auto"])
    starts = [two.frames(i)[0, 0, :2] for i in range(2)]
    assert np.linalg.norm(starts[0] - starts[1]) > 0.5, starts


def test_the_readme_s_python_lines_run_as_written(root, monkeypatch):
    readme = open(os.path.join(root, "README.md"), encoding="utf-8").read()
    block = readme.split("## Python", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
    assert "shade_sim.import_motion(" in block
    monkeypatch.chdir(root)
    names = {}
    exec(compile(block, "README.md", "exec"), names)
    assert names["mjcf"].startswith("<mujoco") and shade_sim.check(names["layouts"][0]) == []


def test_a_walk_through_where_a_seat_must_stand_is_a_user_warning(root):
    path = os.path.join(root, "tests", "inputs", "walk_through_the_chair.json")
    with pytest.warns(UserWarning, match="reader's right_knee-right_ankle is 0.146 m into where reader sits"):
        layouts = shade_sim.generate(path, guidance="none", repair=False)
    assert len(layouts) == 1


def test_a_clip_that_climbs_is_warned_about_and_a_room_lower_than_the_person_refused(root):
    # CMU 01_03 stands on playground bars for 8 s: no piece is for standing on.
    climb = shade_sim.import_motion([clip(root, "cmu_01_03.bvh")], "bedroom", (5, 4), place=["auto"])
    with pytest.warns(UserWarning) as caught:
        layouts = shade_sim.generate(climb, seed=0, require_clean=True, attempts=2)
    assert layouts == []
    messages = [str(w.message) for w in caught]
    assert any("input 0: h0's feet are off the floor at frames 103–341" in m for m in messages), messages
    # Sampled once, not once per attempt: no layout can hold the climber.
    assert any("input 0: no clean layout in 1 samples" in m for m in messages), messages
    with pytest.raises(shade_sim.MotionError, match=r"the neck–head is 0.31 m inside the ceiling \(1.50 m high\)"):
        shade_sim.import_motion([clip(root, "freebvh_walk.bvh")], "bedroom", (5, 4), place=["auto"], height=1.5)
