"""Evaluate Mitsuba 3's `hair` BSDF (Chiang 2016) on direction pairs given in the pbrt hair frame.

stdin : CSV with header wi_x,wi_y,wi_z,wo_x,wo_y,wo_z[,h]  (extra columns are passed through)
        pbrt convention: fibre tangent = +X, normal = +Z, wi -> light, wo -> viewer, both pointing away.
stdout: the input rows with f_r,f_g,f_b appended.

Mapping to Mitsuba (tangent = local +Y, shading normal = +Z, si.wi -> viewer, eval's wo -> light):
  * pbrt wo (viewer) -> Mitsuba si.wi ; pbrt wi (light) -> Mitsuba wo.
  * theta: pbrt sin(theta) = w.x  ->  Mitsuba w.y.
  * azimuth: pbrt phi = atan2(w.z, w.y) (pbrt-v4 HairBxDF::f); Mitsuba phi = atan2(w.z, w.x).
  * h: Mitsuba has no h input; eval computes h = sin(gamma_i), gamma_i = signed angle of si.wi's
    normal-plane projection from +Z. So we rotate both directions about the tangent so that the viewer's
    azimuth is pi/2 + asin(h); the light keeps pbrt's phi_i - phi_o. theta_i, theta_o, delta-phi
    unchanged. Checked against hairmath on rows with h of both signs and phi of both signs.
    Without an h column, h = wo_y / hypot(wo_y, wo_z) (what the fixed mapping implies for wo_z > 0).
Output f = Mitsuba eval() unchanged = sum_p M_p A_p N_p (pbrt-v3 `fsum`); the plugin applies no cosine.
--pbrt-f divides by |wi_z| (pbrt's f() = fsum / AbsCosTheta(wi)).
"""
import argparse, csv, math, sys
import numpy as np

ap = argparse.ArgumentParser()
ap.add_argument("--beta-m", type=float, default=0.3)
ap.add_argument("--beta-n", type=float, default=0.3)
ap.add_argument("--alpha-deg", type=float, default=2.0)
ap.add_argument("--eta", type=float, default=1.55)
ap.add_argument("--sigma-a", default="0.5,0.8,1.4", help="R,G,B absorption per unit fibre radius")
ap.add_argument("--variant", default="llvm_ad_rgb", help="llvm_ad_rgb (needs DRJIT_LIBLLVM_PATH) or scalar_rgb")
ap.add_argument("--pbrt-f", action="store_true", help="divide by |wi_z| like pbrt's HairBSDF::f")
args = ap.parse_args()

import drjit as dr
import mitsuba as mi
mi.set_variant(args.variant)
sig = [float(s) for s in args.sigma_a.split(",")]
assert len(sig) == 3
bsdf = mi.load_dict({"type": "hair", "longitudinal_roughness": args.beta_m,
                     "azimuthal_roughness": args.beta_n, "scale_tilt": args.alpha_deg,
                     "int_ior": args.eta, "ext_ior": 1.0,
                     "sigma_a": {"type": "rgb", "value": sig}})

rd = csv.reader(sys.stdin)
header = [c.strip() for c in next(rd)]
rows = [r for r in rd if r]
col = {n: i for i, n in enumerate(header)}
A = lambda n: np.array([float(r[col[n]]) for r in rows], dtype=np.float64)
wi = np.stack([A("wi_x"), A("wi_y"), A("wi_z")], 1)
wo = np.stack([A("wo_x"), A("wo_y"), A("wo_z")], 1)
wi /= np.linalg.norm(wi, axis=1, keepdims=True)
wo /= np.linalg.norm(wo, axis=1, keepdims=True)
h = A("h") if "h" in col else wo[:, 1] / np.maximum(np.hypot(wo[:, 1], wo[:, 2]), 1e-30)

def to_mi(w, psi):  # pbrt direction -> Mitsuba local with given Mitsuba azimuth psi
    s = np.clip(w[:, 0], -1, 1); c = np.sqrt(1 - s * s)
    return np.stack([c * np.cos(psi), s, c * np.sin(psi)], 1)
phi_o = np.arctan2(wo[:, 2], wo[:, 1]); phi_i = np.arctan2(wi[:, 2], wi[:, 1])
psi_cam = np.pi / 2 + np.arcsin(np.clip(h, -1, 1))
m_cam = to_mi(wo, psi_cam)                      # Mitsuba si.wi (viewer)
m_lig = to_mi(wi, psi_cam + (phi_i - phi_o))    # Mitsuba wo (light)

ctx = mi.BSDFContext()
n = len(rows)
if args.variant.startswith("scalar"):
    f = np.zeros((n, 3))
    for k in range(n):
        si = dr.zeros(mi.SurfaceInteraction3f)
        si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
        si.wi = mi.Vector3f(*m_cam[k])
        v = bsdf.eval(ctx, si, mi.Vector3f(*m_lig[k]))
        f[k] = [v[0], v[1], v[2]]
else:
    V = lambda a: mi.Vector3f(*[mi.Float(a[:, j].astype(np.float32)) for j in range(3)])
    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
    si.wi = V(m_cam)
    v = bsdf.eval(ctx, si, V(m_lig))
    f = np.stack([np.asarray(v[j]) for j in range(3)], 1).reshape(n, 3)
if args.pbrt_f:
    f = f / np.maximum(np.abs(wi[:, 2]), 1e-30)[:, None]

w = csv.writer(sys.stdout, lineterminator="\n")
w.writerow(header + ["f_r", "f_g", "f_b"])
for r, fr in zip(rows, f):
    w.writerow(r + ["%.7g" % x for x in fr])
