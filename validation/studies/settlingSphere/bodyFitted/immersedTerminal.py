#!/usr/bin/env python3
"""The immersed boundary's terminal velocity in the duct, from results.txt.

For each fluid, bodyFitted/Allrun -immersed measured the immersed drag at
the measured velocity u_m as a ratio r of the body-fitted drag there, and
the body-fitted secant gave the terminal velocity u_t (drag = weight) and
the drag at u_m (F_m/W). Between u_t and u_m the body-fitted drag follows
F ~ u^n with n = ln(F_m/W)/ln(u_m/u_t). The immersed drag is r times it, so
the immersed sphere's drag equals its weight at u_t r^(-1/n).

    immersedTerminal.py [results.txt]

Prints the table and exits 1 when any fluid is off by more than 2%.
"""
import math
import re
import sys

path = sys.argv[1] if len(sys.argv) > 1 else __file__.rsplit('/', 1)[0] + '/results.txt'
bf, ib = {}, {}
for line in open(path):
    m = re.match(r'(E\d) level \d.*terminal velocity ([\d.eE+-]+) m/s.*measured ([\d.]+)\), '
                 r'drag at the measured velocity ([\d.]+) x weight', line)
    if m:
        bf[m.group(1)] = tuple(float(m.group(i)) for i in (2, 3, 4))
    m = re.match(r'(E\d) immersed .*: ([+-][\d.]+)%', line)
    if m:
        ib[m.group(1)] = 1 + float(m.group(2))/100
if not bf or set(bf) != set(ib):
    sys.exit('%s: no complete body-fitted and immersed rows' % path)
print('fluid  u_t body-fitted [m/s]  exponent n  immersed drag ratio  u_t immersed [m/s]  difference')
worst = 0
for f in sorted(bf):
    ut, um, fm = bf[f]
    n = math.log(fm)/math.log(um/ut)
    ui = ut*ib[f]**(-1/n)
    d = ui/ut - 1
    worst = max(worst, abs(d))
    print('%-5s  %20.5f  %10.3f  %19.4f  %18.5f  %+9.2f%%' % (f, ut, n, ib[f], ui, 100*d))
# 2%: issue 18's target for the immersed sphere against the body-fitted
# one; the body-fitted drag moved by about 0.5% from level 3 to 4
# (README), so the reference's own error is a quarter of the band
sys.exit(0 if worst <= 0.02 else 1)
