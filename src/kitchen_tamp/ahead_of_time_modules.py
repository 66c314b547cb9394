"""numba kernels compiled ahead of time into extension modules: their names, loading, building.

Importing numba and readying its compiler cost a process most of a second of one core, more than
many planning runs take. So ``make install`` (``python -m kitchen_tamp.cli.prepare``) compiles the
kernels a kitchen run needs with numba's ``pycc`` into an extension module that loads with numpy
alone: the sphere model's validity and clearance (``motion.geometry.spheres.kernels.loading``). (The
activity planner's greedy search is built in C instead, ``planning.search.native_greedy``, which needs
no numpy.) A module is named
after a digest of its kernels' sources, so an edited kernel is never served by a stale module
(until the next ``make install``, its JIT kernel serves, the same code), and, when it is compiled
for this machine's processor, of the processor too, so that an install shared by several
machines never runs it on another one.

``pycc`` compiles an exported function from its Python source with flags of its own, not the
ones its ``numba.njit`` gave it (``fastmath``), while the functions it calls keep theirs: a kernel
with flags is exported through a wrapper that only calls it.

Loading imports neither numba nor the kernels; building (`AheadOfTimeModule.compile`) does.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

_PROCESSOR_FIELDS = ("vendor_id", "cpu family", "model", "model name", "flags", "Features", "CPU implementer",
                     "CPU architecture", "CPU variant", "CPU part")
"""The fields of ``/proc/cpuinfo`` that say which processor code is compiled for (x86 and ARM)."""


def processor_signature() -> str:
    """What code compiled for this machine's processor depends on: its model and features as Linux
    reports them for the first processor (else what ``platform`` says); cheap, unlike asking LLVM
    (70 ms with llvmlite's import)."""
    import platform

    try:
        first = Path("/proc/cpuinfo").read_text().split("\n\n")[0]
    except OSError:
        return f"{platform.machine()} {platform.processor()}"
    lines = (line.split(":", 1) for line in first.splitlines() if ":" in line)
    kept = (f"{key.strip()}:{value.strip()}" for key, value in lines if key.strip() in _PROCESSOR_FIELDS)
    return "\n".join(kept)


@dataclass(frozen=True)
class AheadOfTimeModule:
    """The extension module compiled from the kernels in ``sources`` into ``folder``, named ``prefix``
    followed by a digest of the sources (and, ``for_this_processor``, of the processor)."""

    prefix: str
    folder: Path
    sources: tuple[Path, ...]
    for_this_processor: bool
    """Compiled for this processor, as numba's JIT compiles (else for a generic one of its family):
    needed where results must equal the JIT kernel's to the bit, since a kernel vectorised for
    another processor may sum in another order."""

    def name(self) -> str:
        """The module's name for the current sources (and processor)."""
        import hashlib  # here, not at load: every kitchen run loads this module

        digest = hashlib.sha256(processor_signature().encode() if self.for_this_processor else b"")
        for source in self.sources:
            digest.update(source.name.encode())
            digest.update(source.read_bytes())
        return self.prefix + digest.hexdigest()[:16]

    def _path(self, name: str) -> Path | None:
        import importlib.machinery  # here, not at load: every kitchen run loads this module

        for suffix in importlib.machinery.EXTENSION_SUFFIXES:
            path = self.folder / (name + suffix)
            if path.exists():
                return path
        return None

    def load(self) -> ModuleType | None:
        """The module compiled from the current sources (for this processor), or None without one."""
        import importlib.util

        name = self.name()
        path = self._path(name)
        if path is None:
            return None
        spec = importlib.util.spec_from_file_location(name, path)
        if spec is None or spec.loader is None:
            return None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module

    def compile(self, exports: Mapping[str, Any]) -> Path:
        """Compile ``exports`` (name -> a numba JIT kernel that has run once, so that numba gave it
        exactly one signature) into the module, unless the current sources' module is there; the
        modules of earlier sources are removed. The module's folder."""
        name = self.name()
        if self._path(name) is not None:
            return self.folder
        signatures = {}
        for export_name, kernel in exports.items():
            overloads = list(kernel.overloads.values())
            if len(overloads) != 1:
                raise RuntimeError(f"expected one compiled signature of {export_name}, "
                                   f"found {len(overloads)}")
            signatures[export_name] = overloads[0].signature
        import warnings

        self.folder.mkdir(exist_ok=True)
        for stale in self.folder.glob(self.prefix + "*"):
            stale.unlink()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # pycc's pending deprecation
            from numba.pycc import CC  # type: ignore[attr-defined]

            module = CC(name)  # type: ignore[no-untyped-call]
            module.output_dir = str(self.folder)
            module.verbose = False
            if self.for_this_processor:
                module.target_cpu = "host"
            for export_name, kernel in exports.items():
                module.export(export_name, signatures[export_name])(kernel.py_func)  # type: ignore[no-untyped-call]
            module.compile()
        return self.folder
