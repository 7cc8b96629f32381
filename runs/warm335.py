import sys, json, math
import numpy as np
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.ocp import line_step
from cable_ocp.schedule import planning as P
from cable_ocp.schedule.sea import vessel_motions
sc = load_dynamic_scene(sys.argv[1])
pb = sc.deployment
heaves = [m.casadi_heave() for m in vessel_motions(sc)]
line = line_step(sc, None)
acc = P.ramp_acceleration(sc, pb)
for v in [float(x) for x in sys.argv[2:]]:
    dur, _, _, spd, length = P.trapezoid(sc.length, pb.target_length, v, acc, pb.time_step)
    exc = P._rollout_limits(line, heaves, pb, dur, spd, length)
    print(v, round(dur, 1), exc, flush=True)
