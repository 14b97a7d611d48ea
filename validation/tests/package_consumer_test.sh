#!/usr/bin/env bash
# Installs swell from its build tree into a scratch prefix, then configures, builds and runs a
# separate project that does find_package(swell). Arguments: <swell build dir> <consumer source>.
set -euo pipefail
build="$1" consumer="$2"
scratch="$build/package-consumer-test"
rm -rf "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
cmake -S "$consumer" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" \
      -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/consumer"
