"""Chunked contour surfaces (issue 24 part 3): morpho.dask.isosurface against the in-memory
morpho.isosurface on an n³ synthetic float32 volume (a gyroid plus a sphere), for several chunk
sizes; checks that the results are identical and prints time and throughput (samples/s).

    python bench/dask_scale.py --n 512 --chunks 64,128,256 [--cluster 2] [--memory-limit 1.5GB]

``--cluster W`` runs on a ``dask.distributed.LocalCluster`` of W single-threaded worker
processes (and prints the workers' peak resident memory); otherwise on the threaded scheduler.
The volume is written to a raw file first and read chunk by chunk by the workers
(``morpho.dask.from_raw``: each task memory-maps the file), so it is not held by the client.
"""

import argparse
import os
import resource
import tempfile
import time

import numpy as np

import morpho
import morpho.dask as mdask


def field(n, path):
    mm = np.memmap(path, dtype=np.float32, mode="w+", shape=(n, n, n))
    t = np.linspace(0, 4 * np.pi, n, dtype=np.float32)
    y, z = np.meshgrid(t, t, indexing="ij")
    for i in range(n):  # slab by slab: bounded memory
        x = t[i]
        g = np.sin(x) * np.cos(y) + np.sin(y) * np.cos(z) + np.sin(z) * np.cos(x)
        r = (x - 2 * np.pi) ** 2 + (y - 2 * np.pi) ** 2 + (z - 2 * np.pi) ** 2
        mm[i] = g + 0.02 * r
    mm.flush()
    del mm


def identical(a, b):
    return all(
        (x is None and y is None) or (x.shape == y.shape and np.array_equal(
            np.ascontiguousarray(x).view(np.uint8), np.ascontiguousarray(y).view(np.uint8)))
        for x, y in zip(a[:3], b[:3]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--chunks", default="64,128")
    ap.add_argument("--level", type=float, default=0.5)
    ap.add_argument("--cluster", type=int, default=0)
    ap.add_argument("--memory-limit", default="1.5GB")
    ap.add_argument("--no-reference", action="store_true")
    a = ap.parse_args()
    n = a.n
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "v.raw")
        t0 = time.perf_counter()
        field(n, path)
        print(f"volume {n}^3 float32 written in {time.perf_counter() - t0:.1f} s")
        mm = np.memmap(path, dtype=np.float32, mode="r", shape=(n, n, n))
        client = cluster = None
        if a.cluster:
            from distributed import Client, LocalCluster

            cluster = LocalCluster(n_workers=a.cluster, threads_per_worker=1, processes=True,
                                   memory_limit=a.memory_limit, dashboard_address=None)
            client = Client(cluster)
        ref = None
        if not a.no_reference:
            vol = np.array(mm)
            t0 = time.perf_counter()
            ref = morpho.isosurface(vol, a.level)
            dt = time.perf_counter() - t0
            print(f"in memory: {dt:.2f} s, {n ** 3 / dt / 1e6:.1f} M samples/s, "
                  f"{len(ref[1])} triangles, peak RSS {peak_mb():.0f} MB")
            del vol
        try:
            for c in (int(s) for s in a.chunks.split(",")):
                d = mdask.from_raw(path, (n, n, n), np.float32, chunks=c)
                t0 = time.perf_counter()
                got = mdask.isosurface(d, a.level)
                dt = time.perf_counter() - t0
                same = "identical" if ref is not None and identical(got, ref) else (
                    "not compared" if ref is None else "DIFFERENT")
                extra = ""
                if client is not None:
                    peaks = client.run(peak_mb)
                    extra = ", worker peak RSS " + ", ".join(f"{v:.0f} MB" for v in peaks.values())
                print(f"chunks {c}^3: {dt:.2f} s, {n ** 3 / dt / 1e6:.1f} M samples/s, "
                      f"{len(got[1])} triangles, {same}{extra}")
        finally:
            if client is not None:
                client.close()
                cluster.close()


def peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


if __name__ == "__main__":
    main()
