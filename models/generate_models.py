"""Write a kitchen's URDF files from its scene file (default: the shipped default kitchen).

The kitchen's models are derived from its scene file (``kitchen_tamp.kitchen.scene.models``)
and written into a cache folder when a kitchen is built, so they never disagree with it. The
files in this folder are the default kitchen's, for reading; a test checks they match:

    python models/generate_models.py [--scene FILE] [--out DIR]
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from kitchen_tamp.kitchen.scene.models import write_models
from kitchen_tamp.kitchen.scene.spec_reader import SceneFileError, read_scene
from kitchen_tamp.shipped_kitchens import default_scene_path

MODELS_DIR = Path(__file__).resolve().parent


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", type=Path, default=default_scene_path(), help="scene file (TOML)")
    parser.add_argument("--out", type=Path, default=MODELS_DIR, help="folder to write the URDFs into")
    args = parser.parse_args(argv)
    try:
        paths = write_models(read_scene(args.scene), args.out)
    except SceneFileError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    for path in paths.values():
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
