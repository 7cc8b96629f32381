"""bench deploy --part compare on one case with the OCP's warm-start grid made finer (a
patch in this runner only: cable_ocp/schedule/planning.py is the lead's). The grid of
discrete_constant_speed is SCAN speeds from speed_max down to floor x speed_max; the
default (SCAN 6, floor 1e-3: a factor 3.16 between speeds) steps over the 3.3.5 line's
window of feasible speeds (1.5-2.07 m/s) and lands on 0.485 m/s (2064 s, 4129 steps)."""
import json
import os
import sys

from cable_ocp.bench import deployment as bd
from cable_ocp.cli.bench_deploy import format_compare
from cable_ocp.cli import output as out
from cable_ocp.schedule import planning

scan, floor = int(sys.argv[3]), float(sys.argv[4])
motion_step = float(sys.argv[5]) if len(sys.argv) > 5 and sys.argv[5] != "-" else None
floor_fraction = float(sys.argv[6]) if len(sys.argv) > 6 else None
planning.SCAN = scan
orig = planning.discrete_constant_speed


def finer(scene, line, heaves, problem, time_step, rel_tol=1e-2, floor_=None):
    return orig(scene, line, heaves, problem, time_step, rel_tol=rel_tol, floor=floor)


planning.discrete_constant_speed = finer
data = {"patch": {"planning.SCAN": scan, "discrete_constant_speed floor": floor},
        "load_average_start": list(os.getloadavg()), "compare": []}


def save(case):
    if not data["compare"] or data["compare"][-1] is not case:
        data["compare"].append(case)
    open(sys.argv[2], "w").write(out.json_text(data) + "\n")


max_iter = int(sys.argv[7]) if len(sys.argv) > 7 else 500
data["patch"]["ipopt.max_iter"] = max_iter
res = bd.compare_case(sys.argv[1], motion_step=motion_step, floor_fraction=floor_fraction,
                      ipopt={"ipopt.max_iter": max_iter, "ipopt.print_level": 5,
                             "ipopt.print_frequency_iter": 50},
                      on_row=save, progress=lambda w: print(w, file=sys.stderr, flush=True))
save(res)
data["load_average_end"] = list(os.getloadavg())
open(sys.argv[2], "w").write(out.json_text(data) + "\n")
print(format_compare([res]))
print("load average at the end:", os.getloadavg())
