"""The parts of a URDF a geometry model needs: the link tree, its joints, and collision shapes.

Read with ``xml.etree`` (no simulator). Poses are 4x4 homogeneous matrices
(``parent_from_child``); a joint's ``origin`` places its child link in its
parent link at zero joint position; a collision's ``origin`` places the shape
in its link. Mesh files named ``package://NAME/...`` resolve beside the URDF
(``NAME`` may be a directory there or the rest of the path), as PyBullet does.
"""

from __future__ import annotations

import functools
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

MOVING_JOINT_TYPES = frozenset({"revolute", "continuous", "prismatic"})
"""Joint types that move (PyBullet's non-fixed joints)."""


class UrdfFormatError(ValueError):
    """A URDF the geometry model cannot read; the message names the file and element."""


def rpy_matrix(rpy: FloatArray) -> FloatArray:
    """3x3 rotation of URDF roll-pitch-yaw (fixed axes x, then y, then z)."""
    roll, pitch, yaw = (float(v) for v in rpy)
    cr, sr, cp, sp, cy, sy = (
        np.cos(roll),
        np.sin(roll),
        np.cos(pitch),
        np.sin(pitch),
        np.cos(yaw),
        np.sin(yaw),
    )
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def _numbers(text: str | None, count: int, default: float, where: str) -> FloatArray:
    if text is None:
        return np.full(count, default)
    values = np.array([float(v) for v in text.split()])
    if values.shape != (count,):
        raise UrdfFormatError(f"{where}: expected {count} numbers, got {text!r}")
    return values


def _origin(element: ElementTree.Element | None, where: str) -> FloatArray:
    pose = np.eye(4)
    if element is not None:
        pose[:3, :3] = rpy_matrix(_numbers(element.get("rpy"), 3, 0.0, where))
        pose[:3, 3] = _numbers(element.get("xyz"), 3, 0.0, where)
    return pose


@dataclass(frozen=True, eq=False)
class UrdfJoint:
    """A joint: ``child`` sits at ``origin`` in ``parent``, then moves along or about ``axis``."""

    name: str
    kind: str
    parent: str
    child: str
    origin: FloatArray
    axis: FloatArray

    @property
    def moves(self) -> bool:
        return self.kind in MOVING_JOINT_TYPES


@dataclass(frozen=True, eq=False)
class UrdfCollision:
    """One collision shape of ``link``: a ``box`` (size), ``sphere`` (radius), ``cylinder``
    (radius, length) or ``mesh`` (file, scale), placed at ``origin`` in the link."""

    link: str
    kind: str
    origin: FloatArray
    size: FloatArray
    """box: (x, y, z) extents; sphere: (r,); cylinder: (r, length); mesh: the (x, y, z) scale."""
    mesh_path: str = ""


@dataclass(frozen=True, eq=False)
class UrdfModel:
    """Links (root first, parents before children), joints and collision shapes of one URDF."""

    path: str
    links: tuple[str, ...]
    joints: tuple[UrdfJoint, ...]
    collisions: tuple[UrdfCollision, ...]

    @property
    def root(self) -> str:
        return self.links[0]

    def joint_to(self, link: str) -> UrdfJoint | None:
        """The joint whose child is ``link`` (None for the root)."""
        return next((j for j in self.joints if j.child == link), None)

    def ancestry(self, link: str) -> list[UrdfJoint]:
        """Joints from ``link`` up to the root."""
        chain = []
        joint = self.joint_to(link)
        while joint is not None:
            chain.append(joint)
            joint = self.joint_to(joint.parent)
        return chain

    def moving_joints_between(self, a: str, b: str) -> int:
        """Number of moving joints on the chain joining links ``a`` and ``b``."""
        chain_a, chain_b = self.ancestry(a), self.ancestry(b)
        shared = {j.name for j in chain_a} & {j.name for j in chain_b}
        return sum(j.moves for j in chain_a + chain_b if j.name not in shared)


def _mesh_path(urdf: Path, filename: str) -> str:
    if filename.startswith("package://"):
        rest = filename.removeprefix("package://")
        package, _, inside = rest.partition("/")
        beside = urdf.parent / package
        return str(beside / inside if beside.is_dir() else urdf.parent / rest)
    return str(Path(filename) if Path(filename).is_absolute() else urdf.parent / filename)


def _collision(urdf: Path, link: str, element: ElementTree.Element) -> UrdfCollision:
    where = f"{urdf}: link {link!r} collision"
    geometry = element.find("geometry")
    shape = None if geometry is None else next(iter(geometry), None)
    if shape is None:
        raise UrdfFormatError(f"{where} has no geometry")
    origin = _origin(element.find("origin"), where)
    if shape.tag == "box":
        return UrdfCollision(link, "box", origin, _numbers(shape.get("size"), 3, 0.0, where))
    if shape.tag == "sphere":
        return UrdfCollision(link, "sphere", origin, _numbers(shape.get("radius"), 1, 0.0, where))
    if shape.tag == "cylinder":
        size = np.r_[
            _numbers(shape.get("radius"), 1, 0.0, where), _numbers(shape.get("length"), 1, 0.0, where)
        ]
        return UrdfCollision(link, "cylinder", origin, size)
    if shape.tag == "mesh" and shape.get("filename"):
        scale = _numbers(shape.get("scale"), 3, 1.0, where)
        return UrdfCollision(link, "mesh", origin, scale, _mesh_path(urdf, str(shape.get("filename"))))
    raise UrdfFormatError(f"{where}: unsupported geometry {shape.tag!r}")


def _joint(urdf: Path, element: ElementTree.Element) -> UrdfJoint:
    name = element.get("name", "")
    where = f"{urdf}: joint {name!r}"
    parent, child = element.find("parent"), element.find("child")
    if parent is None or child is None:
        raise UrdfFormatError(f"{where} lacks a parent or child")
    axis = element.find("axis")
    text = None if axis is None else axis.get("xyz")
    direction = _numbers(text, 3, 0.0, where) if text else np.array([1.0, 0.0, 0.0])
    return UrdfJoint(
        name,
        element.get("type", "fixed"),
        parent.get("link", ""),
        child.get("link", ""),
        _origin(element.find("origin"), where),
        direction,
    )


@functools.lru_cache(maxsize=32)
def read_urdf(path: str) -> UrdfModel:
    """The link tree and collision shapes of the URDF at ``path``."""
    urdf = Path(path)
    try:
        root = ElementTree.parse(urdf).getroot()
    except (OSError, ElementTree.ParseError) as error:
        raise UrdfFormatError(f"{urdf}: cannot read URDF ({error})") from error
    names = [link.get("name", "") for link in root.findall("link")]
    joints = [_joint(urdf, element) for element in root.findall("joint")]
    children = {j.child for j in joints}
    roots = [name for name in names if name not in children]
    if len(roots) != 1:
        raise UrdfFormatError(f"{urdf}: expected one root link, found {roots}")
    ordered, frontier = [], roots
    while frontier:
        ordered += frontier
        frontier = [j.child for j in joints if j.parent in frontier]
    collisions = [
        _collision(urdf, link.get("name", ""), element)
        for link in root.findall("link")
        for element in link.findall("collision")
    ]
    return UrdfModel(str(urdf), tuple(ordered), tuple(joints), tuple(collisions))
