#!/usr/bin/env bash
# Build with AddressSanitizer + UndefinedBehaviorSanitizer in build-sanitize/
# and run the C++ tests (ctest: unit tests, example 1 serial and on 2 ranks).
# Leak checking is off: MPI and PETSc keep allocations until exit by design.
# ctest uses no Python bindings, and the ffcx kernels are generated code
# (CMakeLists.txt): neither is built instrumented here.
set -euo pipefail
cd "$(dirname "$0")/.."
# the packages only: build/ is the test leg's (CI runs this leg beside it)
bash scripts/setup.sh --packages-only >/dev/null
cmake -B build-sanitize -S . -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPIEZO_SANITIZE=ON -DPIEZO_PYTHON=OFF \
  -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build build-sanitize -j"$(nproc)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
cd build-sanitize && ctest --output-on-failure
