"""The heavy elastica: the large deflection of an inextensible cantilever under its own weight,
the reference of the large-deflection plate checks (unittest/python/test_membrane.py,
examples/membranes/validate_bending.py)."""


def heavy_elastica_drop(alpha, n=2000):
    """Tip drop / L of an inextensible cantilever under its own weight (the heavy elastica):
    theta'' = -alpha (1 - s) cos(theta) on s in [0, 1] (theta the slope angle, downwards),
    theta(0) = 0 (clamped), theta'(1) = 0 (free tip), alpha = q L^3 / D; shooting on theta'(0)
    by bisection with RK4, the drop by Simpson's rule. Small alpha gives alpha / 8."""
    import math

    def shoot(k0):
        h, th, w, z = 1.0 / n, 0.0, k0, 0.0

        def f(s, th, w):
            return w, -alpha * (1 - s) * math.cos(th)
        for i in range(n):
            s = i * h
            k1 = f(s, th, w)
            k2 = f(s + h / 2, th + h / 2 * k1[0], w + h / 2 * k1[1])
            k3 = f(s + h / 2, th + h / 2 * k2[0], w + h / 2 * k2[1])
            k4 = f(s + h, th + h * k3[0], w + h * k3[1])
            thn = th + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            wn = w + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            thm = th + h / 2 * k2[0]
            z += h / 6 * (math.sin(th) + 4 * math.sin(thm) + math.sin(thn))
            th, w = thn, wn
        return w, z

    lo, hi = 0.0, 2.0 * alpha
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if shoot(mid)[0] > 0:
            hi = mid
        else:
            lo = mid
    return shoot(mid)[1]
