"""Checks of a scene's layout that no single key shows: names used once, surfaces on the
counter or clear of it and apart, drawers inside the cabinet and apart, boxes that fit."""

from __future__ import annotations

from kitchen_tamp.kitchen.scene.spec import (
    DRAWER_LINK_SUFFIXES,
    RESERVED_NAMES,
    Interval,
    KitchenSpec,
    SceneFileError,
    overlap,
)


def check_layout(spec: KitchenSpec) -> None:
    """Names used once; surfaces on the counter or clear of it, not overlapping; drawers in the
    cabinet, not overlapping; every box fits on some place."""
    path = spec.path
    seen: dict[str, str] = {}
    entries = [("surfaces", s.name) for s in spec.surfaces] + [("drawers", d.name) for d in spec.drawers]
    entries += [("boxes", b.name) for b in spec.boxes]
    for section, name in entries:
        key = f"{section}.{name}.name"
        if name in RESERVED_NAMES:
            raise SceneFileError(path, key, f"{name!r} is a name the kitchen's models use themselves")
        if name in seen:
            raise SceneFileError(path, key, f"name {name!r} used twice (also in {seen[name]})")
        seen[name] = section
    for drawer in spec.drawers:
        for suffix in DRAWER_LINK_SUFFIXES:
            if drawer.name + suffix in seen:
                raise SceneFileError(
                    path, f"drawers.{drawer.name}.name", f"name {drawer.name + suffix!r} used twice "
                    "(the drawer's own link has that name too)"
                )
    _check_surfaces(spec)
    _check_drawers(spec)
    _check_boxes(spec)


def _inside(inner: Interval, outer: Interval) -> bool:
    return outer[0] <= inner[0] and inner[1] <= outer[1]


def _check_surfaces(spec: KitchenSpec) -> None:
    if not spec.surfaces:
        raise SceneFileError(spec.path, "surfaces", "a kitchen needs at least one surface ([[surfaces]])")
    counter = spec.counter
    half_x, half_y = spec.mount.size[0] / 2, spec.mount.size[1] / 2
    mount = ((-half_x, half_x), (-half_y, half_y))
    for i, surface in enumerate(spec.surfaces):
        key = f"surfaces.{surface.name}"
        if spec.on_counter(surface):
            if not (_inside(surface.x_range, counter.x_range) and _inside(surface.y_range, counter.y_range)):
                raise SceneFileError(spec.path, f"{key}.extent", "lies partly on the counter, partly off it")
            if surface.height <= counter.height:
                raise SceneFileError(
                    spec.path, f"{key}.height", f"{surface.height} m is not above the counter's top "
                    f"({counter.height} m)"
                )
        if overlap(surface.x_range, mount[0]) and overlap(surface.y_range, mount[1]):
            raise SceneFileError(spec.path, f"{key}.extent", "overlaps the robot's mount")
        for other in spec.surfaces[:i]:
            if overlap(surface.x_range, other.x_range) and overlap(surface.y_range, other.y_range):
                raise SceneFileError(spec.path, f"{key}.extent", f"overlaps surface {other.name!r}")


def _check_drawers(spec: KitchenSpec) -> None:
    counter = spec.counter
    for i, drawer in enumerate(spec.drawers):
        key = f"drawers.{drawer.name}"
        length, _, height = drawer.outer
        if length + drawer.gap + counter.panel > counter.depth:
            raise SceneFileError(spec.path, f"{key}.size", f"the tray ({length:.3f} m long) does not fit "
                                 f"the counter's depth ({counter.depth} m)")
        if height + 2 * drawer.gap + counter.panel > counter.slab_bottom:
            raise SceneFileError(spec.path, f"{key}.size", f"the tray ({height:.3f} m high) does not fit "
                                 f"under the slab ({counter.slab_bottom:.3f} m)")
        low, high = drawer.cavity_y
        if low - counter.panel < counter.y_range[0] or high + counter.panel > counter.y_range[1]:
            raise SceneFileError(spec.path, f"{key}.y", "the drawer's cavity reaches past the counter's side")
        for other in spec.drawers[:i]:
            if overlap(drawer.cavity_y, other.cavity_y):
                raise SceneFileError(spec.path, f"{key}.y", f"its cavity overlaps drawer {other.name!r}")


def _check_boxes(spec: KitchenSpec) -> None:
    places = [(s.x_range[1] - s.x_range[0], s.y_range[1] - s.y_range[0]) for s in spec.surfaces]
    places += [(d.inner[0], d.inner[1]) for d in spec.drawers]
    for box in spec.boxes:
        footprint = sorted(box.size[:2])
        if not any(footprint[0] <= min(p) and footprint[1] <= max(p) for p in places):
            raise SceneFileError(
                spec.path, f"boxes.{box.name}.size",
                f"the box ({box.size[0]} x {box.size[1]} m) is larger than every surface and drawer",
            )
