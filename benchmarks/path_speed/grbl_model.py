# SPDX-License-Identifier: MIT
"""A reference model of grbl's look-ahead planner, written from its documented formulas (not its code).

Blocks are straight moves. For each block: the unit direction u, the length L, the nominal speed
(the feed, limited by every axis's maximum rate: v <= vmax_axis / |u_axis|) and the acceleration
(limited by every axis: a <= amax_axis / |u_axis|). The largest entry speed of a block is grbl's
junction deviation:

    v_j^2 = a * delta * sin(phi/2) / (1 - sin(phi/2)),

phi the angle between the reversed incoming direction and the outgoing one (180 degrees straight
on), capped by both blocks' nominal speeds. With a planner buffer of N blocks, block i's exit speed
comes from a backward pass over the next blocks in the buffer (i+1 .. i+N-1), the last of which
must end at rest; N = None is an unbounded buffer. Each block then runs a trapezoid (constant
acceleration, no jerk limit) from its entry to its exit speed, cruising at its nominal speed.
The job time is the sum of the block times.
"""
import math


def _sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def _norm(a):
    return math.sqrt(sum(x * x for x in a))


class Block:
    """One straight move of a polyline."""

    def __init__(self, start, end, feed, axes_vmax, axes_amax, a_max):
        d = _sub(end, start)
        self.length = _norm(d)
        self.unit = tuple(x / self.length for x in d) if self.length > 0 else (0.0,) * len(d)
        v = feed
        a = a_max
        for component, vmax, amax in zip(self.unit, axes_vmax, axes_amax):
            c = abs(component)
            if c > 0:
                v = min(v, vmax / c)
                a = min(a, amax / c)
        self.nominal = v
        self.acceleration = a


def junction_speed(previous, current, deviation):
    """grbl's junction speed between two blocks (mm/s)."""
    cos_theta = sum(p * c for p, c in zip(previous.unit, current.unit))  # deflection: 1 straight on
    sin_half_phi = math.sqrt(max(0.0, (1 + cos_theta) / 2))  # phi = 180 - deflection
    cap = min(previous.nominal, current.nominal)
    if sin_half_phi >= 1.0 - 1e-12:
        return cap
    if sin_half_phi <= 0.0:
        return 0.0
    a = min(previous.acceleration, current.acceleration)
    return min(cap, math.sqrt(a * deviation * sin_half_phi / (1 - sin_half_phi)))


def trapezoid_time(length, v0, v1, cruise, a):
    """Time to travel `length` from v0 to v1 at acceleration a, cruising at most at `cruise`."""
    peak_sq = (2 * a * length + v0 * v0 + v1 * v1) / 2
    peak = math.sqrt(max(peak_sq, 0.0))
    if peak > cruise:
        accelerate = (cruise * cruise - v0 * v0) / (2 * a)
        decelerate = (cruise * cruise - v1 * v1) / (2 * a)
        return (cruise - v0) / a + (cruise - v1) / a + max(0.0, length - accelerate - decelerate) / cruise
    return max(0.0, peak - v0) / a + max(0.0, peak - v1) / a


def job_time(blocks, deviation, buffer_blocks=16):
    """The job time of `blocks` (Block list) with junction deviation `deviation`, mm."""
    blocks = [b for b in blocks if b.length > 0]
    n = len(blocks)
    if n == 0:
        return 0.0
    junction = [0.0] * (n + 1)  # junction[i]: largest speed at the start of block i
    for i in range(1, n):
        junction[i] = junction_speed(blocks[i - 1], blocks[i], deviation)
    total = 0.0
    entry = 0.0
    for i, block in enumerate(blocks):
        last = n - 1 if buffer_blocks is None else min(n - 1, i + buffer_blocks - 1)
        v = 0.0  # the buffer's last block ends at rest
        for k in range(last, i, -1):
            v = min(junction[k], math.sqrt(v * v + 2 * blocks[k].acceleration * blocks[k].length))
        exit_speed = min(v, math.sqrt(entry * entry + 2 * block.acceleration * block.length))
        total += trapezoid_time(block.length, entry, exit_speed, block.nominal, block.acceleration)
        entry = exit_speed
    return total


def blocks_from_moves(moves, machine):
    """Blocks of [(start, end, kind)] moves ('rapid' or 'feed', feed in mm/s in the tuple's 4th place)."""
    axes = machine.get("axes", {})
    names = ("x", "y", "z")
    vmax = [axes.get(a, {}).get("v_max", 0) or machine["v_max"] for a in names]
    amax = [axes.get(a, {}).get("a_max", 0) or machine["a_max"] for a in names]
    rapid = machine.get("rapid", machine["v_max"])
    out = []
    for start, end, kind, feed in moves:
        speed = min(rapid if kind == "rapid" else feed, machine["v_max"])
        out.append(Block(start, end, speed, vmax, amax, machine["a_max"]))
    return out
