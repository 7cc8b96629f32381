import sys, time, json, math
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.planning import solve_schedule
from cable_ocp.schedule.sea import vessel_motions
import numpy as np
path = sys.argv[1]
over = json.loads(sys.argv[2]) if len(sys.argv) > 2 else {}
sc = load_dynamic_scene(path, over) if over else load_dynamic_scene(path)
mot = vessel_motions(sc)
t0 = time.perf_counter()
ip = json.loads(sys.argv[3]) if len(sys.argv) > 3 else None
res = solve_schedule(sc, [m.casadi_heave() for m in mot], ipopt=ip)
print("wall", time.perf_counter() - t0, flush=True)
print("status", res.status); print("message", res.message); print("binding", res.binding)
print("warm", res.warm_start)
print("diag", {k: v for k, v in res.diagnostics.items() if not hasattr(v, "__len__") or isinstance(v, str)})
s = res.solution
if s is not None:
    print("duration", s.duration, "violations", s.violations)
    print("vmax", np.max(s.speed))
