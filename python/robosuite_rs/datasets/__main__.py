"""``python -m robosuite_rs.datasets <command> ...``:

* ``states-to-obs``: robomimic's ``dataset_states_to_obs.py`` (same arguments) plus
  ``--num_workers`` and ``--overwrite``, with a progress bar on stderr.
* ``playback``: robosuite's ``playback_demonstrations_from_hdf5.py`` without a viewer
  (``--use-actions`` prints each demo's largest divergence from its stored states).
* ``convert``: robomimic's ``convert_robosuite.py`` into a new file.
"""

from __future__ import annotations

import argparse
import sys

from . import DatasetError, convert_to_robomimic, playback, states_to_obs


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m robosuite_rs.datasets")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("states-to-obs", help="robomimic's dataset_states_to_obs.py")
    p.add_argument("--dataset", type=str, required=True, help="path to input hdf5 dataset")
    p.add_argument("--output_name", type=str, help="name of output hdf5 dataset (in the dataset's folder)")
    p.add_argument("--n", type=int, default=None, help="(optional) stop after n trajectories are processed")
    p.add_argument("--shaped", action="store_true", help="(optional) use shaped rewards")
    p.add_argument("--camera_names", type=str, nargs="+", default=[], help="(optional) camera name(s) for image observations")
    p.add_argument("--camera_height", type=int, default=84, help="(optional) height of image observations")
    p.add_argument("--camera_width", type=int, default=84, help="(optional) width of image observations")
    p.add_argument("--depth", action="store_true", help="(optional) use depth observations for each camera")
    p.add_argument("--done_mode", type=int, default=0,
                   help="how to write done signal. If 0, done is 1 whenever s' is a success state. "
                        "If 1, done is 1 at the end of each trajectory. If 2, both.")
    p.add_argument("--copy_rewards", action="store_true", help="(optional) copy rewards from source file")
    p.add_argument("--copy_dones", action="store_true", help="(optional) copy dones from source file")
    p.add_argument("--exclude-next-obs", action="store_true", help="(optional) exclude next obs in dataset")
    p.add_argument("--compress", action="store_true", help="(optional) compress observations with gzip")
    p.add_argument("--num_workers", type=int, default=None, help="worker threads (default: every core)")
    p.add_argument("--ray_actors", type=int, default=None,
                   help="process the demos on this many Ray actors (a Ray cluster, or a local Ray) instead of threads")
    p.add_argument("--overwrite", action="store_true", help="replace an existing output file")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")

    pb = sub.add_parser("playback", help="robosuite's playback_demonstrations_from_hdf5.py, without a viewer")
    pb.add_argument("--dataset", type=str, required=True)
    pb.add_argument("--use-actions", action="store_true")

    pc = sub.add_parser("convert", help="robomimic's convert_robosuite.py, into a new file")
    pc.add_argument("--dataset", type=str, required=True)
    pc.add_argument("--output", type=str, default=None)
    pc.add_argument("--val_ratio", type=float, default=0.1)
    pc.add_argument("--overwrite", action="store_true")

    args = parser.parse_args(argv)
    try:
        if args.command == "states-to-obs":
            r = states_to_obs(
                args.dataset,
                output_name=args.output_name,
                n=args.n,
                shaped=args.shaped,
                camera_names=args.camera_names,
                camera_height=args.camera_height,
                camera_width=args.camera_width,
                depth=args.depth,
                done_mode=args.done_mode,
                copy_rewards=args.copy_rewards,
                copy_dones=args.copy_dones,
                exclude_next_obs=args.exclude_next_obs,
                compress=args.compress,
                num_workers=args.num_workers,
                ray_actors=args.ray_actors,
                overwrite=args.overwrite,
                progress=not args.no_progress,
            )
            rate = r.states / max(r.seconds, 1e-9)
            print(f"Wrote {r.demos} trajectories to {r.output} ({r.states} states in {r.seconds:.2f} s, "
                  f"{rate:.0f} states/s, {r.num_workers} worker(s))")
        elif args.command == "playback":
            for demo, res in playback(args.dataset, use_actions=args.use_actions).items():
                if args.use_actions and len(res.divergence):
                    print(f"{demo}: {res.steps} actions, largest divergence {res.divergence.max():.3g} "
                          f"at step {int(res.divergence.argmax())}")
                else:
                    print(f"{demo}: {res.steps} {'actions' if args.use_actions else 'states'}")
        else:
            print(convert_to_robomimic(args.dataset, args.output, val_ratio=args.val_ratio, overwrite=args.overwrite))
    except (DatasetError, FileExistsError, FileNotFoundError, PermissionError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
