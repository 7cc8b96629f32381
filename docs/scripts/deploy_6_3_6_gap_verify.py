"""verified_schedule on the 6.3.6 line with the OCP's hold (gap636).

usage: python runs/gap636_verify.py OUT.json HOLD ROUNDS [OVERRIDES_JSON]"""
import json
import sys
import time

import numpy as np

from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.planning import verified_schedule
from cable_ocp.schedule.sea import vessel_motions

out, hold, rounds = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
over = json.loads(sys.argv[4]) if len(sys.argv) > 4 else {}
scene = load_dynamic_scene("problems/dynamics/deploy_6_3_6.toml", over or None)
motions = vessel_motions(scene)
t0 = time.perf_counter()
res = verified_schedule(scene, motions, hold=hold, rounds=rounds)
wall = time.perf_counter() - t0
rows = []
for r in res.checks:
    run = r.runs[0]
    after = run.tension_min_line[run.t > r.duration + 1e-9]
    rows.append(dict(margins=r.margins, status=r.status, duration=r.duration,
                     violations=r.violations, tmin=float(run.tension_min_line.min()),
                     t_at=float(run.t[np.argmin(run.tension_min_line)]),
                     hold_min=float(after.min()) if after.size else None))
    print(rows[-1], flush=True)
sol = res.solution
doc = dict(status=res.status, message=res.message, duration=res.duration,
           gain=sol.ahc_gain if sol else None, wall=wall,
           diagnostics={k: (v if isinstance(v, (int, float, str)) else str(v))
                        for k, v in res.diagnostics.items()}, rounds=rows)
print(json.dumps(doc, indent=1), flush=True)
json.dump(doc, open(out, "w"), indent=1)
if sol is not None:
    np.savez(out.replace(".json", ".npz"), time=sol.time, length=sol.length, speed=sol.speed,
             accel=sol.accel, gain=sol.ahc_gain, tensions=sol.tensions, outputs=sol.outputs,
             heave=sol.heave)
