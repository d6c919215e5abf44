#!/usr/bin/env bash
# Builds the libFuzzer targets with clang in build-fuzz/ and runs them for ${FUZZ_SECONDS:-60}
# seconds in all: half for the CAN protocol's decoder (protocol_decode_fuzzer), half for the
# operator console's message parser (link_operator_message_fuzzer). Exits non-zero when a fuzzer
# finds a crash; the crashing input is kept in build-fuzz/artifacts/ — replay it with the fuzzer
# binary and the file as argument.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${repo}/build-fuzz"
seconds="${FUZZ_SECONDS:-60}"
target=protocol_decode_fuzzer
link_target=link_operator_message_fuzzer
# Half each; the protocol fuzzer gets the odd second, and each at least one.
link_seconds=$(( seconds / 2 > 0 ? seconds / 2 : 1 ))
protocol_seconds=$(( seconds - seconds / 2 > 0 ? seconds - seconds / 2 : 1 ))

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: skipped, clang++ not found"
  exit 0
fi

CC=clang CXX=clang++ cmake -S "${repo}" -B "${build}" -G Ninja \
  -DMARSOKHOD_FUZZ=ON -DMARSOKHOD_BENCHMARKS=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined"
cmake --build "${build}" --target "${target}" "${link_target}" -j "${FUZZ_JOBS:-$(nproc)}"

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

# run_fuzzer NAME BINARY SECONDS CORPUS [libFuzzer options...]
run_fuzzer() {
  local name="$1" binary="$2" time="$3" dir="$4"
  shift 4
  echo "fuzz: running ${name} for ${time} s (corpus ${dir})"
  local status=0
  "${binary}" "${dir}" -max_total_time="${time}" -artifact_prefix="${artifacts}/" \
    -print_final_stats=1 "$@" || status=$?
  if [ "${status}" -ne 0 ]; then
    echo "fuzz: ${name} failed (exit ${status}); crashing inputs are in ${artifacts}/" >&2
    exit "${status}"
  fi
  echo "fuzz: ${name} ran ${time} s without a crash"
}

run_fuzzer "${target}" "${build}/fuzz/protocol/${target}" "${protocol_seconds}" "${corpus}"

# Seeds for the console's messages: one legal message of each type, and a few near misses.
link_corpus="${build}/corpus/${link_target}"
mkdir -p "${link_corpus}"
link_seed() { printf '%s' "$2" >"${link_corpus}/seed-$1"; }
link_seed gamepad '{"type":"gamepad","axes":[0,-1,0.5,1],"buttons":[false,true,false,false,false,false,false,false,false,false,false,false,true,false,false,false,false]}'
link_seed targets '{"type":"targets","v1":2.25,"v2":-1.5,"v4":0,"v6":0.5,"v7":-0.5,"gait":"rolking-extended-base","gait_speed":-1,"calibration_mode":false}'
link_seed configure '{"type":"configure","max_drop_v":1.5,"load_distribution":"v","behaviours":{"power_management":true,"slant_response":false,"contract_on_turn":true,"axle_placement":false},"speed_scale":0.5}'
link_seed stop '{"type":"stop"}'
link_seed clear-faults '{"type":"clear_faults"}'
link_seed take-control '{"type":"take_control"}'
link_seed release-control '{"type":"release_control"}'
link_seed ping '{"type":"ping"}'
link_seed out-of-range '{"type":"gamepad","axes":[0,1.7,0,0],"buttons":[]}'
link_seed duplicate '{"type":"stop","type":"ping"}'
link_seed overflow '{"type":"targets","v1":1e999}'

run_fuzzer "${link_target}" "${build}/fuzz/link/${link_target}" "${link_seconds}" \
  "${link_corpus}" -dict="${repo}/fuzz/link/operator_message.dict" -max_len=4200
