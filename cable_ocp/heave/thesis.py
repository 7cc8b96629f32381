"""Numbers printed in Huang (1992) chapter 6, with where they come from.

Only values the thesis prints live here; chosen values (limits, noise, weights) live in the
problem files ``problems/heave/*.toml`` with their justification.
"""

from __future__ import annotations

import numpy as np

# Example 6.2.6 (regulator): a, b identified from the nonlinear cable model (text after the
# data table; Fig. 6.12's caption prints b = 0.1996759, the text 0.1906759 - the text is used).
A_626 = 7.339769  # s^2
B_626 = 0.1906759  # s
# Fig. 6.13: quadratic-damping model (6.3).
A_626_NL = 7.326944  # s^2
B_626_NL = 0.0719096  # s^2/m
# Fig. 6.10: boom-tip motion from a Pierson-Moskowitz spectrum, Hs = 6 m, Tz = 14 s.
HS_626 = 6.0  # m
TZ_626 = 14.0  # s
TAU_626 = 0.2  # s, Fig. 6.17
# Printed gains, u0 = -G x (Figs. 6.15/6.16: [x, x', u]; Fig. 6.17: (6.14) state order).
G3_626 = np.array([[93.944, 41.41, 5.166]])
G5_626 = np.array([[296.97, 132.73, 15.95, 2.306, 0.164]])

# Example 6.3.6 (stochastic): sea state 5, ship filter, winch, unit.
HS_636 = 3.048  # m (10 ft)
WM_636 = 0.785  # rad/s
WV_636, ZETA_V_636, KV_636 = 0.393, 0.6, 0.5  # rad/s, -, -
K_636 = 1.0  # 1/s
A_636, B_636 = 0.8959, 0.1658  # s^2, s
SIGMA_UNCONTROLLED_636 = 0.255  # m (Fig. 6.23)
SIGMA_CONTROLLED_636 = 2.96e-4  # m (Fig. 6.24)
