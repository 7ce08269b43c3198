#!/bin/bash
P="nice /usr/bin/python3 run_lobpcg.py"
$P --n 32 64 --prec exactK --b 4 --maxit 3000
$P --n 32 64 --prec exactK --b 1 --maxit 3000 --random
$P --n 32 64 128 256 --prec dst --b 4 --margin 0.02 --random
$P --n 256 --prec dst --b 4 --margin 0.02
J="nice /usr/bin/python3 run_jd.py"
$J --n 32 64 128 256 --m 5 --nexp 4
$J --n 32 64 128 256 --m 10 --nexp 4
$J --n 32 64 128 256 --m 20 --nexp 4
$J --n 32 64 128 256 --m 10 --nexp 4 --margin 0.02
