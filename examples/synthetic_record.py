"""Writes data/records/synthetic_10s.AT2: a synthetic ground-acceleration record in the PEER NGA
AT2 format, for trying `voussoir dem --record` without a real record at hand.

It is NOT an earthquake: a sum of sines of 1.1-7.9 Hz (amplitudes 1/(1+k), phases k) under a
trapezoidal envelope (1 s rise, 6 s strong motion, 3 s decay), sampled every 0.01 s for 10 s
and scaled to a peak of 0.1 g, the same recipe as benches/dynamic.rs (which runs 30 s). Real
records come from the PEER NGA-West2 database (Ancheta et al. 2014); voussoir reads both of
its header styles.

    python3 examples/synthetic_record.py
"""

import math
import pathlib

DT = 0.01
N = 1000  # intervals: 1001 samples, 0 to 10 s
FREQS = [1.1, 1.9, 2.7, 3.6, 5.2, 7.9]
PEAK_G = 0.1


def envelope(t: float) -> float:
    return max(0.0, min(t / 1.0, 1.0, (10.0 - t) / 3.0))


def main() -> None:
    raw = []
    for i in range(N + 1):
        t = i * DT
        s = sum(math.sin(2 * math.pi * f * t + k) / (1 + k) for k, f in enumerate(FREQS))
        raw.append(envelope(t) * s)
    peak = max(abs(a) for a in raw)
    accel = [PEAK_G * a / peak for a in raw]
    lines = [
        "SYNTHETIC RECORD (not an earthquake): sum of sines 1.1-7.9 Hz, trapezoidal envelope",
        "voussoir examples/synthetic_record.py, peak 0.1 g, horizontal",
        "ACCELERATION TIME HISTORY IN UNITS OF G",
        f"NPTS= {N + 1:6d}, DT= {DT:8.4f} SEC",
    ]
    for i in range(0, len(accel), 5):
        lines.append("".join(f"{a:15.7E}" for a in accel[i : i + 5]))
    root = pathlib.Path(__file__).resolve().parent.parent
    out = root / "data" / "records" / "synthetic_10s.AT2"
    out.write_text("\n".join(lines) + "\n")
    print(f"wrote {out.relative_to(root)} ({N + 1} samples, dt {DT} s, peak {PEAK_G} g)")


if __name__ == "__main__":
    main()
