#!/bin/bash
# Variants of the preconditioned LOBPCG (results_batch1.txt)
P="nice /usr/bin/python3 run_lobpcg.py"
$P --n 32 64 128 256 --prec dst --b 4
$P --n 32 64 128 256 --prec dst --b 4 --random
$P --n 32 64 128 256 --prec dst --b 1
$P --n 32 64 128 256 --prec dst --b 2
$P --n 32 64 128 256 --prec dst --b 8
$P --n 32 64 128 --prec dst --b 4 --margin 0.02
$P --n 32 64 128 --prec dst --b 4 --margin 0.3
$P --n 32 64 128 --prec dst --b 4 --margin 1.0
$P --n 32 64 128 --prec dst --b 4 --pad 1
$P --n 32 64 128 --prec dst --b 4 --pad 2
$P --n 32 64 128 --prec fft --b 4 --margin 0.3 --maxit 2000
$P --n 32 64 128 --prec fft --b 4 --pad 4 --margin 0.3 --maxit 2000
$P --n 32 64 128 --prec dstK --b 4 --maxit 2000
$P --n 32 64 --prec fftK --b 4 --maxit 2000
$P --n 32 64 --prec none --b 4 --maxit 2000
