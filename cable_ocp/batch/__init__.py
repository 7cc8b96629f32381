"""Load-case studies: one problem file, a matrix of cases (grids, ranges, seeded random
samples of any dotted key), run on every local core by default or on a dask.distributed
cluster, with every case ending as a row and nothing lost when a case or a worker fails.

Modules
-------
study      run_batch and its result, BatchResult: the cases cut into chunks, run, stored
cases      the case matrix (grid in snake order, ranges, random samples, per-case seeds)
kinds      what a case of each scene kind computes, and its row
executors  in-process, local worker processes, dask
store      CSV + JSON lines written as rows arrive; the lock, the meta record, resume
arrays     per-case arrays in one netCDF file; the envelope across cases (range graph)
summary    the extremes of every output and the parameter values of the cases that gave them
response   frequency-response sweeps: time runs until periodic, one case per frequency and
           amplitude, beside the linear transfer function (frequency_response)

Example
-------
>>> from cable_ocp.batch import run_batch, parse_range
>>> res = run_batch("problems/dezoysa_sea_buggy.toml",
...                 ranges=[parse_range("layout.psi0_deg=0:180:7")])  # doctest: +SKIP
>>> res.column("max_tension [N]")                                     # doctest: +SKIP
"""

from cable_ocp.batch.cases import Case, build_cases, parse_grid, parse_random, parse_range
from cable_ocp.batch.study import BatchResult, run_batch

__all__ = ["BatchResult", "Case", "build_cases", "parse_grid", "parse_random", "parse_range",
           "run_batch"]
