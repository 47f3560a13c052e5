#!/usr/bin/env python3
"""Copies a ugs field series (ugs-flow output) keeping only the steps at the given dates.

    subset_steps.py IN.h5 OUT.h5 DATE[,DATE...]

ugs-solve steps on the dates of its pressure fields: a subset times chosen steps of a long history
(bench/solve/run.sh, HISTORY_SAMPLE=1) without running the steps before them one by one. The
mechanics between two kept dates is then one step (sub-stepped if needed)."""
import shutil
import sys

import h5py


def main():
    src, dst, dates = sys.argv[1], sys.argv[2], set(sys.argv[3].split(','))
    shutil.copy(src, dst)
    with h5py.File(dst, 'r+') as f:
        steps = f['steps']
        names = sorted(steps)
        keep = [s for s in names if steps[s].attrs['date'].decode() in dates]
        missing = dates - {steps[s].attrs['date'].decode() for s in keep}
        if missing:
            sys.exit(f'subset_steps.py: error: {src}: no step at {", ".join(sorted(missing))}')
        for s in names:
            if s not in keep:
                del steps[s]
        # Renumber 000000.. in date order (ugs reads the steps in name order).
        for k, s in enumerate(keep):
            steps.move(s, f'tmp{k:06d}')
        for k in range(len(keep)):
            steps.move(f'tmp{k:06d}', f'{k:06d}')


if __name__ == '__main__':
    main()
