"""shade-sim from Python: furniture layouts for rooms in which given human motions can happen,
proven physically.

    import shade_sim
    scene = shade_sim.load_scene("scenes/examples/living_l.json")
    layout = shade_sim.generate(scene, seed=0, require_clean=True)[0]
    assert shade_sim.check(layout) == []

Scenes are the shade-scene/1 format (z up, metres). Every function that takes a scene also takes
a path or a dict of the file format. Errors raise ``SceneError`` (a bad scene file or dict),
``ModelError`` (a model folder that cannot be loaded) or ``ValueError`` (a bad argument), with the
same text as the ``shade-sim`` command line.
"""

from __future__ import annotations

import os
import tempfile
from typing import Any, Union

# A declared dependency, imported first: without it the arrays would fail inside Rust (pyo3's
# PanicException) at the first call that returns one, instead of here as an ImportError.
import numpy as _numpy  # noqa: F401

from ._native import (
    ModelError,
    Scene,
    SceneError,
    __version__,
    check,
    free_spot,
    generate,
    load_scene,
    to_mjcf,
)
from ._native import mocap_motion_of as mocap_motion

SceneLike = Union[Scene, str, "os.PathLike[str]", dict]

__all__ = [
    "ModelError",
    "Scene",
    "SceneError",
    "__version__",
    "check",
    "free_spot",
    "generate",
    "load_scene",
    "mocap_motion",
    "robosuite_arena",
    "to_mjcf",
]


def robosuite_arena(scene: SceneLike) -> Any:
    """The scene as a ``robosuite.models.arenas.Arena``: its floor, walls and furniture, and its
    humans as mocap bodies without keyframes (replay them with ``mocap_motion(scene)``) and without
    contact pairs (what ``shade-sim export --format robosuite`` writes). Needs the ``robosuite``
    package."""
    from robosuite.models.arenas import Arena

    xml = to_mjcf(scene, keyframes=False, contact_pairs=False)
    with tempfile.TemporaryDirectory(prefix="shade_sim_") as folder:
        path = os.path.join(folder, "arena.xml")
        with open(path, "w", encoding="utf-8") as f:
            f.write(xml)
        return Arena(path)
