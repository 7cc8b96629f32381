import sys, time, json
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.forward import resimulate, trapezoid_schedule
from cable_ocp.schedule.sea import vessel_motions
sc = load_dynamic_scene(sys.argv[1])
kw = json.loads(sys.argv[2])
mot = vessel_motions(sc)
dp = sc.deployment
for v in [float(x) for x in sys.argv[3:]]:
    sched = trapezoid_schedule(sc.length, dp.target_length, v, dp.accel_max)
    t0 = time.perf_counter()
    c = resimulate(sc, sched, mot[0], **kw)
    print(f"v={v} dur={sched.duration:.1f} wall={time.perf_counter()-t0:.1f} {c.status} slack={c.slack} tmin={c.tension_min_line.min():.0f} tmax={c.tension_max_line.max():.0f} viol={ {a: round(b, 4) for a, b in c.violations.items()} }", flush=True)
