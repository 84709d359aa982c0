"""Regenerates tests/data/mitsuba_chiang.csv: Mitsuba 3's `hair` BSDF evaluated on random
direction pairs for several parameter sets, an independent implementation of Chiang 2016 to test
hairmath's against.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy
    /tmp/mi/bin/python tools/make_mitsuba_reference.py > tests/data/mitsuba_chiang.csv
"""
import csv, io, math, random, subprocess, sys, os

SETS = [  # beta_m, beta_n, alpha_deg, eta, sigma_a
    (0.3, 0.3, 2.0, 1.55, (0.5, 0.8, 1.4)),
    (0.1, 0.1, 2.0, 1.55, (0.2, 0.4, 0.9)),
    (0.7, 0.5, 0.0, 1.55, (0.0, 0.0, 0.0)),
    (0.2, 0.8, -5.0, 1.33, (2.0, 3.0, 6.0)),
    (1.0, 1.0, 10.0, 1.9, (0.05, 0.1, 0.2)),
]
rng = random.Random(20261122)

def unit():
    z = rng.uniform(-1, 1); p = rng.uniform(-math.pi, math.pi); r = math.sqrt(1 - z * z)
    return (z, r * math.cos(p), r * math.sin(p))

here = os.path.dirname(os.path.abspath(__file__))
out = csv.writer(sys.stdout, lineterminator="\n")
out.writerow(["beta_m", "beta_n", "alpha_deg", "eta", "sa_r", "sa_g", "sa_b",
              "wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "h", "f_r", "f_g", "f_b"])
for bm, bn, a, eta, sa in SETS:
    rows = io.StringIO(); w = csv.writer(rows, lineterminator="\n")
    w.writerow(["wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "h"])
    for _ in range(60):
        w.writerow(["%.17g" % x for x in unit() + unit() + (rng.uniform(-1, 1),)])
    res = subprocess.run([sys.executable, os.path.join(here, "mitsuba_eval.py"), "--variant", "scalar_rgb",
                          "--beta-m", str(bm), "--beta-n", str(bn), "--alpha-deg", str(a), "--eta", str(eta),
                          "--sigma-a", ",".join(map(str, sa))], input=rows.getvalue(), capture_output=True,
                         text=True, check=True)
    for r in list(csv.reader(io.StringIO(res.stdout)))[1:]:
        out.writerow([bm, bn, a, eta, *sa, *r])
