import numpy as np, sys
from common import load
from lattice import operators
for n in map(int, sys.argv[1:]):
    A0, A1, _ = load(n)
    K, L = operators(n)
    print(n, 'max|A0 - K|', abs(A0 - K).max(), 'max|-A1 - L|', abs(-A1 - L).max())
