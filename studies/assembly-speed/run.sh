#!/usr/bin/env bash
# Assembly speed of W + G on 2D square lattices (Google Benchmark), with the memory-copy bandwidth of the
# same run; twice: default malloc, and malloc backed by transparent huge pages (glibc.malloc.hugetlb=1),
# because on this virtual machine first-touch page faults dominate fresh allocations.
set -euo pipefail
bin=$1
out=$2
filter=${ASSEMBLY_FILTER:-.}
# Wall, user and kernel seconds of each run (last line of time_<mode>.txt): kernel time is page-fault handling.
TIMEFORMAT='%R %U %S'
{ time "$bin/assembly_benchmark" --benchmark_filter="$filter" --benchmark_format=json \
  >"$out/benchmark_default.json"; } 2>"$out/time_default.txt"
{ time GLIBC_TUNABLES=glibc.malloc.hugetlb=1 "$bin/assembly_benchmark" --benchmark_filter="$filter" \
  --benchmark_format=json >"$out/benchmark_hugepages.json"; } 2>"$out/time_hugepages.txt"
"${PYTHON:-/usr/bin/python3}" benchmarks/relative_executable.py "$out/benchmark_default.json" \
  "$out/benchmark_hugepages.json"
"${PYTHON:-/usr/bin/python3}" "$(dirname "$0")/report.py" "$out"
