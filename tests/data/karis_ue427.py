#!/usr/bin/env python3
"""An independent port of Unreal Engine 4.27's `HairShading` (HairBsdf.ush), as listed in
shared/seeds/hair-models-survey-kajiya-marschner-weta-ue4.txt ("UE4.27 源码 / 核心代码"), for
the expected values of tests/models_karis.rs.

Written literally from the HLSL, in UE's own conventions: world-space L (to the light),
V (to the viewer) and N, the hair tangent pointing to the ROOT. The test's directions are
given in hairmath's local frame (tangent +X, root to tip); this script maps them into another
world frame, where N = Q (-1, 0, 0) = +Y, so nothing of hairmath's frame leaks in.

Configuration (UE's deferred HairBxDF for direct lighting): Specular = 0.5, Backlit = 1,
Area = 0, bUseSeparableR = true, non-legacy absorption, no multiple scattering; asinFast
replaced by the exact asin. The refit variant swaps in hairmath's refitted constants
(src/models/constants.rs) and inverts the colour at its own beta_n.

Run: python3 tests/data/karis_ue427.py   (prints the two tables pasted into the test)
"""
import math

PI = math.pi


# ---------------------------------------------------------------- HLSL helpers
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def mul(s, a):
    return [s * a[0], s * a[1], s * a[2]]


def saturate(x):
    return min(max(x, 0.0), 1.0)


def clamp(x, lo, hi):
    return min(max(x, lo), hi)


def rsqrt(x):
    return 1.0 / math.sqrt(x)


def pow2(x):
    return x * x


def pow5(x):
    return x * x * x * x * x


def hair_g(b, theta):
    return math.exp(-0.5 * pow2(theta) / (b * b)) / (math.sqrt(2 * PI) * b)


def hair_f(cos_theta):
    n = 1.55
    f0 = pow2((1 - n) / (1 + n))
    return f0 + (1 - f0) * pow5(1 - cos_theta)


def hair_color_to_absorption(c, b=0.3):
    b2 = b * b
    b3 = b * b2
    b4 = b2 * b2
    b5 = b * b4
    d = 5.969 - 0.215 * b + 2.532 * b2 - 10.73 * b3 + 5.574 * b4 + 0.245 * b5
    return [pow2(math.log(ch) / d) for ch in c]


UE427 = dict(n_prime=(1.19, 0.36), d_tt=(-3.65, -3.98), d_trt=(17.0, -16.78), h_tt=(0.6, 0.8))
# hairmath's refits (src/models/constants.rs: KARIS_ETA_PRIME, KARIS_D_TT, KARIS_D_TRT, KARIS_H_TT).
REFIT = dict(
    n_prime=(1.18961678e0, 3.67378675e-1),
    d_tt=(-3.47141378e0, -3.82753911e0),
    d_trt=(1.77451764e1, -1.75499604e1),
    h_tt=(7.48362401e-1, 1.08647371e0),
)


def hair_shading(base_color, roughness, L, V, N, consts=UE427, color_beta_n=0.3):
    """The listing's HairShading with the configuration above; returns S per channel."""
    specular, in_backlit, area = 0.5, 1.0, 0.0
    clamped_roughness = clamp(roughness, 1 / 255.0, 1.0)
    backlit = min(in_backlit, 1.0)

    # N is the vector parallel to hair pointing toward root
    VoL = dot(V, L)
    sin_theta_l = clamp(dot(N, L), -1.0, 1.0)
    sin_theta_v = clamp(dot(N, V), -1.0, 1.0)
    cos_theta_d = math.cos(0.5 * abs(math.asin(sin_theta_v) - math.asin(sin_theta_l)))

    Lp = sub(L, mul(sin_theta_l, N))
    Vp = sub(V, mul(sin_theta_v, N))
    cos_phi = dot(Lp, Vp) * rsqrt(dot(Lp, Lp) * dot(Vp, Vp) + 1e-4)
    cos_half_phi = math.sqrt(saturate(0.5 + 0.5 * cos_phi))

    a0, b0 = consts["n_prime"]
    n_prime = a0 / cos_theta_d + b0 * cos_theta_d

    shift = 0.035
    alpha = [-shift * 2, shift, shift * 4]
    r2 = pow2(clamped_roughness)
    B = [area + r2, area + r2 / 2, area + r2 * 2]

    S = [0.0, 0.0, 0.0]

    # R
    sa = math.sin(alpha[0])
    ca = math.cos(alpha[0])
    shift_r = 2 * sa * (ca * cos_half_phi * math.sqrt(1 - sin_theta_v * sin_theta_v) + sa * sin_theta_v)
    b_scale = math.sqrt(2.0) * cos_half_phi
    mp = hair_g(B[0] * b_scale, sin_theta_l + sin_theta_v - shift_r)
    np_ = 0.25 * cos_half_phi
    fp = hair_f(math.sqrt(saturate(0.5 + 0.5 * VoL)))
    r = mp * np_ * fp * (specular * 2) * (1 + (backlit - 1) * saturate(-VoL))
    S = [s + r for s in S]

    # TT
    mp = hair_g(B[1], sin_theta_l + sin_theta_v - alpha[1])
    a = 1 / n_prime
    c1, c2 = consts["h_tt"]
    h = cos_half_phi * (1 + a * (c1 - c2 * cos_phi))
    f = hair_f(cos_theta_d * math.sqrt(saturate(1 - h * h)))
    fp = pow2(1 - f)
    absorption = hair_color_to_absorption(base_color, color_beta_n)
    tp = [math.exp(-s * 2 * abs(1 - pow2(h * a) / cos_theta_d)) for s in absorption]
    k, c = consts["d_tt"]
    np_ = math.exp(k * cos_phi + c)
    S = [s + mp * np_ * fp * t * backlit for s, t in zip(S, tp)]

    # TRT
    mp = hair_g(B[2], sin_theta_l + sin_theta_v - alpha[2])
    f = hair_f(cos_theta_d * 0.5)
    fp = pow2(1 - f) * f
    tp = [math.pow(ch, 0.8 / cos_theta_d) for ch in base_color]
    k, c = consts["d_trt"]
    np_ = math.exp(k * cos_phi + c)
    S = [s + mp * np_ * fp * t for s, t in zip(S, tp)]

    return [-min(-s, 0.0) for s in S]


# ---------------------------------------------------------------- the test points
# hairmath's local (x, y, z) is UE's world (z, -x, y): a signed permutation, exact in floating
# point (a general rotation would perturb sin theta = +-1 by an ulp, where asin is infinitely
# steep). UE's N, the tangent towards the root, is then world +Y.
Q = [[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]


def to_world(v):
    return [dot(row, v) for row in Q]


def local(sin_theta, phi):
    c = math.sqrt(1 - sin_theta * sin_theta)
    return [sin_theta, c * math.cos(phi), c * math.sin(phi)]


def directions():
    """(label, wi, wo) in hairmath's local frame: generic, hard cases, lobe peaks."""
    g = local(0.3, 0.4)
    out = [
        ("generic", local(-0.3, 0.2), local(0.3, 2.9)),
        ("README pair", [-0.3, 0.2, math.sqrt(1 - 0.13)], [0.3, 0.1, math.sqrt(0.9)]),
        ("wi = wo", g, g),
        ("wi = -wo", g, [-x for x in g]),
        ("phi = 0", local(-0.5, 1.0), local(0.2, 1.0)),
        ("phi = pi", local(-0.2, 0.3), local(0.25, 0.3 + PI)),
        ("R peak (specular cone, phi = 0)", local(-0.1, 0.0), local(0.17, 0.0)),
        ("TT peak (forward, phi = pi)", local(-0.25, -1.2), local(0.22, -1.2 + PI)),
        ("TRT (phi = 0.6)", local(-0.35, 0.0), local(0.2, 0.6)),
        ("grazing wi", local(0.9999999, 1.3), local(0.1, -0.5)),
        ("grazing both, opposite ends", local(-0.9999999, 0.5), local(0.9999999, 2.0)),
        ("wi along +X (tip)", [1.0, 0.0, 0.0], local(-0.4, 0.9)),
        ("wo along -X (root)", local(0.2, -2.2), [-1.0, 0.0, 0.0]),
        ("wi = -wo along the tangent", [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]),
        ("wi = wo along the tangent", [-1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]),
        ("normal plane, phi = 2", local(0.0, 0.0), local(0.0, 2.0)),
    ]
    return out


MATERIALS = [
    # (label, BaseColor, Roughness)
    ("brown", [0.026, 0.0069, 0.0004], 0.539),
    ("blonde", [0.62, 0.45, 0.24], 0.3),
    ("white, smooth", [1.0, 1.0, 1.0], 0.12),
    ("dark, roughest", [0.01, 0.02, 0.05], 1.0),
]

REFIT_MATERIALS = [
    # (label, BaseColor, Roughness, beta_n)
    ("brown at beta_n 0.6", [0.026, 0.0069, 0.0004], 0.539, 0.6),
    ("blonde at beta_n 0.9", [0.62, 0.45, 0.24], 0.3, 0.9),
]


def rust(v):
    return "[" + ", ".join(repr(float(x)) for x in v) + "]"


def main():
    N = to_world([-1.0, 0.0, 0.0])
    print("/// (BaseColor, Roughness, wi, wo, S): UE 4.27's constants, the colour inverted at")
    print("/// beta_n = 0.3. Generated by tests/data/karis_ue427.py.")
    print("#[rustfmt::skip]")
    print("const UE427_ROWS: &[UeRow] = &[")
    for label, color, rough in MATERIALS:
        print(f"    // {label}")
        for dlabel, wi, wo in directions():
            s = hair_shading(color, rough, to_world(wi), to_world(wo), N)
            print(f"    // {dlabel}")
            print(f"    ({rust(color)}, {rough!r}, {rust(wi)}, {rust(wo)}, {rust(s)}),")
    print("];")
    print()
    print("/// (BaseColor, Roughness, beta_n, wi, wo, S): hairmath's refitted constants, the colour")
    print("/// inverted at beta_n. Generated by tests/data/karis_ue427.py.")
    print("#[rustfmt::skip]")
    print("const REFIT_ROWS: &[RefitRow] = &[")
    for label, color, rough, beta_n in REFIT_MATERIALS:
        print(f"    // {label}")
        for dlabel, wi, wo in directions():
            s = hair_shading(color, rough, to_world(wi), to_world(wo), N, REFIT, beta_n)
            print(f"    // {dlabel}")
            print(f"    ({rust(color)}, {rough!r}, {beta_n!r}, {rust(wi)}, {rust(wo)}, {rust(s)}),")
    print("];")


if __name__ == "__main__":
    main()
