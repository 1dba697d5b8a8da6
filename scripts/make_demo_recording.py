#!/usr/bin/env python3
"""Writes assets/recordings/icub_left_arm_demo/: a small synthetic recording in yarpdatadumper's
format, for configs/replay_recording.yaml and the docs (no real robot made it):

  left_arm_state/  /icub/left_arm/state:o at 100 Hz for 8 s, 16 encoder values [deg] (7 arm
                   joints waving, 9 hand joints still), with a 0.5 s dropout at t = 5 s;
  skin_events/     /skinManager/skin_events:o at 50 Hz: the left forearm touched twice
                   (t = 2.0-2.4 s, 6.0-6.3 s) and the right palm once (t = 3.0-3.1 s).

Usage: scripts/make_demo_recording.py [OUT_DIR]   (default: assets/recordings/icub_left_arm_demo)
"""
import math
import os
import sys

T0 = 1700000000.0  # Unix time of the first message [s]


def write_log(folder, port, lines):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "info.log"), "w") as f:
        f.write("Type: Bottle;\n")
        f.write(f"[{T0 - 0.5:.6f}] {port} [connected]\n")
        f.write(f"[{T0 + 8.5:.6f}] {port} [disconnected]\n")
    with open(os.path.join(folder, "data.log"), "w") as f:
        f.write("".join(lines))


def arm_lines():
    lines = []
    seq = 0
    for k in range(800):
        t = k * 0.01
        if 5.0 <= t < 5.5:
            continue  # dropout
        w = 2 * math.pi * 0.25
        arm = [-40 + 12 * math.sin(w * t), 40 + 8 * math.sin(2 * w * t), 10, 60 + 25 * math.sin(w * t),
               20 * math.sin(w * t), -10, 5]
        hand = [20, 20, 10, 10, 10, 10, 10, 10, 10]
        lines.append(f"{seq} {T0 + t:.6f} " + " ".join(f"{v:.6f}" for v in arm + hand) + "\n")
        seq += 1
    return lines


def contact(cid, body, link, part, taxels, pressure):
    return (f"(({cid} {body} {link} {part}) (0.0 0.0 0.0) (0.0 0.0 0.0) (0.0 0.0 0.0) "
            f"(0.0 0.0 0.0) (0.0 0.0 0.0) ({' '.join(map(str, taxels))}) {pressure:.6f})")


def skin_lines():
    lines = []
    cid = 1
    for k in range(400):
        t = k * 0.02
        contacts = []
        if 2.0 <= t < 2.4 or 6.0 <= t < 6.3:
            contacts.append(contact(cid, 3, 4, 2, [3, 4, 5, 6, 7] if t < 5 else [15, 16, 17], 40.0))
            cid += 1
        if 3.0 <= t < 3.1:
            contacts.append(contact(cid, 4, 6, 4, [101, 102, 103], 35.0))
            cid += 1
        lines.append(f"{k} {T0 + t:.6f} {' '.join(contacts)}\n")
    return lines


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "assets", "recordings", "icub_left_arm_demo")
    write_log(os.path.join(out, "left_arm_state"), "/icub/left_arm/state:o", arm_lines())
    write_log(os.path.join(out, "skin_events"), "/skinManager/skin_events:o", skin_lines())


if __name__ == "__main__":
    main()
