#!/usr/bin/env python3
"""Reads a candump log with python-can's reader and writes it back with python-can's writer, so the
C++ test can check both directions against src/bus/candump_log.hpp:

    /usr/bin/python3 tests/bus/python_can_log_reader.py IN.log FRAMES.txt OUT.log

FRAMES.txt gets one line per frame python-can read: TIMESTAMP ID DLC DATA CHANNEL EXTENDED REMOTE
(TIMESTAMP as repr(float), ID and DATA hex, DATA '-' when empty). Exit 77 when python-can is missing.
"""
import sys

try:
    import can
except ImportError:
    print("python-can is not installed for this interpreter: apt-get install python3-can", file=sys.stderr)
    sys.exit(77)


def main(log_in, frames_out, log_out):
    messages = list(can.LogReader(log_in))  # .log selects can.io.CanutilsLogReader
    with open(frames_out, "w", encoding="ascii") as out:
        for m in messages:
            data = bytes(m.data).hex().upper() or "-"
            out.write(f"{m.timestamp!r} {m.arbitration_id:X} {m.dlc} {data} {m.channel} "
                      f"{int(m.is_extended_id)} {int(m.is_remote_frame)}\n")
    with can.CanutilsLogWriter(log_out) as writer:
        for m in messages:
            writer.on_message_received(m)
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
