"""The README's sample outputs are what a run gives today.

Every ``$ cable-ocp ...`` command in a fenced block of the README that shows output is run
(its output files sent to a temporary folder), and every shown line must be a line of the
run's standard output: the same words, and every number equal to the digits shown (one unit
in the last shown digit: the last digit of a value printed from a rounding-level quantity may
flip between machines). A shown line that ends in ``...`` is a prefix of the run's line; a
line that is only ``...`` stands for lines left out. Left out of the comparison: timings
(lines that start ``wall time`` or ``build time``) and solver residuals at rounding level
(a shown value below 1e-11 only requires the run's to be below 1e-11 too).
"""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FENCE = re.compile(r"^```[a-z]*\n(.*?)^```", re.S | re.M)
NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
OUTPUT_OPTIONS = {"--plot", "--json", "--csv", "--out", "--netcdf"}
TIMING = ("wall time", "build time")
ROUNDING_LEVEL = 1e-11
#: README commands whose sample another test compares with a run it makes anyway (the same
#: command with output files only added: the same standard output), by the rules here
#: (:func:`shown_lines_missing`): the sample's run is not made twice
CHECKED_ELSEWHERE = {
    "cable-ocp deploy problems/dynamics/deploy_small.toml":
        "tests/test_deploy_cli.py::test_the_readme_deploy_sample_is_this_run",
}


def samples(text: str) -> list[tuple[str, list[str]]]:
    """(command, shown output lines) of every ``$ cable-ocp`` command that shows output.

    Parameters
    ----------
    text : str
        A markdown page.
    """
    out: list[tuple[str, list[str]]] = []
    for block in FENCE.findall(text):
        lines = block.splitlines()
        k = 0
        while k < len(lines):
            if not lines[k].startswith("$ cable-ocp "):
                k += 1
                continue
            cmd = lines[k][2:]
            while cmd.endswith("\\"):
                k += 1
                cmd = cmd[:-1] + " " + lines[k].strip()
            k += 1
            shown = []
            while k < len(lines) and not lines[k].startswith("$ "):
                shown.append(lines[k])
                k += 1
            if any(s.strip() for s in shown):
                out.append((cmd, shown))
    return out


def _shape(line: str) -> tuple[str, list[str]]:
    """The line's words with every number replaced by '#', whitespace collapsed; its numbers."""
    return " ".join(NUMBER.sub("#", line).split()), NUMBER.findall(line)


def _unit_in_last_place(shown: str) -> float:
    mantissa, _, exponent = shown.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (-decimals + (int(exponent) if exponent else 0))


def line_matches(shown: str, actual: str) -> bool:
    """Whether the run's line ``actual`` is the README's line ``shown`` (rules: module doc).

    Parameters
    ----------
    shown : str
        The line in the README.
    actual : str
        A line of the run's standard output.
    """
    prefix = shown.rstrip().endswith("...")
    shape_s, nums_s = _shape(shown.rstrip().removesuffix("...") if prefix else shown)
    shape_a, nums_a = _shape(actual)
    if prefix:
        if not shape_a.startswith(shape_s.rstrip(", ")):
            return False
        nums_a = nums_a[: len(nums_s)]
    elif shape_a != shape_s:
        return False
    if shown.strip().startswith(TIMING):
        return True
    if len(nums_a) != len(nums_s):
        return False
    for s, a in zip(nums_s, nums_a, strict=True):
        vs, va = float(s), float(a)
        if abs(vs) < ROUNDING_LEVEL and "e" in s.lower():
            if abs(va) >= ROUNDING_LEVEL:
                return False
        elif abs(va - vs) > _unit_in_last_place(s) * (1 + 1e-9):
            return False
    return True


def test_the_comparison_is_not_blind() -> None:
    """The rules accept the same line, a flipped last digit, a timing and a rounding-level
    residual, and refuse a changed value, a changed word and a shorter line."""
    assert line_matches("top tension  27601.3 .. 112939 N", "top tension       27601.3 .. 112939 N")
    assert line_matches("length L  305.0000 m", "length L  305.0001 m")
    assert not line_matches("length L  305.0000 m", "length L  305.0003 m")
    assert not line_matches("length L  305.0000 m", "length M  305.0000 m")
    assert line_matches("wall time  7.78 s (0.00389 s per simulated s)",
                        "wall time  2.06 s (0.00103 s per simulated s)")
    assert line_matches("residual 1.38e-13", "residual 1.09e-13")
    assert not line_matches("residual 1.38e-13", "residual 1.09e-10")
    assert line_matches("error (relative) 2.97e-09 (-) (1.83e-05 N, ...",
                        "error (relative) 2.97e-09 (-) (1.83e-05 N, 2.49e-07 m; more)")
    assert not line_matches("error (relative) 2.97e-09 (-) (1.83e-05 N, ...",
                            "error (relative) 9.23e-10 (-) (1.11e-08 N, 2.49e-07 m; more)")
    assert len(samples((ROOT / "README.md").read_text(encoding="utf-8"))) >= 3


def shown_lines_missing(shown: list[str], stdout: str) -> list[str]:
    """The README's shown lines that no line of a run's standard output matches
    (:func:`line_matches`; blank and ``...`` lines stand for nothing).

    Parameters
    ----------
    shown : list of str
        The sample's lines (:func:`samples`).
    stdout : str
        The run's standard output.
    """
    actual = stdout.splitlines()
    return [line for line in shown if line.strip() and line.strip() != "..."
            and not any(line_matches(line, a) for a in actual)]


def test_the_samples_checked_elsewhere_are_readme_samples() -> None:
    """Every command left to another test is a sample of the README (a renamed or removed
    sample would otherwise leave its test checking nothing)."""
    cmds = {cmd for cmd, _ in samples((ROOT / "README.md").read_text(encoding="utf-8"))}
    assert set(CHECKED_ELSEWHERE) <= cmds


def _argv(cmd: str, tmp: Path) -> list[str]:
    words = shlex.split(cmd)[1:]
    for k in range(len(words) - 1):
        if words[k] in OUTPUT_OPTIONS:
            words[k + 1] = str(tmp / Path(words[k + 1]).name)
    return [sys.executable, "-m", "cable_ocp", *words]


def test_readme_sample_outputs_match_a_run(tmp_path: Path) -> None:
    """Each sample command of the README, run now (all at once: they are independent),
    prints every line the README shows for it (those of ``CHECKED_ELSEWHERE`` by their
    tests)."""
    cases = [(cmd, shown) for cmd, shown in samples((ROOT / "README.md").read_text(
        encoding="utf-8")) if cmd not in CHECKED_ELSEWHERE]
    procs = [subprocess.Popen(_argv(cmd, tmp_path), cwd=ROOT, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True) for cmd, _ in cases]
    problems = []
    for (cmd, shown), proc in zip(cases, procs, strict=True):
        stdout, stderr = proc.communicate(timeout=300)
        if proc.returncode != 0:
            problems.append(f"{cmd}: exit {proc.returncode}: {stderr.strip()[-300:]}")
            continue
        actual = stdout.splitlines()
        for line in shown_lines_missing(shown, stdout):
            problems.append(f"{cmd}:\n  README: {line}\n  run:    "
                            + "\n          ".join(a for a in actual
                                                  if _shape(a)[0][:12] == _shape(line)[0][:12]))
    if problems:
        pytest.fail("README samples differ from a run today:\n" + "\n".join(problems))
