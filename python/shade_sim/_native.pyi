"""Type stubs of the compiled part of shade_sim (python/src/lib.rs)."""

import os
from typing import Any, Dict, List, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

SceneLike = Union["Scene", str, os.PathLike, Dict[str, Any]]

__version__: str

class SceneError(ValueError):
    """A scene that cannot be read or breaks the shade-scene/1 format."""

class ModelError(ValueError):
    """A model folder (config.json + model.safetensors) that cannot be loaded."""

class MotionError(ValueError):
    """A motion file or array that cannot be imported."""

class Scene:
    """A shade-scene/1 scene (immutable)."""

    @property
    def room_type(self) -> str: ...
    @property
    def object_ids(self) -> List[str]: ...
    @property
    def categories(self) -> List[str]: ...
    @property
    def human_ids(self) -> List[str]: ...
    def floor(self) -> npt.NDArray[np.float64]:
        """The floor plan's polygon, (N, 2), metres, counter-clockwise."""
    def boxes(self) -> npt.NDArray[np.float64]:
        """The objects' boxes, (N, 7): centre x, y, z, size x, y, z (m), yaw (rad)."""
    def frames(self, human: Union[int, str]) -> npt.NDArray[np.float64]:
        """A human's joint positions, (T, J, 3), metres, z up."""
    def to_dict(self) -> Dict[str, Any]: ...
    def to_json(self) -> str: ...
    def save(self, path: Union[str, os.PathLike]) -> None: ...
    def __eq__(self, other: object) -> bool: ...

def load_scene(source: SceneLike) -> Scene: ...
@overload
def generate(
    input: SceneLike,
    samples: int = 1,
    seed: int = 0,
    guidance: str = "all",
    repair: Union[None, bool, str, os.PathLike] = None,
    require_clean: bool = False,
    attempts: int = 8,
    model: Union[None, str, os.PathLike] = None,
) -> List[Scene]: ...
@overload
def generate(
    input: Union[List[SceneLike], Tuple[SceneLike, ...]],
    samples: int = 1,
    seed: int = 0,
    guidance: str = "all",
    repair: Union[None, bool, str, os.PathLike] = None,
    require_clean: bool = False,
    attempts: int = 8,
    model: Union[None, str, os.PathLike] = None,
) -> List[List[Scene]]: ...
def check(scene: SceneLike, stability: bool = True) -> List[Dict[str, Any]]: ...
def to_mjcf(scene: SceneLike, free_furniture: bool = False, keyframes: bool = True, contact_pairs: bool = True) -> str: ...
def mocap_motion_of(scene: SceneLike) -> Dict[str, Any]:
    """{"fps": float, "bodies": [str], "frames": (T, B, 7) array of x, y, z, qw, qx, qy, qz}."""
def free_spot(scene: SceneLike, clearance: float = 0.35) -> Optional[Tuple[float, float]]: ...
def import_motion(
    motions: List[Union[str, os.PathLike, bytes]],
    room: str,
    floor: Any,
    place: Optional[List[Union[None, str, Tuple[float, float, float]]]] = None,
    trim: Optional[List[Optional[Tuple[float, Optional[float]]]]] = None,
    fps: float = 30.0,
    stature: Optional[float] = None,
    units: str = "auto",
    up: str = "auto",
    source_fps: float = 30.0,
    height: float = 2.8,
    actions: Optional[List[Optional[List[Dict[str, Any]]]]] = None,
) -> Scene:
    """A generation input from motion files or .npz archives' bytes (shade_sim.import_motion)."""
