#!/bin/bash
P="nice /usr/bin/python3 run_lobpcg.py"
$P --n 256 --prec fft --b 4 --margin 0.3 --maxit 3000
$P --n 256 --prec dstK --b 4 --maxit 3000
$P --n 512 --prec dst --b 4 --margin 0.02 --random
