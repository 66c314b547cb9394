"""Drawing the toy rooms domain and a bilevel planner's graph as it grows, frame by frame, into a GIF.

Shared by the ``examples/bilevel_*.py`` scripts. A frame shows everything the
planner had built up to one sample: rooms reached (abstract state nodes, shaded),
low-level states (dots), sampled trajectories (action edges, thin lines),
failed samples (red), and the sample just drawn in bold. For SeSamE-style
planners the refinement in progress is drawn thicker than abandoned branches.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import numpy.typing as npt
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Rectangle

from kitchen_tamp.bilevel import BilevelResult, SampleEvent
from kitchen_tamp.bilevel.toy_rooms import BlockedPath, Passage, Point, RoomsScene, RoomsWorld

ASSETS = Path(__file__).resolve().parents[1] / "docs" / "assets"
WIDTH_PX = 360
DPI = 100
MAX_FRAMES = 56

WALL = "#2b2b2b"
FLOOR = "#ffffff"
REACHED = "#dceaf7"
GOAL = "#2e8b57"
EDGE = "#5a7fa8"
CURRENT = "#1f4e89"
FAILED = "#d62728"
PLAN = "#2ca02c"
PILLAR = "#8c8c8c"
CRATE = "#a0522d"
HIDDEN = "#bbbbbb"

Frame = npt.NDArray[np.uint8]
RoomsResult = BilevelResult[Point, Point, str, Passage]
RoomsEvent = SampleEvent[str, Passage]


@dataclass(frozen=True)
class Shadow:
    """Shade the part of ``room`` from which the straight way to ``door`` is blocked."""

    room: str
    door: str


def new_figure(world: RoomsWorld) -> tuple[Figure, Axes]:
    x_max = max(room.x_max for room in world.rooms)
    y_max = max(room.y_max for room in world.rooms)
    width_in = WIDTH_PX / DPI
    figure = Figure(figsize=(width_in, width_in * (y_max + 0.1) / (x_max + 0.1) + 0.42), dpi=DPI)
    axes = figure.add_axes((0.0, 0.0, 1.0, 1.0 - 0.42 / figure.get_figheight()))
    axes.set_xlim(-0.05, x_max + 0.05)
    axes.set_ylim(-0.05, y_max + 0.05)
    axes.set_aspect("equal")
    axes.axis("off")
    return figure, axes


def rasterise(figure: Figure) -> Frame:
    """The figure's pixels as an RGB array."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="rgba", dpi=DPI)
    pixels = np.frombuffer(buffer.getvalue(), dtype=np.uint8)
    width = round(float(figure.get_size_inches()[0]) * DPI)
    rgba = pixels.reshape(-1, width, 4)
    return rgba[..., :3].copy()


def draw_shadow(axes: Axes, world: RoomsWorld, shadow: Shadow) -> None:
    room, door = world.room(shadow.room), world.door(shadow.door)
    approach = door.point_inside(room.name, world.robot_radius)
    xs = np.linspace(room.x_min, room.x_max, 90)
    ys = np.linspace(room.y_min, room.y_max, 90)
    hidden = np.array([[world.obstacle_hit(np.array([x, y]), approach) is not None for x in xs] for y in ys])
    axes.contourf(xs, ys, hidden.astype(float), levels=[0.5, 1.5], colors=[HIDDEN], alpha=0.45, zorder=1)


def draw_world(axes: Axes, scene: RoomsScene, reached: set[str], shadows: Sequence[Shadow] = ()) -> None:
    """Rooms (shaded once reached), walls with doorways, obstacles, room names, the goal room."""
    world = scene.world
    for room in world.rooms:
        fill = REACHED if room.name in reached else FLOOR
        axes.add_patch(Rectangle((room.x_min, room.y_min), room.x_max - room.x_min, room.y_max - room.y_min,
                                 facecolor=fill, edgecolor="none", zorder=0))
        label_color = GOAL if room.name == scene.goal_room else "#555555"
        axes.text(room.x_min + 0.06, room.y_max - 0.06, room.name + (" (goal)" if room.name == scene.goal_room
                                                                     else ""),
                  ha="left", va="top", fontsize=8, color=label_color, fontweight="bold", zorder=6)
        if room.name == scene.goal_room:
            axes.add_patch(Rectangle((room.x_min + 0.03, room.y_min + 0.03), room.x_max - room.x_min - 0.06,
                                     room.y_max - room.y_min - 0.06, fill=False, edgecolor=GOAL,
                                     linewidth=1.5, linestyle="--", zorder=1))
    for shadow in shadows:
        draw_shadow(axes, world, shadow)
    for room in world.rooms:
        corners = [(room.x_min, room.y_min), (room.x_max, room.y_min), (room.x_max, room.y_max),
                   (room.x_min, room.y_max), (room.x_min, room.y_min)]
        xs, ys = zip(*corners, strict=True)
        axes.plot(xs, ys, color=WALL, linewidth=2.5, solid_capstyle="projecting", zorder=2)
    for door in world.doors:
        half = door.width / 2
        along = np.array([door.normal[1], -door.normal[0]])
        center = np.array(door.center)
        ends = np.array([center - half * along, center + half * along])
        fills = {REACHED if name in reached else FLOOR for name in door.rooms}
        axes.plot(ends[:, 0], ends[:, 1], color=REACHED if fills == {REACHED} else FLOOR, linewidth=4.0,
                  solid_capstyle="butt", zorder=3)
    for obstacle in world.obstacles:
        x, y = obstacle.center
        if obstacle.kind == "crate":
            side = obstacle.radius * 1.6
            axes.add_patch(Rectangle((x - side / 2, y - side / 2), side, side, facecolor=CRATE,
                                     edgecolor="#5c2e0e", linewidth=1.0, zorder=4))
        else:
            axes.add_patch(Circle((x, y), obstacle.radius, facecolor=PILLAR, edgecolor="#555555", zorder=4))


def _polyline(axes: Axes, points: Sequence[Point], color: str, width: float, style: str = "-",
              alpha: float = 1.0, zorder: int = 5) -> None:
    array = np.array(points)
    axes.plot(array[:, 0], array[:, 1], color=color, linewidth=width, linestyle=style, alpha=alpha,
              zorder=zorder)


def blocked_part(blocked: BlockedPath, robot_radius: float) -> list[Point]:
    """The tried path up to where the robot first touches the obstacle."""
    start, end = blocked.waypoints[blocked.segment], blocked.waypoints[blocked.segment + 1]
    center = np.array(blocked.obstacle.center)
    reach = blocked.obstacle.radius + robot_radius
    contact = end
    for t in np.linspace(0.0, 1.0, 200):
        position = start + t * (end - start)
        if float(np.linalg.norm(position - center)) < reach:
            contact = position
            break
    return [*blocked.waypoints[: blocked.segment + 1], contact]


def frame_samples(total: int, budget: int = MAX_FRAMES) -> list[int]:
    """The sample numbers to draw a frame at: all of them, or ``budget`` spread evenly (last included)."""
    if total <= budget:
        return list(range(0, total + 1))
    return sorted({round(i * total / (budget - 1)) for i in range(budget)})


class GrowthRenderer:
    """Draws the planning graph of ``result`` as it stood after any sample."""

    def __init__(self, scene: RoomsScene, result: RoomsResult, events: Sequence[RoomsEvent], title: str,
                 shadows: Sequence[Shadow] = ()) -> None:
        self.scene, self.result, self.events, self.title, self.shadows = scene, result, events, title, shadows
        self.failures = {failed.sample: failed for failed in result.graph.failed_samples}

    def caption(self, sample: int) -> str:
        if sample == 0:
            return "start"
        event = self.events[sample - 1]
        where = ""
        if event.plan_index is not None and event.step_index is not None:
            where = f"plan {event.plan_index + 1}, step {event.step_index + 1}: "
        verdict = "ok" if event.succeeded else "failed"
        return f"sample {sample}: {where}{event.transition.action} {verdict}"

    def _current_branch(self, event: RoomsEvent | None) -> set[int]:
        """The state nodes of the refinement in progress (SeSamE-style planners only)."""
        if event is None or event.plan_index is None:
            return set()
        tip = event.target_node if event.target_node is not None else event.source_node
        return {edge.target for edge in self.result.graph.path_to(tip)}

    def _draw_graph(self, axes: Axes, sample: int, current: set[int]) -> None:
        graph = self.result.graph
        robot_radius = self.scene.world.robot_radius
        for failed in graph.failed_samples:
            if failed.sample < sample and isinstance(failed.error, BlockedPath):
                _polyline(axes, blocked_part(failed.error, robot_radius), FAILED, 0.7, ":", alpha=0.5)
        for edge in graph.action_edges:
            if edge.sample <= sample:
                bold = edge.target in current
                _polyline(axes, edge.trajectory.states, CURRENT if bold else EDGE, 1.6 if bold else 0.8,
                          alpha=1.0 if bold or not current else 0.55)
        for node in graph.state_nodes:
            if node.sample <= sample:
                bold = node.id in current or node.id == 0
                axes.plot(node.state[0], node.state[1], "o", color=CURRENT if bold else EDGE,
                          markersize=6 if node.id == 0 else 4, zorder=7)

    def _draw_latest_sample(self, axes: Axes, event: RoomsEvent) -> None:
        failed = self.failures.get(event.sample)
        if failed is not None and isinstance(failed.error, BlockedPath):
            tried = blocked_part(failed.error, self.scene.world.robot_radius)
            _polyline(axes, tried, FAILED, 2.0, zorder=8)
            axes.plot(tried[-1][0], tried[-1][1], "x", color=FAILED, markersize=8, markeredgewidth=2.2,
                      zorder=9)
        elif event.target_node is not None:
            edge = self.result.graph.path_to(event.target_node)[-1]
            _polyline(axes, edge.trajectory.states, CURRENT, 2.4, zorder=8)

    def _status(self, sample: int, final: bool) -> str:
        if not final:
            return self.caption(sample)
        if self.result.plan is None:
            return f"failed after {self.result.counts.samples} samples"
        return f"solved: {len(self.result.plan.steps)} steps, {self.result.counts.samples} samples"

    def frame(self, sample: int, final: bool = False) -> Frame:
        """The picture after sample number ``sample``; ``final`` adds the plan (or the verdict)."""
        graph = self.result.graph
        figure, axes = new_figure(self.scene.world)
        reached = {graph.abstract_state_of(node.id) for node in graph.state_nodes if node.sample <= sample}
        draw_world(axes, self.scene, reached, self.shadows)
        event = self.events[sample - 1] if sample > 0 else None
        self._draw_graph(axes, sample, self._current_branch(event))
        if event is not None and not final:
            self._draw_latest_sample(axes, event)
        if final and self.result.plan is not None:
            _polyline(axes, self.result.plan.trajectory.states, PLAN, 3.0, zorder=8)
        figure.text(0.02, 0.985, self.title, ha="left", va="top", fontsize=9, fontweight="bold")
        failed_verdict = final and self.result.plan is None
        status_y = 0.985 - 0.2 / figure.get_figheight()
        figure.text(0.02, status_y, self._status(sample, final), ha="left", va="top", fontsize=7.5,
                    color=FAILED if failed_verdict else "#333333")
        return rasterise(figure)

    def write_gif(self, path: Path, frame_ms: int = 280, hold_ms: int = 2200) -> None:
        samples = frame_samples(self.result.counts.samples)
        frames = [self.frame(sample) for sample in samples]
        frames.append(self.frame(self.result.counts.samples, final=True))
        durations = [frame_ms] * (len(frames) - 1) + [hold_ms]
        durations[0] = 900
        path.parent.mkdir(parents=True, exist_ok=True)
        iio.imwrite(path, np.stack(frames), duration=durations, loop=0)
        print(f"wrote {path} ({len(frames)} frames, {path.stat().st_size // 1024} KB)")
