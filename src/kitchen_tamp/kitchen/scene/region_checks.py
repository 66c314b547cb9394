"""Checks of a scene's regions and obstacles that no single key shows: names used once, each
region within its surface and apart from the others there, each obstacle standing on one thing
and clear of surfaces, regions and the robot's mount."""

from __future__ import annotations

from kitchen_tamp.kitchen.scene.spec import (
    DRAWER_LINK_SUFFIXES,
    RESERVED_NAMES,
    Interval,
    KitchenSpec,
    ObstacleSpec,
    RegionSpec,
    SceneFileError,
    contains,
    overlap,
)


def check_regions_and_obstacles(spec: KitchenSpec) -> None:
    """Raise ``SceneFileError`` for a region or obstacle the kitchen cannot have."""
    _check_names(spec)
    for i, region in enumerate(spec.regions):
        _check_region(spec, region, spec.regions[:i])
    for obstacle in spec.obstacles:
        _check_obstacle(spec, obstacle)


def _check_names(spec: KitchenSpec) -> None:
    taken = {s.name: "surfaces" for s in spec.surfaces}
    taken.update({b.name: "boxes" for b in spec.boxes})
    for drawer in spec.drawers:
        taken[drawer.name] = "drawers"
        taken.update({drawer.name + suffix: "drawers" for suffix in DRAWER_LINK_SUFFIXES})
    entries = [("regions", r.name) for r in spec.regions] + [("obstacles", o.name) for o in spec.obstacles]
    for section, name in entries:
        key = f"{section}.{name}.name"
        if name in RESERVED_NAMES:
            raise SceneFileError(spec.path, key, f"{name!r} is a name the kitchen's models use themselves")
        if name in taken:
            raise SceneFileError(spec.path, key, f"name {name!r} used twice (also in {taken[name]})")
        taken[name] = section


def _size(x_range: Interval, y_range: Interval) -> str:
    return f"{x_range[1] - x_range[0]:.3g} x {y_range[1] - y_range[0]:.3g} m"


def _check_region(spec: KitchenSpec, region: RegionSpec, earlier: tuple[RegionSpec, ...]) -> None:
    key = f"regions.{region.name}"
    surface = spec.surface_named(region.surface)
    if surface is None:
        known = ", ".join(s.name for s in spec.surfaces)
        raise SceneFileError(
            spec.path, f"{key}.surface", f"no surface {region.surface!r} (surfaces: {known})"
        )
    width, depth = (r[1] - r[0] for r in (region.x_range, region.y_range))
    if width > surface.x_range[1] - surface.x_range[0] or depth > surface.y_range[1] - surface.y_range[0]:
        raise SceneFileError(
            spec.path, f"{key}.extent", f"the region ({_size(region.x_range, region.y_range)}) is larger "
            f"than its surface {surface.name!r} ({_size(surface.x_range, surface.y_range)})"
        )
    if not (contains(surface.x_range, region.x_range) and contains(surface.y_range, region.y_range)):
        raise SceneFileError(spec.path, f"{key}.extent", f"lies partly off its surface {surface.name!r}")
    for other in earlier:
        if other.surface == region.surface and overlap(region.x_range, other.x_range) and overlap(
            region.y_range, other.y_range
        ):
            raise SceneFileError(spec.path, f"{key}.extent", f"overlaps region {other.name!r}")


def _check_obstacle(spec: KitchenSpec, obstacle: ObstacleSpec) -> None:
    key = f"obstacles.{obstacle.name}"
    footprint = (obstacle.x_range, obstacle.y_range)
    counter = spec.counter
    if spec.on_counter(obstacle) and not (
        contains(counter.x_range, obstacle.x_range) and contains(counter.y_range, obstacle.y_range)
    ):
        raise SceneFileError(spec.path, f"{key}.extent", "lies partly on the counter, partly off it")
    for surface in spec.surfaces:
        inside = contains(surface.x_range, footprint[0]) and contains(surface.y_range, footprint[1])
        if not inside and overlap(surface.x_range, footprint[0]) and overlap(surface.y_range, footprint[1]):
            raise SceneFileError(spec.path, f"{key}.extent", f"lies partly on surface {surface.name!r}")
    for region in spec.regions:
        if overlap(region.x_range, footprint[0]) and overlap(region.y_range, footprint[1]):
            raise SceneFileError(spec.path, f"{key}.extent", f"overlaps region {region.name!r}")
    half_x, half_y = spec.mount.size[0] / 2, spec.mount.size[1] / 2
    if overlap(footprint[0], (-half_x, half_x)) and overlap(footprint[1], (-half_y, half_y)):
        raise SceneFileError(spec.path, f"{key}.extent", "overlaps the robot's mount")
    base = spec.obstacle_base(obstacle)
    if obstacle.height <= base:
        raise SceneFileError(
            spec.path, f"{key}.height", f"{obstacle.height} m is not above what it stands on ({base} m)"
        )
