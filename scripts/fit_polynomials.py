#!/usr/bin/python3
"""Coefficients of the fixed polynomials in the core's hot path, and their measured accuracy.

1. ContactPressure::factors() for uniform pressure below y = 0.4: kappa(y) = phi1/phi2 (Deur eq 43)
   and lambda(y) = phi1/(1 - 2 (1 + y) phi3) (eq 57), phi_k(y) = sum_n (-y)^n/(n + k)!, degree 8.
2. sinCos() on |r| <= pi/4: sin(r)/r as a polynomial of degree 6 in u = r^2, cos(r) of degree 7.

Each is interpolated at the Chebyshev points of its interval in 40-digit arithmetic (mpmath, Debian
package python3-mpmath) and written in the monomial basis; the script evaluates the double-precision
polynomial in the order the C++ code uses (Estrin's scheme) and prints its largest relative error
against the 40-digit function. Usage: scripts/fit_polynomials.py
"""
import mpmath as mp

mp.mp.dps = 40


def chebyshev_fit(f, upper, degree):
    n = degree + 1
    nodes = [upper / 2 + upper / 2 * mp.cos(mp.pi * (j + mp.mpf(1) / 2) / n) for j in range(n)]
    vandermonde = mp.matrix([[x ** i for i in range(n)] for x in nodes])
    return [float(c) for c in mp.lu_solve(vandermonde, mp.matrix([f(x) for x in nodes]))]


def estrin(c, y):
    """Estrin's scheme for up to 9 coefficients, grouped as in the C++ code."""
    c = list(c) + [0.0] * (9 - len(c))
    y2 = y * y
    y4 = y2 * y2
    pairs = [c[0] + c[1] * y, c[2] + c[3] * y, c[4] + c[5] * y, c[6] + c[7] * y]
    return (pairs[0] + pairs[1] * y2) + (pairs[2] + pairs[3] * y2) * y4 + c[8] * (y4 * y4)


def report(name, coefficients, value, exact, upper, points=4000):
    worst = 0
    for j in range(1, points + 1):
        x = float(upper * j / points)
        worst = max(worst, abs((mp.mpf(value(coefficients, x)) - exact(x)) / exact(x)))
    print(f'{name}: {{{", ".join(repr(c) for c in coefficients)}}}')
    print(f'  largest relative error on (0, {float(upper):.6g}]: {float(worst):.2e}')


def phi(k, y):
    return mp.nsum(lambda n: (-y) ** n / mp.factorial(n + k), [0, mp.inf])


def kappa(y):
    return phi(1, y) / phi(2, y) if y != 0 else mp.mpf(2)


def lam(y):
    return phi(1, y) / (1 - 2 * (1 + y) * phi(3, y)) if y != 0 else mp.mpf(1.5)


LIMIT = mp.mpf('0.4')
report('kappa', chebyshev_fit(kappa, LIMIT, 8), estrin, kappa, LIMIT)
report('lambda', chebyshev_fit(lam, LIMIT, 8), estrin, lam, LIMIT)

QUARTER_PI = mp.pi / 4
sin_over_r = chebyshev_fit(lambda u: mp.sin(mp.sqrt(u)) / mp.sqrt(u) if u != 0 else mp.mpf(1), QUARTER_PI ** 2, 6)
cos_of_root = chebyshev_fit(lambda u: mp.cos(mp.sqrt(u)), QUARTER_PI ** 2, 7)
report('sin', sin_over_r, lambda c, r: r * estrin(c, r * r), mp.sin, QUARTER_PI)
report('cos', cos_of_root, lambda c, r: estrin(c, r * r), mp.cos, QUARTER_PI)
