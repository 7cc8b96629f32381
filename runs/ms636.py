import sys, time, json
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.forward import resimulate, trapezoid_schedule
from cable_ocp.schedule.sea import vessel_motions
sc = load_dynamic_scene("problems/dynamics/deploy_6_3_6.toml")
mot = vessel_motions(sc)
sched = trapezoid_schedule(200.0, 300.0, 0.5, 0.2)
for kw in [dict(), dict(motion_step=0.25), dict(time_step=0.1, motion_step=0.25), dict(time_step=0.1, segments=10, motion_step=0.25)]:
    t0 = time.perf_counter()
    c = resimulate(sc, sched, mot[0], hold=0.0, **kw)
    print(kw, f"wall {time.perf_counter()-t0:.2f}", c.status, f"tmin={c.tension_min_line.min():.0f} tmax={c.tension_max_line.max():.0f}", flush=True)
