"""A large batch of online-generation problems on Dask: chunks of trajkit.otg inputs are
shipped to the workers (everything pickles, intermediate waypoints included: every fourth
problem passes through one), each chunk is solved there with trajkit.batch.otg (all the
worker's cores), and the durations come back in order.

    python examples/dask_batch.py --problems 100000            # a local cluster
    python examples/dask_batch.py --scheduler tcp://host:8786  # the same code on a cluster
"""
import argparse

import numpy as np

import trajkit
from trajkit import batch, otg


def make_inputs(n, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        inp = otg.InputParameter(7)
        inp.current_position = list(rng.uniform(-1, 1, 7))
        inp.current_velocity = list(rng.uniform(-0.5, 0.5, 7))
        inp.target_position = list(rng.uniform(-1, 1, 7))
        if k % 4 == 0:
            middle = (np.array(inp.current_position) + inp.target_position) / 2
            inp.intermediate_positions = [middle + rng.uniform(-0.3, 0.3, 7)]
        inp.max_velocity = [2.0] * 7
        inp.max_acceleration = [5.0] * 7
        inp.max_jerk = [50.0] * 7
        out.append(inp)
    return out


def solve_chunk(inputs):
    """Runs on a worker: one call, all of its cores; durations (NaN for a failed input)."""
    res = batch.otg(inputs, delta_time=0.001)
    return [float("nan") if isinstance(r, trajkit.TrajkitError) else r.duration for r in res]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--problems", type=int, default=10000)
    ap.add_argument("--chunk", type=int, default=1000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler")
    args = ap.parse_args()

    from dask.distributed import Client, LocalCluster

    inputs = make_inputs(args.problems)
    chunks = [inputs[i:i + args.chunk] for i in range(0, len(inputs), args.chunk)]
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                     processes=True, dashboard_address=None))
    with client:
        futures = client.map(solve_chunk, chunks)
        durations = [d for part in client.gather(futures) for d in part]
    local = solve_chunk(inputs)
    assert np.array_equal(np.array(durations), np.array(local), equal_nan=True)
    print(f"{len(durations)} problems, mean duration {np.nanmean(durations):.4f} s; "
          "the cluster's results match the local batch")


if __name__ == "__main__":
    main()
