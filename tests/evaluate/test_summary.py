"""summary.md from results rows: the success table, the pooled random problems and their section."""

from __future__ import annotations

from pathlib import Path

from kitchen_tamp.evaluate.results_table import COLUMNS
from kitchen_tamp.evaluate.summary import summary_text


def _row(problem: str, seed: int, status: str, stage: str = "") -> dict[str, str]:
    row = dict.fromkeys(COLUMNS, "")
    row.update(problem=problem, mode="rrt", seed=str(seed), status=status, failure_stage=stage,
               task_id=f"{problem}-rrt-seed{seed}", wall_s="3.0", path_length_rad="12.5",
               abstract_plans_tried=str(1 + seed), facts_learned=str(seed))
    return row


def test_random_problems_are_pooled_and_counted(tmp_path: Path) -> None:
    keys = ("problem", "layout_attempts", "symbolically_solvable", "plan_length")
    manifest = [dict(zip(keys, ("random-000", "1", "true", "3"), strict=True)),
                dict(zip(keys, ("random-001", "2", "false", ""), strict=True))]
    rows = [
        _row("problem", 0, "solved"),
        _row("random-000", 0, "solved"),
        _row("random-000", 1, "solved"),
        _row("random-001", 0, "failed", "symbolic"),
    ]
    text = summary_text(tmp_path, rows, manifest)
    assert "| problem | rrt | 1/1 | 100% [21, 100] | 3.0 | 3.0 | 1 | 0 | 12.5 | - | - |" in text
    assert "| random (2 problems) | rrt | 2/3 | 67% [21, 94] | 3.0 | 3.0 | 1 | 0 |" in text
    assert "| random-000 |" not in text  # single random problems only in the pooled row
    assert "symbolic 1" in text
    assert "- generated: 2, each laid out in the kitchen (1 at the first start drawn)" in text
    assert "- symbolically solvable: 1/2 (shortest plans of 3 to 3 actions)" in text
    assert "solved by the system with every seed: 1, with at least one: 1" in text
    assert "- solved with no seed: random-001" in text
