import cProfile, pstats, sys
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.forward import resimulate, trapezoid_schedule
from cable_ocp.schedule.sea import vessel_motions
sc = load_dynamic_scene("problems/dynamics/deploy_6_3_6.toml")
mot = vessel_motions(sc)
sched = trapezoid_schedule(200.0, 300.0, 0.5, 0.2)
cProfile.run("c = resimulate(sc, sched, mot[0], hold=0.0)", "/tmp/p636")
print(c.status, sched.duration)
pstats.Stats("/tmp/p636").sort_stats("cumulative").print_stats(25)
