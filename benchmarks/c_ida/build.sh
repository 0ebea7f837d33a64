#!/usr/bin/env bash
# Build seed3_ida and pendulum_ida against the SUNDIALS shared libraries inside the scikit-sundae wheel.
# PYTHON: the interpreter whose scikit-sundae to use (default python3; the benchmarks pass theirs).
set -euo pipefail
cd "$(dirname "$0")"
LIBS=$("${PYTHON:-python3}" -c "import sksundae, os; print(os.path.join(os.path.dirname(os.path.dirname(sksundae.__file__)), 'scikit_sundae.libs'))")
lib() { basename "$(ls "$LIBS"/lib"$1"-*.so.* | head -n 1)"; }
for prog in seed3_ida pendulum_ida; do
  gcc -O2 -std=c99 -D_POSIX_C_SOURCE=199309L -I../../csrc -o "$prog" "$prog".c -L"$LIBS" \
      -l:"$(lib sundials_ida)" -l:"$(lib sundials_nvecserial)" -l:"$(lib sundials_sunmatrixdense)" \
      -l:"$(lib sundials_sunlinsoldense)" -l:"$(lib sundials_core)" -lm -Wl,-rpath,"$LIBS"
  echo "built $(pwd)/$prog"
done
