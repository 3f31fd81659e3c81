#!/usr/bin/env python3
"""Writes configs/input/demo-session.txt: a recorded-input session for the demo.

A desk observer (head around the desktop config's home, 1.1 m) sways gently while the
wand: flies 0.5 m forward, turns the CAVE 20 degrees left by dragging, switches to the
lighting layout and sweeps the spotlight across the room like a flashlight, tints it
(saturation, then hue), doubles its intensity, then switches to the renderer settings
(one more propagation step, more absorption, next lambda preset). 150 polls at 30 Hz.
The format is the one master/input/input_playback.h documents; this script only writes it."""
import math
import sys

DT = 1.0 / 30.0
POLLS = 150
L, M, R, C, AUX = 1, 2, 4, 8, 16


def rot_y_x(yaw, pitch):
    """Column-major Ry(yaw) * Rx(pitch)."""
    cy, sy, cp, sp = math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch)
    return [cy, 0.0, -sy, sy * sp, cp, cy * sp, sy * cp, -sp, cy * cp]


def fmt(v):
    return "%.9g" % v


def main(path):
    out = ["cavelight-input 1",
           "# demo session written by scripts/make_demo_session.py; format in docs/input.md"]
    prev_wand, prev_buttons, prev_axes = None, 0, (0.0, 0.0)
    for k in range(POLLS):
        t = k * DT
        head = (0.1 * math.sin(2 * math.pi * t / 3), 1.1 + 0.02 * math.sin(2 * math.pi * t / 2),
                0.05 * math.sin(2 * math.pi * t / 4))
        out.append("head %s %s %s" % (fmt(t), " ".join(fmt(v) for v in head),
                                      " ".join(fmt(v) for v in rot_y_x(-0.1 * math.sin(2 * math.pi * t / 3), 0))))
        buttons, yaw, pitch, axes = 0, 0.0, 0.0, (0.0, 0.0)
        if 15 <= k <= 26:
            buttons |= C                                   # fly forward
        if 31 <= k <= 50:
            buttons |= L                                   # drag: turn 20 degrees left
            yaw = 0.35 * (k - 31) / 19
        if k == 55 or k == 125:
            buttons |= R                                   # next layout
        if 56 <= k <= 119:
            buttons |= C                                   # flashlight
            yaw = 0.6 * math.cos(math.pi * (k - 56) / 63)
            pitch = -0.25
        if 70 <= k <= 89:
            axes = (1.0, 0.0)                              # saturation up
        if 90 <= k <= 109:
            axes = (0.0, 1.0)                              # hue
        if k in (112, 116, 128):
            buttons |= M                                   # intensity up, then one more step
        if 130 <= k <= 139:
            axes = (1.0, 0.0)                              # absorption up
        if k == 142:
            buttons |= AUX                                 # next lambda preset
        wand_pos = (head[0] + 0.15, head[1] - 0.2, head[2] - 0.35)
        wand = [*wand_pos, *rot_y_x(yaw, pitch)]
        if wand != prev_wand:
            out.append("wand %s %s" % (fmt(t), " ".join(fmt(v) for v in wand)))
            prev_wand = wand
        pressed = buttons & ~prev_buttons
        if buttons != prev_buttons or pressed:
            out.append("buttons %s %x %x" % (fmt(t), buttons, pressed))
            prev_buttons = buttons
        if axes != prev_axes:
            out.append("axes %s %s %s 0 0" % (fmt(t), fmt(axes[0]), fmt(axes[1])))
            prev_axes = axes
        out.append("poll %s %s" % (fmt(t), fmt(DT if k else 0.0)))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "configs/input/demo-session.txt")
