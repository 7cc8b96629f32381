"""The fuzz corpus that CI replays: the cases of the long fuzz that reach distinct code.

``tests/test_fuzz.py`` draws mutated problem files with Hypothesis (330 cases, about
40 s of CPU on the 2-core machine). CI replays a corpus instead: the fewest of those
cases (weighted by their run time) that together reach every line of ``cable_ocp`` that
the drawn cases of at most 2.5 CPU seconds reach (the few costlier ones are full runs of the
cable plants and the deployment, which their own tests run; the summary counts the lines
only they reach). A replayed case is checked exactly as a drawn one (no traceback,
exit code and JSON status agree, the one error line names a mutated key, every solved
statics answer passes the independent physics of ``test_fuzz.check_statics_physics``).

Regenerate the corpus after a change of the scene schema, the shipped problems or the
commands (it needs ``coverage``: ``pip install coverage``)::

    python tests/fuzz_corpus.py                  # 330 drawn cases -> tests/fuzz_corpus.json
    python tests/fuzz_corpus.py --cases 600      # a longer draw

and run the long, drawn fuzz itself with ``CABLE_OCP_FUZZ=full python -m pytest
tests/test_fuzz.py``. The corpus file records, for each case, the lines only it reached
when it was chosen, its outcome and its run time.
"""

from __future__ import annotations

import argparse
import base64
import json
import shutil
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CORPUS = HERE / "fuzz_corpus.json"


def encode(case: dict[str, Any]) -> dict[str, Any]:
    """A drawn case as JSON: the file relative to the repository, the mutated bytes in
    base64, the mutated key paths (what ``test_fuzz._names_a_key`` needs)."""
    return {"command": case["command"], "file": str(case["file"].relative_to(ROOT)),
            "extra": list(case["extra"]), "bytes": base64.b64encode(case["bytes"]).decode(),
            "mutated": [[list(p), repr(m)] for p, m in case["mutated"]],
            "what": case["what"]}


def decode(entry: dict[str, Any]) -> dict[str, Any]:
    """The inverse of :func:`encode` (the mutation itself only as its repr)."""
    return {"command": entry["command"], "file": ROOT / entry["file"],
            "extra": tuple(entry["extra"]), "bytes": base64.b64decode(entry["bytes"]),
            "mutated": [(tuple(p), m) for p, m in entry["mutated"]], "what": entry["what"]}


def load() -> list[dict[str, Any]]:
    """The corpus cases, decoded (:data:`CORPUS`)."""
    data = json.loads(CORPUS.read_text(encoding="utf-8"))
    return [decode(e) for e in data["cases"]]


def select(n_cases: int, out: Path, max_cpu_s: float = 2.5) -> dict[str, Any]:
    """Draw ``n_cases`` cases as the long fuzz does, measure each one's lines of
    ``cable_ocp`` and run time, and keep a greedy cover: repeatedly the case with the most
    not yet covered lines per second of its run time, among the cases of at most
    ``max_cpu_s`` (s) each (the lines only costlier cases reach, full runs of the cable
    plants and the deployment, are counted in the summary: their own tests run them)."""
    import coverage
    from hypothesis import HealthCheck, given, settings

    sys.path.insert(0, str(HERE))
    import test_fuzz as tf

    work = Path(tempfile.mkdtemp(prefix="cable_ocp_fuzz_corpus_"))
    (work / "cases").mkdir()
    shutil.copytree(ROOT / "problems" / "dynamics", work / "dynamics")
    drawn: list[tuple[dict[str, Any], frozenset, float, str]] = []
    counts: Counter = Counter()
    cov = coverage.Coverage(data_file=None, source=[str(ROOT / "cable_ocp")], branch=False)

    @settings(max_examples=n_cases, derandomize=True, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(case=tf.cases())
    def run(case: dict[str, Any]) -> None:
        cov.erase()
        t0 = time.process_time()
        cov.start()
        try:
            rc, lines = tf.run_case(case, work / "cases", counts, [])
            outcome = f"exit {rc}" + (f": {lines[0][:80]}" if lines else "")
        finally:
            cov.stop()
        cpu = time.process_time() - t0
        data = cov.get_data()
        hit = frozenset((f, n) for f in data.measured_files() for n in (data.lines(f) or ()))
        drawn.append((case, hit, cpu, outcome))

    try:
        run()
    finally:
        shutil.rmtree(work, ignore_errors=True)
    every = frozenset().union(*(h for _, h, _, _ in drawn))
    cheap = [d for d in drawn if d[2] <= max_cpu_s]
    reach = frozenset().union(*(h for _, h, _, _ in cheap))
    left, chosen = set(reach), []
    while left:
        best = max(cheap, key=lambda d: len(d[1] & left) / max(d[2], 0.05))
        new = best[1] & left
        if not new:
            break
        chosen.append((best, len(new)))
        left -= new
    entries = [{**encode(c), "outcome": o, "cpu_s": round(t, 3), "new_lines": n}
               for (c, _, t, o), n in chosen]
    summary = {"drawn": len(drawn), "chosen": len(chosen), "lines": len(every),
               "max_cpu_s": max_cpu_s, "lines_only_costlier_cases_reach": len(every - reach),
               "cpu_drawn_s": round(sum(d[2] for d in drawn), 1),
               "cpu_chosen_s": round(sum(e["cpu_s"] for e in entries), 1)}
    out.write_text(json.dumps({"summary": summary, "cases": entries}, indent=1,
                              ensure_ascii=False) + "\n", encoding="utf-8")
    return summary


def main() -> None:
    """``python tests/fuzz_corpus.py [--cases N] [--out PATH]``."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=330, help="drawn cases (330)")
    parser.add_argument("--out", type=Path, default=CORPUS, help="the corpus file")
    parser.add_argument("--max-cpu", type=float, default=2.5,
                        help="CPU seconds a case may take to be chosen (2.5)")
    args = parser.parse_args()
    print(json.dumps(select(args.cases, args.out, args.max_cpu)))


if __name__ == "__main__":
    main()
