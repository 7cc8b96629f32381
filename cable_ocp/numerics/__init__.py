"""Numerical building blocks below the physics: the C compile helper for CasADi functions
(:mod:`~cable_ocp.numerics.compile`), the kept sparse LU (:mod:`~cable_ocp.numerics.sparse_lu`),
sparse solves that never warn (:mod:`~cable_ocp.numerics.linalg`), block-tridiagonal
elimination in CasADi SX (:mod:`~cable_ocp.numerics.block_tridiagonal`), the Gauss
quadrature rules (:mod:`~cable_ocp.numerics.quadrature`) and numbers that strict JSON can
hold (:mod:`~cable_ocp.numerics.jsonable`).

Nothing here knows about cables: these modules import no other part of the package.
"""
