"""Numerical building blocks below the physics: the C compile helper for CasADi functions
(:mod:`~cable_ocp.numerics.compile`), the kept sparse LU (:mod:`~cable_ocp.numerics.sparse_lu`),
sparse solves that never warn (:mod:`~cable_ocp.numerics.linalg`), block-tridiagonal
elimination in CasADi SX (:mod:`~cable_ocp.numerics.block_tridiagonal`), the Gauss
quadrature rules (:mod:`~cable_ocp.numerics.quadrature`), numbers that strict JSON can
hold (:mod:`~cable_ocp.numerics.jsonable`), files written whole or not at all
(:mod:`~cable_ocp.numerics.atomic`) and what every result shows its users: a short summary,
the optional pandas and xarray, netCDF files (:mod:`~cable_ocp.numerics.export`), text
tables that fit 100 columns (:mod:`~cable_ocp.numerics.text_table`) and the one handling of
Ctrl-C and SIGTERM, also inside CasADi's solvers (:mod:`~cable_ocp.numerics.interrupt`), and
the rotations of rigid bodies (:mod:`~cable_ocp.numerics.rotation`), the quintic
smooth step of every fade-in and ramp (:mod:`~cable_ocp.numerics.ramp`), and the
piecewise-linear tables of time whose cost does not grow with their rows
(:mod:`~cable_ocp.numerics.table`).

Nothing here knows about cables: these modules import no other part of the package.
"""
