#!/bin/sh
# Installs this build into a fresh prefix, then builds and runs the out-of-tree testbench of
# examples/testbench against it through find_package(endatsim): headers, libraries and the
# CMake package must be complete, and the testbench (its own master, endatsim's encoder model
# and checker) must pass.
# usage: install_test.sh BUILD_DIR SOURCE_DIR WORK_DIR CXX_FLAGS check|skip (the check for build paths)
set -eu
build=$1 source=$2 work=$3 flags=$4 paths=${5:-check}
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
for f in include/endatsim/scenarios/scenarios.hpp include/endatsim/checker/checker.hpp lib/cmake/endatsim/endatsimConfig.cmake \
         share/endatsim/schema/scenario.schema.json share/endatsim/sigrok/endat/pd.py bin/endatsim bin/endatsim-vcdlint; do
  [ -e "$work/prefix/$f" ] || { echo "FAIL: $f was not installed" >&2; exit 1; }
done
"$work/prefix/bin/endatsim" --version
# Every scenario folder is installed, and the installed program finds the bundled profiles in its
# own prefix: no path of the source or build tree is compiled into it.
for folder in bundled field safety sweeps; do
  [ -n "$(ls "$work/prefix/share/endatsim/scenarios/$folder"/*.json)" ] || { echo "FAIL: scenarios/$folder was not installed" >&2; exit 1; }
done
# (Debug information names the sources by design: the programs are checked without it.)
if [ "$paths" = check ]; then
  for program in endatsim endatsim-vcdlint; do
    objcopy --strip-debug "$work/prefix/bin/$program" "$work/$program.stripped"
    if grep -q -F -e "$source" -e "$build" "$work/$program.stripped"; then
      echo "FAIL: the installed $program holds a path of the source or build tree" >&2; exit 1
    fi
  done
fi
( cd "$work" && env -u ENDATSIM_PROFILES "$work/prefix/bin/endatsim" run --quiet \
    "$work/prefix/share/endatsim/scenarios/bundled/datum_shift_linear_3_6_2.json" ) \
  || { echo "FAIL: the installed endatsim does not run a scenario with a bundled profile" >&2; exit 1; }
# The project's warning flags stay its own: nothing exported asks a user's build for -Werror.
if grep -r -q -e "-Werror" "$work/prefix/lib/cmake/endatsim"; then
  echo "FAIL: the installed CMake package exports -Werror" >&2; exit 1
fi
# The EnDat decoder for sigrok loads from where it was installed.
SIGROKDECODE_DIR="$work/prefix/share/endatsim/sigrok" sigrok-cli -L | grep -q "^ *endat " \
  || { echo "FAIL: sigrok-cli does not load the installed EnDat decoder" >&2; exit 1; }
cmake -S "$source/examples/testbench" -B "$work/tb" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_FLAGS="$flags" >"$work/configure.log" \
  || { cat "$work/configure.log" >&2; exit 1; }
cmake --build "$work/tb" >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; exit 1; }
"$work/tb/testbench"
# The co-simulation bridge is installed beside the libraries, and a Verilated master builds
# against the installed package (examples/hdl/verilator) and passes its bench.
# (Sanitized builds leave the bridge out: a simulator that is not instrumented cannot load it.)
if [ -e "$build/cosim/vpi/endatsim_vpi.vpi" ]; then
  [ -e "$work/prefix/lib/endatsim/endatsim_vpi.vpi" ] || { echo "FAIL: the VPI bridge was not installed" >&2; exit 1; }
fi
if command -v verilator >/dev/null; then
  cmake -S "$source/examples/hdl/verilator" -B "$work/vl" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_FLAGS="$flags" \
    >"$work/vl-configure.log" || { cat "$work/vl-configure.log" >&2; exit 1; }
  cmake --build "$work/vl" -j 2 >"$work/vl-build.log" 2>&1 || { cat "$work/vl-build.log" >&2; exit 1; }
  "$work/vl/endat_master_verilated" "$source/examples/hdl/bench_8mhz_50m.json"
  # A bench with a bundled profile: the program, built against a package installed elsewhere than
  # the prefix its libraries were built for, finds that package's profiles.
  sed 's/"encoder": {/"encoder": { "profile": "rotary_singleturn_25bit",/' "$source/examples/hdl/bench_8mhz_50m.json" \
    > "$work/profile_bench.json"
  ( cd "$work" && env -u ENDATSIM_PROFILES "$work/vl/endat_master_verilated" "$work/profile_bench.json" ) \
    || { echo "FAIL: a Verilated master built against the package does not find its bundled profiles" >&2; exit 1; }
fi
