import sys, time
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.forward import resimulate, trapezoid_schedule
from cable_ocp.schedule.sea import vessel_motions
sc = load_dynamic_scene(sys.argv[1])
mot = vessel_motions(sc)
dp = sc.deployment
L1 = sc.length + float(sys.argv[2])
sched = trapezoid_schedule(sc.length, L1, float(sys.argv[3]), dp.accel_max)
for seg, dt in [(int(a.split(',')[0]), float(a.split(',')[1])) for a in sys.argv[4:]]:
    t0 = time.perf_counter()
    chk = resimulate(sc, sched, mot[0], time_step=dt, segments=seg, hold=0.0)
    w = time.perf_counter() - t0
    print(seg, dt, f"sim {sched.duration:.1f} s wall {w:.2f} s ratio {w/sched.duration:.3f}", chk.status, chk.violations, flush=True)
