#!/usr/bin/env python3
"""RGB complex indices of refraction (eta, k) for the conductor presets
(src/scene/metal_presets.cpp, docs/path-tracing.md "Conductor presets"), from
published measured optical constants. Standard library only; the output is the
same on every run.

    python3 tools/dev/metal_presets.py            # the C++ table rows
    python3 tools/dev/metal_presets.py --check    # and the fit's residuals

Data:
- Ag, Al, Au, Cr, Cu, Ni, Pt, Ti, W: the Lorentz-Drude fits of Rakic, Djurisic,
  Elazar and Majewski, "Optical properties of metallic films for vertical-cavity
  optoelectronic devices", Applied Optics 37(22), 5271-5283 (1998), Table 1
  (fits to the measured data they collect, valid 0.1-5 eV / 0.25-12 um).
- Fe: Palik, "Handbook of Optical Constants of Solids" (1985-1998), as permittivity
  in Lumerical's default material database ("Fe (Iron) - Palik"), about every
  20 nm from 380 to 782 nm.

Method. An RGB renderer needs, per channel, one (eta, k) whose Fresnel
reflectance curve stands for the spectral one. The spectral reflectance
F(theta, lambda) is linear in light, so it is projected to linear sRGB for 16
angles of incidence (CIE 1931 observer, the analytic fit of Wyman, Sloan and
Shirley, JCGT 2(2) 2013; equal-energy light; each channel normalised so that a
reflectance of 1 at every wavelength projects to 1); then per channel (eta, k)
is fitted to those 16 values by least squares weighted by cos(theta) (the
weight of an angle in an albedo). Fitting reflectances, rather than projecting
eta and k themselves (Mitsuba 0.5's RGB mode and tables copied from it), keeps
the colour of the metal: eta and k are not linear in light.
"""
import cmath
import math
import sys

# Rakic et al. 1998, Table 1: plasma energy (eV), then (f, Gamma, omega) of the
# Drude term (omega 0) and the Lorentz oscillators, energies in eV.
RAKIC = {
    "Ag": (9.01, [(0.845, 0.048, 0.0), (0.065, 3.886, 0.816), (0.124, 0.452, 4.481), (0.011, 0.065, 8.185),
                  (0.840, 0.916, 9.083), (5.646, 2.419, 20.29)]),
    "Al": (14.98, [(0.523, 0.047, 0.0), (0.227, 0.333, 0.162), (0.050, 0.312, 1.544), (0.166, 1.351, 1.808),
                   (0.030, 3.382, 3.473)]),
    "Au": (9.03, [(0.760, 0.053, 0.0), (0.024, 0.241, 0.415), (0.010, 0.345, 0.830), (0.071, 0.870, 2.969),
                  (0.601, 2.494, 4.304), (4.384, 2.214, 13.32)]),
    "Cr": (10.75, [(0.168, 0.047, 0.0), (0.151, 3.175, 0.121), (0.150, 1.305, 0.543), (1.149, 2.676, 1.970),
                   (0.825, 1.335, 8.775)]),
    "Cu": (10.83, [(0.575, 0.030, 0.0), (0.061, 0.378, 0.291), (0.104, 1.056, 2.957), (0.723, 3.213, 5.300),
                   (0.638, 4.305, 11.18)]),
    "Ni": (15.92, [(0.096, 0.048, 0.0), (0.100, 4.511, 0.174), (0.135, 1.334, 0.582), (0.106, 2.178, 1.597),
                   (0.729, 6.292, 6.089)]),
    "Pt": (9.59, [(0.333, 0.080, 0.0), (0.191, 0.517, 0.780), (0.659, 1.838, 1.314), (0.547, 3.668, 3.141),
                  (3.576, 8.517, 9.249)]),
    "Ti": (7.29, [(0.148, 0.082, 0.0), (0.899, 2.276, 0.777), (0.393, 2.518, 1.545), (0.187, 1.663, 2.509),
                  (0.001, 1.762, 19.43)]),
    "W": (13.22, [(0.206, 0.064, 0.0), (0.054, 0.530, 1.004), (0.166, 1.281, 1.917), (0.706, 3.332, 3.580),
                  (2.590, 5.836, 7.498)]),
}

# Palik, iron: wavelength (nm), Re(epsilon), Im(epsilon).
PALIK_FE = [
    (380.0, -5.04421, 15.7296), (400.602, -5.33, 16.7558), (419.558, -5.56816, 17.611),
    (440.397, -5.80632, 18.4661), (461.005, -6.02066, 19.2358), (481.013, -6.21119, 19.9199),
    (500.0, -6.37791, 20.5185), (520.548, -6.54462, 21.1171), (539.554, -6.68752, 21.6302),
    (560.0, -6.83041, 22.1433), (578.261, -6.94949, 22.5709), (601.81, -7.09239, 23.084),
    (618.605, -7.18765, 23.4261), (640.964, -7.30673, 23.8537), (660.05, -7.402, 24.1957),
    (680.307, -7.49726, 24.5378), (701.847, -7.59253, 24.8799), (718.919, -7.66398, 25.1364),
    (743.017, -7.75924, 25.4785), (762.178, -7.83069, 25.735), (782.353, -7.90214, 25.9916),
]


def eps_rakic(metal, wavelength_nm):
    wp, terms = RAKIC[metal]
    w = 1239.84193 / wavelength_nm
    eps = complex(1.0, 0.0)
    for f, gamma, w0 in terms:
        eps += f * wp * wp / (w0 * w0 - w * w - 1j * w * gamma)
    return eps


def eps_palik_fe(wavelength_nm):
    pts = PALIK_FE
    if wavelength_nm <= pts[0][0]:
        return complex(pts[0][1], pts[0][2])
    for (l0, r0, i0), (l1, r1, i1) in zip(pts, pts[1:]):
        if wavelength_nm <= l1:
            t = (wavelength_nm - l0) / (l1 - l0)
            return complex(r0 + t * (r1 - r0), i0 + t * (i1 - i0))
    return complex(pts[-1][1], pts[-1][2])


def nk(eps):
    n = cmath.sqrt(eps)
    return n.real, abs(n.imag)


def fresnel_conductor(cos_i, eta, k):
    """Unpolarised reflectance of a conductor of index eta + ik, from a medium of index 1."""
    n = complex(eta, k)
    sin2 = 1.0 - cos_i * cos_i
    cos_t = cmath.sqrt(1.0 - sin2 / (n * n))
    rs = (cos_i - n * cos_t) / (cos_i + n * cos_t)
    rp = (n * cos_i - cos_t) / (n * cos_i + cos_t)
    return 0.5 * (abs(rs) ** 2 + abs(rp) ** 2)


def g(x, mu, s1, s2):
    t = (x - mu) / (s1 if x < mu else s2)
    return math.exp(-0.5 * t * t)


def cie_xyz(lam):
    """CIE 1931 2-degree observer, Wyman, Sloan and Shirley 2013 (multi-lobe fit)."""
    x = 1.056 * g(lam, 599.8, 37.9, 31.0) + 0.362 * g(lam, 442.0, 16.0, 26.7) - 0.065 * g(lam, 501.1, 20.4, 26.2)
    y = 0.821 * g(lam, 568.8, 46.9, 40.5) + 0.286 * g(lam, 530.9, 16.3, 31.1)
    z = 1.217 * g(lam, 437.0, 11.8, 36.0) + 0.681 * g(lam, 459.0, 26.0, 13.8)
    return x, y, z


XYZ_TO_SRGB = ((3.2404542, -1.5371385, -0.4985314), (-0.9692660, 1.8760108, 0.0415560),
               (0.0556434, -0.2040259, 1.0572252))
WAVELENGTHS = [380.0 + 5.0 * i for i in range(81)]  # 380..780 nm
ANGLES_COS = [math.cos(math.radians(a)) for a in (0, 10, 20, 30, 40, 50, 55, 60, 65, 70, 75, 80, 84, 87, 89, 89.9)]


def channel_weights():
    """Per wavelength, the linear sRGB response (r, g, b) of the observer."""
    out = []
    for lam in WAVELENGTHS:
        xyz = cie_xyz(lam)
        out.append(tuple(sum(XYZ_TO_SRGB[c][j] * xyz[j] for j in range(3)) for c in range(3)))
    return out


def project(values, weights):
    """RGB of a spectral reflectance sampled at WAVELENGTHS (a flat 1 projects to (1, 1, 1))."""
    rgb = []
    for c in range(3):
        num = sum(v * w[c] for v, w in zip(values, weights))
        den = sum(w[c] for w in weights)
        rgb.append(num / den)
    return rgb


def fit_channel(targets):
    """(eta, k) whose Fresnel curve best matches targets[i] at ANGLES_COS[i] (cos-weighted)."""
    def err(p):
        eta, k = p
        if eta <= 0.01 or k < 0.0:
            return 1e9
        return sum(c * (fresnel_conductor(c, eta, k) - t) ** 2 for c, t in zip(ANGLES_COS, targets))

    best = min(((e, k) for e in [0.05 * 1.25 ** i for i in range(20)] for k in [0.25 * i for i in range(1, 41)]),
               key=err)
    step = [best[0] * 0.25, 0.25]
    p = list(best)
    for _ in range(200):  # pattern search, halving the steps
        improved = False
        for d in range(2):
            for s in (1, -1):
                q = list(p)
                q[d] += s * step[d]
                if err(q) < err(p):
                    p, improved = q, True
        if not improved:
            step = [x * 0.5 for x in step]
            if max(step) < 1e-7:
                break
    return p, math.sqrt(err(p) / sum(ANGLES_COS))


def metal_spectrum(name):
    if name == "Fe":
        return [nk(eps_palik_fe(l)) for l in WAVELENGTHS]
    return [nk(eps_rakic(name, l)) for l in WAVELENGTHS]


def main():
    check = "--check" in sys.argv
    weights = channel_weights()
    names = sorted(list(RAKIC) + ["Fe"])
    for name in names:
        spectrum = metal_spectrum(name)
        per_angle = [project([fresnel_conductor(c, n, k) for n, k in spectrum], weights) for c in ANGLES_COS]
        eta, k, residual = [], [], []
        for ch in range(3):
            (e, kk), r = fit_channel([pa[ch] for pa in per_angle])
            eta.append(e)
            k.append(kk)
            residual.append(r)
        f0 = [fresnel_conductor(1.0, e, kk) for e, kk in zip(eta, k)]
        print(f'    {{"{name}", {{{eta[0]:.4f}f, {eta[1]:.4f}f, {eta[2]:.4f}f}}, '
              f'{{{k[0]:.4f}f, {k[1]:.4f}f, {k[2]:.4f}f}}}},')
        if check:
            print(f"      // F0 = ({f0[0]:.3f}, {f0[1]:.3f}, {f0[2]:.3f}); rms residual of the fit "
                  f"({residual[0]:.4f}, {residual[1]:.4f}, {residual[2]:.4f})")


if __name__ == "__main__":
    main()
