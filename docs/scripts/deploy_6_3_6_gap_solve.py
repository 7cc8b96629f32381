"""Solve the 6.3.6 OCP once and save its optimum (gap636)."""
import json
import sys
import time

import numpy as np

from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.planning import solve_schedule
from cable_ocp.schedule.sea import vessel_motions

out = sys.argv[1] if len(sys.argv) > 1 else "runs/gap636_opt.npz"
over = json.loads(sys.argv[2]) if len(sys.argv) > 2 else {}
scene = load_dynamic_scene("problems/dynamics/deploy_6_3_6.toml", over or None)
motions = vessel_motions(scene)
t0 = time.perf_counter()
hold = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
res = solve_schedule(scene, [m.casadi_heave() for m in motions], hold=hold)
sol = res.solution
print(res.status, res.message, time.perf_counter() - t0, flush=True)
print(res.diagnostics, flush=True)
np.savez(out, time=sol.time, length=sol.length, speed=sol.speed, accel=sol.accel,
         gain=sol.ahc_gain, tensions=sol.tensions, outputs=sol.outputs, heave=sol.heave,
         w=sol.variables_vector, status=res.status,
         diag=json.dumps({k: (v if isinstance(v, (int, float, str)) else str(v))
                          for k, v in res.diagnostics.items()}))
print("duration", sol.duration if hasattr(sol, "duration") else sol.time[-1], "g", sol.ahc_gain)
