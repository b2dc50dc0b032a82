#!/usr/bin/env python3
"""Error per sample, Tessera against Mitsuba 3, on the same scene file: relMSE at a fixed sample
count over several seeds, against a converged reference, with no clock involved.

Usage:
    scripts/error_per_sample.py SCENE.xml --reference REF.exr [--spp 16] [--seeds 24]
        [--tessera target/release/tessera] [--variant scalar_rgb] [-D name=value ...]
        [--make-reference SPP]

relMSE = mean((a - b)^2 / (b^2 + 0.01)) over every pixel and channel, computed by
`scripts/mitsuba_bench.py`'s `errors`, as `tessera bench` computes it. Each renderer renders the
scene --seeds times at --spp samples per pixel (Tessera with seeds 1..N, Mitsuba with 0..N-1);
the script prints per renderer the mean relMSE, its standard error, and the median (the mean
of a scene with small bright lights is dominated by rare outliers, the median is not).

With --make-reference SPP, the reference is first rendered by Mitsuba (passes of 512 spp with
seeds 1000, 1001, ..., averaged in float64) and written to --reference.
"""
import argparse
import os
import subprocess
import tempfile

import numpy as np
import mitsuba as mi

from mitsuba_bench import errors, rgb


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('scene')
    ap.add_argument('--reference', required=True)
    ap.add_argument('--spp', type=int, default=16)
    ap.add_argument('--seeds', type=int, default=24)
    ap.add_argument('--tessera', default='target/release/tessera')
    ap.add_argument('--variant', default='scalar_rgb')
    ap.add_argument('--make-reference', type=int, default=0, metavar='SPP')
    ap.add_argument('-D', action='append', default=[], metavar='name=value')
    a = ap.parse_args()
    mi.set_variant(a.variant)
    defs = dict(d.split('=', 1) for d in a.D)
    scene = mi.load_file(a.scene, **defs)
    if a.make_reference:
        passes = max(1, a.make_reference // 512)
        acc = sum(np.array(mi.render(scene, spp=512, seed=1000 + p), dtype=np.float64)
                  for p in range(passes))
        mi.Bitmap((acc / passes).astype(np.float32)).write(a.reference)
    ref = rgb(mi.Bitmap(a.reference))

    def relmse(img):
        return errors(rgb(img), ref)[1]

    def report(name, v):
        v = np.array(v)
        print(f'{name}: relMSE mean {v.mean():.4g} (std. error {v.std() / np.sqrt(len(v)):.2g}), '
              f'median {np.median(v):.4g}, {len(v)} renders of {a.spp} spp')

    report(f'mitsuba {a.variant}',
           [relmse(mi.render(scene, spp=a.spp, seed=s))
            for s in range(a.seeds)])
    out = os.path.join(tempfile.mkdtemp(), 't.exr')
    t = []
    for s in range(a.seeds):
        cmd = [a.tessera, 'render', a.scene, '--spp', str(a.spp), '--seed', str(s + 1), '-o', out]
        for d in a.D:
            cmd += ['-D', d]
        subprocess.run(cmd, check=True, capture_output=True)
        t.append(relmse(mi.Bitmap(out)))
    report('tessera', t)


if __name__ == '__main__':
    main()
