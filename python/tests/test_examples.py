"""The examples run for real: robosuite environment, scene stream, Ray scale-out."""

import os

import numpy as np
import pytest

import shade_sim


def test_a_panda_steps_200_times_in_a_generated_room(example):
    import robosuite_env

    r = robosuite_env.run(example("living_rect"), seed=0, steps=200)
    assert r["steps"] == 200 and r["finite"]
    assert abs(r["time"] - 200 * 0.05) < 1e-6  # robosuite's default 20 Hz control
    assert 0.01 < np.linalg.norm(r["eef_end"] - r["eef_start"]) < 2.0
    assert r["objects"] > 0 and r["mocap_bodies"] > 0
    # The people replay: each step places them at the step's start time, so after 200 steps they
    # are where the motion has them at 199 × 0.05 s (looped).
    scene = shade_sim.generate(example("living_rect"), seed=0, require_clean=True)[0]
    motion = shade_sim.mocap_motion(scene)
    frame = motion["frames"][int(round(199 * 0.05 * motion["fps"])) % len(motion["frames"])]
    assert np.allclose(r["mocap_pos"], frame[:, :3], atol=1e-6)


def test_the_robosuite_arena_merges_with_a_robot(example):
    from robosuite.models.robots import Panda
    from robosuite.models.world import MujocoWorldBase

    scene = shade_sim.generate(example("bedroom_l"), seed=0)[0]
    world = MujocoWorldBase()
    world.merge(shade_sim.robosuite_arena(scene))
    robot = Panda()
    x, y = shade_sim.free_spot(scene, 0.3)
    robot.set_base_xpos([x, y, 0.0])
    world.merge(robot)
    model = world.get_model(mode="mujoco")
    assert model.nmocap >= len(shade_sim.mocap_motion(scene)["bodies"])
    assert all(model.body(f"{o}").id >= 0 for o in scene.object_ids)


def test_the_scene_stream_is_checked_and_reproducible(example):
    import itertools

    import gym_scenes

    inputs = [example("bedroom_rect"), example("dining_l")]
    first = list(itertools.islice(gym_scenes.scenes(inputs, seed=5), 3))
    again = list(itertools.islice(gym_scenes.scenes(inputs, seed=5), 3))
    assert [s.mjcf for s in first] == [s.mjcf for s in again]
    assert [os.path.basename(s.input) for s in first] == ["bedroom_rect.json", "dining_l.json", "bedroom_rect.json"]
    assert [s.seed for s in first] == [5, 6, 7]
    assert all(shade_sim.check(s.scene) == [] for s in first)
    assert first[0].mjcf != first[2].mjcf


@pytest.fixture(scope="module")
def inputs(tmp_path_factory, example):
    folder = tmp_path_factory.mktemp("inputs")
    for name in ("bedroom_rect", "living_l"):
        (folder / f"{name}.json").write_bytes(open(example(name), "rb").read())
    return str(folder)


def test_ray_on_two_workers_writes_what_one_process_writes(inputs, tmp_path):
    import ray_generate

    alone = ray_generate.run(inputs, 2, 0, str(tmp_path / "alone"), seed=11)
    spread = ray_generate.run(inputs, 2, 2, str(tmp_path / "ray"), seed=11)
    names = sorted(os.listdir(tmp_path / "alone"))
    assert names == ["bedroom_rect_0.json", "bedroom_rect_1.json", "living_l_0.json", "living_l_1.json"]
    assert sorted(os.listdir(tmp_path / "ray")) == names
    for n in names:
        assert (tmp_path / "alone" / n).read_bytes() == (tmp_path / "ray" / n).read_bytes(), n
    assert alone["written"] == spread["written"] == 4
    # Seeds are seed + k: the first sample is the library's own generate with seed 11.
    assert (tmp_path / "alone" / "living_l_0.json").read_text() == shade_sim.generate(f"{inputs}/living_l.json", seed=11)[0].to_json()


def test_ray_retries_a_task_whose_worker_dies(inputs, tmp_path):
    import ray_generate

    markers = tmp_path / "attempts"
    markers.mkdir()
    r = ray_generate.run(inputs, 1, 2, str(tmp_path / "out"), seed=11, kill_first_attempt=str(markers))
    assert r["written"] == 2
    assert sorted(os.listdir(markers)) == ["bedroom_rect_0.json.attempted", "living_l_0.json.attempted"]
    expected = shade_sim.generate(f"{inputs}/bedroom_rect.json", seed=11)[0].to_json()
    assert (tmp_path / "out" / "bedroom_rect_0.json").read_text() == expected


def test_ray_names_a_bad_input(inputs, tmp_path):
    import ray_generate

    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "broken.json").write_text('{"format": "shade-scene/1"')
    with pytest.raises(shade_sim.SceneError, match="broken.json"):
        ray_generate.run(str(bad), 1, 2, str(tmp_path / "out"))
    assert not (tmp_path / "out").exists() or os.listdir(tmp_path / "out") == []
