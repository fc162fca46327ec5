#!/usr/bin/env python3
"""Tiles on Dask (issue 17): the speed-up of kepler.dask.render_tiles with 1, 2 and 4 worker
processes, against Scene.render in this process, measured in the same run.

    pip install "./python[dask]" && python3 scripts/tiles.py [--scene scenes/metropolis.toml]
        [--tiles 8x8] [--runs 3] [--workers 1,2,4]

For each worker count, a local cluster of that many single-threaded worker processes (each
running the engine on one thread: RAYON_NUM_THREADS=1) is started once, the scene scattered
to it once, and the tiled drawing timed N times (median; the cluster's start-up and the
scene's transfer are reported apart). Scene.render runs in this process on every core. Each
tiled drawing is checked against the whole one, bit for bit. Peak resident memory: this
process, and the largest worker's.
"""

import argparse
import os
import resource
import statistics
import sys
import time

import kepler
import kepler.dask


def bits(lines):
    return [(p.edge_class, p.visible, p.points.tobytes()) for p in lines]


def peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("--scene", default=os.path.join(root, "scenes", "metropolis.toml"))
    parser.add_argument("--tiles", default="8x8")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--workers", default="1,2,4")
    args = parser.parse_args()
    tiles = tuple(int(n) for n in args.tiles.split("x"))
    from dask.distributed import Client, LocalCluster

    clock = time.perf_counter()
    scene = kepler.Scene.load(args.scene)
    print(f"{args.scene}: {len(scene.objects())} objects, loaded in "
          f"{time.perf_counter() - clock:.2f} s; {os.cpu_count()} cores")

    def timed(job):
        times, result = [], None
        for _ in range(args.runs):
            clock = time.perf_counter()
            result = job()
            times.append(time.perf_counter() - clock)
        return statistics.median(times), result

    whole_time, whole = timed(lambda: scene.render(hidden=True))
    print(f"{'Scene.render, all cores, this process':46} {whole_time:7.3f} s  "
          f"({len(whole)} polylines; peak {peak_mb():.0f} MB)")
    windows = scene.tile_windows(None, tiles)
    hand_time, hand = timed(lambda: kepler.stitch(
        [scene.render_tile(w) for w in windows], hidden=True))
    assert bits(hand) == bits(whole), "tiles by hand differ from the whole drawing"
    print(f"{f'{args.tiles} tiles one by one, this process':46} {hand_time:7.3f} s  "
          f"(×{whole_time / hand_time:.2f} of render)")
    one = None
    for n in [int(w) for w in args.workers.split(",")]:
        clock = time.perf_counter()
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                          dashboard_address=None, env={"RAYON_NUM_THREADS": "1"}) as cluster, \
                Client(cluster) as client:
            started = time.perf_counter() - clock
            clock = time.perf_counter()
            client.scatter(scene, broadcast=True, hash=False)
            sent = time.perf_counter() - clock
            tiled_time, tiled = timed(lambda: kepler.dask.render_tiles(
                scene, tiles=tiles, client=client, hidden=True))
            assert bits(tiled) == bits(whole), f"{n} workers: tiles differ from the whole"
            worker_mb = max(client.run(lambda: resource.getrusage(
                resource.RUSAGE_SELF).ru_maxrss / 1024).values())
        one = one or tiled_time
        print(f"{f'Dask, {n} worker(s), {args.tiles} tiles':46} {tiled_time:7.3f} s  "
              f"(speed-up ×{one / tiled_time:.2f} over 1 worker, ×{whole_time / tiled_time:.2f} "
              f"of render; cluster start {started:.1f} s, scene sent {sent:.2f} s; "
              f"largest worker {worker_mb:.0f} MB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
