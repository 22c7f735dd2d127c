"""The same UKF work in filterpy, for the README's speed comparison (`npm run bench:filterpy`).

A 3D-CTRA Unscented Kalman Filter (9 states, van der Merwe points with alpha 1, beta 2,
kappa 3 - n, as loratrack's) predicts 0.1 s and updates on a full-state measurement, 20 000
times; prints the median cost of one predict + update in microseconds. Needs
`pip install filterpy` (numpy, scipy). Not part of `npm test`.
"""
import math
import statistics
import time

import numpy as np
from filterpy.kalman import MerweScaledSigmaPoints, UnscentedKalmanFilter


def arc(alpha, k, v0, a, t):
    """loratrack's arc_integral: the integral of (v0 + a s) e^{i(alpha + k s)} over [0, t]."""
    u = k * t
    if abs(u) < 1e-9:
        f, g_re, g_im = complex(1.0, 0.5 * u), 0.5, u / 3.0
    else:
        f = (complex(math.cos(u), math.sin(u)) - 1.0) / (1j * u)
        g = (complex(math.cos(u), math.sin(u)) * (1.0 - 1j * u) - 1.0) / (u * u)
        g_re, g_im = g.real, g.imag
    z = complex(math.cos(alpha), math.sin(alpha)) * (v0 * t * f + a * t * t * complex(g_re, g_im))
    return z.real, z.imag


def ctra3d(s, dt):
    x, y, z, th, ph, v, a, om, ps = s
    p = arc(th + ph, om + ps, v, a, dt)
    m = arc(th - ph, om - ps, v, a, dt)
    vert = arc(ph, ps, v, a, dt)
    return np.array([x + 0.5 * (p[0] + m[0]), y + 0.5 * (p[1] + m[1]), z + vert[1],
                     th + om * dt, ph + ps * dt, v + a * dt, a, om, ps])


def main(steps=20000, rounds=5):
    n = 9
    points = MerweScaledSigmaPoints(n, alpha=1.0, beta=2.0, kappa=3.0 - n)
    ukf = UnscentedKalmanFilter(dim_x=n, dim_z=n, dt=0.1, fx=ctra3d, hx=lambda s: s, points=points)
    ukf.x = np.array([0, 0, 50, 0.3, 0.1, 8, 0.2, 0.1, 0.05], dtype=float)
    ukf.P *= 0.1
    ukf.Q = np.eye(n) * 0.01
    ukf.R = np.diag([0.8274, 0.8274, 3.7481, 0.0085, 0.0085, 0.25, 0.1521, 0.0003, 0.0003])
    rng = np.random.default_rng(1)
    truth = ukf.x.copy()
    samples = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        for _ in range(steps // rounds):
            truth = ctra3d(truth, 0.1)
            ukf.predict()
            ukf.update(truth + rng.normal(0, np.sqrt(np.diag(ukf.R))))
        samples.append((time.perf_counter() - t0) / (steps // rounds) * 1e6)
    print(f"filterpy {__import__('filterpy').__version__} UKF 3D-CTRA predict + update: "
          f"{statistics.median(samples):.1f} us (median of {rounds} rounds)")


if __name__ == "__main__":
    main()
