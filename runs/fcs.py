import sys, time, json
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule import forward
from cable_ocp.schedule.sea import vessel_motions
sc = load_dynamic_scene(sys.argv[1])
kw = json.loads(sys.argv[2]) if len(sys.argv) > 2 else {}
mot = vessel_motions(sc)
orig = forward.resimulate
def logged(scene, sched, m, **k):
    t0 = time.perf_counter()
    c = orig(scene, sched, m, **k)
    print(f"run v={max(sched.speed):.4f} dur={sched.duration:.1f} wall={time.perf_counter()-t0:.1f} {c.status} slack={c.slack} viol={ {a: round(b, 4) for a, b in c.violations.items()} }", flush=True)
    return c
forward.resimulate = logged
t0 = time.perf_counter()
r = forward.fastest_constant_speed(sc, mot, **kw)
print("total wall", time.perf_counter() - t0)
print(r.status, r.message, r.speed, r.duration, r.simulations, r.bracket, r.binding)
