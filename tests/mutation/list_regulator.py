"""Mutations of the thesis' printed gains as scene controllers (issue 24 item 7, third
bullet: cable_ocp/heave/printed.py, the printed-g3/g5 checks of cable_ocp/scene/heave.py)."""

SCENE = "tests/heave/test_printed_scene.py"

MUTATIONS = [
    dict(name="printed-gain-on-the-scene-delay", area="heave",
         file="cable_ocp/heave/printed.py",
         old="winch=dataclasses.replace(scene.winch, delay=g.tau))",
         new="winch=dataclasses.replace(scene.winch, delay=scene.winch.delay))",
         tests=(SCENE,),
         description="a printed gain runs on the scene's [winch] delay instead of the delay "
                     "of its design (G5 on ex_6_2_6.toml then runs without its 0.2 s delay)"),
    dict(name="printed-stability-check-without-the-delay", area="heave",
         file="cable_ocp/heave/printed.py",
         old="lqr.true_discrete_loop(des, g.tau, h).A",
         new="lqr.true_discrete_loop(des, 0.0, h).A",
         tests=(SCENE,),
         description="the design's stability check samples the loop without the true delay "
                     "(G5 held over 50 ms then passes it)"),
    dict(name="printed-g5-sample-check-dropped", area="scene",
         file="cable_ocp/scene/heave.py",
         old=("        if abs(ratio - round(ratio)) > 1e-9:\n"
              "            raise CableOCPError(f\"{ctrl}:"),
         new="        if False:\n            raise CableOCPError(f\"{ctrl}:",
         tests=(SCENE,),
         description="a printed-g5 scene whose sample time does not divide G5's 0.2 s delay "
                     "is accepted"),
]
