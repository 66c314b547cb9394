"""Checks of a scene's layout that no single key shows: names used once, surfaces on the
counter or clear of it and apart, the counter clear of the robot's mount, drawers inside
the cabinet and apart and free to slide out (past no floor-standing surface, not into the
mount), boxes that fit."""

from __future__ import annotations

from kitchen_tamp.kitchen.scene.spec import (
    DRAWER_LINK_SUFFIXES,
    RESERVED_NAMES,
    DrawerSpec,
    Interval,
    KitchenSpec,
    SceneFileError,
    overlap,
)

Extent = tuple[Interval, Interval, Interval]
"""An axis-aligned block: x, y and z intervals."""


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
    _check_counter(spec)
    _check_surfaces(spec)
    _check_drawers(spec)
    _check_drawer_paths(spec)
    _check_boxes(spec)


def _check_counter(spec: KitchenSpec) -> None:
    counter = spec.counter
    extent = (counter.x_range, counter.y_range, (0.0, counter.height))
    if _blocks_meet(extent, _mount_extent(spec)):
        raise SceneFileError(
            spec.path, "counter.front", f"the counter (from x = {counter.front} m) cuts through the "
            f"robot's mount (to x = {spec.mount.size[0] / 2} m)"
        )


def _check_drawer_paths(spec: KitchenSpec) -> None:
    """A drawer opens into free space: no floor-standing surface and not the mount in its way."""
    for drawer in spec.drawers:
        swept = _pulled_out_extent(spec, drawer)
        key = f"drawers.{drawer.name}.travel"
        if _blocks_meet(swept, _mount_extent(spec)):
            raise SceneFileError(spec.path, key, f"drawer {drawer.name!r} slides into the robot's mount "
                                 f"when it opens ({drawer.travel} m)")
        for surface in spec.surfaces:
            block = (surface.x_range, surface.y_range, (0.0, surface.height))
            if not spec.on_counter(surface) and _blocks_meet(swept, block):
                raise SceneFileError(spec.path, key, f"drawer {drawer.name!r} slides into surface "
                                     f"{surface.name!r} when it opens ({drawer.travel} m)")


def _inside(inner: Interval, outer: Interval) -> bool:
    return outer[0] <= inner[0] and inner[1] <= outer[1]


def _blocks_meet(a: Extent, b: Extent) -> bool:
    return all(overlap(i, j) for i, j in zip(a, b, strict=True))


def _mount_extent(spec: KitchenSpec) -> Extent:
    half_x, half_y = spec.mount.size[0] / 2, spec.mount.size[1] / 2
    return ((-half_x, half_x), (-half_y, half_y), (0.0, spec.mount.height))


def _pulled_out_extent(spec: KitchenSpec, drawer: DrawerSpec) -> Extent:
    """Where the tray and its handle sweep outside the counter as the drawer opens fully: from
    the counter's front to the handle's far side, across the tray or the bar, whichever is
    wider, from the tray's bottom (it hangs ``gap`` above its cavity's floor under the slab)
    to its top."""
    front, handle = spec.counter.front, drawer.handle
    _, width, height = drawer.outer
    reach = drawer.travel + handle.standoff + handle.bar[0] / 2
    half = max(width, handle.bar[1]) / 2
    bottom = spec.counter.slab_bottom - drawer.gap - height
    return ((front - reach, front), (drawer.y - half, drawer.y + half), (bottom, bottom + height))


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
        if high - low + 2 * counter.panel > counter.width:
            raise SceneFileError(spec.path, f"{key}.size", f"the tray ({drawer.outer[1]:.3f} m wide) with "
                                 f"its cavity does not fit the counter's width ({counter.width} m)")
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
