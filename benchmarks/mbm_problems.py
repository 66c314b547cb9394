"""MotionBenchMaker's Panda problems, fetched once into the user cache and read from there.

The problems (Chamzas et al., "MotionBenchMaker: A Tool to Generate and Benchmark Motion
Planning Datasets", RA-L 2022; 7 scenarios x 100 problems for the Panda) ship inside the
``vamp-planner`` source distribution on PyPI as ``resources/panda/problems.tar.bz2``
(``problems/<scenario>_panda/sceneNNNN.yaml`` and ``requestNNNN.yaml``). On first use the
source distribution is downloaded with pip (no build), that one archive is kept in
``$XDG_CACHE_HOME/kitchen_tamp/motionbenchmaker/`` and the rest deleted; nothing is copied
into the repository. The files are read by `kitchen_tamp.motion.motion_bench_maker`.
"""

from __future__ import annotations

import re
import subprocess
import sys
import tarfile
import tempfile
from collections.abc import Sequence
from pathlib import Path

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.motion.motion_bench_maker import MBM_SCENARIOS, MbmProblem, read_mbm_problem
from kitchen_tamp.user_cache import cache_directory

VAMP_SDIST = "vamp-planner==0.6.4"
"""The source distribution the problems are taken from (65 MB)."""
ARCHIVE_IN_SDIST = "vamp_planner-0.6.4/resources/panda/problems.tar.bz2"


class ProblemsUnavailableError(RuntimeError):
    """The problems could not be fetched or read; the message says why and where."""


def problems_directory() -> Path:
    """Where the problem archive and the obstacle URDFs of the problems are kept."""
    return cache_directory() / "motionbenchmaker"


def problem_archive() -> Path:
    """The Panda problem archive in the cache, fetched from PyPI (and said so) when absent."""
    archive = problems_directory() / "panda-problems.tar.bz2"
    if archive.is_file():
        return archive
    print(
        f"MotionBenchMaker problems: downloading the {VAMP_SDIST} source distribution (65 MB) from "
        f"PyPI once, keeping only its resources/panda/problems.tar.bz2 as {archive}",
        file=sys.stderr,
    )
    with tempfile.TemporaryDirectory() as scratch:
        command = [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps"]
        done = subprocess.run(
            [*command, VAMP_SDIST, "-d", scratch], capture_output=True, text=True, check=False
        )
        sdists = sorted(Path(scratch).glob("vamp_planner-*.tar.gz"))
        if done.returncode != 0 or not sdists:
            reason = (done.stderr.strip().splitlines() or ["no source distribution"])[-1]
            raise ProblemsUnavailableError(f"pip download {VAMP_SDIST} failed: {reason}")
        try:
            with tarfile.open(sdists[0], "r:gz") as sdist:
                member = sdist.extractfile(ARCHIVE_IN_SDIST)
                if member is None:
                    raise KeyError(ARCHIVE_IN_SDIST)
                write_atomically(archive, member.read())
        except (KeyError, OSError, tarfile.TarError) as error:
            raise ProblemsUnavailableError(f"{sdists[0].name}: no {ARCHIVE_IN_SDIST} ({error})") from None
    return archive


_MEMBER = re.compile(r"problems/(?P<scenario>\w+)_panda/(?P<kind>scene|request)(?P<index>\d+)\.yaml$")


def load_problems(scenarios: Sequence[str] = MBM_SCENARIOS, count: int = 100) -> list[MbmProblem]:
    """The first ``count`` problems (by number) of each scenario, in the order given."""
    unknown = sorted(set(scenarios) - set(MBM_SCENARIOS))
    if unknown:
        raise ProblemsUnavailableError(f"unknown scenarios {unknown}; choose from {', '.join(MBM_SCENARIOS)}")
    archive = problem_archive()
    texts: dict[tuple[str, int, str], str] = {}
    try:
        with tarfile.open(archive, "r:bz2") as problems:
            for member in problems.getmembers():
                matched = _MEMBER.search(member.name)
                if matched is None or matched["scenario"] not in scenarios:
                    continue
                stream = problems.extractfile(member)
                if stream is not None:
                    key = (matched["scenario"], int(matched["index"]), matched["kind"])
                    texts[key] = stream.read().decode()
    except (OSError, tarfile.TarError) as error:
        raise ProblemsUnavailableError(
            f"{archive}: cannot read ({error}); delete it to fetch it again"
        ) from None
    loaded = []
    for scenario in scenarios:
        indices = sorted({index for s, index, _ in texts if s == scenario})[:count]
        for index in indices:
            where = {
                kind: f"{archive.name}:{scenario}/{kind}{index:04d}.yaml" for kind in ("scene", "request")
            }
            scene, request = texts.get((scenario, index, "scene")), texts.get((scenario, index, "request"))
            if scene is None or request is None:
                raise ProblemsUnavailableError(
                    f"{archive}: {scenario} problem {index} lacks a scene or request"
                )
            loaded.append(read_mbm_problem(scenario, index, scene, request, where))
    return loaded
