#!/usr/bin/env bash
# Builds the libFuzzer target of the CAN protocol with clang in build-fuzz/ and runs it for
# ${FUZZ_SECONDS:-60} seconds. Exits non-zero when the fuzzer finds a crash; the crashing input
# is kept in build-fuzz/artifacts/ — replay it with the fuzzer binary and the file as argument.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${repo}/build-fuzz"
seconds="${FUZZ_SECONDS:-60}"
target=protocol_decode_fuzzer

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: skipped, clang++ not found"
  exit 0
fi

CC=clang CXX=clang++ cmake -S "${repo}" -B "${build}" -G Ninja \
  -DMARSOKHOD_FUZZ=ON -DMARSOKHOD_BENCHMARKS=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined"
cmake --build "${build}" --target "${target}" -j "${FUZZ_JOBS:-$(nproc)}"

# Seeds, one legal frame each: 2 bytes id (big-endian), 1 byte DLC, the data.
corpus="${build}/corpus/${target}"
artifacts="${build}/artifacts"
mkdir -p "${corpus}" "${artifacts}"
seed() { printf '%b' "$2" >"${corpus}/seed-$1"; }
seed control-request '\x01\x80\x03\x03\x01\x2c'                           # µ3 drv eim pwm 300
seed control-response '\x02\x88\x08\x12\x34\x9c\x40\x02\x01\x9a\xbc'     # µ5
seed configuration-request '\x03\x10\x05\x01\xff\x00\x00\x01'            # µ6 icr 511 con 1
seed configuration-response '\x00\x18\x02\xff\xff'                       # µ0 tim 65535
seed measurement-request '\x04\x00\x08\xb2\x34\x2e\x30\x56\x20\x6f\x6b'  # "24.0V ok", led0
seed measurement-response '\x04\x08\x08\x7e\x45\x3e\x5e\x83\xf2\x7c\xe0' # TYP readings
seed dead-man-request '\x04\x10\x01\x04'                                 # dog 4
seed dead-man-response '\x04\x18\x00'

echo "fuzz: running ${target} for ${seconds} s (corpus ${corpus})"
status=0
"${build}/fuzz/protocol/${target}" "${corpus}" \
  -max_total_time="${seconds}" -artifact_prefix="${artifacts}/" -print_final_stats=1 || status=$?
if [ "${status}" -ne 0 ]; then
  echo "fuzz: ${target} failed (exit ${status}); crashing inputs are in ${artifacts}/" >&2
  exit "${status}"
fi
echo "fuzz: ${target} ran ${seconds} s without a crash"
