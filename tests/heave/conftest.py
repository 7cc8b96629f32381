"""Shared fixtures: the thesis' example plants (Huang 1992, sections 6.2.6 and 6.3.6)."""

from __future__ import annotations

import pytest

from cable_ocp.heave import plant as pl
from cable_ocp.heave import sea
from cable_ocp.heave.thesis import A_636, B_636, HS_636, WM_636


@pytest.fixture(scope="session")
def plant_636() -> pl.HeavePlant:
    """The 11-state plant (6.28) of example 6.3.6, built from blocks."""
    f = sea.thesis_shaping_filter(HS_636, WM_636)
    return pl.assemble_plant(A_636, B_636, pl.winch_first(1.0),
                             vessel=pl.vessel_block(0.393, 0.6, 0.5), sea=f)
