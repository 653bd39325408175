"""tools/plot/tdo_compact.py against the samples of the same answer: the committed log's Map1
answer carries both forms (SAMPLES_ON); every sample time must give the sample to 1e-9 m.
usage: py_compact.py LOG PYTYPES_DIR"""
import os
import sys

import lcm

sys.path.insert(0, sys.argv[2])
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                                "plot"))
import tdo  # noqa: E402
import tdo_compact  # noqa: E402

both = [t for t in (tdo.trajectory_t.decode(ev.data) for ev in lcm.EventLog(sys.argv[1], "r")
                    if ev.channel == "TDO_TRAJECTORY")
        if t.n_samples > 0 and t.n_pieces > 0]
if not both:
    sys.exit("FAILED: no answer with both forms in the log")
worst = 0.0
for t in both:
    for row in t.samples:
        got = tdo_compact.state(t, row[0])
        worst = max(worst, max(abs(got[k] - row[k]) for k in range(1, 4)))
print(f"{len(both)} answers, {sum(t.n_samples for t in both)} samples: max |dp| {worst:.3g} m")
sys.exit(0 if worst <= 1e-9 else "FAILED: more than 1e-9 m")
