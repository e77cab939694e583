"""shade-sim from Python: furniture layouts for rooms in which given human motions can happen,
proven physically.

    import shade_sim
    scene = shade_sim.load_scene("scenes/examples/living_l.json")
    layout = shade_sim.generate(scene, seed=0, require_clean=True)[0]
    assert shade_sim.check(layout) == []

Scenes are the shade-scene/1 format (z up, metres). Every function that takes a scene also takes
a path or a dict of the file format. Motion comes in through ``import_motion``: BVH files, or
joint positions as files or numpy arrays. Errors raise ``SceneError`` (a bad scene file or dict),
``ModelError`` (a model folder that cannot be loaded), ``MotionError`` (a motion that cannot be
imported) or ``ValueError`` (a bad argument), with the same text as the ``shade-sim`` command
line.
"""

from __future__ import annotations

import io
import os
import tempfile
from typing import Any, Optional, Sequence, Tuple, Union

# A declared dependency, imported first: without it the arrays would fail inside Rust (pyo3's
# PanicException) at the first call that returns one, instead of here as an ImportError.
import numpy as _numpy

from . import _native
from ._native import (
    ModelError,
    MotionError,
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
    "MotionError",
    "Scene",
    "SceneError",
    "__version__",
    "check",
    "free_spot",
    "generate",
    "import_motion",
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


MotionLike = Union[str, "os.PathLike[str]", "_numpy.ndarray", dict]


def import_motion(
    motions: Sequence[MotionLike],
    room: str,
    floor: Any,
    *,
    place: Optional[Sequence[Union[None, str, Tuple[float, float, float]]]] = None,
    trim: Optional[Sequence[Optional[Tuple[float, Optional[float]]]]] = None,
    fps: float = 30.0,
    stature: Optional[float] = None,
    units: str = "auto",
    up: str = "auto",
    source_fps: float = 30.0,
    height: float = 2.8,
    actions: Optional[Sequence[Optional[Sequence[dict]]]] = None,
) -> Scene:
    """A generation input from human motion, one human per motion (ids h0, h1, ...), as
    ``shade-sim import-motion`` writes it: retargeted onto our body, the lowest toe on the floor,
    placed, trimmed, resampled to ``fps`` and each frame's action labelled (docs/FORMAT.md).

    A motion is a file (BVH, ``.npy``, ``.npz``), a (T, J, 3) array of joint positions (SMPL's 22,
    24, 52 or 55 joints in their order, or our 19), or a dict ``{"joints": array, "names": [...],
    "fps": 120}`` (names and fps optional; an array's fps is ``source_fps``) — what a body model
    gives for an AMASS or SMPL-X fit. Units and the up axis are detected unless ``units`` ("m",
    "cm", "in", "cmu") or ``up`` ("y", "z") say; ``stature`` scales the person to that height.

    ``floor``: (W, D) metres from the origin, a list of (x, y) corners, or a scene whose floor
    plan is taken (``height``: the ceiling of the first two). ``place``: per motion, None (kept
    where captured), (x, y, yaw_deg) for its first pelvis and facing, or "auto" (the first of the
    plan's centre and a 5 x 5 grid, each facing four ways, that keeps the motion inside the plan
    and out of its walls). ``trim``: per motion,
    None or (from, to) seconds of the motion, to None for its end. ``actions``: per motion, None or
    a list of ``{"action": "sit", "start": 30, "end": 90}`` (frames as written) that replace the
    automatic labels where they lie. A motion that cannot be read,
    that leaves the floor plan or reaches into a wall raises ``MotionError`` naming the file (or
    ``<motion k>`` for an array) and the frame."""
    items = [_motion_item(m) for m in motions]
    if isinstance(place, str):
        # A bare "auto" would be read as four entries, one per letter.
        raise ValueError(f"place: one entry per motion, e.g. [{place!r}], not the string {place!r}")
    return _native.import_motion(
        items, room, floor, place=None if place is None else list(place), trim=None if trim is None else list(trim),
        fps=fps, stature=stature, units=units, up=up, source_fps=source_fps, height=height,
        actions=None if actions is None else [None if a is None else list(a) for a in actions],
    )


def _motion_item(motion: MotionLike) -> Union[str, bytes]:
    """A path as it is; an array or a dict of arrays as the bytes of a .npz archive."""
    if isinstance(motion, (str, os.PathLike)):
        return os.fspath(motion)
    if isinstance(motion, dict):
        unknown = set(motion) - {"joints", "names", "fps"}
        if unknown or "joints" not in motion:
            raise ValueError(f"motions: a dict holds 'joints' and optionally 'names' and 'fps', not {sorted(motion)}")
        arrays = {"joints": _numpy.asarray(motion["joints"])}
        if motion.get("names") is not None:
            arrays["names"] = _numpy.asarray([str(n) for n in motion["names"]])
        if motion.get("fps") is not None:
            arrays["fps"] = _numpy.asarray(float(motion["fps"]))
    elif isinstance(motion, _numpy.ndarray) or isinstance(motion, (list, tuple)):
        arrays = {"joints": _numpy.asarray(motion)}
    else:
        raise ValueError(f"motions: expected a path, an array or a dict of arrays, not {type(motion).__name__}")
    if arrays["joints"].dtype.kind not in "fiu":
        raise ValueError(f"motions: joint positions must be numbers, not {arrays['joints'].dtype}")
    arrays["joints"] = _numpy.ascontiguousarray(arrays["joints"], dtype=_numpy.float64)
    buffer = io.BytesIO()
    _numpy.savez(buffer, **arrays)
    return buffer.getvalue()
