"""The URDFs in models/ are exactly what models/generate_models.py writes."""

from __future__ import annotations

import importlib.util
import sys

from tests.kitchen.conftest import REPO


def test_generated_models_are_up_to_date() -> None:
    spec = importlib.util.spec_from_file_location("generate_models", REPO / "models" / "generate_models.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    try:
        spec.loader.exec_module(module)
    finally:
        del sys.modules[spec.name]
    for file_name, text in module.model_texts().items():
        assert (REPO / "models" / file_name).read_text() == text, f"regenerate models/{file_name}"
