"""The delay line of the winch command: the one place that delays a command by ``tau``.

The winch applies the command issued ``tau`` seconds earlier (Huang (1992), section 6.2.5;
here exactly, not by the Pade or Taylor models (6.13)-(6.14)). A heave scene's delay is a
whole number of control samples, ``tau = d h`` (checked by
:func:`cable_ocp.scene.heave.check`), and a command is held over its sample (ZOH), so the
command applied over sample ``k`` is ``u0_{k-d}`` on every one of its sub-steps: on the
plant's sub-step grid of ``m`` steps per sample that is a delay of exactly
``nd_fine = d m`` sub-steps.

One :class:`DelayLine` serves both sides of the loop:

* the plant side (:func:`cable_ocp.heave.closed_loop.run_loop`): :meth:`DelayLine.push`
  returns the command the winch applies over the coming sample;
* the prediction side: :attr:`DelayLine.buffer` is the shift register
  ``[u0_{k-d}, ..., u0_{k-1}]`` of the sampled delayed model
  (:func:`cable_ocp.heave.discrete.discretize_delayed`), which the MPC
  (:class:`cable_ocp.heave.mpc.LinearMPC`) and the estimators
  (:mod:`cable_ocp.heave.estimators`) keep for their own commands.
"""

from __future__ import annotations

import numpy as np

__all__ = ["DelayLine"]


class DelayLine:
    """Shift register of the last ``d`` commands (oldest first), all zero at the start.

    Parameters
    ----------
    d : int
        Delay in samples (``tau / h``, :func:`cable_ocp.heave.discrete.delay_steps`).
    """

    def __init__(self, d: int) -> None:
        self.d = int(d)
        self.reset()

    def reset(self) -> None:
        """Empty the line: every past command (and the last one) is 0."""
        self._buf = np.zeros(self.d)
        self.last = 0.0

    @property
    def buffer(self) -> np.ndarray:
        """``[u0_{k-d}, ..., u0_{k-1}]`` (m), the delayed model's last ``d`` states; a view:
        do not modify."""
        return self._buf

    def push(self, u0: float) -> float:
        """Shift in the command ``u0`` (m) issued now; returns the command applied over this
        sample, ``u0_{k-d}`` (``u0`` itself without delay)."""
        self.last = u0
        if not self.d:
            return u0
        applied = self._buf[0]
        self._buf = np.concatenate([self._buf[1:], [u0]])
        return applied
