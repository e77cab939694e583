"""Generation, the check and the exports through the package."""

import threading
import time

import mujoco
import numpy as np

import shade_sim


def test_the_same_seed_gives_the_same_layouts_and_another_seed_others(example):
    a = shade_sim.generate(example("living_l"), samples=2, seed=3)
    b = shade_sim.generate(example("living_l"), samples=2, seed=3)
    c = shade_sim.generate(example("living_l"), samples=2, seed=4)
    assert len(a) == 2 and all(s.room_type == "living" for s in a)
    assert [s.to_json() for s in a] == [s.to_json() for s in b]
    assert [s.to_json() for s in a] != [s.to_json() for s in c]
    # The input's people and floor come back unchanged; only objects are added.
    src = shade_sim.load_scene(example("living_l")).to_dict()
    out = a[0].to_dict()
    assert (out["humans"], out["floor_plan"]) == (src["humans"], src["floor_plan"])
    assert len(out["objects"]) > 0


def test_generate_matches_the_command_line_byte_for_byte(example, cli, tmp_path):
    import subprocess

    subprocess.run([cli, "-q", "generate", "--input", example("dining_l"), "--out", str(tmp_path), "--seed", "7"], check=True)
    ours = shade_sim.generate(example("dining_l"), seed=7)[0]
    assert (tmp_path / "dining_l_0.json").read_text() == ours.to_json()


def test_require_clean_layouts_pass_the_check_and_unrepaired_ones_mostly_do_not(example):
    clean = shade_sim.generate(example("bedroom_l"), samples=2, seed=0, require_clean=True)
    assert len(clean) == 2
    assert all(shade_sim.check(s) == [] for s in clean)
    raw = shade_sim.generate(example("bedroom_l"), samples=4, seed=0, guidance="none", repair=False)
    violations = [shade_sim.check(s) for s in raw]
    assert any(violations)
    kinds = {v["kind"] for vs in violations for v in vs}
    assert kinds <= {"penetration", "unsupported", "object_overlap", "object_wall", "outside_floor", "unstable"}


def test_people_in_a_wall_are_named_in_a_warning_and_get_no_layout(root):
    import os

    import pytest

    path = os.path.join(root, "tests", "inputs", "sitter_feet_in_the_wall.json")
    with pytest.warns(UserWarning, match=r"input 0: no layout can pass the check: desk's .* m into wall0"):
        layouts = shade_sim.generate(path, seed=0, require_clean=True, attempts=3)
    assert layouts == []


def test_people_inside_each_other_are_a_warning_in_check_and_generate(root):
    import warnings

    import pytest

    raw = shade_sim.load_scene(f"{root}/tests/inputs/three_on_a_sofa.json").to_dict()
    # No one meets in the input as built.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        shade_sim.check(raw, stability=False)
    # A fourth sitter 10 cm from the first: their bodies overlap, which is a warning, not a violation.
    first = raw["humans"][0]
    twin = dict(first, id="twin", frames=[[[x + 0.1, y, z] for x, y, z in frame] for frame in first["frames"]])
    raw["humans"].append(twin)
    with pytest.warns(UserWarning, match=r"left and twin are inside each other: left's .* m into twin's"):
        found = shade_sim.check(raw, stability=False)
    # With no furniture the sitters are unsupported, and that is all the check calls a violation.
    assert {v["kind"] for v in found} == {"unsupported"}
    with pytest.warns(UserWarning, match=r"input 0: left and twin are inside each other"):
        shade_sim.generate(raw, seed=0, repair=False, guidance="none")


def test_more_people_in_contact_than_the_model_sees_are_named_in_a_warning(root):
    import pytest

    raw = shade_sim.load_scene(f"{root}/tests/inputs/dinner_for_three.json").to_dict()
    # Three diners copied 4.5 m along, three times: twelve sitters (no one meets another), and the
    # dining model anchors eight.
    diners = raw["humans"][:3]
    raw["floor_plan"]["polygon"] = [[0, 0], [18, 0], [18, 3.6], [0, 3.6]]
    raw["humans"] = [
        dict(h, id=f"{h['id']}{k}", frames=[[[x + 4.5 * k, y, z] for x, y, z in f] for f in h["frames"]])
        for k in range(4)
        for h in diners
    ]
    with pytest.warns(UserWarning) as said:
        shade_sim.generate(raw, seed=0, repair=False, guidance="none")
    notes = [str(w.message) for w in said]
    assert any(n.startswith("input 0: 4 contact spans beyond the 8 the model conditions on (head2 sit, ") for n in notes), notes
    # The 18 m × 3.6 m room is larger and longer than any the dining model was trained on, and it
    # says so too.
    assert any("its 64.8 m² is larger than any" in n and "it is 18.0 m long, longer than any" in n for n in notes), notes


def test_a_floor_unlike_any_training_room_is_named_in_a_warning(root):
    import pytest

    raw = shade_sim.load_scene(f"{root}/tests/inputs/dinner_for_three.json").to_dict()
    # 10 m × 8 m: twice the largest of the dining model's training rooms (40 m²).
    raw["floor_plan"]["polygon"] = [[-3, -2], [7, -2], [7, 6], [-3, 6]]
    with pytest.warns(UserWarning, match=r"input 0: the floor plan is unlike the model's dining training rooms: its 80\.0 m² is larger than any \(10\.0–40\.0 m²\)"):
        shade_sim.generate(raw, seed=0, repair=False, guidance="none")


def test_check_reports_two_overlapping_pieces(root):
    raw = shade_sim.load_scene(f"{root}/scenes/reference/bedroom_rect.json").to_dict()
    first = raw["objects"][0]
    raw["objects"].append(dict(first, id="copy"))
    found = shade_sim.check(raw, stability=False)
    overlap = [v for v in found if v["kind"] == "object_overlap"]
    assert overlap and {overlap[0]["object"], overlap[0]["other"]} == {first["id"], "copy"}
    assert overlap[0]["depth"] > 0.1


def test_the_gil_is_released_while_rust_generates(example):
    done = threading.Event()
    ticks = 0

    def work():
        shade_sim.generate(example("bedroom_rect"), samples=2, seed=1)
        done.set()

    thread = threading.Thread(target=work)
    start = time.perf_counter()
    thread.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    thread.join()
    elapsed = time.perf_counter() - start
    # A held GIL would stop this loop for the whole call; released, it ticks about once a ms.
    assert elapsed > 0.2 and ticks > elapsed * 200, (ticks, elapsed)


def test_the_mjcf_world_replays_the_people_in_mujoco(root):
    scene = shade_sim.load_scene(f"{root}/scenes/reference/living_l.json")
    model = mujoco.MjModel.from_xml_string(shade_sim.to_mjcf(scene))
    data = mujoco.MjData(model)
    motion = shade_sim.mocap_motion(scene)
    frames = motion["frames"]
    assert model.nkey == frames.shape[0] and model.nmocap == frames.shape[1] == len(motion["bodies"])
    ids = [model.body(name).mocapid[0] for name in motion["bodies"]]
    for k in (0, model.nkey // 2, model.nkey - 1):
        mujoco.mj_resetDataKeyframe(model, data, k)
        mujoco.mj_forward(model, data)
        assert np.allclose(data.mocap_pos[ids], frames[k, :, :3], atol=1e-5)
    free = mujoco.MjModel.from_xml_string(shade_sim.to_mjcf(scene, free_furniture=True, keyframes=False))
    # Every standing piece gets a free joint (hanging ones stay fixed to their wall).
    assert free.nkey == 0 and 0 < free.njnt <= len(scene.object_ids)
    assert all(free.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE for j in range(free.njnt))
    assert "<pair" not in shade_sim.to_mjcf(scene, contact_pairs=False)


def test_the_free_spot_is_on_the_floor_and_clear_of_everything(root):
    scene = shade_sim.load_scene(f"{root}/scenes/reference/dining_l.json")
    x, y = shade_sim.free_spot(scene, 0.3)
    p = np.array([x, y])
    joints = np.concatenate([scene.frames(i).reshape(-1, 3)[:, :2] for i in range(len(scene.human_ids))])
    assert np.min(np.linalg.norm(joints - p, axis=1)) > 0.3
    for cx, cy, _, sx, sy, _, yaw in scene.boxes():
        c, s = np.cos(-yaw), np.sin(-yaw)
        d = p - [cx, cy]
        local = np.abs([d[0] * c - d[1] * s, d[0] * s + d[1] * c]) - [sx / 2, sy / 2]
        assert np.linalg.norm(np.maximum(local, 0)) >= 0.3
    assert shade_sim.free_spot(scene, 50.0) is None


def test_a_list_of_inputs_gives_what_the_command_line_gives_for_a_folder(example, cli, tmp_path):
    import shutil
    import subprocess

    names = ["living_rect", "bedroom_l", "living_l"]
    folder = tmp_path / "in"
    folder.mkdir()
    for i, n in enumerate(names):
        # The CLI reads a folder in name order: number the files to keep this order.
        shutil.copy(example(n), folder / f"{i}_{n}.json")
    subprocess.run([cli, "-q", "generate", "--input", str(folder), "--out", str(tmp_path / "out"), "--samples", "2", "--seed", "9"], check=True)
    lists = shade_sim.generate([example(n) for n in names], samples=2, seed=9)
    assert [len(x) for x in lists] == [2, 2, 2]
    for i, (n, layouts) in enumerate(zip(names, lists)):
        for k, s in enumerate(layouts):
            assert (tmp_path / "out" / f"{i}_{n}_{k}.json").read_text() == s.to_json(), (n, k)
    # A tuple works as a list; one input alone is a flat list.
    assert [s.to_json() for s in shade_sim.generate((example("bedroom_l"),), seed=9)[0]] == [
        s.to_json() for s in shade_sim.generate(example("bedroom_l"), seed=9)
    ]
