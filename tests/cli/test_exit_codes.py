"""How a command's end becomes its exit code: the same rules for both programs."""

from __future__ import annotations

import pytest

from kitchen_tamp.cli import ExitCode, exit_code_of


class _UserMistake(Exception):
    pass


def _line_for_mistakes(error: Exception) -> str | None:
    return f"bad: {error}" if isinstance(error, _UserMistake) else None


def _raising(error: BaseException) -> int:
    raise error


@pytest.mark.parametrize(
    ("error", "code", "last_line"),
    [
        (_UserMistake("no such file"), ExitCode.BAD_INPUT, "error: bad: no such file"),
        (KeyboardInterrupt(), ExitCode.INTERRUPTED, "interrupted"),
        (RuntimeError("a bug"), ExitCode.INTERNAL_ERROR, "internal error: RuntimeError: a bug"),
    ],
)
def test_each_ending_has_its_code_and_line(
    capsys: pytest.CaptureFixture[str], error: BaseException, code: int, last_line: str
) -> None:
    assert exit_code_of(lambda: _raising(error), _line_for_mistakes) == code
    err = capsys.readouterr().err
    assert err.strip().splitlines()[-1] == last_line
    assert ("Traceback" in err) == (code == ExitCode.INTERNAL_ERROR)  # only a bug shows its traceback


def test_a_normal_end_keeps_the_body_s_code(capsys: pytest.CaptureFixture[str]) -> None:
    assert exit_code_of(lambda: int(ExitCode.NO_PLAN), _line_for_mistakes) == ExitCode.NO_PLAN
    assert capsys.readouterr().err == ""
