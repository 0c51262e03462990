#!/usr/bin/python3
"""The Python twin of `piezo-contact`: same config, flags and summary.json.

    /usr/bin/python3 demos/piezo_contact.py --config demos/square.json \
        --output out/py [--set mesh.n=64 --set time.steps=64]
"""

from mpi4py import MPI

from piezocontact import cli, config, twin


def main():
    args = cli.parser(__doc__.splitlines()[0]).parse_args()
    comm = MPI.COMM_WORLD
    try:
        cfg = config.load(args.config, args.set)
        cli.prepare_output(args.output, args.config, comm)
        twin.run(cfg, args.output, comm, progress=not args.quiet, source=args.config)
    except config.ConfigError as err:
        cli.fail(str(err), config.EXIT_CONFIG_ERROR)
    except twin.NewtonFailure as err:
        cli.fail(str(err), cli.EXIT_RUN_ERROR)


if __name__ == "__main__":
    main()
