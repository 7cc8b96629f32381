"""The pull on the unit of a saved 6.3.6 optimum: the OCP's against resimulate's (gap636).

usage: python runs/gap636_unit.py OPT.npz seg:dt:motion_step ...  (dt "ocp" = T/N)"""
import sys

import numpy as np

from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.forward import Schedule, resimulate
from cable_ocp.schedule.sea import vessel_motions

o = np.load(sys.argv[1])
scene = load_dynamic_scene("problems/dynamics/deploy_6_3_6.toml",
                           {"deployment.tension_at": ["unit", "top"]})
mot = vessel_motions(scene)[0]
tn = o["time"]
T, N = float(tn[-1]), tn.size - 1
pull = o["outputs"][0][:, 2]
print(f"OCP: T={T:.3f} g={float(o['gain']):.4f}: min pull {np.nanmin(pull[1:]):.0f} N at "
      f"{tn[1 + np.nanargmin(pull[1:])]:.2f} s; min element {o['tensions'][0].min():.0f} N")
sch = Schedule.from_speed(tn, o["speed"], scene.length, float(o["gain"]))
for case in sys.argv[2:]:
    seg, dt, ms = case.split(":")
    dt = T / N if dt == "ocp" else float(dt)
    ms = T / N if ms == "ocp" else float(ms)
    r = resimulate(scene, sch, mot, time_step=dt, segments=int(seg), motion_step=ms)
    a = r.t <= T + 1e-9
    pu, el = r.unit_tension, r.tension_min_line
    d = np.nan
    if abs(dt - T / N) < 1e-12:
        d = float(np.max(np.abs(np.interp(tn[1:], r.t, pu) - pull[1:])))
    print(f"{seg:>3s} el dt={dt:.4f} ms={ms:.4f}: pull min <=T {pu[a].min():8.0f} at "
          f"{r.t[a][pu[a].argmin()]:7.2f}, hold {pu[~a].min():8.0f} at "
          f"{r.t[~a][pu[~a].argmin()]:7.2f}"
          f"; element min <=T {el[a].min():8.0f}, hold {el[~a].min():8.0f}; "
          f"viol {r.violations['tension_min']:.4f}; |pull - OCP's| max {d:.0f} N", flush=True)
