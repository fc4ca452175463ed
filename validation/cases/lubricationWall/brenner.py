#!/usr/bin/env python3
"""Brenner's (1961) exact drag of a sphere moving normal to a plane wall in
Stokes flow: F = 6 pi mu a U lambda,

  lambda = 4/3 sinh(alpha) sum_{n>=1} n(n+1)/((2n-1)(2n+3))
           [ (2 sinh((2n+1) alpha) + (2n+1) sinh(2 alpha))
             / (4 sinh^2((n+1/2) alpha) - (2n+1)^2 sinh^2(alpha)) - 1 ],

alpha = arccosh(z/a), z the centre's distance from the wall. Near the wall
lambda -> a/h (h = z - a the gap). Run alone it prints a table.
"""
import math


def brenner(gap, a):
    """lambda of Brenner's series at gap h = gap for a sphere of radius a"""
    alpha = math.acosh(1 + gap/a)
    s = 0.0
    for n in range(1, 100000):
        k = 2*n + 1
        num = 2*math.sinh(k*alpha) + k*math.sinh(2*alpha)
        den = 4*math.sinh((n + 0.5)*alpha)**2 - k*k*math.sinh(alpha)**2
        term = n*(n + 1)/((2*n - 1)*(2*n + 3))*(num/den - 1)
        s += term
        if abs(term) < 1e-12*abs(s) and n > 5:
            break
    return 4.0/3.0*math.sinh(alpha)*s


if __name__ == "__main__":
    for g in (10, 1, 0.1, 0.05, 0.01, 0.001):
        lam = brenner(g, 1.0)
        print("h/a %8.4f  lambda %10.5f  a/h %10.5f  ratio %.4f" % (g, lam, 1/g, lam*g))
