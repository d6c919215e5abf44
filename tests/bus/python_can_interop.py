#!/usr/bin/env python3
"""Talks to a socketcand server through python-can's `socketcand` interface, a peer we did not
write: sends each request frame and waits for the matching response frame.

    /usr/bin/python3 tests/bus/python_can_interop.py --port N \
        [--traffic 400#C1 COUNT] [--exchange 180#03012C 188#1234010...] [--exchange 410#05 418#]

Frames are written as in candump logs (ID#DATA, hex). Exit 0 when every response arrived with the
expected bytes in time, 1 otherwise, 77 when python-can is missing (the test then skips).
"""
import argparse
import sys
import time

try:
    import can
except ImportError:
    print("python-can is not installed for this interpreter: apt-get install python3-can", file=sys.stderr)
    sys.exit(77)


def frame(text):
    """'180#03012C' -> (0x180, b'\\x03\\x01\\x2c')"""
    identifier, _, data = text.partition("#")
    return int(identifier, 16), bytes.fromhex(data)


def await_response(bus, expected_id, expected_data, timeout_s):
    deadline = time.monotonic() + timeout_s
    while (remaining := deadline - time.monotonic()) > 0:
        message = bus.recv(timeout=remaining)
        if message is None or message.arbitration_id != expected_id:
            continue
        if bytes(message.data) != expected_data or message.dlc != len(expected_data):
            print(f"response 0x{expected_id:X}: got {bytes(message.data).hex()} (DLC {message.dlc}), "
                  f"expected {expected_data.hex()}", file=sys.stderr)
            return False
        return True
    print(f"no response 0x{expected_id:X} within {timeout_s} s", file=sys.stderr)
    return False


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, required=True)
    parser.add_argument("--channel", default="can0")
    parser.add_argument("--timeout", type=float, default=5.0, help="seconds to wait for each response")
    # The µ3 control exchange of the end-to-end issue; the C++ test passes frames built by the codec.
    parser.add_argument("--exchange", nargs=2, action="append", metavar=("REQUEST", "RESPONSE"))
    parser.add_argument("--traffic", nargs=2, metavar=("FRAME", "COUNT"),
                        help="first receive COUNT copies of FRAME that the server sends unasked")
    args = parser.parse_args()
    exchanges = args.exchange or [["180#03012C", "188#123401020A0B81FF"]]

    bus = can.Bus(interface="socketcand", host=args.host, port=args.port, channel=args.channel)
    try:
        if args.traffic:
            for _ in range(int(args.traffic[1])):
                if not await_response(bus, *frame(args.traffic[0]), args.timeout):
                    return 1
        for request, response in exchanges:
            request_id, request_data = frame(request)
            bus.send(can.Message(arbitration_id=request_id, data=request_data, is_extended_id=False))
            if not await_response(bus, *frame(response), args.timeout):
                return 1
        print(f"python-can {can.__version__}: {len(exchanges)} exchanges over socketcand OK")
        return 0
    finally:
        bus.shutdown()


if __name__ == "__main__":
    sys.exit(main())
