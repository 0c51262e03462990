#!/usr/bin/env bash
# Run a command in the Debian 13 (trixie: dolfinx 0.9) root:
# scripts/debian.sh trixie, kept under its old name.
exec bash "$(dirname "$0")/debian.sh" trixie "$@"
