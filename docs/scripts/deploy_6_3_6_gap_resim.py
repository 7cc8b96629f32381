"""Re-simulate a saved 6.3.6 OCP optimum at several resolutions (gap636).

usage: python runs/gap636_resim.py OPT.npz CASE [CASE ...]
CASE = name:segments:time_step:motion_step:law   (time_step / motion_step "ocp" = T/N;
law "speed" = resimulate's speed table v + g dh/dt; "length" = a length table L_k + g h_k
at the OCP's nodes, linear between: the OCP's own sampled motion)
Prints the smallest element tension, when and where, the excess over tension_min, and
(at the OCP's grid) the largest node-by-node difference against the OCP's tensions.
"""
import copy
import json
import math
import sys
import time

import numpy as np

from cable_ocp.dynamics import simulate
from cable_ocp.scene.dynamics import dynamic_scene_from_dict, load_dynamic_scene
from cable_ocp.schedule.forward import Schedule, _motion_keys, _speed_rows
from cable_ocp.schedule.sea import vessel_motions

opt = np.load(sys.argv[1])
scene = load_dynamic_scene("problems/dynamics/deploy_6_3_6.toml")
motion = vessel_motions(scene)[0]
tn, vn, ln, g = opt["time"], opt["speed"], opt["length"], float(opt["gain"])
T, N = float(tn[-1]), tn.size - 1
dt_ocp = T / N
sched = Schedule.from_speed(tn, vn, scene.length, g)
ocp_t = opt["tensions"][0]  # (N+1, n)
tmin_lim = scene.deployment.tension_min
k_ocp = int(np.argmin(ocp_t.min(axis=1)))
print(f"OCP: T={T:.3f} s N={N} dt={dt_ocp:.5f} g={g:.4f}; smallest element tension "
      f"{ocp_t.min():.1f} N at t={tn[k_ocp]:.2f} s L={ln[k_ocp]:.1f} m element "
      f"{int(np.argmin(ocp_t[k_ocp]))}", flush=True)
hold = 20.0
rows = []
for case in sys.argv[2:]:
    name, seg, ts, ms, law = case.split(":")
    seg = int(seg)
    dt = dt_ocp if ts == "ocp" else float(ts)
    mstep = dt_ocp if ms == "ocp" else float(ms)
    steps = math.ceil((T + hold) / dt - 1e-9)
    dur = steps * dt
    raw = copy.deepcopy(scene.raw)
    if law == "speed":
        tt, vv = _speed_rows(sched, motion, dur, mstep)
        top = {"payout_law": "table", "payout_speed_table": [[float(a), float(b)]
                                                             for a, b in zip(tt, vv, strict=True)]}
    else:  # the OCP's own: L + g h at its nodes, linear between
        lw = ln + g * motion.heave(tn)
        tl = np.append(tn, dur + 1.0)
        lw = np.append(lw, lw[-1] + g * (motion.heave(np.array([dur + 1.0]))[0]
                                          - motion.heave(tn[-1:])[0]))
        top = {"payout_law": "table", "payout_length_table": [[float(a), float(b)]
                                                              for a, b in zip(tl, lw, strict=True)]}
    top.update(_motion_keys(motion, dur, mstep))
    raw["top_motion"] = top
    sim = dict(raw["simulation"])
    sim.update(duration=dur, time_step=dt, output_step=dt, segments=seg)
    raw["simulation"] = sim
    w0 = time.perf_counter()
    res = simulate(dynamic_scene_from_dict(raw))
    wall = time.perf_counter() - w0
    t = np.asarray(res.t)
    ten = np.asarray(res.segment_tensions).reshape(len(t), -1)
    L = np.asarray(res.length)
    k = int(np.argmin(ten.min(axis=1)))
    e = int(np.argmin(ten[k]))
    tmin = float(ten[k, e])
    # the OCP's nodes: the sample nearest each node
    diff = math.nan
    if seg == ocp_t.shape[1]:
        idx = np.clip(np.rint(tn / dt).astype(int), 0, len(t) - 1)
        near = np.abs(t[idx] - tn) < 1e-6 * dt + 1e-9
        if near.all():
            d = ten[idx] - ocp_t
            diff = float(np.max(np.abs(d)))
            kd = int(np.unravel_index(np.argmax(np.abs(d)), d.shape)[0])
    exc = max(0.0, (tmin_lim - tmin) / tmin_lim)
    # the OCP tensions' smallest interpolated to the forward element positions is not
    # comparable: report the unit-end element too
    row = dict(case=name, segments=seg, dt=dt, motion_step=mstep, law=law, tmin=tmin,
               t_at=float(t[k]), L_at=float(L[k]), element=e, excess=exc, status=res.status,
               max_node_diff=diff, wall=wall, tmin_cruise_end=float(ten[t <= T].min()))
    rows.append(row)
    print(f"{name:18s} seg={seg:2d} dt={dt:.4f} ms={mstep:.4f} {law:6s} tmin={tmin:9.1f} N "
          f"t={t[k]:7.2f} L={L[k]:7.1f} el={e:2d} excess={100*exc:5.2f} % "
          f"node-diff={diff:8.1f} N ({res.status}, {wall:.0f} s)", flush=True)
    if not math.isnan(diff):
        print(f"    largest node diff at t={tn[kd]:.2f} s", flush=True)
    np.savez(f"runs/gap636_sim_{name}.npz", t=t, ten=ten, L=L)
with open(sys.argv[1].replace(".npz", "_resim.json"), "a") as f:
    for r in rows:
        f.write(json.dumps(r) + "\n")
