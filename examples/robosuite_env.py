"""A robosuite environment whose arena is a generated shade-sim scene.

    python examples/robosuite_env.py [INPUT.json] [--seed S] [--steps N]

Generates a checked layout for INPUT (default: scenes/examples/living_rect.json) with the
shade_sim package, builds a robosuite manipulation environment around it (a Panda on its mount at
the floor point furthest from the furniture, the walls and everywhere the people move), replays
the people as mocap bodies while the robot acts, resets it and steps it N times (default 200) with
random actions, headless. Needs robosuite and the shade_sim wheel (scripts/setup_python.sh,
scripts/build_python.sh).
"""

from __future__ import annotations

import argparse
import os
import sys

import numpy as np

import shade_sim
from robosuite.environments.manipulation.manipulation_env import ManipulationEnv
from robosuite.models.tasks import ManipulationTask

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_INPUT = os.path.join(ROOT, "scenes", "examples", "living_rect.json")


class ShadeSceneEnv(ManipulationEnv):
    """A robot in a shade-sim scene: the scene's room and furniture as the arena, its people as
    mocap bodies that replay their motion in time with the simulation (looping), and the robot's
    base at ``shade_sim.free_spot``. No task: the reward is 0 and an episode never succeeds."""

    def __init__(self, scene, robots="Panda", clearance=0.35, **kwargs):
        self.scene = shade_sim.load_scene(scene)
        spot = shade_sim.free_spot(self.scene, clearance)
        if spot is None:
            raise ValueError(f"no floor point of the scene is {clearance} m clear of furniture, walls and people")
        self.robot_spot = spot
        self.motion = shade_sim.mocap_motion(self.scene)
        kwargs.setdefault("has_renderer", False)
        kwargs.setdefault("has_offscreen_renderer", False)
        kwargs.setdefault("use_camera_obs", False)
        kwargs.setdefault("render_camera", None)
        super().__init__(robots=robots, **kwargs)

    def _load_model(self):
        super()._load_model()
        robot = self.robots[0].robot_model
        robot.set_base_xpos([self.robot_spot[0], self.robot_spot[1], 0.0])
        self.model = ManipulationTask(mujoco_arena=shade_sim.robosuite_arena(self.scene), mujoco_robots=[robot])

    def _setup_references(self):
        super()._setup_references()
        model = self.sim.model._model
        self.mocap_ids = np.array([model.body(name).mocapid[0] for name in self.motion["bodies"]], dtype=int)

    def _reset_internal(self):
        super()._reset_internal()
        self._place_people(0.0)

    def _pre_action(self, action, policy_step=False):
        super()._pre_action(action, policy_step)
        self._place_people(self.cur_time)

    def _place_people(self, time):
        """Puts the mocap bodies where the people are at `time` (s), looping the motion."""
        frames = self.motion["frames"]
        if len(frames) == 0 or len(self.mocap_ids) == 0:
            return
        frame = frames[int(round(time * self.motion["fps"])) % len(frames)]
        self.sim.data.mocap_pos[self.mocap_ids] = frame[:, :3]
        self.sim.data.mocap_quat[self.mocap_ids] = frame[:, 3:]

    def reward(self, action=None):
        return 0.0

    def _check_success(self):
        return False


def run(input_path: str, seed: int = 0, steps: int = 200) -> dict:
    """Generates a clean layout for `input_path`, builds the environment, resets it and steps it
    `steps` times with seeded random actions. Returns what happened, for the caller to check."""
    layouts = shade_sim.generate(input_path, seed=seed, require_clean=True)
    if not layouts:
        raise RuntimeError(f"{input_path}: no clean layout in 8 attempts")
    env = ShadeSceneEnv(layouts[0], horizon=steps, seed=seed)
    obs = env.reset()
    rng = np.random.default_rng(seed)
    low, high = env.action_spec
    start = np.array(obs["robot0_eef_pos"])
    for _ in range(steps):
        obs, _, _, _ = env.step(rng.uniform(low, high))
    sim = env.sim
    result = {
        "objects": len(layouts[0].object_ids),
        "robot_spot": env.robot_spot,
        "steps": steps,
        "time": float(sim.data.time),
        "eef_start": start,
        "eef_end": np.array(obs["robot0_eef_pos"]),
        "finite": bool(np.isfinite(sim.data.qpos).all() and np.isfinite(sim.data.qvel).all()),
        "mocap_bodies": len(env.mocap_ids),
        "mocap_pos": np.array(sim.data.mocap_pos[env.mocap_ids]),
    }
    env.close()
    return result


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input", nargs="?", default=DEFAULT_INPUT)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--steps", type=int, default=200)
    args = parser.parse_args(argv)
    try:
        r = run(args.input, args.seed, args.steps)
    except (shade_sim.SceneError, ValueError, RuntimeError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    print(
        f"{args.input}: {r['objects']} pieces, a Panda at ({r['robot_spot'][0]:.2f}, {r['robot_spot'][1]:.2f}), "
        f"{r['mocap_bodies']} mocap bones; {r['steps']} steps ({r['time']:.1f} s simulated), "
        f"end effector moved {np.linalg.norm(r['eef_end'] - r['eef_start']):.2f} m, state finite: {r['finite']}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
