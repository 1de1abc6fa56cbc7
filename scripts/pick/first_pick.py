#!/usr/bin/env python3
"""Prints the first pick of a PICKS.json (object, pose, score) and pick's time per stage;
exits 1 when the file has no pick. Reads the ranked list `picks` (best first), or
`first_pick` where pick writes one. Usage: first_pick.py PICKS.json
"""
import json
import math
import sys


def first_pick(picks_json):
    first = picks_json.get("first_pick")
    if isinstance(first, dict) and "t_mm" in first:
        return first
    picks = picks_json.get("picks") or []
    return picks[0] if picks else None


def rotation_degrees(r):
    """The angle of the rotation R (row-major) about its axis, in degrees."""
    cosine = max(-1.0, min(1.0, (r[0] + r[4] + r[8] - 1.0) / 2.0))
    return math.degrees(math.acos(cosine))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: first_pick.py PICKS.json")
    with open(sys.argv[1]) as f:
        picks_json = json.load(f)
    pick = first_pick(picks_json)
    if pick is None:
        print(f"{sys.argv[1]}: no pick", file=sys.stderr)
        return 1
    t, r = pick["t_mm"], pick["R"]
    print(f"first pick: object {pick['obj_id']}, pick score {pick.get('pick_score', float('nan')):.3f}, "
          f"at x {t[0]:.1f}, y {t[1]:.1f}, z {t[2]:.1f} mm (left camera), "
          f"turned {rotation_degrees(r):.1f} degrees")
    print("  R (model to camera) = [" + "; ".join(" ".join(f"{v:.3f}" for v in r[i:i + 3]) for i in (0, 3, 6)) + "]")
    stages = picks_json.get("seconds", {})
    print("  seconds: " + ", ".join(f"{name} {value:.2f}" for name, value in stages.items()
                                    if isinstance(value, (int, float))))
    if "seconds_to_first_pick" in picks_json:
        print(f"  seconds to the first pick: {picks_json['seconds_to_first_pick']:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
