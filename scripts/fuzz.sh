#!/usr/bin/env bash
# Builds the libFuzzer targets with clang in build-fuzz/ and runs the five of them for
# ${FUZZ_SECONDS:-150} seconds in all, split evenly, each at least 20 s: the CAN protocol's decoder
# (protocol_decode_fuzzer), the operator console's message parser (link_operator_message_fuzzer),
# the socketcand protocol (bus_socketcand_fuzzer), the candump log parser (bus_candump_fuzzer)
# and the scenario loader (runner_scenario_fuzzer). Exits non-zero when a fuzzer finds a crash;
# the crashing input is kept in build-fuzz/artifacts/ — replay it with the fuzzer binary and the
# file as argument.
set -euo pipefail
# The fuzz build is unoptimised by default (FUZZ_OPT=-O0): under ASan and UBSan it compiles in
# about a third of the time of -O1 (the Beast sessions: 15 s against 41 s), which CI's 30 minutes
# need; the fuzzers then run fewer inputs a second. For a long run, FUZZ_OPT=-O1.

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${repo}/build-fuzz"
seconds="${FUZZ_SECONDS:-150}"
target=protocol_decode_fuzzer
link_target=link_operator_message_fuzzer
socketcand_target=bus_socketcand_fuzzer
candump_target=bus_candump_fuzzer
scenario_target=runner_scenario_fuzzer
# An even share each, at least 20 s: less finds little beyond the seeds.
share=$(( seconds / 5 ))
share=$(( share < 20 ? 20 : share ))
protocol_seconds=${share}
link_seconds=${share}

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: skipped, clang++ not found"
  exit 0
fi

CC=clang CXX=clang++ cmake -S "${repo}" -B "${build}" -G Ninja \
  -DMARSOKHOD_FUZZ=ON -DMARSOKHOD_BENCHMARKS=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${FUZZ_OPT:--O0} -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined"
cmake --build "${build}" --target "${target}" "${link_target}" "${socketcand_target}" \
  "${candump_target}" "${scenario_target}" -j "${FUZZ_JOBS:-$(nproc)}"

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
link_seed gamepad '{"type":"gamepad","seq":1,"sent_ms":1718040000123.5,"axes":[0,-1,0.5,1],"buttons":[false,true,false,false,false,false,false,false,false,false,false,false,true,false,false,false,false]}'
link_seed targets '{"type":"targets","seq":9007199254740991,"sent_ms":0,"v1":2.25,"v2":-1.5,"v4":0,"v6":0.5,"v7":-0.5,"gait":"rolking-extended-base","gait_speed":-1,"calibration_mode":false}'
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

# The socketcand protocol: byte 0 is where the stream is cut in two, then the stream.
sc_corpus="${build}/corpus/${socketcand_target}"
mkdir -p "${sc_corpus}"
sc_seed() { printf '%b' "$2" >"${sc_corpus}/seed-$1"; }
sc_seed handshake '\x05< open can0 >< rawmode >< send 180 3 3 1 2c >'
sc_seed frame '\x00< frame 188 1436509052.249713 12340001000202FB >< echo >'
sc_seed extended '\x09< send 1AAAAAAA 0 >< error it\x1b[2J >'
sc_seed browser-post '\x10POST / HTTP/1.1\r\nHost: 127.0.0.1:29536\r\n\r\n< open can0 >'
sc_seed broken '\x03< send 180 1 01< echo >junk< >'
run_fuzzer "${socketcand_target}" "${build}/fuzz/bus/${socketcand_target}" "${share}" \
  "${sc_corpus}" -max_len=1024

# candump log lines.
cd_corpus="${build}/corpus/${candump_target}"
mkdir -p "${cd_corpus}"
cd_seed() { printf '%s' "$2" >"${cd_corpus}/seed-$1"; }
cd_seed frame '(1436509052.249713) can0 188#12340001000202FB'
cd_seed python-can '(1.000000) vcan0 180#03012C R'
cd_seed extended '(0.5) can1 1AAAAAAA#'
cd_seed remote '(2.25) can0 183#R'
cd_seed nan '(nan) can0 180#00'
run_fuzzer "${candump_target}" "${build}/fuzz/bus/${candump_target}" "${share}" \
  "${cd_corpus}" -max_len=256

# Scenario files: two of the shipped ones and a few near misses.
sn_corpus="${build}/corpus/${scenario_target}"
mkdir -p "${sn_corpus}"
cp "${repo}/scenarios/link-loss.toml" "${repo}/scenarios/straight-and-spin.toml" "${sn_corpus}/"
sn_seed() { printf '%b' "$2" >"${sn_corpus}/seed-$1"; }
sn_seed faults 'duration_s = 5.0\n[[fault]]\nt = 1.0\nframe_loss = 0.1\nlost_pulses = { motor = 2, fraction = 0.3 }\n'
sn_seed nan '[[input]]\nt = nan\ntargets = { v1 = inf }\n'
sn_seed phases '[[phase]]\nname = "a"\nfrom_s = 0.0\nto_s = 1.0\n[[check]]\nmetric = "a.distance_m"\nmin = 0.1\n'
run_fuzzer "${scenario_target}" "${build}/fuzz/runner/${scenario_target}" "${share}" \
  "${sn_corpus}" -max_len=4096
