#!/usr/bin/env python3
"""Writes a small synthetic studio environment map, cli/results/balls/studio.hdr (Radiance RGBE,
equirectangular, 128 x 64, flat scanlines): a dim blue-grey sky gradient, a darker warm floor, a
large softbox up and to the left of the camera, a strip light on the right and a warm rim light
behind the ball. Used by tools/scripts/preview_balls.sh for the `--env` balls in docs/colour.md.
Standard library only; the RGBE encoding is Ward's (Graphics Gems II, "Real pixels", 1991)."""
import math
import os

W, H = 128, 64


def radiance(u, v):
    """Linear RGB radiance at texture coordinates u (0..1, 0.5 = straight ahead of the camera,
    behind the ball) and v (0 = up, 1 = down)."""
    if v > 0.5:  # floor
        return (0.05, 0.045, 0.04)
    t = v / 0.5  # 0 at the zenith, 1 at the horizon
    sky = (0.10 + 0.06 * t, 0.12 + 0.06 * t, 0.16 + 0.04 * t)
    # Softbox: behind the camera (u near 0/1) and to the viewer's left (u < 0.5 is left of the camera's back).
    du = min(abs(u - 0.12), 1 - abs(u - 0.12))
    if du < 0.07 and 0.18 < v < 0.34:
        return (6.0, 6.0, 5.8)
    # Strip light on the right.
    if abs(u - 0.78) < 0.015 and 0.2 < v < 0.46:
        return (3.0, 3.2, 3.6)
    # Warm rim light behind the ball, above it.
    if abs(u - 0.5) < 0.04 and 0.22 < v < 0.3:
        return (4.0, 2.6, 1.4)
    return sky


def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return bytes((0, 0, 0, 0))
    mant, exp = math.frexp(m)
    scale = mant * 256.0 / m
    return bytes((int(r * scale), int(g * scale), int(b * scale), exp + 128))


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    path = os.path.join(root, "cli", "results", "balls", "studio.hdr")
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {H} +X {W}\n".encode())
        for y in range(H):
            for x in range(W):
                f.write(rgbe(*radiance((x + 0.5) / W, (y + 0.5) / H)))
    print(f"wrote {os.path.normpath(path)} ({W} x {H})")


if __name__ == "__main__":
    main()
