#!/usr/bin/python3
"""The Python twin of `piezo-contact`: same config, flags and summary.json.

    /usr/bin/python3 demos/piezo_contact.py --config demos/square.json \
        --output out/py [--set mesh.n=64 --set time.steps=64]
    /usr/bin/python3 demos/piezo_contact.py --output out/py --resume \
        [--set time.T=2 --set time.steps=128]
"""

import sys

from mpi4py import MPI

from piezocontact import cli, config, output, twin


def main():
    ap = cli.parser(__doc__.splitlines()[0])
    args = ap.parse_args()
    if args.resume and args.config:
        ap.error("--resume takes the config from DIR/summary.json: no --config")
    if not args.resume and not args.config:
        ap.error("--config is required")
    twin.install_interrupt_handlers()
    output.silence_hdf5_errors()  # failures are reported in one line
    comm = MPI.COMM_WORLD
    try:
        if args.resume:
            summary, cfg = cli.resumable_summary(args.output, "python", args.set)
            twin.run(cfg, args.output, comm, progress=not args.quiet,
                     source=summary["config_file"], resume=summary)
        else:
            cfg = config.load(args.config, args.set)
            cli.prepare_output(args.output, args.config, comm)
            twin.run(cfg, args.output, comm, progress=not args.quiet, source=args.config)
    except config.ConfigError as err:
        cli.fail(str(err), config.EXIT_CONFIG_ERROR)
    except twin.NewtonFailure as err:
        cli.fail(str(err), cli.EXIT_RUN_ERROR)
    except output.OutputError as err:
        cli.fail(str(err), output.EXIT_OUTPUT_ERROR)
    except twin.Interrupted as err:
        if comm.rank == 0:
            print(err, file=sys.stderr, flush=True)
        sys.exit(128 + err.signum)


if __name__ == "__main__":
    main()
