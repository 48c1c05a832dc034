#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets: fixed pseudo-random byte strings (every byte string decodes
to a case, fuzz_input.h), the same on every run. Usage: make_corpus.py OUT_DIR [count]"""
import os
import random
import sys

out = sys.argv[1]
count = int(sys.argv[2]) if len(sys.argv) > 2 else 48
os.makedirs(out, exist_ok=True)
rng = random.Random(20261201)
for i in range(count):
    # A first byte below 171 makes a prism, above a sheet; keep the radius byte off the extremes.
    data = bytearray(rng.getrandbits(8) for _ in range(160))
    data[0] = (i * 37) % 256
    with open(os.path.join(out, "seed_%03d" % i), "wb") as f:
        f.write(bytes(data))
